//! calcomp evaluation: the reference interpreter (`interp`), which reproduces rcalc's
//! results bit for bit, and (later) a Cranelift JIT that must agree with it; plus the
//! data files Radiance's functions read.

/// Data files are parsed in `lang` (the checker validates them); evaluation lives here.
pub use radc_lang::datafile;
pub mod interp;

pub use interp::{Error, Interpreter, Record};
