//! Calls of user functions: arguments as call-by-need thunks in an argument block (or
//! values, where they are numbers or already computed), small non-recursive functions
//! inlined with their arguments computed on first use in the caller's frame, and the
//! argument-count checks.

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    /// calfunc.c `argument`: parameter `n`, computed once per call in the caller's
    /// context (one level less deep).
    pub(super) fn argument(&mut self, n: u32) -> Value {
        if let Some(&v) = self.known_args.get(&Key::Arg(0, n)) {
            return v;
        }
        let v = self.compute_argument(n);
        self.know(Key::Arg(0, n), v);
        v
    }

    pub(super) fn compute_argument(&mut self, n: u32) -> Value {
        let Some(block) = self.block else {
            return self.fail(E_TOO_FEW, NO_SYM);
        };
        let osym = self.owner_sym();
        let (j, out) = self.join();
        self.check_arg_count(block, n, osym, j);
        let off = slot_offset(n as usize - 1);
        let state = self
            .b
            .ins()
            .load(types::I64, mem(), block, off + OFF_SLOT_STATE);
        let have = self.b.create_block();
        let compute = self.b.create_block();
        self.b.ins().brif(state, have, &[], compute, &[]);
        self.b.switch_to_block(have);
        let v = self
            .b
            .ins()
            .load(types::F64, mem(), block, off + OFF_SLOT_VALUE);
        self.jump_with(j, v);
        self.b.switch_to_block(compute);
        self.add_depth(-1);
        let thunk = self
            .b
            .ins()
            .load(self.st.ptr, mem(), block, off + OFF_SLOT_THUNK);
        let parent = self.b.ins().load(self.st.ptr, mem(), block, OFF_PARENT);
        let sig = self.thunk_sig();
        let slot = self.b.ins().iadd_imm_s(block, i64::from(off));
        self.sync_depth();
        let inst = self
            .b
            .ins()
            .call_indirect(sig, thunk, &[self.raw, parent, slot]);
        self.errno_clear = None;
        let v = self.b.inst_results(inst)[0];
        self.add_depth(1);
        self.check_failed();
        self.b.ins().store(mem(), v, block, off + OFF_SLOT_VALUE);
        let one = self.i64c(1);
        self.b.ins().store(mem(), one, block, off + OFF_SLOT_STATE);
        self.jump_with(j, v);
        self.b.switch_to_block(j);
        out
    }

    /// "too few arguments" (for the function `osym`) when the block has fewer than
    /// `n`; the failing path ends at `j`. Continues on the good path.
    pub(super) fn check_arg_count(&mut self, block: Value, n: u32, osym: u32, j: ir::Block) {
        let nargs = self.b.ins().load(types::I64, mem(), block, OFF_NARGS);
        let short = self
            .b
            .ins()
            .icmp_imm_s(IntCC::UnsignedLessThan, nargs, i64::from(n));
        let (bad, ok) = self.cold_branch(short);
        self.b.switch_to_block(bad);
        let zero = self.fail(E_TOO_FEW, osym);
        self.jump_with(j, zero);
        self.b.switch_to_block(ok);
    }

    /// Parameter `n` of the inlined call `self.cur`: calfunc.c `argument` as
    /// [`Lower::argument`] does it, with the argument's expression lowered in place
    /// (in the caller's frame, one level less deep) instead of called as a thunk.
    pub(super) fn inline_argument(&mut self, n: u32) -> R<Value> {
        let k = self.cur;
        let frame = &self.frames[k as usize - 1];
        let (args, parent, sym) = (frame.args, frame.parent, frame.sym);
        let Some(arg) = (n as usize).checked_sub(1).and_then(|i| args.get(i)) else {
            return Ok(self.fail(E_TOO_FEW, sym));
        };
        if let Some(&v) = self.known_args.get(&Key::Arg(k, n)) {
            return Ok(v);
        }
        let (flag, value) = frame.vars[n as usize - 1];
        let v = if self.maybe_computed.insert((k, n)) {
            self.inline_compute(parent, arg)?
        } else {
            let done = self.b.use_var(flag);
            let (j, out) = self.join();
            let have = self.b.create_block();
            let compute = self.b.create_block();
            self.b.ins().brif(done, have, &[], compute, &[]);
            self.b.switch_to_block(have);
            let v = self.b.use_var(value);
            self.jump_with(j, v);
            self.b.switch_to_block(compute);
            let known = self.mark();
            let v = self.inline_compute(parent, arg)?;
            self.rewind(known);
            self.jump_with(j, v);
            self.b.switch_to_block(j);
            // Either way the argument's one value: computed now or before, it is
            // the same expression in the same frame.
            let n = self.vn(v);
            self.vns.insert(out, n);
            out
        };
        let one = self.b.ins().iconst(types::I8, 1);
        self.b.def_var(flag, one);
        self.b.def_var(value, v);
        self.know(Key::Arg(k, n), v);
        Ok(v)
    }

    pub(super) fn inline_compute(&mut self, parent: u32, arg: &'m Expr) -> R<Value> {
        self.add_depth(-1);
        let here = std::mem::replace(&mut self.cur, parent);
        let v = self.expr(arg);
        self.cur = here;
        let v = v?;
        self.add_depth(1);
        Ok(v)
    }

    /// A user function call inlined: `Evaluator::call`'s depth bookkeeping around
    /// the body, lowered in a new frame whose parameters are the call's arguments.
    pub(super) fn inline_call(&mut self, def: DefId, sym: u32, args: &'m [Expr]) -> R<Value> {
        self.st.compiled_defs.insert(def);
        let d = self.add_depth(1);
        self.depth_event(sym, d, self.depth);
        let zero = self.b.ins().iconst(types::I8, 0);
        let nothing = self.f64c(0.0);
        let mut vars = Vec::with_capacity(args.len());
        for _ in args {
            let flag = self.b.declare_var(types::I8);
            let value = self.b.declare_var(types::F64);
            self.b.def_var(flag, zero);
            self.b.def_var(value, nothing);
            vars.push((flag, value));
        }
        self.frames.push(Inline {
            args,
            parent: self.cur,
            sym,
            vars,
        });
        let id = self.frames.len() as u32;
        let here = std::mem::replace(&mut self.cur, id);
        let module = self.st.module;
        let v = self.expr(&module.def(def).body);
        self.cur = here;
        let v = v?;
        self.add_depth(-1);
        Ok(v)
    }

    /// Inlined code never builds argument blocks (see `State::inline_size`); this
    /// guards the rule.
    pub(super) fn in_own_frame(&self) -> R<()> {
        if self.cur == 0 {
            Ok(())
        } else {
            Err(JitError::Backend(
                "internal: an argument block inside inlined code".into(),
            ))
        }
    }

    // ---- calls ------------------------------------------------------------------------

    /// calfunc.c `efunc` by name: a user function if the name's definition is one,
    /// else the library function.
    pub(super) fn call_sym(&mut self, s: SymId, args: &'m [Expr]) -> R<Value> {
        let module = self.st.module;
        if let Some(def) = module
            .current_def(s)
            .filter(|&d| module.def(d).is_function())
        {
            // Inside inlined code every call is inlined (see `State::inline_size`);
            // the outermost inlined call was charged for them.
            let inline = match self.st.inline_size(def) {
                Some(_) if self.cur != 0 => true,
                Some(size) => self.st.charge_inline(size),
                None => false,
            };
            if inline {
                let sym = module.def(def).sym.0;
                return self.inline_call(def, sym, args);
            }
            self.in_own_frame()?;
            let fid = self.st.user_fn(def)?;
            let fill = self.st.uses_fn_values(def);
            let block = self.build_block(args, CalleeName::Static(s), fill)?;
            let f = self.func_ref(fid);
            self.sync_depth();
            self.errno_clear = None;
            let inst = self.b.ins().call(f, &[self.raw, block]);
            let v = self.b.inst_results(inst)[0];
            self.check_failed();
            return Ok(v);
        }
        Ok(match module.symbol(s).lib {
            Some(LibFn::Builtin(b)) => self.builtin(b, s.0, args)?,
            Some(LibFn::In) => {
                self.lib_enter(s.0);
                self.set_errno(ERRNO_NONE);
                let x = self.lib_arg(args, 0, s.0)?;
                let d = self.call_import_f64("radc_in", &[self.raw, x]);
                self.check_failed();
                self.lib_result(d, s.0)
            }
            Some(LibFn::Renderer(r)) => {
                self.lib_enter(s.0);
                self.set_errno(ERRNO_NONE);
                let zero = self.b.ins().f64const(0.0);
                let mut vals = [zero; 3];
                for (i, v) in vals.iter_mut().enumerate().take(r.arity.min(3)) {
                    *v = self.lib_arg(args, i, s.0)?;
                }
                let sym = self.b.ins().iconst(types::I32, i64::from(s.0));
                let d = self.call_import_f64(
                    "radc_renderer_fn",
                    &[self.raw, sym, vals[0], vals[1], vals[2]],
                );
                self.check_failed();
                self.lib_result(d, s.0)
            }
            None => {
                self.lib_enter(s.0);
                self.fail(E_UNDEFINED_FUNCTION, s.0)
            }
        })
    }

    /// A call through parameter `n`: calfunc.c `eargf`, resolved when the argument
    /// block was built, called here.
    pub(super) fn call_arg(&mut self, n: u32, args: &'m [Expr]) -> R<Value> {
        self.in_own_frame()?;
        let Some(block) = self.block else {
            return Ok(self.fail(E_NOT_FUNCTION, NO_SYM));
        };
        let osym = self.owner_sym();
        let (j, out) = self.join();
        self.check_arg_count(block, n, osym, j);
        let off = slot_offset(n as usize - 1);
        let fp = self
            .b
            .ins()
            .load(self.st.ptr, mem(), block, off + OFF_SLOT_FN_PTR);
        let code = self
            .b
            .ins()
            .load(types::I64, mem(), block, off + OFF_SLOT_FN_CODE);
        let sym = self.b.ins().ushr_imm_u(code, FN_SHIFT as i64);
        let new_block = self.build_block(args, CalleeName::Dynamic(sym), true)?;
        let direct = self.b.create_block();
        let via_host = self.b.create_block();
        self.b.ins().brif(fp, direct, &[], via_host, &[]);
        self.b.switch_to_block(direct);
        let sig = self.uniform_sig();
        self.sync_depth();
        self.errno_clear = None;
        let inst = self.b.ins().call_indirect(sig, fp, &[self.raw, new_block]);
        let v = self.b.inst_results(inst)[0];
        self.check_failed();
        self.jump_with(j, v);
        self.b.switch_to_block(via_host);
        self.sync_depth();
        let v = self.call_import_f64("radc_fnval", &[self.raw, new_block, code]);
        self.check_failed();
        self.jump_with(j, v);
        self.b.switch_to_block(j);
        Ok(out)
    }

    /// The argument block of a call, in this frame: a thunk per argument (numbers
    /// are stored as already computed), and, if the callee may call them, each
    /// argument as a function value.
    pub(super) fn build_block(
        &mut self,
        args: &'m [Expr],
        callee: CalleeName,
        fill: bool,
    ) -> R<Value> {
        let size = (BLOCK_SIZE + args.len() as i32 * SLOT_SIZE) as u32;
        let ss = self.b.create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            size,
            3,
        ));
        let base = self.b.ins().stack_addr(self.st.ptr, ss, 0);
        let parent = match self.block {
            Some(b) => b,
            None => self.b.ins().iconst(self.st.ptr, 0),
        };
        self.b.ins().store(mem(), parent, base, OFF_PARENT);
        let nargs = self.i64c(args.len() as u64);
        self.b.ins().store(mem(), nargs, base, OFF_NARGS);
        let mut not_function: Option<Value> = None;
        for (i, a) in args.iter().enumerate() {
            let off = slot_offset(i);
            if let Node::Num(v) = a.node {
                let v = self.f64c(v);
                self.b.ins().store(mem(), v, base, off + OFF_SLOT_VALUE);
                let one = self.i64c(1);
                self.b.ins().store(mem(), one, base, off + OFF_SLOT_STATE);
            } else if self.pure_ready(a) {
                // Evaluating it now is unobservable: no warning, error, errno or
                // depth event can come of it, and it gives what the thunk would.
                let v = self.expr(a)?;
                self.b.ins().store(mem(), v, base, off + OFF_SLOT_VALUE);
                let one = self.i64c(1);
                self.b.ins().store(mem(), one, base, off + OFF_SLOT_STATE);
            } else if let Node::Chan(n @ 1..) = a.node {
                let zero = self.i64c(0);
                self.b.ins().store(mem(), zero, base, off + OFF_SLOT_STATE);
                let id = self.st.imports["radc_chan_thunk"];
                let fr = self.func_ref(id);
                let addr = self.b.ins().func_addr(self.st.ptr, fr);
                self.b.ins().store(mem(), addr, base, off + OFF_SLOT_THUNK);
                let n = self.i64c(u64::from(n));
                self.b.ins().store(mem(), n, base, off + OFF_SLOT_AUX);
            } else {
                let zero = self.i64c(0);
                self.b.ins().store(mem(), zero, base, off + OFF_SLOT_STATE);
                let tid = self.st.thunk(a, self.owner)?;
                let fr = self.func_ref(tid);
                let addr = self.b.ins().func_addr(self.st.ptr, fr);
                self.b.ins().store(mem(), addr, base, off + OFF_SLOT_THUNK);
            }
            if fill {
                let (fp, code) = self.fn_value(a, callee, &mut not_function)?;
                self.b.ins().store(mem(), fp, base, off + OFF_SLOT_FN_PTR);
                self.b
                    .ins()
                    .store(mem(), code, base, off + OFF_SLOT_FN_CODE);
            }
        }
        Ok(base)
    }
}
