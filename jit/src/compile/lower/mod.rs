//! Lowering one function body from the calcomp IR to Cranelift IR, with the
//! interpreter's (`radc_lang::cal::eval`) semantics step by step: the same operation
//! order, the same `errno` updates, the same depth counting, lazy call-by-need
//! arguments, and only the taken side of `if`/`select` evaluated.
//!
//! What the lowering does beyond a step-by-step translation is unobservable (the same
//! bits, warnings, errors and depth counting):
//! - small non-recursive user functions that never call through a parameter are
//!   inlined (`State::inline_size`, up to `INLINE_NODES` expanded nodes), their
//!   parameters computed on first use in the caller's frame as call-by-need requires;
//!   small `=` variables are inlined at their uses with the freshness test,
//!   stamp-before-evaluating and stale-on-abort of a variable body (`INLINE_VAR_NODES`,
//!   `INLINE_VAR_NESTING` deep). Every inlined body is charged to a per-program budget
//!   (`INLINE_BUDGET`, `Jit::with_inline_budget`): past it, calls are calls, so chains of
//!   derived variables used in many branches cannot multiply code
//!   (`jit/tests/jit_compile_size.rs` bounds it);
//! - numbers and arithmetic on them are folded (`folding`), library calls and `^` too
//!   when the result is finite; `if`/`select` with a number condition generate only the
//!   side taken, and `select` of four or more cases is a jump table (`control`);
//!   arguments that are numbers or already computed values are passed as values, not
//!   thunks (`calls`);
//! - values are numbered (`numbering`): a pure C library result is reused for an equal
//!   argument, directly where every path computed it and through a flag in an SSA
//!   variable where only some did (`MAX_LAZY` per function); an input column is read
//!   once per call and its `errno` raised again on reuse;
//! - the `errno` test after a library call is skipped where no argument can set it or
//!   `errno` is known 0 in the block; NaN operands are tested only where one may be a
//!   signalling NaN (an input column, a cached variable, a parameter): for quiet ones
//!   the SSE instruction's result is already the interpreter's first-NaN rule;
//! - in an entry function (run at depth 0) the depth is known while compiling, so below
//!   the first report level no depth check is generated.
//!
//! The scoping rule for everything known while compiling: what `known_args` and the
//! numbering record was computed on every path to the current point; a branch's
//! additions are undone after it.

mod builtins;
mod calls;
mod control;
mod emit;
mod expressions;
mod folding;
mod numbering;
mod variables;

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
}
