//! `select` (and `if`, which lowers through it): only the side taken is generated for a
//! number index, a jump table from four cases on.

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    /// calfunc.c `l_select`: the rounded index picks one argument, evaluated alone;
    /// 0 gives the count of the rest; out of range is a domain error.
    pub(super) fn select(&mut self, args: &'m [Expr], sym: u32) -> R<Value> {
        let a1 = self.lib_arg(args, 0, sym)?;
        if args.is_empty() {
            return Ok(a1);
        }
        let nargs = args.len() as i64;
        let half = self.f64c(0.5);
        let r = self.b.ins().fadd(a1, half);
        let n = self.b.ins().fcvt_to_sint_sat(types::I64, r);
        let nan = self.b.ins().fcmp(FloatCC::Unordered, a1, a1);
        let lim = self.f64c(-0.5);
        let low = self.b.ins().fcmp(FloatCC::LessThan, a1, lim);
        // Past C's int, `(int)(x + .5)` is INT_MIN (`c_round`): not out of range
        // above, but "Bad call to argument!" below.
        let int_limit = self.f64c(2_147_483_648.0);
        let big = self.b.ins().fcmp(FloatCC::GreaterThanOrEqual, r, int_limit);
        let high = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedGreaterThanOrEqual, n, nargs);
        let fits = self.b.ins().bxor_imm_u(big, 1);
        let high = self.b.ins().band(high, fits);
        let bad = self.b.ins().bor(nan, low);
        let bad = self.b.ins().bor(bad, high);
        let (j, out) = self.join();
        let (dom, ok) = self.cold_branch(bad);
        self.b.switch_to_block(dom);
        self.set_errno(ERRNO_DOMAIN);
        let zero = self.f64c(0.0);
        self.jump_with(j, zero);
        self.b.switch_to_block(ok);
        let (huge, ok) = self.cold_branch(big);
        self.b.switch_to_block(huge);
        let zero = self.fail(E_BAD_CALL, sym);
        self.jump_with(j, zero);
        self.b.switch_to_block(ok);
        // Here 0 <= n < args.len().
        if args.len() >= 4 {
            let cases: Vec<ir::Block> = (0..args.len()).map(|_| self.b.create_block()).collect();
            let calls: Vec<ir::BlockCall> = cases
                .iter()
                .map(|&c| self.b.func.dfg.block_call(c, &[]))
                .collect();
            let Some(&last) = calls.last() else {
                return Ok(out);
            };
            let jt = self
                .b
                .create_jump_table(ir::JumpTableData::new(last, &calls));
            let idx = self.b.ins().ireduce(types::I32, n);
            self.b.ins().br_table(idx, jt);
            for (k, &case) in cases.iter().enumerate() {
                self.b.switch_to_block(case);
                self.select_case(args, k, sym, j)?;
            }
            self.b.switch_to_block(j);
            return Ok(out);
        }
        for k in 0..args.len() {
            let case = self.b.create_block();
            if k + 1 < args.len() {
                let next = self.b.create_block();
                let is_k = self.b.ins().icmp_imm_s(IntCC::Equal, n, k as i64);
                self.b.ins().brif(is_k, case, &[], next, &[]);
                self.b.switch_to_block(case);
                self.select_case(args, k, sym, j)?;
                self.b.switch_to_block(next);
            } else {
                self.b.ins().jump(case, &[]);
                self.b.switch_to_block(case);
                self.select_case(args, k, sym, j)?;
            }
        }
        self.b.switch_to_block(j);
        Ok(out)
    }

    pub(super) fn select_case(
        &mut self,
        args: &'m [Expr],
        k: usize,
        sym: u32,
        j: ir::Block,
    ) -> R<()> {
        let known = self.mark();
        let v = if k == 0 {
            self.f64c((args.len() - 1) as f64)
        } else {
            self.lib_arg(args, k, sym)?
        };
        self.jump_with(j, v);
        self.rewind(known);
        Ok(())
    }
}
