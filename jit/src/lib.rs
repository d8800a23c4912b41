//! calcomp evaluation: the reference interpreter (`interp`), which reproduces rcalc's
//! results bit for bit, and a Cranelift JIT (`compile`) that agrees with it; plus the
//! data files Radiance's functions read; and rcalc's record loop over either engine
//! (`records`).

/// Data files are parsed in `lang` (the checker validates them); evaluation lives here.
pub use radc_lang::datafile;
pub mod compile;
pub mod engine;
pub mod interp;
pub mod records;

pub use compile::{Compiled, Context, Jit, JitError, JitProgram};
pub use engine::RecordEngine;
pub use interp::{Error, Interpreter, Record};
