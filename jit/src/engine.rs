//! What `radc calc` needs from an evaluator, record by record: implemented by the
//! reference interpreter and by the JIT, so the command can run either.

use crate::compile::JitProgram;
use crate::interp::{Error, Interpreter, Outputs, Record};
use radc_lang::cal::eval::Warning;

pub trait RecordEngine {
    /// rcalc `-n`: one record with no input.
    fn single(&mut self) -> Result<Outputs, Error>;
    /// One input record: `None` when `cond` rejects it.
    fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error>;
    /// The columns of a failed record computed before the error.
    fn take_partial(&mut self) -> Outputs;
    /// Warnings raised since the last call, in order.
    fn take_warnings(&mut self) -> Vec<Warning>;
}

impl RecordEngine for Interpreter<'_> {
    fn single(&mut self) -> Result<Outputs, Error> {
        Interpreter::single(self)
    }
    fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        Interpreter::record(self, record)
    }
    fn take_partial(&mut self) -> Outputs {
        Interpreter::take_partial(self)
    }
    fn take_warnings(&mut self) -> Vec<Warning> {
        Interpreter::take_warnings(self)
    }
}

impl RecordEngine for JitProgram {
    fn single(&mut self) -> Result<Outputs, Error> {
        JitProgram::single(self)
    }
    fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        JitProgram::record(self, record)
    }
    fn take_partial(&mut self) -> Outputs {
        JitProgram::take_partial(self)
    }
    fn take_warnings(&mut self) -> Vec<Warning> {
        JitProgram::take_warnings(self)
    }
}
