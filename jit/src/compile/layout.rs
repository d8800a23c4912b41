//! The memory the generated code shares with Rust: the evaluation context, the
//! per-definition value cache and the argument blocks of calls. Everything here is
//! `#[repr(C)]` because the generated code reads it at fixed offsets.

use radc_lang::cal::builtins::LibFn;
use radc_lang::cal::eval::{EvalError, MathErrors, Warning};
use std::ffi::c_void;
use std::mem::offset_of;
use std::sync::Arc;

/// `errno` values as the generated code stores them.
pub const ERRNO_NONE: u64 = 0;
pub const ERRNO_DOMAIN: u64 = 1;
pub const ERRNO_RANGE: u64 = 2;

/// A `:` value never expires (the interpreter's `FOREVER`).
pub const FOREVER: u64 = u64::MAX;

/// The first call depth that is reported (with a warning; `Raw::next_report` starts
/// here and only grows, and "too deep" is further still): below it a call needs no
/// depth check.
pub const FIRST_DEPTH_REPORT: u64 = 100;
const _: () = assert!(radc_lang::cal::eval::MAX_DEPTH >= FIRST_DEPTH_REPORT);

/// A symbol id meaning "no name": the interpreter reports `?` there.
pub const NO_SYM: u32 = u32::MAX;

/// One cached variable value (the interpreter's `Cached`): `tick` is the record clock
/// it was computed at, [`FOREVER`] for `:` values, 0 for never.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct Cached {
    pub tick: u64,
    pub value: f64,
}

/// The evaluation state the generated code reads and writes through a pointer (its
/// first argument). The fields after `hosts` are for Rust only.
#[repr(C)]
pub struct Raw {
    /// The record clock (`Evaluator::next_record`).
    pub clock: u64,
    pub errno: u64,
    /// Non-zero once a fatal error was raised: every function returns at once.
    pub failed: u64,
    /// Call nesting, counted as the interpreter counts it.
    pub depth: u64,
    /// The depth at which the host must be told (a warning or "too deep").
    pub depth_limit: u64,
    /// Lowest stack address the generated code may reach before failing.
    pub stack_limit: u64,
    pub cache: *mut Cached,
    pub hosts: *const f64,
    /// The `errno` code (0 for none) the last read of an input column raised.
    pub chan_errno: u64,
    /// Where an entry of every output column stores its values, and how many it
    /// stored (`Compiled::eval_outputs`).
    pub out: *mut f64,
    pub done: u64,
    // ---- not read by generated code ----
    /// `*mut &mut dyn Input` during a call, else null.
    pub input: *mut c_void,
    pub next_report: u64,
    pub warnings: Vec<Warning>,
    pub error: Option<EvalError>,
    pub tables: Arc<Tables>,
}

/// What the host needs to know about the program at run time, by symbol id.
#[derive(Debug, Default)]
pub struct Tables {
    pub names: Vec<String>,
    pub libs: Vec<Option<LibFn>>,
    pub policy: MathErrors,
}

pub const OFF_CLOCK: i32 = offset_of!(Raw, clock) as i32;
pub const OFF_ERRNO: i32 = offset_of!(Raw, errno) as i32;
pub const OFF_FAILED: i32 = offset_of!(Raw, failed) as i32;
pub const OFF_DEPTH: i32 = offset_of!(Raw, depth) as i32;
pub const OFF_DEPTH_LIMIT: i32 = offset_of!(Raw, depth_limit) as i32;
pub const OFF_STACK_LIMIT: i32 = offset_of!(Raw, stack_limit) as i32;
pub const OFF_CACHE: i32 = offset_of!(Raw, cache) as i32;
pub const OFF_HOSTS: i32 = offset_of!(Raw, hosts) as i32;
pub const OFF_CHAN_ERRNO: i32 = offset_of!(Raw, chan_errno) as i32;
pub const OFF_OUT: i32 = offset_of!(Raw, out) as i32;
pub const OFF_DONE: i32 = offset_of!(Raw, done) as i32;
pub const CACHED_SIZE: i32 = std::mem::size_of::<Cached>() as i32;
pub const OFF_TICK: i32 = offset_of!(Cached, tick) as i32;
pub const OFF_VALUE: i32 = offset_of!(Cached, value) as i32;

impl Raw {
    pub fn name(&self, sym: u32) -> String {
        self.tables
            .names
            .get(sym as usize)
            .cloned()
            .unwrap_or_else(|| String::from("?"))
    }

    /// Record a fatal error (the first one wins, as the interpreter stops there).
    pub fn fail(&mut self, e: EvalError) {
        if self.failed == 0 {
            self.failed = 1;
            self.error = Some(e);
        }
    }
}

/// A thunk: evaluates one argument expression of a call in the caller's context (the
/// block it is given is the caller's own argument block; the slot is the argument's,
/// for thunks shared by many arguments, which read `aux`).
pub type ThunkFn = unsafe extern "C" fn(*mut Raw, *mut Block, *mut Slot) -> f64;

/// The head of a call's argument block, followed in memory by `nargs` [`Slot`]s. It
/// lives in the caller's stack frame for the duration of the call: calcomp arguments
/// are call-by-need (calfunc.c `argument`), so the callee computes each slot at most
/// once, when it first needs it.
#[repr(C)]
pub struct Block {
    /// The caller's own block: the context thunks run in (null at top level).
    pub parent: *mut Block,
    pub nargs: u64,
}

#[repr(C)]
pub struct Slot {
    pub value: f64,
    /// 0 until computed.
    pub state: u64,
    pub thunk: Option<ThunkFn>,
    /// The argument as a function value (when the callee calls its parameter): the
    /// compiled function, or null with `fn_code` saying what the host must do.
    pub fn_ptr: *const u8,
    /// `(symbol << 3) | FN_*`.
    pub fn_code: u64,
    /// For a shared thunk: the input column an argument `$N` reads.
    pub aux: u64,
}

pub const BLOCK_SIZE: i32 = std::mem::size_of::<Block>() as i32;
pub const SLOT_SIZE: i32 = std::mem::size_of::<Slot>() as i32;
pub const OFF_PARENT: i32 = offset_of!(Block, parent) as i32;
pub const OFF_NARGS: i32 = offset_of!(Block, nargs) as i32;
pub const OFF_SLOT_VALUE: i32 = offset_of!(Slot, value) as i32;
pub const OFF_SLOT_STATE: i32 = offset_of!(Slot, state) as i32;
pub const OFF_SLOT_THUNK: i32 = offset_of!(Slot, thunk) as i32;
pub const OFF_SLOT_FN_PTR: i32 = offset_of!(Slot, fn_ptr) as i32;
pub const OFF_SLOT_FN_CODE: i32 = offset_of!(Slot, fn_code) as i32;
pub const OFF_SLOT_AUX: i32 = offset_of!(Slot, aux) as i32;

/// Function-value kinds (low 3 bits of `Slot::fn_code`).
pub const FN_USER: u64 = 0;
/// A library function: the host evaluates it.
pub const FN_LIB: u64 = 1;
/// Neither a function definition nor a library function: "undefined function".
pub const FN_UNDEFINED: u64 = 2;
/// The argument list was too short: "too few arguments" for the symbol's call.
pub const FN_TOO_FEW: u64 = 3;
/// The argument was an expression, not a name: "argument not a function".
pub const FN_NOT_FUNCTION: u64 = 4;
pub const FN_SHIFT: u64 = 3;

/// Warning codes passed to the host.
pub const W_DIVISION: u32 = 0;
pub const W_POWER: u32 = 1;
pub const W_DOMAIN: u32 = 2;
pub const W_RANGE: u32 = 3;
pub const W_NONCONSTANT: u32 = 4;

/// Fatal error codes passed to the host.
pub const E_UNDEFINED_VARIABLE: u32 = 0;
pub const E_UNDEFINED_FUNCTION: u32 = 1;
pub const E_TOO_FEW: u32 = 2;
pub const E_NOT_FUNCTION: u32 = 3;
pub const E_ILLEGAL_CHANNEL: u32 = 4;
pub const E_NOT_AVAILABLE: u32 = 5;
pub const E_TOO_DEEP: u32 = 6;
pub const E_BAD_CALL: u32 = 7;
