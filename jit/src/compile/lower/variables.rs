//! Variables and the entry points: outputs, function bodies, `=` and `:` variables with
//! their cache freshness (stamped before evaluating, stale on abort), inlined at their
//! uses when small.

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    /// Every output in order, as separate entries would compute them one after the
    /// other in the same record (each starts at depth 0 with no fatal error, as
    /// `Compiled::run` starts them), storing each value and the count as it goes:
    /// on a fatal error the host has the columns before it. What one column
    /// computed (variables, input columns, library results) the next reuses.
    pub(super) fn outputs(&mut self, list: &'m [&'m Expr]) -> R<Value> {
        let out = self.load_raw(self.st.ptr, OFF_OUT);
        for (k, e) in list.iter().enumerate() {
            let v = self.expr(e)?;
            self.check_failed();
            self.b.ins().store(mem(), v, out, k as i32 * 8);
            let n = self.i64c(k as u64 + 1);
            self.store_raw(n, OFF_DONE);
        }
        Ok(self.f64c(0.0))
    }

    pub(super) fn func_body(&mut self, def: DefId) -> R<Value> {
        self.st.compiled_defs.insert(def);
        let sym = self.st.module.def(def).sym.0;
        self.stack_check(sym);
        let d = self.add_depth(1);
        self.depth_event(sym, d, self.depth);
        let body = &self.st.module.def(def).body;
        let v = self.expr(body)?;
        self.add_depth(-1);
        Ok(v)
    }

    /// Whether the cache slot holds a value for the current record (or for good).
    pub(super) fn fresh(&mut self, def: DefId, idx: u32) -> Value {
        let cache = self.cache_ptr;
        let off = idx as i32 * CACHED_SIZE;
        let tick = self.b.ins().load(types::I64, mem(), cache, off + OFF_TICK);
        if is_constant(self.st.module, def) {
            self.b.ins().icmp_imm_s(IntCC::Equal, tick, FOREVER as i64)
        } else {
            // Never-computed slots hold 0, and the clock is never 0 (a context
            // starts at 1 and wraps to 1).
            self.b.ins().icmp(IntCC::Equal, tick, self.clock)
        }
    }

    pub(super) fn cached_value(&mut self, idx: u32) -> Value {
        let cache = self.cache_ptr;
        let off = idx as i32 * CACHED_SIZE;
        self.b.ins().load(types::F64, mem(), cache, off + OFF_VALUE)
    }

    /// caldefn.c `dvalue` past the definition lookup: the cached value if fresh, else
    /// the body evaluated at top level and cached.
    pub(super) fn var_body(&mut self, def: DefId) -> R<Value> {
        let module = self.st.module;
        let d = module.def(def);
        let sym = d.sym.0;
        let (_, idx) = self.st.var_fn(def)?;
        self.st.compiled_defs.insert(def);
        self.stack_check(sym);
        if is_constant(module, def) && self.st.warn_nonconstant {
            let w = self.i32c(W_NONCONSTANT);
            self.warn(w, sym);
        }
        let fresh = self.fresh(def, idx);
        let hit = self.b.create_block();
        let miss = self.b.create_block();
        self.b.ins().brif(fresh, hit, &[], miss, &[]);
        self.b.switch_to_block(hit);
        let v = self.cached_value(idx);
        self.b.ins().return_(&[v]);
        self.b.switch_to_block(miss);
        // The stamp is set before evaluating, as caldefn.c does: a definition that
        // refers to itself (directly or through others) sees its previous value.
        let tick = if is_constant(module, def) {
            self.i64c(FOREVER)
        } else {
            self.clock
        };
        let cache = self.cache_ptr;
        let off = idx as i32 * CACHED_SIZE;
        self.b.ins().store(mem(), tick, cache, off + OFF_TICK);
        // A fatal error in the body leaves the slot stale, as the interpreter's
        // restored stamp does: every abort from here on stamps it "never computed"
        // (0), stale at this clock and every later one as the stamp it had was
        // (missing, it was an earlier clock, or 0; `:` slots missing hold 0) until
        // the clock wraps after 2^64 records. No old stamp stays live across the
        // body (it held a register through every call). The value is untouched.
        let outer_abort = self.abort.take();
        let restore = self.b.create_block();
        self.b.set_cold_block(restore);
        self.abort = Some(restore);
        let v = self.expr(&d.body)?;
        self.check_failed();
        self.b.ins().store(mem(), v, cache, off + OFF_VALUE);
        self.restore = Some((restore, cache, off));
        self.abort = outer_abort;
        Ok(v)
    }

    // ---- expressions ----------------------------------------------------------------

    /// A reference to a variable: caldefn.c `dvalue`, with the freshness test inline.
    pub(super) fn variable(&mut self, s: SymId) -> R<Value> {
        let module = self.st.module;
        let Some(def) = module
            .current_def(s)
            .filter(|&d| !module.def(d).is_function())
        else {
            return Ok(self.fail(E_UNDEFINED_VARIABLE, s.0));
        };
        if let Some(&k) = self.st.host_vars.get(&def) {
            let hosts = self.load_raw(self.st.ptr, OFF_HOSTS);
            return Ok(self.b.ins().load(types::F64, mem(), hosts, k as i32 * 8));
        }
        if let Node::Num(v) = module.def(def).body.node {
            return Ok(self.f64c(v));
        }
        // (Constants that warn on every read are never known.)
        if let Some(&v) = self.known_args.get(&Key::Var(def.0)) {
            return Ok(v);
        }
        // Reads of a variable in its own body see the previous value: known there,
        // but not numbered as the variable's value.
        let own = self.inlining_vars.contains(&def) || self.job_var == Some(def);
        if !own
            && self.inlining_vars.len() < INLINE_VAR_NESTING
            && let Some(size) = self.st.var_inline_size(def)
            && self.st.charge_inline(size)
        {
            let v = self.inline_variable(def)?;
            self.know(Key::Var(def.0), v);
            self.label(v, Key::Var(def.0));
            return Ok(v);
        }
        let (fid, idx) = self.st.var_fn(def)?;
        let f = self.func_ref(fid);
        if is_constant(module, def) && self.st.warn_nonconstant {
            // Every read warns: nothing to reuse.
            self.sync_depth();
            self.errno_clear = None;
            let inst = self.b.ins().call(f, &[self.raw]);
            let v = self.b.inst_results(inst)[0];
            self.check_failed();
            return Ok(v);
        }
        if let Some(&v) = self.known_args.get(&Key::Var(def.0)) {
            return Ok(v);
        }
        let v = self.cached_variable(def, f, idx);
        self.know(Key::Var(def.0), v);
        if !own {
            self.label(v, Key::Var(def.0));
        }
        Ok(v)
    }

    /// [`Lower::var_body`] inlined at a use: the cached value if fresh, else the body
    /// evaluated here (at top level: a variable's body has no parameters) with the
    /// stamp set first and put back if a fatal error aborts it.
    pub(super) fn inline_variable(&mut self, def: DefId) -> R<Value> {
        self.st.compiled_defs.insert(def);
        let idx = self.st.var_slot(def);
        let fresh = self.fresh(def, idx);
        let (j, out) = self.join();
        let hit = self.b.create_block();
        let miss = self.b.create_block();
        self.b.ins().brif(fresh, hit, &[], miss, &[]);
        self.b.switch_to_block(hit);
        let v = self.cached_value(idx);
        self.jump_with(j, v);
        self.b.switch_to_block(miss);
        let known = self.mark();
        let tick = self.clock;
        let cache = self.cache_ptr;
        let off = idx as i32 * CACHED_SIZE;
        self.b.ins().store(mem(), tick, cache, off + OFF_TICK);
        let outer = self.abort_block();
        let restore = self.b.create_block();
        self.b.set_cold_block(restore);
        self.abort = Some(restore);
        self.inlining_vars.push(def);
        let here = std::mem::replace(&mut self.cur, 0);
        let module = self.st.module;
        let v = self.expr(&module.def(def).body);
        self.cur = here;
        self.inlining_vars.pop();
        let v = v?;
        self.abort = Some(outer);
        self.b.ins().store(mem(), v, cache, off + OFF_VALUE);
        self.restores.push((restore, cache, off, outer));
        self.rewind(known);
        self.jump_with(j, v);
        self.b.switch_to_block(j);
        Ok(out)
    }

    /// The inline freshness test, calling the variable's function on a miss.
    pub(super) fn cached_variable(&mut self, def: DefId, f: FuncRef, idx: u32) -> Value {
        let fresh = self.fresh(def, idx);
        let (j, out) = self.join();
        let hit = self.b.create_block();
        let miss = self.b.create_block();
        self.b.ins().brif(fresh, hit, &[], miss, &[]);
        self.b.switch_to_block(hit);
        let v = self.cached_value(idx);
        self.jump_with(j, v);
        self.b.switch_to_block(miss);
        self.sync_depth();
        self.errno_clear = None;
        let inst = self.b.ins().call(f, &[self.raw]);
        let v = self.b.inst_results(inst)[0];
        self.check_failed();
        self.jump_with(j, v);
        self.b.switch_to_block(j);
        out
    }
}
