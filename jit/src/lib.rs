//! calcomp evaluation: the reference interpreter (`interp`), which reproduces rcalc's
//! results bit for bit, and (later) a Cranelift JIT that must agree with it.

pub mod interp;

pub use interp::{Error, Interpreter, Record};
