//! What `radc calc` needs from an evaluator, record by record: implemented by the
//! reference interpreter and by the JIT, so the command can run either with one
//! driver (rcalc.c `execute`, `putout`).

use crate::compile::JitProgram;
use crate::interp::{Error, Interpreter, Outputs, Record};
use radc_lang::cal::eval::{Input, Warning};

/// rcalc's record numbering (rcalc.c `execute`): `recno` counts the records read in
/// the current input file, `outno` the records `cond` accepted plus the one begun, so
/// both are 1 in a file's first record. Both engines keep it in one of these.
#[derive(Clone, Copy, Debug, Default)]
pub struct RecordNumbering {
    records: u64,
    accepted: u64,
}

/// The numbers a record begun gets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecordNumbers {
    pub recno: f64,
    pub outno: f64,
}

impl RecordNumbering {
    /// A new input file: numbering starts again from 1.
    pub fn start_file(&mut self) {
        *self = RecordNumbering::default();
    }

    /// Number the next record `n + 1`, as if `n` records came before.
    pub fn set_records_before(&mut self, n: u64) {
        self.records = n;
    }

    /// Counts a new record and gives its `recno` and `outno`.
    pub fn begin(&mut self) -> RecordNumbers {
        self.records += 1;
        RecordNumbers {
            recno: self.records as f64,
            outno: (self.accepted + 1) as f64,
        }
    }

    /// Whether `cond`'s value accepts the record begun (`varvalue("cond") > 0.0`: a NaN
    /// rejects it), counting it for `outno` if so.
    pub fn accept(&mut self, cond: f64) -> bool {
        let accepted = cond.partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater);
        self.accepted += u64::from(accepted);
        accepted
    }

    /// A record accepted without a `cond`.
    pub fn accept_all(&mut self) {
        self.accepted += 1;
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_are_numbered_per_file_and_outputs_per_accepted_record() {
        let mut n = RecordNumbering::default();
        let first = n.begin();
        assert_eq!((first.recno, first.outno), (1.0, 1.0));
        assert!(!n.accept(0.0));
        let second = n.begin();
        assert_eq!((second.recno, second.outno), (2.0, 1.0));
        assert!(!n.accept(f64::NAN));
        n.begin();
        assert!(n.accept(0.5));
        let fourth = n.begin();
        assert_eq!((fourth.recno, fourth.outno), (4.0, 2.0));
        n.start_file();
        n.set_records_before(9);
        let next = n.begin();
        assert_eq!((next.recno, next.outno), (10.0, 1.0));
    }
}
