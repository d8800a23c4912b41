//! What `radc calc` needs from an evaluator, record by record: implemented by the
//! reference interpreter and by the JIT, so the command can run either with one
//! driver (rcalc.c `execute`, `putout`).

use crate::compile::JitProgram;
use crate::interp::{Error, Interpreter, Outputs, Record};
use radc_lang::cal::eval::{Input, Warning};

pub trait RecordEngine {
    /// A new input file: rcalc numbers records (`recno`, `outno`) from 1 in each.
    fn start_file(&mut self);
    /// Start rcalc's single `-n` record.
    fn begin_single(&mut self);
    /// Number the next record `n + 1` (`recno`): for a chunk of a file run on
    /// another engine than the records before it.
    fn set_records_before(&mut self, n: u64);
    /// Start a record: set `recno`/`outno`, expire `=` values and test `cond`;
    /// `false` when `cond` rejects it.
    fn begin_record(&mut self, input: &mut dyn Input) -> Result<bool, Error>;
    /// Set a variable for this record, as rcalc does for an input format's fields.
    /// Returns false if the program has no such variable.
    fn set_named(&mut self, name: &str, value: f64) -> bool;
    /// The `$N` columns of the record begun, appended to `out` in ascending column
    /// order. On an error, `out` holds the columns computed before it (rcalc has
    /// printed them by the time it stops).
    fn outputs_into(&mut self, input: &mut dyn Input, out: &mut Outputs) -> Result<(), Error>;
    /// The value of the `k`th expression the engine was built with (an `-o` format's
    /// number fields), in the record begun.
    fn field(&mut self, k: usize, input: &mut dyn Input) -> Result<f64, Error>;
    /// Warnings raised since the last call, in order.
    fn take_warnings(&mut self) -> Vec<Warning>;
    /// rcalc `-n`: one record with no input.
    fn single(&mut self) -> Result<Outputs, Error>;
    /// One input record: `None` when `cond` rejects it.
    fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error>;
    /// After [`RecordEngine::single`] or [`RecordEngine::record`] failed: the
    /// columns computed before the error.
    fn take_partial(&mut self) -> Outputs;
}

impl RecordEngine for Interpreter<'_> {
    fn start_file(&mut self) {
        Interpreter::start_file(self)
    }
    fn begin_single(&mut self) {
        Interpreter::begin_single(self)
    }
    fn set_records_before(&mut self, n: u64) {
        Interpreter::set_records_before(self, n)
    }
    fn begin_record(&mut self, input: &mut dyn Input) -> Result<bool, Error> {
        Interpreter::begin_record(self, input)
    }
    fn set_named(&mut self, name: &str, value: f64) -> bool {
        Interpreter::set_named(self, name, value)
    }
    fn outputs_into(&mut self, input: &mut dyn Input, out: &mut Outputs) -> Result<(), Error> {
        Interpreter::outputs_into(self, input, out)
    }
    fn field(&mut self, k: usize, input: &mut dyn Input) -> Result<f64, Error> {
        Interpreter::field(self, k, input)
    }
    fn take_warnings(&mut self) -> Vec<Warning> {
        Interpreter::take_warnings(self)
    }
    fn single(&mut self) -> Result<Outputs, Error> {
        Interpreter::single(self)
    }
    fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        Interpreter::record(self, record)
    }
    fn take_partial(&mut self) -> Outputs {
        Interpreter::take_partial(self)
    }
}

impl RecordEngine for JitProgram {
    fn start_file(&mut self) {
        JitProgram::start_file(self)
    }
    fn begin_single(&mut self) {
        JitProgram::begin_single(self)
    }
    fn set_records_before(&mut self, n: u64) {
        JitProgram::set_records_before(self, n)
    }
    fn begin_record(&mut self, input: &mut dyn Input) -> Result<bool, Error> {
        JitProgram::begin_record(self, input)
    }
    fn set_named(&mut self, name: &str, value: f64) -> bool {
        JitProgram::set_named(self, name, value)
    }
    fn outputs_into(&mut self, input: &mut dyn Input, out: &mut Outputs) -> Result<(), Error> {
        JitProgram::outputs_into(self, input, out)
    }
    fn field(&mut self, k: usize, input: &mut dyn Input) -> Result<f64, Error> {
        JitProgram::field(self, k, input)
    }
    fn take_warnings(&mut self) -> Vec<Warning> {
        JitProgram::take_warnings(self)
    }
    fn single(&mut self) -> Result<Outputs, Error> {
        JitProgram::single(self)
    }
    fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        JitProgram::record(self, record)
    }
    fn take_partial(&mut self) -> Outputs {
        JitProgram::take_partial(self)
    }
}
