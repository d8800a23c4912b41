//! The library functions: calls through function-valued arguments, the C math library
//! with its `errno` policy (the warning test skipped where no argument can set
//! `errno`), and the pure ones reused by value numbering.

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    /// An argument expression as a function value (calfunc.c `eargf` rules).
    pub(super) fn fn_value(
        &mut self,
        a: &'m Expr,
        callee: CalleeName,
        not_function: &mut Option<Value>,
    ) -> R<(Value, Value)> {
        let module = self.st.module;
        let code = |s: u32, kind: u64| (u64::from(s) << FN_SHIFT) | kind;
        Ok(match a.node {
            Node::Var(s) => {
                match module
                    .current_def(s)
                    .filter(|&d| module.def(d).is_function())
                {
                    Some(def) => {
                        let fid = self.st.user_fn(def)?;
                        let fr = self.func_ref(fid);
                        let fp = self.b.ins().func_addr(self.st.ptr, fr);
                        (fp, self.i64c(code(s.0, FN_USER)))
                    }
                    None => {
                        let kind = if module.symbol(s).lib.is_some() {
                            FN_LIB
                        } else {
                            FN_UNDEFINED
                        };
                        (self.i64c(0), self.i64c(code(s.0, kind)))
                    }
                }
            }
            Node::Arg(m) => match self.block {
                Some(block) => {
                    let osym = self.owner_sym();
                    let j = self.b.create_block();
                    let fp = self.b.append_block_param(j, self.st.ptr);
                    let cd = self.b.append_block_param(j, types::I64);
                    let nargs = self.b.ins().load(types::I64, mem(), block, OFF_NARGS);
                    let ok = self.b.ins().icmp_imm_s(
                        IntCC::UnsignedGreaterThanOrEqual,
                        nargs,
                        i64::from(m),
                    );
                    let copy = self.b.create_block();
                    let short = self.b.create_block();
                    self.b.ins().brif(ok, copy, &[], short, &[]);
                    self.b.switch_to_block(copy);
                    let off = slot_offset(m as usize - 1);
                    let p = self
                        .b
                        .ins()
                        .load(self.st.ptr, mem(), block, off + OFF_SLOT_FN_PTR);
                    let c = self
                        .b
                        .ins()
                        .load(types::I64, mem(), block, off + OFF_SLOT_FN_CODE);
                    self.b
                        .ins()
                        .jump(j, &[BlockArg::Value(p), BlockArg::Value(c)]);
                    self.b.switch_to_block(short);
                    let p = self.b.ins().iconst(self.st.ptr, 0);
                    let c = self.i64c(code(osym, FN_TOO_FEW));
                    self.b
                        .ins()
                        .jump(j, &[BlockArg::Value(p), BlockArg::Value(c)]);
                    self.b.switch_to_block(j);
                    (fp, cd)
                }
                None => (self.i64c(0), self.i64c(code(NO_SYM, FN_NOT_FUNCTION))),
            },
            _ => {
                let c = match *not_function {
                    Some(c) => c,
                    None => {
                        let c = match callee {
                            CalleeName::Static(s) => self.i64c(code(s.0, FN_NOT_FUNCTION)),
                            CalleeName::Dynamic(sym) => {
                                let shifted = self.b.ins().ishl_imm_u(sym, FN_SHIFT as i64);
                                self.b.ins().bor_imm_u(shifted, FN_NOT_FUNCTION as i64)
                            }
                        };
                        *not_function = Some(c);
                        c
                    }
                };
                (self.i64c(0), c)
            }
        })
    }

    // ---- library functions, inline -----------------------------------------------------

    /// A library call's entry in `Evaluator::call`: one level deeper while it runs,
    /// but its arguments are evaluated back at the caller's depth, so only the check
    /// is needed here.
    pub(super) fn lib_enter(&mut self, sym: u32) {
        if let Some(d) = self.depth {
            let v = self.i64c(d + 1);
            self.depth_event(sym, v, Some(d + 1));
            return;
        }
        let d = self.load_raw(types::I64, OFF_DEPTH);
        let d = self.b.ins().iadd_imm_s(d, 1);
        self.depth_event(sym, d, None);
    }

    pub(super) fn lib_arg(&mut self, args: &'m [Expr], i: usize, sym: u32) -> R<Value> {
        match args.get(i) {
            Some(a) => self.expr(a),
            None => Ok(self.fail(E_TOO_FEW, sym)),
        }
    }

    /// calfunc.c `libfunc`'s epilogue: a raised `errno` warns and gives 0.
    pub(super) fn lib_result(&mut self, d: Value, sym: u32) -> Value {
        self.nonfinite(d);
        if self.errno_is_clear() {
            return d;
        }
        let errno = self.load_raw(types::I64, OFF_ERRNO);
        let (j, out) = self.join();
        let (bad, ok) = self.cold_branch(errno);
        self.b.switch_to_block(bad);
        let is_domain = self
            .b
            .ins()
            .icmp_imm_s(IntCC::Equal, errno, ERRNO_DOMAIN as i64);
        let domain = self.i32c(W_DOMAIN);
        let range = self.i32c(W_RANGE);
        let w = self.b.ins().select(is_domain, domain, range);
        self.warn(w, sym);
        let zero = self.f64c(0.0);
        self.jump_with(j, zero);
        self.b.switch_to_block(ok);
        self.jump_with(j, d);
        self.b.switch_to_block(j);
        self.quiet_if(out, &[d])
    }

    pub(super) fn builtin(&mut self, b: Builtin, sym: u32, args: &'m [Expr]) -> R<Value> {
        if let Some(v) = self.pure_builtin(b, sym, args)? {
            return Ok(v);
        }
        self.lib_enter(sym);
        self.set_errno(ERRNO_NONE);
        let d = match b {
            // A number for condition: only the side taken is generated (the
            // interpreter evaluates the number, with no effect, then that side).
            Builtin::If
                if args.len() >= 3
                    && let Some(c) =
                        args.first().and_then(|a| self.const_value(a, CONST_DEPTH)) =>
            {
                self.lib_arg(args, if c > 0.0 { 1 } else { 2 }, sym)?
            }
            Builtin::Select
                if let Some(n) = args
                    .first()
                    .and_then(|a| self.const_value(a, CONST_DEPTH))
                    .filter(|a| *a >= 0.5)
                    .map(c_round)
                    .filter(|&n| n >= 1 && n < args.len() as i64) =>
            {
                self.lib_arg(args, n as usize, sym)?
            }
            Builtin::If => {
                let c = self.lib_arg(args, 0, sym)?;
                let zero = self.f64c(0.0);
                let gt = self.b.ins().fcmp(FloatCC::GreaterThan, c, zero);
                let (j, out) = self.join();
                let yes = self.b.create_block();
                let no = self.b.create_block();
                self.b.ins().brif(gt, yes, &[], no, &[]);
                let known = self.mark();
                self.b.switch_to_block(yes);
                let v = self.lib_arg(args, 1, sym)?;
                self.jump_with(j, v);
                self.rewind(known);
                self.b.switch_to_block(no);
                let v = self.lib_arg(args, 2, sym)?;
                self.jump_with(j, v);
                self.rewind(known);
                self.b.switch_to_block(j);
                out
            }
            Builtin::Select => self.select(args, sym)?,
            Builtin::Max | Builtin::Min => {
                let mut best = self.lib_arg(args, 0, sym)?;
                let cc = if b == Builtin::Max {
                    FloatCC::GreaterThan
                } else {
                    FloatCC::LessThan
                };
                for k in (1..args.len()).rev() {
                    let v = self.lib_arg(args, k, sym)?;
                    let keep = self.b.ins().fcmp(cc, best, v);
                    best = self.b.ins().select(keep, best, v);
                }
                best
            }
            // Arguments right to left, as for `^`.
            Builtin::Atan2 => {
                let x = self.lib_arg(args, 1, sym)?;
                let y = self.lib_arg(args, 0, sym)?;
                self.atan2(y, x)
            }
            // Exact operations (floor, ceil, sqrt) are the hardware instruction, the
            // others calls of the very functions the interpreter calls.
            other => {
                let x = self.lib_arg(args, 0, sym)?;
                self.unary(other, x)
            }
        };
        Ok(self.lib_result(d, sym))
    }

    /// A C library function whose arguments are [`Lower::pure_ready`]: evaluating
    /// them leaves `errno` as the call cleared it, so without the non-finite policy
    /// the result is the function's value, with no warning to test for. With
    /// numbers for arguments the value is computed now (by the very function the
    /// generated code would call) when finite; a one-argument function already
    /// called on the same value reuses that result. The depth check stays: it is
    /// what the interpreter does on entering any call.
    pub(super) fn pure_builtin(
        &mut self,
        b: Builtin,
        sym: u32,
        args: &'m [Expr],
    ) -> R<Option<Value>> {
        let arity = match b {
            Builtin::If | Builtin::Select | Builtin::Max | Builtin::Min => return Ok(None),
            Builtin::Atan2 => 2,
            _ => 1,
        };
        let Some(used) = args.get(..arity) else {
            return Ok(None);
        };
        if !used.iter().all(|a| self.pure_ready(a)) {
            return Ok(None);
        }
        self.lib_enter(sym);
        self.set_errno(ERRNO_NONE);
        let consts: Option<Vec<f64>> = used
            .iter()
            .map(|a| self.const_value(a, CONST_DEPTH))
            .collect();
        if let Some(c) = consts {
            let d = match b {
                Builtin::Atan2 => c[0].atan2(c[1]),
                _ => b.unary(c[0]).unwrap_or(0.0),
            };
            if d.is_finite() {
                return Ok(Some(self.f64c(d)));
            }
        }
        let d = if b == Builtin::Atan2 {
            let x = self.expr(&used[1])?;
            let y = self.expr(&used[0])?;
            self.atan2(y, x)
        } else {
            let x = self.expr(&used[0])?;
            self.unary(b, x)
        };
        Ok(Some(if self.st.policy == MathErrors::NonFinite {
            self.lib_result(d, sym)
        } else {
            d
        }))
    }

    pub(super) fn atan2(&mut self, y: Value, x: Value) -> Value {
        let key = Key::Atan2(self.vn(y), self.vn(x));
        self.pure_call(key, |lw| lw.call_lib("radc_atan2", &[y, x]))
    }

    /// A one-argument C library function, inline where it is one instruction.
    pub(super) fn unary(&mut self, b: Builtin, x: Value) -> Value {
        match b {
            Builtin::Floor | Builtin::Ceil => {
                let r = if b == Builtin::Floor {
                    self.b.ins().floor(x)
                } else {
                    self.b.ins().ceil(x)
                };
                let zero = self.f64c(0.0);
                let is_zero = self.b.ins().fcmp(FloatCC::Equal, r, zero);
                let v = self.b.ins().select(is_zero, zero, r);
                self.quiet.insert(v);
                v
            }
            Builtin::Sqrt => {
                let v = self.b.ins().sqrt(x);
                self.quiet.insert(v);
                v
            }
            other => {
                let key = Key::Call(other, self.vn(x));
                self.pure_call(key, |lw| match unary_symbol(other) {
                    Some(name) => lw.call_lib(name, &[x]),
                    None => lw.f64c(0.0),
                })
            }
        }
    }
}
