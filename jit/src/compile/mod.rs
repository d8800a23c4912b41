//! The Cranelift JIT for calcomp: compiles the definitions a set of entry points
//! reaches to native code that computes exactly what the reference interpreter
//! computes, bit for bit, with the same warnings and errors in the same order.
//!
//! How the interpreter's rules map to generated code:
//! - every variable definition becomes a function that checks its cache slot (in the
//!   [`Context`]) against the record clock, so `=` values are computed once per record
//!   and `:` values once; the fast path of that check is inlined at each reference;
//! - every user function becomes a function `(ctx, block) -> f64`; `block` is the
//!   call's argument block, built in the caller's frame, holding one thunk per
//!   argument and its memoised value (call-by-need, evaluated in the caller's
//!   context), plus the argument as a function value for calls through parameters;
//! - library functions are inlined: `if`/`select` branch, `min`/`max` compare, the C
//!   library functions are calls into the Rust functions the interpreter uses;
//! - `errno`, the depth counter and the "failed" flag live in the context, so a
//!   division by zero inside `max(...)` poisons the call exactly as in calfunc.c, and
//!   a fatal error makes every function return at once.
//!
//! `unsafe` is confined to the call boundary ([`Compiled`]'s `run`), the host
//! functions' access to the context and argument blocks (`host.rs`), freeing the code,
//! and the `Send`/`Sync` claims for [`Compiled`] and [`Context`], each with its SAFETY
//! argument.

mod codegen;
mod host;
pub mod inspect;
mod layout;
mod lower;
mod program;

pub use program::{JitProgram, StartError};

use codegen::{EntryBody, Job, State};
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Module as _};
use layout::{Block, Cached, Raw, Slot, Tables};
use radc_lang::cal::Module;
use radc_lang::cal::eval::{EvalError, Input, MAX_DEPTH, MathErrors, NoInput, Warning};
use radc_lang::cal::ir::{DefId, Expr};
use std::ffi::c_void;
use std::fmt;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// Why a program was not compiled; the caller falls back to the interpreter.
#[derive(Clone, Debug, PartialEq)]
pub enum JitError {
    /// An entry point names nothing the program defines.
    UnknownEntry(String),
    /// Past the size or nesting limits.
    TooLarge(String),
    /// Cranelift refused (unsupported host, a code generation limit).
    Backend(String),
}

impl fmt::Display for JitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JitError::UnknownEntry(n) => write!(f, "{n}: no such variable, function or output"),
            JitError::TooLarge(why) => write!(f, "program too large to compile: {why}"),
            JitError::Backend(why) => write!(f, "code generation failed: {why}"),
        }
    }
}

impl std::error::Error for JitError {}

/// Compiler options.
#[derive(Clone, Debug, Default)]
pub struct Jit {
    policy: MathErrors,
    host_variables: Vec<String>,
    /// `(nodes, nesting)` in place of [`codegen::MAX_NODES`], [`codegen::MAX_NESTING`].
    limits: Option<(usize, usize)>,
    /// In place of [`codegen::INLINE_BUDGET`].
    inline_budget: Option<usize>,
}

/// A compiled entry point, from [`Compiled::entry`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry(usize);

#[derive(Clone, Copy, Debug)]
enum EntryCode {
    /// `(ctx) -> f64`: a variable's value or an output column.
    Value(*const u8),
    /// `(ctx, block) -> f64`: a function, called with host-supplied arguments.
    Function(*const u8),
    /// `(ctx) -> f64` storing this many output columns at `Raw::out`.
    Outputs(*const u8, usize),
}

enum EntryPlan<'m> {
    Body(EntryBody<'m>),
    Function(DefId),
}

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// Default native stack the generated code may use below the caller's frame.
pub const DEFAULT_STACK_BUDGET: usize = 1 << 20;

impl Jit {
    pub fn new() -> Self {
        Jit::default()
    }

    /// Which non-finite results count as errors (as `Evaluator::with_policy`).
    pub fn with_policy(mut self, policy: MathErrors) -> Self {
        self.policy = policy;
        self
    }

    /// Decline programs (with [`JitError::TooLarge`]) whose reachable expressions
    /// have more than `nodes` nodes or nest deeper than `nesting` levels, instead of
    /// the defaults (2,000,000 nodes, 1000 levels). The parser's own limits keep
    /// single statements well within the defaults; these bound whole programs.
    pub fn with_size_limits(mut self, nodes: usize, nesting: usize) -> Self {
        self.limits = Some((nodes, nesting));
        self
    }

    /// How many expression nodes inlining may add to the program, in place of the
    /// default (1000): 0 inlines nothing. Results are the same whatever the budget;
    /// speed and compile time are not.
    pub fn with_inline_budget(mut self, nodes: usize) -> Self {
        self.inline_budget = Some(nodes);
        self
    }

    /// Variables whose value the host sets per evaluation (rcalc's `recno` and
    /// `outno`), read from the context instead of their definitions; see
    /// [`Context::set_host`]. Names that resolve to no variable are ignored.
    pub fn with_host_variables(mut self, names: &[&str]) -> Self {
        self.host_variables = names.iter().map(|n| n.to_string()).collect();
        self
    }

    /// Compile what `entries` reach. An entry is a variable or function name as
    /// written, `$N` for output column N, or `$*` for every output column in
    /// ascending order, evaluated by one call of [`Compiled::eval_outputs`] (what
    /// one column computes, the next reuses: variables, input columns, library
    /// results).
    pub fn compile(&self, module: &Module, entries: &[&str]) -> Result<Compiled, JitError> {
        self.compile_with_expressions(module, entries, &[])
    }

    /// As [`Jit::compile`], plus expressions of the module that no definition holds
    /// (an rcalc `-o` format's fields, made by `Module::add_expression`): entry `#k`
    /// computes `exprs[k]`.
    pub fn compile_with_expressions(
        &self,
        module: &Module,
        entries: &[&str],
        exprs: &[&Expr],
    ) -> Result<Compiled, JitError> {
        // A Cranelift panic is a bug to report, but never a reason to fail the
        // program: the caller falls back to the interpreter.
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            self.compile_unguarded(module, entries, exprs)
        }))
        .unwrap_or_else(|_| Err(JitError::Backend("code generator panicked".into())))
    }

    fn compile_unguarded(
        &self,
        module: &Module,
        entries: &[&str],
        exprs: &[&Expr],
    ) -> Result<Compiled, JitError> {
        let all_outputs: Vec<&Expr> = module.outputs().values().map(|o| &o.body).collect();
        let mut plans = Vec::new();
        let mut roots = Vec::new();
        let mut syms = Vec::new();
        for &name in entries {
            if name == "$*" {
                roots.extend(all_outputs.iter().copied());
                plans.push(EntryPlan::Body(EntryBody::Outputs(&all_outputs)));
                continue;
            }
            if let Some(col) = name.strip_prefix('$') {
                let body = col
                    .parse::<u32>()
                    .ok()
                    .and_then(|c| module.outputs().get(&c))
                    .map(|o| &o.body)
                    .ok_or_else(|| JitError::UnknownEntry(name.to_string()))?;
                roots.push(body);
                plans.push(EntryPlan::Body(EntryBody::Output(body)));
                continue;
            }
            let sym = module
                .lookup(name)
                .ok_or_else(|| JitError::UnknownEntry(name.to_string()))?;
            syms.push(sym);
            match module
                .current_def(sym)
                .filter(|&d| module.def(d).is_function())
            {
                Some(d) => plans.push(EntryPlan::Function(d)),
                None => plans.push(EntryPlan::Body(EntryBody::Variable(sym))),
            }
        }
        for &e in exprs {
            roots.push(e);
            plans.push(EntryPlan::Body(EntryBody::Output(e)));
        }
        let defs = codegen::reachable(module, &roots, &syms);
        let limits = self
            .limits
            .unwrap_or((codegen::MAX_NODES, codegen::MAX_NESTING));
        codegen::check_size(module, &roots, &defs, limits)?;

        let mut state = State::new(module, self.policy)?;
        state.inline_budget = self.inline_budget.unwrap_or(codegen::INLINE_BUDGET);
        let mut host_names = Vec::new();
        for name in &self.host_variables {
            let def = module
                .lookup(name)
                .and_then(|s| module.current_def(s))
                .filter(|&d| !module.def(d).is_function());
            if let Some(d) = def {
                state.host_vars.insert(d, host_names.len() as u32);
                host_names.push(name.clone());
            }
        }
        // Per entry: its function, and whether it takes arguments (`None`) or how
        // many outputs it stores (`Some(n)`, 0 for a plain value).
        let mut ids: Vec<(FuncId, Option<usize>)> = Vec::new();
        for plan in &plans {
            match plan {
                EntryPlan::Body(what) => {
                    let id = state
                        .jit
                        .declare_anonymous_function(&state.sig_var)
                        .map_err(|e| JitError::Backend(e.to_string()))?;
                    state.queue.push(Job::Entry { id, what: *what });
                    let n = match what {
                        EntryBody::Outputs(list) => list.len(),
                        _ => 0,
                    };
                    ids.push((id, Some(n)));
                }
                EntryPlan::Function(d) => ids.push((state.user_fn(*d)?, None)),
            }
        }
        codegen::drain(&mut state)?;
        state
            .jit
            .finalize_definitions()
            .map_err(|e| JitError::Backend(e.to_string()))?;
        let codes = ids
            .iter()
            .zip(&plans)
            .map(|(&(id, outputs), plan)| {
                let p = state.jit.get_finalized_function(id);
                match (outputs, plan) {
                    (None, _) => EntryCode::Function(p),
                    (Some(n), EntryPlan::Body(EntryBody::Outputs(_))) => EntryCode::Outputs(p, n),
                    (Some(_), _) => EntryCode::Value(p),
                }
            })
            .collect();
        let tables = Tables {
            names: module.symbols().iter().map(|s| s.name.clone()).collect(),
            libs: module.symbols().iter().map(|s| s.lib).collect(),
            policy: self.policy,
        };
        Ok(Compiled {
            functions: state.compiled_defs.len(),
            instructions: state.instructions,
            entry_names: entries
                .iter()
                .map(|e| e.to_string())
                .chain((0..exprs.len()).map(|k| format!("#{k}")))
                .collect(),
            codes,
            tables: Arc::new(tables),
            cache_init: state.cache_init,
            host_names,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            jit: Some(state.jit),
        })
    }
}

/// Compiled code for a module's entry points. Evaluate with a [`Context`] made by
/// [`Compiled::context`].
pub struct Compiled {
    jit: Option<JITModule>,
    entry_names: Vec<String>,
    codes: Vec<EntryCode>,
    tables: Arc<Tables>,
    cache_init: Vec<Cached>,
    host_names: Vec<String>,
    functions: usize,
    instructions: usize,
    id: u64,
}

/// The state of evaluation for one [`Compiled`] program: cached values, the record
/// clock, host variables, warnings. Like the interpreter's `Evaluator`.
pub struct Context {
    raw: Raw,
    cache: Vec<Cached>,
    hosts: Vec<f64>,
    owner: u64,
    stack_budget: usize,
}

impl Context {
    /// Start a new record: every `=` value is recomputed on next use.
    pub fn next_record(&mut self) {
        self.raw.clock += 1;
        if self.raw.clock == layout::FOREVER {
            self.raw.clock = 1;
        }
    }

    /// Set host variable `index` (its position among those that resolved in
    /// [`Jit::with_host_variables`], see [`Compiled::host_index`]).
    pub fn set_host(&mut self, index: usize, value: f64) {
        if let Some(v) = self.hosts.get_mut(index) {
            *v = value;
        }
    }

    /// Warnings raised since the last call, in order.
    pub fn take_warnings(&mut self) -> Vec<Warning> {
        std::mem::take(&mut self.raw.warnings)
    }

    /// Whether any warning was raised since the last [`Context::take_warnings`].
    pub fn has_warnings(&self) -> bool {
        !self.raw.warnings.is_empty()
    }

    /// Native stack the generated code may use below the caller before failing with
    /// "recursion too deep" (calcomp recursion is unbounded; a thread's stack is not).
    pub fn set_stack_budget(&mut self, bytes: usize) {
        self.stack_budget = bytes;
    }

    pub fn stack_budget(&self) -> usize {
        self.stack_budget
    }
}

impl Compiled {
    pub fn entry(&self, name: &str) -> Option<Entry> {
        self.entry_names.iter().position(|n| n == name).map(Entry)
    }

    /// Where a host variable is in the context, if it resolved.
    pub fn host_index(&self, name: &str) -> Option<usize> {
        self.host_names.iter().position(|n| n == name)
    }

    /// Variable and function definitions compiled, as functions or inlined into
    /// their uses (thunks not counted).
    pub fn function_count(&self) -> usize {
        self.functions
    }

    /// Cranelift instructions generated for the whole program, before
    /// optimisation: what compile time grows with, counted the same whatever the
    /// machine's load.
    pub fn instruction_count(&self) -> usize {
        self.instructions
    }

    /// A new evaluation context, in its first record: `=` values computed now are
    /// kept until [`Context::next_record`]. (An interpreter `Evaluator` keeps
    /// nothing before its first `next_record`; the JIT's code relies on values not
    /// changing within a record, so it has no such state. Drivers that start every
    /// record with `next_record`, as `radc calc`'s do, see no difference.)
    pub fn context(&self) -> Context {
        Context {
            raw: Raw {
                // In its first record already (see `Compiled::context`).
                clock: 1,
                errno: layout::ERRNO_NONE,
                failed: 0,
                depth: 0,
                depth_limit: layout::FIRST_DEPTH_REPORT,
                stack_limit: 0,
                cache: std::ptr::null_mut(),
                hosts: std::ptr::null(),
                chan_errno: 0,
                out: std::ptr::null_mut(),
                done: 0,
                input: std::ptr::null_mut(),
                next_report: layout::FIRST_DEPTH_REPORT,
                warnings: Vec::new(),
                error: None,
                tables: Arc::clone(&self.tables),
            },
            cache: self.cache_init.clone(),
            hosts: vec![0.0; self.host_names.len()],
            owner: self.id,
            stack_budget: DEFAULT_STACK_BUDGET,
        }
    }

    /// Evaluate a `$*` entry: every output column in ascending order, appended to
    /// `out`. On an error `out` holds the columns computed before it, as separate
    /// [`Compiled::eval`] calls of each `$N` in turn would have given.
    pub fn eval_outputs(
        &self,
        entry: Entry,
        ctx: &mut Context,
        input: &mut dyn Input,
        out: &mut Vec<f64>,
    ) -> Result<(), EvalError> {
        let Some(&EntryCode::Outputs(p, n)) = self.codes.get(entry.0) else {
            return Err(EvalError::NotAvailable(format!(
                "entry #{} (not every output)",
                entry.0
            )));
        };
        if ctx.owner != self.id {
            return Err(EvalError::NotAvailable(
                "a context made for another compiled program".into(),
            ));
        }
        // The generated code stores straight into `out`'s spare capacity.
        out.reserve(n);
        let len = out.len();
        // SAFETY: `reserve` made room for `n` more values after the `len` there.
        ctx.raw.out = unsafe { out.as_mut_ptr().add(len) };
        ctx.raw.done = 0;
        let result = self.run(EntryCode::Value(p), &[], ctx, input);
        ctx.raw.out = std::ptr::null_mut();
        let done = (ctx.raw.done as usize).min(n);
        // SAFETY: the generated code stores column `k` (`k < n`, within the spare
        // capacity) and then sets `done` to `k + 1`, for each `k` from 0 in turn, so
        // the first `done` values after `len` are initialised.
        unsafe { out.set_len(len + done) };
        result.map(|_| ())
    }

    /// The value of a variable or output entry (a function entry is called with no
    /// arguments).
    pub fn eval(
        &self,
        entry: Entry,
        ctx: &mut Context,
        input: &mut dyn Input,
    ) -> Result<f64, EvalError> {
        self.call(entry, &[], ctx, input)
    }

    /// Evaluate with no input columns.
    pub fn eval_no_input(&self, entry: Entry, ctx: &mut Context) -> Result<f64, EvalError> {
        self.call(entry, &[], ctx, &mut NoInput)
    }

    /// Call a function entry with arguments (for a variable or output entry the
    /// arguments are ignored).
    pub fn call(
        &self,
        entry: Entry,
        args: &[f64],
        ctx: &mut Context,
        input: &mut dyn Input,
    ) -> Result<f64, EvalError> {
        let code = match self.codes.get(entry.0) {
            Some(EntryCode::Outputs(..)) => {
                return Err(EvalError::NotAvailable(format!(
                    "entry #{} (every output: see eval_outputs)",
                    entry.0
                )));
            }
            Some(&code) => code,
            None => return Err(EvalError::NotAvailable(format!("entry #{}", entry.0))),
        };
        if ctx.owner != self.id {
            return Err(EvalError::NotAvailable(
                "a context made for another compiled program".into(),
            ));
        }
        self.run(code, args, ctx, input)
    }

    fn run(
        &self,
        code: EntryCode,
        args: &[f64],
        ctx: &mut Context,
        input: &mut dyn Input,
    ) -> Result<f64, EvalError> {
        let marker = 0u8;
        let here = std::hint::black_box(&marker) as *const u8 as usize;
        let raw = &mut ctx.raw;
        raw.stack_limit = here.saturating_sub(ctx.stack_budget) as u64;
        raw.cache = ctx.cache.as_mut_ptr();
        raw.hosts = ctx.hosts.as_ptr();
        raw.depth = 0;
        raw.failed = 0;
        raw.error = None;
        raw.depth_limit = raw.next_report.min(MAX_DEPTH + 1);
        let mut input_ref: &mut dyn Input = input;
        raw.input = (&mut input_ref) as *mut &mut dyn Input as *mut c_void;
        let raw_ptr: *mut Raw = raw;
        let value = match code {
            EntryCode::Value(p) => {
                // SAFETY: `p` is a finalized function of `self.jit` (alive as long as
                // `self`) generated with the `(ctx) -> f64` system-ABI signature.
                let f: extern "C" fn(*mut Raw) -> f64 = unsafe { std::mem::transmute(p) };
                f(raw_ptr)
            }
            EntryCode::Function(p) => {
                let mut words = host_block(args);
                // SAFETY: as above, with the `(ctx, block) -> f64` signature; the block
                // is laid out as the generated code expects and outlives the call.
                let f: extern "C" fn(*mut Raw, *mut Block) -> f64 =
                    unsafe { std::mem::transmute(p) };
                f(raw_ptr, words.as_mut_ptr() as *mut Block)
            }
            // Called through `eval_outputs` as a value entry, never here.
            EntryCode::Outputs(..) => 0.0,
        };
        let raw = &mut ctx.raw;
        raw.input = std::ptr::null_mut();
        raw.cache = std::ptr::null_mut();
        raw.hosts = std::ptr::null();
        if raw.failed != 0 {
            raw.failed = 0;
            return Err(raw
                .error
                .take()
                .unwrap_or_else(|| EvalError::TooDeep(String::from("?"))));
        }
        Ok(value)
    }
}

/// An argument block of already computed values, for calling a function entry.
fn host_block(args: &[f64]) -> Vec<u64> {
    let words = (layout::BLOCK_SIZE as usize + args.len() * layout::SLOT_SIZE as usize) / 8;
    let mut buf = vec![0u64; words];
    buf[1] = args.len() as u64;
    let per_slot = layout::SLOT_SIZE as usize / 8;
    for (i, &v) in args.iter().enumerate() {
        let at = layout::BLOCK_SIZE as usize / 8 + i * per_slot;
        buf[at] = v.to_bits();
        buf[at + 1] = 1;
        // A plain number is not a function: fn_ptr stays null, fn_code is
        // "argument not a function" with no name.
        buf[at + 4] = (u64::from(layout::NO_SYM) << layout::FN_SHIFT) | layout::FN_NOT_FUNCTION;
    }
    buf
}

const _: () = {
    assert!(std::mem::size_of::<Block>() == 16);
    assert!(std::mem::size_of::<Slot>() == 48);
    assert!(std::mem::offset_of!(Slot, value) == 0);
    assert!(std::mem::offset_of!(Slot, state) == 8);
    assert!(std::mem::offset_of!(Slot, fn_code) == 32);
    assert!(std::mem::offset_of!(Block, nargs) == 8);
};

impl Drop for Compiled {
    fn drop(&mut self) {
        if let Some(jit) = self.jit.take() {
            // SAFETY: the code is only reachable through `self.codes`, used only by
            // `&self` methods, none of which can be running while `self` is dropped.
            unsafe { jit.free_memory() };
        }
    }
}

// SAFETY: the only fields that are not `Send` are the entry pointers, which point into
// code owned by `jit` (a `Send` `JITModule`) and move with it.
unsafe impl Send for Compiled {}
// SAFETY: `&self` methods never touch `jit`; they read the immutable entry pointers and
// tables, and the generated code and host functions write only the `Context` passed by
// `&mut` and argument blocks on the calling thread's stack. So one program can be
// evaluated from many threads at once, each with its own context.
unsafe impl Sync for Compiled {}
// SAFETY: the raw pointers in a context are null except during `Compiled::run`, which
// holds the context by `&mut` and clears them before returning.
unsafe impl Send for Context {}
