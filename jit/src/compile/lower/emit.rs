//! The instructions every lowering step is made of: constants, the context block's raw
//! fields, `errno`, calls into the host and the C library, blocks for failures and
//! joins, and the call depth counted as the interpreter counts it.

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    pub(super) fn owner_sym(&self) -> u32 {
        self.owner.map_or(NO_SYM, |d| self.st.module.def(d).sym.0)
    }

    pub(super) fn f64c(&mut self, v: f64) -> Value {
        let c = self.b.ins().f64const(v);
        self.numbers.insert(c, v);
        c
    }

    pub(super) fn i64c(&mut self, v: u64) -> Value {
        self.b.ins().iconst(types::I64, v as i64)
    }

    pub(super) fn i32c(&mut self, v: u32) -> Value {
        self.b.ins().iconst(types::I32, i64::from(v))
    }

    pub(super) fn load_raw(&mut self, ty: ir::Type, off: i32) -> Value {
        self.b.ins().load(ty, mem(), self.raw, off)
    }

    pub(super) fn store_raw(&mut self, v: Value, off: i32) {
        if off == OFF_ERRNO {
            self.errno_clear = None;
        }
        self.b.ins().store(mem(), v, self.raw, off);
    }

    pub(super) fn set_errno(&mut self, e: u64) {
        if e == ERRNO_NONE && self.errno_is_clear() {
            return;
        }
        let v = self.i64c(e);
        self.store_raw(v, OFF_ERRNO);
        if e == ERRNO_NONE {
            self.errno_clear = self.b.current_block();
        }
    }

    /// Whether `errno` is known to be 0 here (see [`Lower::errno_clear`]).
    pub(super) fn errno_is_clear(&self) -> bool {
        self.errno_clear.is_some() && self.errno_clear == self.b.current_block()
    }

    pub(super) fn func_ref(&mut self, id: FuncId) -> FuncRef {
        if let Some(&r) = self.refs.get(&id) {
            return r;
        }
        let r = self.st.jit.declare_func_in_func(id, self.b.func);
        self.refs.insert(id, r);
        r
    }

    pub(super) fn call_import(&mut self, name: &'static str, args: &[Value]) -> Option<Value> {
        let id = self.st.imports[name];
        let f = self.func_ref(id);
        self.errno_clear = None;
        let inst = self.b.ins().call(f, args);
        self.b.inst_results(inst).first().copied()
    }

    pub(super) fn call_import_f64(&mut self, name: &'static str, args: &[Value]) -> Value {
        match self.call_import(name, args) {
            Some(v) => v,
            None => self.f64c(0.0),
        }
    }

    /// A C library function of `host.rs` (pow, atan2, the unary ones): its result is
    /// never a signalling NaN (see [`Lower::quiet`]).
    pub(super) fn call_lib(&mut self, name: &'static str, args: &[Value]) -> Value {
        // The C library does not touch the context: `errno` stays as it was.
        let clear = self.errno_clear;
        let v = self.call_import_f64(name, args);
        self.errno_clear = clear;
        self.quiet.insert(v);
        v
    }

    pub(super) fn uniform_sig(&mut self) -> SigRef {
        if let Some(s) = self.uniform {
            return s;
        }
        let s = self.b.import_signature(self.st.sig_uniform.clone());
        self.uniform = Some(s);
        s
    }

    pub(super) fn thunk_sig(&mut self) -> SigRef {
        if let Some(s) = self.thunk_sig {
            return s;
        }
        let s = self.b.import_signature(self.st.sig_thunk.clone());
        self.thunk_sig = Some(s);
        s
    }

    pub(super) fn abort_block(&mut self) -> ir::Block {
        if let Some(b) = self.abort {
            return b;
        }
        let b = self.b.create_block();
        self.b.set_cold_block(b);
        self.abort = Some(b);
        b
    }

    /// Return at once (with 0) if a fatal error was raised.
    pub(super) fn check_failed(&mut self) {
        let failed = self.load_raw(types::I64, OFF_FAILED);
        let cont = self.b.create_block();
        let abort = self.abort_block();
        self.b.ins().brif(failed, abort, &[], cont, &[]);
        self.b.switch_to_block(cont);
    }

    /// Raise a fatal error and return; code emitted after this is unreachable.
    pub(super) fn fail(&mut self, code: u32, sym: u32) -> Value {
        let c = self.i32c(code);
        let s = self.i32c(sym);
        self.call_import("radc_fail", &[self.raw, c, s]);
        let abort = self.abort_block();
        self.b.ins().jump(abort, &[]);
        let dead = self.b.create_block();
        self.b.switch_to_block(dead);
        self.f64c(0.0)
    }

    pub(super) fn warn(&mut self, code: Value, sym: u32) {
        let s = self.i32c(sym);
        self.call_import("radc_warn", &[self.raw, code, s]);
    }

    pub(super) fn join(&mut self) -> (ir::Block, Value) {
        let j = self.b.create_block();
        let v = self.b.append_block_param(j, types::F64);
        (j, v)
    }

    pub(super) fn jump_with(&mut self, j: ir::Block, v: Value) {
        self.b.ins().jump(j, &[BlockArg::Value(v)]);
    }

    /// Branch on `cond`: the `cold` side first, then the other, both ending at `j`.
    pub(super) fn cold_branch(&mut self, cond: Value) -> (ir::Block, ir::Block) {
        let yes = self.b.create_block();
        let no = self.b.create_block();
        self.b.set_cold_block(yes);
        self.b.ins().brif(cond, yes, &[], no, &[]);
        (yes, no)
    }

    /// Fail with "too deep" instead of overflowing the native stack.
    pub(super) fn stack_check(&mut self, sym: u32) {
        let sp = self.b.ins().get_stack_pointer(self.st.ptr);
        let limit = self.load_raw(self.st.ptr, OFF_STACK_LIMIT);
        let low = self.b.ins().icmp(IntCC::UnsignedLessThan, sp, limit);
        let (bad, ok) = self.cold_branch(low);
        self.b.switch_to_block(bad);
        self.fail(E_TOO_DEEP, sym);
        self.b.ins().jump(ok, &[]);
        self.b.switch_to_block(ok);
    }

    /// `Evaluator::call`'s depth bookkeeping for a call entering nesting `depth`.
    /// Nothing to do below the first report level when the depth is `known`.
    pub(super) fn depth_event(&mut self, sym: u32, depth: Value, known: Option<u64>) {
        if known.is_some_and(|d| d < FIRST_DEPTH_REPORT) {
            return;
        }
        let limit = self.load_raw(types::I64, OFF_DEPTH_LIMIT);
        let hit = self
            .b
            .ins()
            .icmp(IntCC::UnsignedGreaterThanOrEqual, depth, limit);
        let (slow, cont) = self.cold_branch(hit);
        self.b.switch_to_block(slow);
        let s = self.i32c(sym);
        self.call_import("radc_depth", &[self.raw, s, depth]);
        self.check_failed();
        self.b.ins().jump(cont, &[]);
        self.b.switch_to_block(cont);
    }

    pub(super) fn add_depth(&mut self, delta: i64) -> Value {
        if let Some(d) = self.depth {
            // Stored only for the functions this one calls (`sync_depth`).
            let d = d.wrapping_add_signed(delta);
            self.depth = Some(d);
            return self.i64c(d);
        }
        let d = self.load_raw(types::I64, OFF_DEPTH);
        let d = self.b.ins().iadd_imm_s(d, delta);
        self.store_raw(d, OFF_DEPTH);
        d
    }

    /// Before calling code that reads `Raw::depth` (generated functions, thunks,
    /// calls through function values): the depth known while compiling, stored.
    pub(super) fn sync_depth(&mut self) {
        if let Some(d) = self.depth {
            let v = self.i64c(d);
            self.store_raw(v, OFF_DEPTH);
        }
    }

    // ---- function bodies ------------------------------------------------------------
}
