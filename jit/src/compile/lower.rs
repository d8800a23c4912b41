//! Lowering one function body from the calcomp IR to Cranelift IR, with the
//! interpreter's (`radc_lang::cal::eval`) semantics step by step: the same operation
//! order, the same `errno` updates, the same depth counting, lazy call-by-need
//! arguments, and only the taken side of `if`/`select` evaluated.

use super::JitError;
use super::codegen::{EntryBody, INLINE_VAR_NESTING, Job, State, is_constant};
use super::host::unary_symbol;
use super::layout::*;
use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::{
    self, BlockArg, FuncRef, InstBuilder, MemFlagsData, SigRef, StackSlotData, StackSlotKind,
    Value, types,
};
use cranelift_frontend::{FunctionBuilder, Variable};
use cranelift_module::{FuncId, Module as _};
use radc_lang::cal::builtins::{Builtin, LibFn};
use radc_lang::cal::eval::{MathErrors, c_round};
use radc_lang::cal::ir::{Callee, DefId, Expr, Node, SymId};
use std::collections::{HashMap, HashSet};

type R<T> = Result<T, JitError>;

/// Whose name a call's "argument not a function" error carries.
#[derive(Clone, Copy)]
enum CalleeName {
    Static(SymId),
    /// Known only at run time (a call through a parameter): the symbol as an i64.
    Dynamic(Value),
}

/// A value number: values with the same number are equal whenever both have been
/// computed (in one call of the generated function), whichever paths computed them.
type Vn = u32;

/// What a value is, as far as the lowering can tell: the keys of what is known to be
/// computed on every path to the current point (`Lower::known_args`) and of the value
/// numbers (`Lower::vns`).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Key {
    /// Parameter `n` of frame `frame`: a slot's value never changes once computed.
    Arg(u32, u32),
    /// A variable: its cached value does not change within a record (except while
    /// the variable itself is being computed: reads of it in its own body see the
    /// previous value, and are not given this key's value number).
    Var(u32),
    /// Input column `n`: the same within a record (`Input` is read, not consumed).
    Chan(u32),
    /// The `errno` code reading column `n` raised (an i64, 0 for none).
    ChanErrno(u32),
    /// The C library's result for an argument value (`pow` and `atan2` for two):
    /// the functions are pure, so a second call with the same value reuses it (the
    /// `errno` and depth bookkeeping around the call is still done each time).
    Call(Builtin, Vn),
    Pow(Vn, Vn),
    Atan2(Vn, Vn),
    /// An exact arithmetic operation (kind, operands): the same operation on the
    /// same values is the same value, so later calls on it can be recognised.
    Op(u8, Vn, Vn),
    /// A number, by bits.
    Num(u64),
    /// A value with no identity beyond itself.
    Val(Value),
}

/// How many library results one generated function remembers across branches (each
/// is two SSA variables: computed, and the value).
const MAX_LAZY: usize = 48;

const OP_ADD: u8 = 0;
const OP_MUL: u8 = 1;
const OP_SUB: u8 = 2;
const OP_NEG: u8 = 3;
const OP_DIV: u8 = 4;

/// How deep [`Lower::const_value`] looks: constant subtrees are small in practice,
/// and the bound keeps the lowering linear.
const CONST_DEPTH: u32 = 6;

/// The interpreter's `nan_first`, for values computed while compiling.
fn nan_first(first: f64, second: f64, result: f64) -> f64 {
    if first.is_nan() {
        first
    } else if second.is_nan() {
        second
    } else {
        result
    }
}

/// One inlined call of a user function: its arguments, still unevaluated (they are
/// computed on first use, in the caller's frame, as call-by-need requires).
struct Inline<'m> {
    args: &'m [Expr],
    /// The frame the arguments are evaluated in (0: the function being generated).
    parent: u32,
    /// The function's symbol, for "too few arguments".
    sym: u32,
    /// Per argument: whether it was computed (i8) and its value, as SSA variables,
    /// for uses that only some paths reach after computing it.
    vars: Vec<(Variable, Variable)>,
}

pub struct Lower<'a, 'b, 'm> {
    b: FunctionBuilder<'b>,
    st: &'a mut State<'m>,
    raw: Value,
    /// The argument block of the activation this code runs in.
    block: Option<Value>,
    /// The function whose parameters `Arg` nodes name.
    owner: Option<DefId>,
    refs: HashMap<FuncId, FuncRef>,
    uniform: Option<SigRef>,
    thunk_sig: Option<SigRef>,
    /// Parameters (`(0, n)`) and variables (`(1, def)`) already computed on every
    /// path to the current point: a slot's value never changes once computed, and a
    /// variable's cached value not within a record, so later uses reuse them.
    known_args: HashMap<Key, Value>,
    /// What each `know` replaced, so a branch's additions can be undone (a copy of
    /// the map per branch would make the lowering quadratic).
    undo: Vec<(Key, Option<Value>)>,
    /// Values that are numbers (made by [`Lower::number`]).
    numbers: HashMap<Value, f64>,
    /// Values that are never a signalling NaN, because the hardware or the C library
    /// made them (an arithmetic instruction's result, a library function's): see
    /// [`Lower::nan_first`]. Never a load (which Cranelift may fold into the other
    /// side of `+` or `*`) nor a negation (`-a * -b` is rewritten to `a * b`).
    quiet: HashSet<Value>,
    /// The block in which `errno` was last stored 0 with nothing since (in that
    /// block) that can change it: no other store of it and no call but the C
    /// library's. There the store is not repeated and a library call's `errno` test
    /// is known to pass.
    errno_clear: Option<ir::Block>,
    /// Inlined calls: frame `k >= 1` is `frames[k - 1]`; frame 0 is the activation
    /// the generated function runs in (`block`, `owner`).
    frames: Vec<Inline<'m>>,
    /// The frame whose parameters `Arg` nodes name.
    cur: u32,
    /// Inlined parameters computed somewhere already emitted: a use elsewhere must
    /// test the flag (those never computed before are computed without a test).
    maybe_computed: HashSet<(u32, u32)>,
    abort: Option<ir::Block>,
    /// A variable body's abort path: the block, the cache and the slot's offset;
    /// emitted after the body.
    restore: Option<(ir::Block, Value, i32)>,
    /// The abort paths of inlined variable bodies: as `restore`, then on to the
    /// abort path that was in force around the body.
    restores: Vec<(ir::Block, Value, i32, ir::Block)>,
    /// Variables whose bodies are being inlined (a body refers to itself, or to a
    /// variable around it, through the cache as usual).
    inlining_vars: Vec<DefId>,
    /// The call depth (`Raw::depth`) here, when known while compiling: in an entry
    /// function, which `Compiled::run` starts at depth 0, every change of depth is
    /// a constant (inlined calls and their arguments; the functions it calls give
    /// the depth back as they found it). Below the first report level, where no
    /// depth event can happen, there is then nothing to check.
    depth: Option<u64>,
    /// `Raw::cache` and `Raw::clock`, loaded once: neither changes while generated
    /// code runs.
    cache_ptr: Value,
    clock: Value,
    /// The variable whose body this function is (`Job::Var`).
    job_var: Option<DefId>,
    /// Value numbers of values, and of keys (see [`Vn`]).
    vns: HashMap<Value, Vn>,
    interned: HashMap<Key, Vn>,
    next_vn: Vn,
    /// Library results computed on some paths: whether (an i8) and what, as SSA
    /// variables, so a later call on an equal argument tests instead of calling.
    lazy: HashMap<Key, (Variable, Variable)>,
}

fn mem() -> MemFlagsData {
    MemFlagsData::trusted()
}

fn slot_offset(i: usize) -> i32 {
    BLOCK_SIZE + i as i32 * SLOT_SIZE
}

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    pub fn build(mut b: FunctionBuilder<'b>, st: &'a mut State<'m>, job: Job<'m>) -> R<()> {
        let entry = b.create_block();
        b.append_block_params_for_function_params(entry);
        b.switch_to_block(entry);
        let params = b.block_params(entry).to_vec();
        let raw = params[0];
        let fixed = mem().with_readonly();
        let cache_ptr = b.ins().load(st.ptr, fixed, raw, OFF_CACHE);
        let clock = b.ins().load(types::I64, fixed, raw, OFF_CLOCK);
        let (owner, block) = match &job {
            Job::Func(d) => (Some(*d), params.get(1).copied()),
            Job::Thunk { owner: Some(d), .. } => (Some(*d), params.get(1).copied()),
            _ => (None, None),
        };
        let mut lw = Lower {
            b,
            st,
            raw,
            block,
            owner,
            refs: HashMap::new(),
            uniform: None,
            thunk_sig: None,
            known_args: HashMap::new(),
            undo: Vec::new(),
            numbers: HashMap::new(),
            quiet: HashSet::new(),
            errno_clear: None,
            frames: Vec::new(),
            cur: 0,
            maybe_computed: HashSet::new(),
            abort: None,
            restore: None,
            restores: Vec::new(),
            inlining_vars: Vec::new(),
            cache_ptr,
            clock,
            depth: match &job {
                Job::Entry { .. } => Some(0),
                _ => None,
            },
            job_var: match &job {
                Job::Var(d) => Some(*d),
                _ => None,
            },
            vns: HashMap::new(),
            interned: HashMap::new(),
            next_vn: 0,
            lazy: HashMap::new(),
        };
        let v = match job {
            Job::Var(d) => lw.var_body(d)?,
            Job::Func(d) => lw.func_body(d)?,
            // No stack check: any recursion passes through a user function or a
            // variable, which check.
            Job::Thunk { expr, .. } => lw.expr(expr)?,
            Job::Entry { what, .. } => match what {
                EntryBody::Variable(s) => lw.variable(s)?,
                EntryBody::Output(e) => lw.expr(e)?,
                EntryBody::Outputs(list) => lw.outputs(list)?,
            },
        };
        lw.b.ins().return_(&[v]);
        for (block, cache, off, then) in std::mem::take(&mut lw.restores) {
            lw.b.switch_to_block(block);
            let never = lw.i64c(0);
            lw.b.ins().store(mem(), never, cache, off + OFF_TICK);
            lw.b.ins().jump(then, &[]);
        }
        if let Some((block, cache, off)) = lw.restore {
            lw.b.switch_to_block(block);
            let never = lw.i64c(0);
            lw.b.ins().store(mem(), never, cache, off + OFF_TICK);
            let zero = lw.b.ins().f64const(0.0);
            lw.b.ins().return_(&[zero]);
        }
        if let Some(abort) = lw.abort {
            lw.b.switch_to_block(abort);
            let zero = lw.b.ins().f64const(0.0);
            lw.b.ins().return_(&[zero]);
        }
        lw.b.seal_all_blocks();
        let config = lw.st.jit.target_config();
        lw.b.finalize(config);
        Ok(())
    }

    // ---- small helpers ------------------------------------------------------------

    fn owner_sym(&self) -> u32 {
        self.owner.map_or(NO_SYM, |d| self.st.module.def(d).sym.0)
    }

    fn f64c(&mut self, v: f64) -> Value {
        let c = self.b.ins().f64const(v);
        self.numbers.insert(c, v);
        c
    }

    fn i64c(&mut self, v: u64) -> Value {
        self.b.ins().iconst(types::I64, v as i64)
    }

    fn i32c(&mut self, v: u32) -> Value {
        self.b.ins().iconst(types::I32, i64::from(v))
    }

    fn load_raw(&mut self, ty: ir::Type, off: i32) -> Value {
        self.b.ins().load(ty, mem(), self.raw, off)
    }

    fn store_raw(&mut self, v: Value, off: i32) {
        if off == OFF_ERRNO {
            self.errno_clear = None;
        }
        self.b.ins().store(mem(), v, self.raw, off);
    }

    fn set_errno(&mut self, e: u64) {
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
    fn errno_is_clear(&self) -> bool {
        self.errno_clear.is_some() && self.errno_clear == self.b.current_block()
    }

    fn func_ref(&mut self, id: FuncId) -> FuncRef {
        if let Some(&r) = self.refs.get(&id) {
            return r;
        }
        let r = self.st.jit.declare_func_in_func(id, self.b.func);
        self.refs.insert(id, r);
        r
    }

    fn call_import(&mut self, name: &'static str, args: &[Value]) -> Option<Value> {
        let id = self.st.imports[name];
        let f = self.func_ref(id);
        self.errno_clear = None;
        let inst = self.b.ins().call(f, args);
        self.b.inst_results(inst).first().copied()
    }

    fn call_import_f64(&mut self, name: &'static str, args: &[Value]) -> Value {
        match self.call_import(name, args) {
            Some(v) => v,
            None => self.f64c(0.0),
        }
    }

    /// A C library function of `host.rs` (pow, atan2, the unary ones): its result is
    /// never a signalling NaN (see [`Lower::quiet`]).
    fn call_lib(&mut self, name: &'static str, args: &[Value]) -> Value {
        // The C library does not touch the context: `errno` stays as it was.
        let clear = self.errno_clear;
        let v = self.call_import_f64(name, args);
        self.errno_clear = clear;
        self.quiet.insert(v);
        v
    }

    fn uniform_sig(&mut self) -> SigRef {
        if let Some(s) = self.uniform {
            return s;
        }
        let s = self.b.import_signature(self.st.sig_uniform.clone());
        self.uniform = Some(s);
        s
    }

    fn thunk_sig(&mut self) -> SigRef {
        if let Some(s) = self.thunk_sig {
            return s;
        }
        let s = self.b.import_signature(self.st.sig_thunk.clone());
        self.thunk_sig = Some(s);
        s
    }

    fn abort_block(&mut self) -> ir::Block {
        if let Some(b) = self.abort {
            return b;
        }
        let b = self.b.create_block();
        self.b.set_cold_block(b);
        self.abort = Some(b);
        b
    }

    /// Return at once (with 0) if a fatal error was raised.
    fn check_failed(&mut self) {
        let failed = self.load_raw(types::I64, OFF_FAILED);
        let cont = self.b.create_block();
        let abort = self.abort_block();
        self.b.ins().brif(failed, abort, &[], cont, &[]);
        self.b.switch_to_block(cont);
    }

    /// Raise a fatal error and return; code emitted after this is unreachable.
    fn fail(&mut self, code: u32, sym: u32) -> Value {
        let c = self.i32c(code);
        let s = self.i32c(sym);
        self.call_import("radc_fail", &[self.raw, c, s]);
        let abort = self.abort_block();
        self.b.ins().jump(abort, &[]);
        let dead = self.b.create_block();
        self.b.switch_to_block(dead);
        self.f64c(0.0)
    }

    fn warn(&mut self, code: Value, sym: u32) {
        let s = self.i32c(sym);
        self.call_import("radc_warn", &[self.raw, code, s]);
    }

    fn join(&mut self) -> (ir::Block, Value) {
        let j = self.b.create_block();
        let v = self.b.append_block_param(j, types::F64);
        (j, v)
    }

    fn jump_with(&mut self, j: ir::Block, v: Value) {
        self.b.ins().jump(j, &[BlockArg::Value(v)]);
    }

    /// Branch on `cond`: the `cold` side first, then the other, both ending at `j`.
    fn cold_branch(&mut self, cond: Value) -> (ir::Block, ir::Block) {
        let yes = self.b.create_block();
        let no = self.b.create_block();
        self.b.set_cold_block(yes);
        self.b.ins().brif(cond, yes, &[], no, &[]);
        (yes, no)
    }

    /// Fail with "too deep" instead of overflowing the native stack.
    fn stack_check(&mut self, sym: u32) {
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
    fn depth_event(&mut self, sym: u32, depth: Value, known: Option<u64>) {
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

    fn add_depth(&mut self, delta: i64) -> Value {
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
    fn sync_depth(&mut self) {
        if let Some(d) = self.depth {
            let v = self.i64c(d);
            self.store_raw(v, OFF_DEPTH);
        }
    }

    // ---- function bodies ------------------------------------------------------------

    /// Every output in order, as separate entries would compute them one after the
    /// other in the same record (each starts at depth 0 with no fatal error, as
    /// `Compiled::run` starts them), storing each value and the count as it goes:
    /// on a fatal error the host has the columns before it. What one column
    /// computed (variables, input columns, library results) the next reuses.
    fn outputs(&mut self, list: &'m [&'m Expr]) -> R<Value> {
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

    fn func_body(&mut self, def: DefId) -> R<Value> {
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
    fn fresh(&mut self, def: DefId, idx: u32) -> Value {
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

    fn cached_value(&mut self, idx: u32) -> Value {
        let cache = self.cache_ptr;
        let off = idx as i32 * CACHED_SIZE;
        self.b.ins().load(types::F64, mem(), cache, off + OFF_VALUE)
    }

    /// caldefn.c `dvalue` past the definition lookup: the cached value if fresh, else
    /// the body evaluated at top level and cached.
    fn var_body(&mut self, def: DefId) -> R<Value> {
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

    fn expr(&mut self, e: &'m Expr) -> R<Value> {
        if !matches!(e.node, Node::Num(_))
            && let Some(v) = self.const_value(e, CONST_DEPTH)
        {
            return Ok(self.number(v));
        }
        Ok(match &e.node {
            Node::Num(v) => self.number(*v),
            Node::Chan(n) => {
                if *n < 1 {
                    self.fail(E_ILLEGAL_CHANNEL, NO_SYM)
                } else {
                    self.channel(*n)
                }
            }
            Node::Var(s) => self.variable(*s)?,
            Node::Arg(n) if self.cur == 0 => self.argument(*n),
            Node::Arg(n) => self.inline_argument(*n)?,
            Node::Neg(a) => {
                let x = self.expr(a)?;
                let k = self.op_key(OP_NEG, x, x);
                self.memo(k, |lw| lw.b.ins().fneg(x))
            }
            // Summed from 0 as calexpr.c `eadd` does: `-0 + -0` is 0.
            Node::Sum(v) => {
                let mut acc = self.number(0.0);
                for x in v {
                    let x = self.expr(x)?;
                    let k = self.op_key(OP_ADD, acc, x);
                    acc = self.memo(k, |lw| {
                        let r = lw.commuted(acc, x, |b, p, q| b.ins().fadd(p, q));
                        lw.nan_first(acc, x, r)
                    });
                }
                acc
            }
            // From 1; `1 * x` is `x` to the bit (a NaN `x` included, which
            // `nan_first` would return), so the first factor starts.
            Node::Product(v) => {
                let mut acc: Option<Value> = None;
                for x in v {
                    let x = self.expr(x)?;
                    acc = Some(match acc {
                        Some(a) => {
                            let k = self.op_key(OP_MUL, a, x);
                            self.memo(k, |lw| {
                                let r = lw.commuted(a, x, |b, p, q| b.ins().fmul(p, q));
                                lw.nan_first(a, x, r)
                            })
                        }
                        None => x,
                    });
                }
                match acc {
                    Some(a) => a,
                    None => self.number(1.0),
                }
            }
            Node::Sub(a, b) => {
                let x = self.expr(a)?;
                let y = self.expr(b)?;
                let k = self.op_key(OP_SUB, x, y);
                self.memo(k, |lw| {
                    let r = lw.b.ins().fsub(x, y);
                    lw.nan_first(x, y, r)
                })
            }
            Node::Div(a, b) => self.divide(a, b)?,
            Node::Pow(a, b) => self.power(a, b)?,
            Node::Call { callee, args } => match callee {
                Callee::Sym(s) => self.call_sym(*s, args)?,
                Callee::Arg(n) => self.call_arg(*n, args)?,
            },
        })
    }

    /// Input column `n` (`n >= 1`): read once on every path (a fatal error aborts),
    /// then reused, with the `errno` the read raised raised again, as a new read
    /// would (`Input::column` gives the same for the same record).
    fn channel(&mut self, n: u32) -> Value {
        if let (Some(&v), Some(&e)) = (
            self.known_args.get(&Key::Chan(n)),
            self.known_args.get(&Key::ChanErrno(n)),
        ) {
            let errno = self.load_raw(types::I64, OFF_ERRNO);
            let new = self.b.ins().select(e, e, errno);
            self.store_raw(new, OFF_ERRNO);
            return v;
        }
        let c = self.i32c(n);
        let v = self.call_import_f64("radc_chan", &[self.raw, c]);
        self.check_failed();
        let e = self.load_raw(types::I64, OFF_CHAN_ERRNO);
        self.know(Key::Chan(n), v);
        self.know(Key::ChanErrno(n), e);
        self.label(v, Key::Chan(n));
        v
    }

    /// A number in an expression (one value per number in each region of code, so
    /// operations on it can be recognised as the same).
    fn number(&mut self, v: f64) -> Value {
        self.memo(Key::Num(v.to_bits()), |lw| {
            let c = lw.f64c(v);
            lw.numbers.insert(c, v);
            c
        })
    }

    /// Whether a value is a number that is not NaN (its NaN test is then known).
    fn not_nan(&self, v: Value) -> bool {
        self.numbers.get(&v).is_some_and(|x| !x.is_nan())
    }

    /// Record that `key` is computed, as `v`, on every path from here.
    fn know(&mut self, key: Key, v: Value) {
        let old = self.known_args.insert(key, v);
        self.undo.push((key, old));
    }

    /// The state of `known_args` before a branch, for [`Lower::rewind`].
    fn mark(&self) -> usize {
        self.undo.len()
    }

    /// Forget what was learned since `mark` (at the end of a branch).
    fn rewind(&mut self, mark: usize) {
        while self.undo.len() > mark {
            let Some((key, old)) = self.undo.pop() else {
                break;
            };
            match old {
                Some(v) => self.known_args.insert(key, v),
                None => self.known_args.remove(&key),
            };
        }
    }

    /// The value already computed for `key` on every path here, or `make`'s.
    fn memo(&mut self, key: Key, make: impl FnOnce(&mut Self) -> Value) -> Value {
        if let Some(&v) = self.known_args.get(&key) {
            return v;
        }
        let v = make(self);
        self.know(key, v);
        self.label(v, key);
        v
    }

    fn intern(&mut self, key: Key) -> Vn {
        if let Some(&n) = self.interned.get(&key) {
            return n;
        }
        let n = self.next_vn;
        self.next_vn += 1;
        self.interned.insert(key, n);
        n
    }

    /// The value number of `v`: its key's if it was given one, else its own.
    fn vn(&mut self, v: Value) -> Vn {
        if let Some(&n) = self.vns.get(&v) {
            return n;
        }
        let n = self.intern(Key::Val(v));
        self.vns.insert(v, n);
        n
    }

    /// `v` is the value of `key` (a value keeps the first number it was given; a
    /// key not yet numbered takes the value's).
    fn label(&mut self, v: Value, key: Key) {
        match self.vns.get(&v) {
            Some(&n) => {
                self.interned.entry(key).or_insert(n);
            }
            None => {
                let n = self.intern(key);
                self.vns.insert(v, n);
            }
        }
    }

    fn op_key(&mut self, kind: u8, x: Value, y: Value) -> Key {
        Key::Op(kind, self.vn(x), self.vn(y))
    }

    /// A pure library function's result for `key`: the value already computed on
    /// every path here; else, if some path may have computed it, a test of that
    /// (the value, or a call); else a call, remembered for later calls.
    fn pure_call(&mut self, key: Key, call: impl FnOnce(&mut Self) -> Value) -> Value {
        if let Some(&v) = self.known_args.get(&key) {
            return v;
        }
        let v = match self.lazy.get(&key).copied() {
            Some((flag, val)) => {
                let done = self.b.use_var(flag);
                let (j, out) = self.join();
                let have = self.b.create_block();
                let compute = self.b.create_block();
                self.b.ins().brif(done, have, &[], compute, &[]);
                self.b.switch_to_block(have);
                let v = self.b.use_var(val);
                self.jump_with(j, v);
                self.b.switch_to_block(compute);
                let d = call(self);
                let one = self.b.ins().iconst(types::I8, 1);
                self.b.def_var(flag, one);
                self.b.def_var(val, d);
                self.jump_with(j, d);
                self.b.switch_to_block(j);
                // Every value of `val` is a result of the same call.
                self.quiet_if(out, &[d])
            }
            None => {
                let d = call(self);
                if self.lazy.len() < MAX_LAZY {
                    // Never defined on the paths that do not compute it, the flag
                    // reads as 0 there (Cranelift's SSA construction zero-fills).
                    let flag = self.b.declare_var(types::I8);
                    let val = self.b.declare_var(types::F64);
                    let one = self.b.ins().iconst(types::I8, 1);
                    self.b.def_var(flag, one);
                    self.b.def_var(val, d);
                    self.lazy.insert(key, (flag, val));
                }
                d
            }
        };
        self.know(key, v);
        self.label(v, key);
        v
    }

    /// `x op y` for a commutative IEEE operation (`+`, `*`: the same value either
    /// way for operands that are not NaN, zeros' signs included), with a number that
    /// is not NaN second, where the machine code can read it from memory; the NaN
    /// cases are `nan_first`'s, which looks at the operands, not at the order.
    fn commuted(
        &mut self,
        x: Value,
        y: Value,
        op: impl FnOnce(&mut FunctionBuilder<'b>, Value, Value) -> Value,
    ) -> Value {
        if self.not_nan(x) && !self.numbers.contains_key(&y) {
            op(&mut self.b, y, x)
        } else {
            op(&mut self.b, x, y)
        }
    }

    /// Whether a value is either not a NaN or a quiet NaN made by the hardware or
    /// the C library ([`Lower::quiet`]), never a signalling NaN.
    fn is_quiet(&self, v: Value) -> bool {
        self.not_nan(v) || self.quiet.contains(&v)
    }

    /// Mark `v` as [`Lower::is_quiet`] when every value it can be is.
    fn quiet_if(&mut self, v: Value, parts: &[Value]) -> Value {
        if parts.iter().all(|&p| self.is_quiet(p)) {
            self.quiet.insert(v);
        }
        v
    }

    /// `Evaluator`'s `nan_first`: with a NaN operand, the first NaN operand itself
    /// (x86 keeps the destination's NaN, and the order is the reference rcalc's);
    /// otherwise the computed result.
    ///
    /// The SSE/AVX instruction `result` was computed by (`first op second`) already
    /// gives that for quiet NaNs: the first source operand if it is a NaN, else the
    /// second, each unchanged when quiet (only a signalling NaN is changed, to its
    /// quiet form). So a test is needed only for an operand that may be a
    /// signalling NaN (an input column, a variable's cached value, a parameter): the
    /// second's when it may be one, and then the first's too (unless a number), so
    /// that a NaN first still wins over the second's select.
    fn nan_first(&mut self, first: Value, second: Value, result: Value) -> Value {
        self.quiet.insert(result);
        let second_quiet = self.is_quiet(second);
        let r = if second_quiet {
            result
        } else {
            let second_nan = self.b.ins().fcmp(FloatCC::Unordered, second, second);
            self.b.ins().select(second_nan, second, result)
        };
        if self.not_nan(first) || (second_quiet && self.is_quiet(first)) {
            return self.quiet_if(r, &[first, second]);
        }
        let first_nan = self.b.ins().fcmp(FloatCC::Unordered, first, first);
        self.b.ins().select(first_nan, first, r)
    }

    /// calexpr.c `edivi` under the reference build's -ffast-math: the denominator
    /// first; a zero or NaN denominator warns, sets `errno` and is itself the result,
    /// without evaluating the numerator.
    fn divide(&mut self, a: &'m Expr, b: &'m Expr) -> R<Value> {
        let den = self.expr(b)?;
        if self
            .const_value(b, CONST_DEPTH)
            .is_some_and(|v| v != 0.0 && !v.is_nan())
        {
            let num = self.expr(a)?;
            let k = self.op_key(OP_DIV, num, den);
            return Ok(self.memo(k, |lw| {
                let q = lw.b.ins().fdiv(num, den);
                lw.quiet.insert(q);
                q
            }));
        }
        let zero = self.f64c(0.0);
        let is_zero = self.b.ins().fcmp(FloatCC::UnorderedOrEqual, den, zero);
        let (j, out) = self.join();
        let (z, nz) = self.cold_branch(is_zero);
        self.b.switch_to_block(z);
        let w = self.i32c(W_DIVISION);
        self.warn(w, NO_SYM);
        self.set_errno(ERRNO_RANGE);
        self.jump_with(j, den);
        self.b.switch_to_block(nz);
        let known = self.mark();
        let num = self.expr(a)?;
        self.rewind(known);
        let q = self.b.ins().fdiv(num, den);
        self.quiet.insert(q);
        self.jump_with(j, q);
        self.b.switch_to_block(j);
        Ok(self.quiet_if(out, &[den]))
    }

    /// calexpr.c `epow`: `errno` cleared, both sides (the exponent first: the
    /// reference build evaluates C arguments right to left), the C library's `pow`. No
    /// `x*x` fast path for integer exponents: the C library's `pow` is not specified
    /// to round as a product does, and results must equal the interpreter's.
    fn power(&mut self, a: &'m Expr, b: &'m Expr) -> R<Value> {
        self.set_errno(ERRNO_NONE);
        let pure = self.pure_ready(a) && self.pure_ready(b);
        if pure
            && let (Some(x), Some(y)) = (
                self.const_value(a, CONST_DEPTH),
                self.const_value(b, CONST_DEPTH),
            )
            && x.powf(y).is_finite()
        {
            return Ok(self.f64c(x.powf(y)));
        }
        let y = self.expr(b)?;
        let x = self.expr(a)?;
        let key = Key::Pow(self.vn(x), self.vn(y));
        let d = self.pure_call(key, |lw| lw.call_lib("radc_pow", &[x, y]));
        // As for library functions: pure operands leave `errno` clear.
        if pure && self.st.policy != MathErrors::NonFinite {
            return Ok(d);
        }
        self.nonfinite(d);
        if self.errno_is_clear() {
            return Ok(d);
        }
        let errno = self.load_raw(types::I64, OFF_ERRNO);
        let (j, out) = self.join();
        let (bad, ok) = self.cold_branch(errno);
        self.b.switch_to_block(bad);
        let w = self.i32c(W_POWER);
        self.warn(w, NO_SYM);
        let zero = self.f64c(0.0);
        self.jump_with(j, zero);
        self.b.switch_to_block(ok);
        self.jump_with(j, d);
        self.b.switch_to_block(j);
        Ok(self.quiet_if(out, &[d]))
    }

    /// `MathErrors::NonFinite`: NaN is a domain error, infinity a range error.
    fn nonfinite(&mut self, d: Value) {
        if self.st.policy != MathErrors::NonFinite {
            return;
        }
        let errno = self.load_raw(types::I64, OFF_ERRNO);
        let nan = self.b.ins().fcmp(FloatCC::Unordered, d, d);
        let abs = self.b.ins().fabs(d);
        let inf = self.f64c(f64::INFINITY);
        let is_inf = self.b.ins().fcmp(FloatCC::Equal, abs, inf);
        let range = self.i64c(ERRNO_RANGE);
        let none = self.i64c(ERRNO_NONE);
        let domain = self.i64c(ERRNO_DOMAIN);
        let code = self.b.ins().select(is_inf, range, none);
        let code = self.b.ins().select(nan, domain, code);
        let unset = self.b.ins().icmp_imm_s(IntCC::Equal, errno, 0);
        let new = self.b.ins().select(unset, code, errno);
        self.store_raw(new, OFF_ERRNO);
    }

    /// A reference to a variable: caldefn.c `dvalue`, with the freshness test inline.
    fn variable(&mut self, s: SymId) -> R<Value> {
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
    fn inline_variable(&mut self, def: DefId) -> R<Value> {
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
    fn cached_variable(&mut self, def: DefId, f: FuncRef, idx: u32) -> Value {
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

    /// calfunc.c `argument`: parameter `n`, computed once per call in the caller's
    /// context (one level less deep).
    fn argument(&mut self, n: u32) -> Value {
        if let Some(&v) = self.known_args.get(&Key::Arg(0, n)) {
            return v;
        }
        let v = self.compute_argument(n);
        self.know(Key::Arg(0, n), v);
        v
    }

    fn compute_argument(&mut self, n: u32) -> Value {
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
    fn check_arg_count(&mut self, block: Value, n: u32, osym: u32, j: ir::Block) {
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
    fn inline_argument(&mut self, n: u32) -> R<Value> {
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

    fn inline_compute(&mut self, parent: u32, arg: &'m Expr) -> R<Value> {
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
    fn inline_call(&mut self, def: DefId, sym: u32, args: &'m [Expr]) -> R<Value> {
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
    fn in_own_frame(&self) -> R<()> {
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
    fn call_sym(&mut self, s: SymId, args: &'m [Expr]) -> R<Value> {
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
    fn call_arg(&mut self, n: u32, args: &'m [Expr]) -> R<Value> {
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
    fn build_block(&mut self, args: &'m [Expr], callee: CalleeName, fill: bool) -> R<Value> {
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

    /// The value of `e` if it is known while compiling and computing it has no
    /// effect: numbers, variables defined as a number (read without a warning, see
    /// [`Lower::variable`]), and the exact arithmetic of those, computed as the
    /// interpreter computes it (a division only by a non-zero number).
    fn const_value(&self, e: &Expr, depth: u32) -> Option<f64> {
        let depth = depth.checked_sub(1)?;
        let c = |x: &Expr| self.const_value(x, depth);
        Some(match &e.node {
            Node::Num(v) => *v,
            Node::Var(s) => {
                let module = self.st.module;
                let d = module
                    .current_def(*s)
                    .filter(|&d| !module.def(d).is_function())?;
                if self.st.host_vars.contains_key(&d) {
                    return None;
                }
                module.def(d).body.as_num()?
            }
            Node::Neg(a) => -c(a)?,
            Node::Sub(a, b) => {
                let (x, y) = (c(a)?, c(b)?);
                nan_first(x, y, x - y)
            }
            Node::Sum(v) => {
                let mut sum = 0.0;
                for x in v {
                    let x = c(x)?;
                    sum = nan_first(sum, x, sum + x);
                }
                sum
            }
            Node::Product(v) => {
                let mut prod = 1.0;
                for x in v {
                    let x = c(x)?;
                    prod = nan_first(prod, x, prod * x);
                }
                prod
            }
            Node::Div(a, b) => {
                let den = c(b)?;
                if den == 0.0 || den.is_nan() {
                    return None;
                }
                c(a)? / den
            }
            _ => return None,
        })
    }

    /// Whether `e` can be computed here with no effect at all: numbers, parameters
    /// and variables already computed on every path to this point, and the
    /// arithmetic of those that cannot warn (`-`, `+`, `*`, `/` by a non-zero number).
    fn pure_ready(&self, e: &Expr) -> bool {
        self.pure_within(e, 16)
    }

    fn pure_within(&self, e: &Expr, depth: u32) -> bool {
        let Some(depth) = depth.checked_sub(1) else {
            return false;
        };
        if self.const_value(e, CONST_DEPTH).is_some() {
            return true;
        }
        match &e.node {
            Node::Num(_) => true,
            Node::Div(a, b) => {
                self.const_value(b, CONST_DEPTH)
                    .is_some_and(|v| v != 0.0 && !v.is_nan())
                    && self.pure_within(a, depth)
            }
            Node::Arg(n) => self.known_args.contains_key(&Key::Arg(self.cur, *n)),
            Node::Var(s) => self
                .st
                .module
                .current_def(*s)
                .is_some_and(|d| self.known_args.contains_key(&Key::Var(d.0))),
            Node::Neg(a) => self.pure_within(a, depth),
            Node::Sub(a, b) => self.pure_within(a, depth) && self.pure_within(b, depth),
            Node::Sum(v) | Node::Product(v) => v.iter().all(|x| self.pure_within(x, depth)),
            _ => false,
        }
    }

    /// An argument expression as a function value (calfunc.c `eargf` rules).
    fn fn_value(
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
    fn lib_enter(&mut self, sym: u32) {
        if let Some(d) = self.depth {
            let v = self.i64c(d + 1);
            self.depth_event(sym, v, Some(d + 1));
            return;
        }
        let d = self.load_raw(types::I64, OFF_DEPTH);
        let d = self.b.ins().iadd_imm_s(d, 1);
        self.depth_event(sym, d, None);
    }

    fn lib_arg(&mut self, args: &'m [Expr], i: usize, sym: u32) -> R<Value> {
        match args.get(i) {
            Some(a) => self.expr(a),
            None => Ok(self.fail(E_TOO_FEW, sym)),
        }
    }

    /// calfunc.c `libfunc`'s epilogue: a raised `errno` warns and gives 0.
    fn lib_result(&mut self, d: Value, sym: u32) -> Value {
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

    fn builtin(&mut self, b: Builtin, sym: u32, args: &'m [Expr]) -> R<Value> {
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
    fn pure_builtin(&mut self, b: Builtin, sym: u32, args: &'m [Expr]) -> R<Option<Value>> {
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

    fn atan2(&mut self, y: Value, x: Value) -> Value {
        let key = Key::Atan2(self.vn(y), self.vn(x));
        self.pure_call(key, |lw| lw.call_lib("radc_atan2", &[y, x]))
    }

    /// A one-argument C library function, inline where it is one instruction.
    fn unary(&mut self, b: Builtin, x: Value) -> Value {
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

    /// calfunc.c `l_select`: the rounded index picks one argument, evaluated alone;
    /// 0 gives the count of the rest; out of range is a domain error.
    fn select(&mut self, args: &'m [Expr], sym: u32) -> R<Value> {
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

    fn select_case(&mut self, args: &'m [Expr], k: usize, sym: u32, j: ir::Block) -> R<()> {
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
