//! The reference interpreter: runs a resolved calcomp [`Module`] record by record the
//! way rcalc does (rcalc.c `execute`, `putout`): a new evaluation clock per record so
//! `=` values are recomputed, `cond` filtering, `recno`/`outno`, and outputs in
//! ascending column order.

mod columns;
mod format;

pub use columns::Record;
pub use format::{format_outputs, write_outputs};

use crate::engine::RecordNumbering;
use radc_lang::cal::Module;
use radc_lang::cal::eval::{EvalError, Evaluator, Input, MathErrors, NoInput, Warning};
use radc_lang::cal::ir::DefId;
use radc_lang::cal::ir::Expr;
use radc_lang::cal::syntax::DefKind;
use std::fmt;

/// Everything that can stop the interpreter: the one error type of this layer.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// A fatal calcomp evaluation error (undefined name, missing argument, ...).
    Eval(EvalError),
    /// rcalc refuses a `cond` defined with `:` ("cond: defined as constant").
    ConstantCond,
    /// An output format names a string variable no `-s` set.
    UndefinedString(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Eval(e) => e.fmt(f),
            Error::ConstantCond => write!(f, "cond: defined as constant"),
            Error::UndefinedString(n) => write!(f, "{n}: undefined string"),
        }
    }
}

impl std::error::Error for Error {}

impl From<EvalError> for Error {
    fn from(e: EvalError) -> Self {
        Error::Eval(e)
    }
}

/// One output record: `(column, value)` in ascending column order.
pub type Outputs = Vec<(u32, f64)>;

pub struct Interpreter<'m> {
    module: &'m Module,
    ev: Evaluator<'m>,
    cond: Option<radc_lang::cal::ir::SymId>,
    recno: Option<DefId>,
    outno: Option<DefId>,
    numbering: RecordNumbering,
    partial: Outputs,
    /// Expressions evaluated on request by [`Interpreter::field`].
    fields: Vec<&'m Expr>,
}

impl<'m> Interpreter<'m> {
    /// `recno` and `outno` are set per record only if the program names them (rcalc
    /// checks `varlookup`); call [`Module::set_variable`] for them before optimizing if
    /// [`Module::lookup`] finds them, as `radc calc` does.
    pub fn new(module: &'m Module, policy: MathErrors) -> Result<Self, Error> {
        let cond = module.lookup("cond").filter(|&s| {
            module
                .current_def(s)
                .is_some_and(|d| !module.def(d).is_function())
        });
        if let Some(s) = cond
            && module
                .current_def(s)
                .is_some_and(|d| module.def(d).kind == DefKind::Constant)
        {
            return Err(Error::ConstantCond);
        }
        let var = |name: &str| {
            module
                .lookup(name)
                .and_then(|s| module.current_def(s))
                .filter(|&d| !module.def(d).is_function())
        };
        Ok(Interpreter {
            module,
            ev: Evaluator::new(module).with_policy(policy),
            cond,
            recno: var("recno"),
            outno: var("outno"),
            numbering: RecordNumbering::default(),
            partial: Vec::new(),
            fields: Vec::new(),
        })
    }

    /// Expressions of this module that are no definition (an `-o` format's number
    /// fields, from [`Module::add_expression`]), evaluated by [`Interpreter::field`].
    pub fn with_fields(mut self, fields: &[&'m Expr]) -> Self {
        self.fields = fields.to_vec();
        self
    }

    /// The value of the `k`th expression given to [`Interpreter::with_fields`].
    pub fn field(&mut self, k: usize, input: &mut dyn Input) -> Result<f64, Error> {
        let e = self
            .fields
            .get(k)
            .copied()
            .ok_or_else(|| EvalError::NotAvailable(format!("format field #{k}")))?;
        Ok(self.ev.eval_top(e, input)?)
    }

    /// rcalc `-n`: one record with no input.
    pub fn single(&mut self) -> Result<Outputs, Error> {
        self.begin_single();
        self.outputs(&mut NoInput)
    }

    /// A new input file: rcalc numbers records (`recno`, `outno`) from 1 in each.
    pub fn start_file(&mut self) {
        self.numbering.start_file();
    }

    /// Number the next record `n + 1` (`recno`), as if `n` records came before.
    pub fn set_records_before(&mut self, n: u64) {
        self.numbering.set_records_before(n);
    }

    /// Start rcalc's single `-n` record, for callers that evaluate their own
    /// expressions (an `-o` format) with [`Interpreter::eval`].
    pub fn begin_single(&mut self) {
        self.ev.next_record();
    }

    /// One input record: `None` when `cond` rejects it.
    pub fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        if !self.begin_record(record)? {
            return Ok(None);
        }
        self.outputs(record).map(Some)
    }

    /// Start a record (rcalc.c `execute`): set `recno`/`outno`, expire `=` values and
    /// test `cond`. `false` when the record is filtered out.
    pub fn begin_record(&mut self, record: &mut dyn Input) -> Result<bool, Error> {
        let n = self.numbering.begin();
        if let Some(d) = self.recno {
            self.ev.set_value(d, n.recno);
        }
        if let Some(d) = self.outno {
            self.ev.set_value(d, n.outno);
        }
        self.ev.next_record();
        match self.cond {
            Some(c) => {
                let cond = self.ev.variable(c, record)?;
                Ok(self.numbering.accept(cond))
            }
            None => {
                self.numbering.accept_all();
                Ok(true)
            }
        }
    }

    /// Set a variable for this record as rcalc's `varset(name, '=', v)` does for an
    /// input format's fields. The module must already define it (with
    /// [`Module::set_variable`]); returns false if it does not.
    pub fn set_named(&mut self, name: &str, value: f64) -> bool {
        let module = self.module;
        match module
            .lookup(name)
            .and_then(|s| module.current_def(s))
            .filter(|&d| !module.def(d).is_function())
        {
            Some(d) => {
                self.ev.set_value(d, value);
                true
            }
            None => false,
        }
    }

    /// Evaluate an expression of this module (an `-o` format field) in the current
    /// record.
    pub fn eval(&mut self, e: &'m Expr, input: &mut dyn Input) -> Result<f64, Error> {
        Ok(self.ev.eval_top(e, input)?)
    }

    /// The `$N` columns of the record begun with [`Interpreter::begin_record`].
    pub fn outputs_for(&mut self, input: &mut dyn Input) -> Result<Outputs, Error> {
        self.outputs(input)
    }

    /// As [`Interpreter::outputs_for`], into a caller's buffer (appended); on an
    /// error it holds the columns computed before it.
    pub fn outputs_into(&mut self, input: &mut dyn Input, out: &mut Outputs) -> Result<(), Error> {
        for (chan, o) in self.module.outputs() {
            out.push((*chan, self.ev.eval_top(&o.body, input)?));
        }
        Ok(())
    }

    fn outputs(&mut self, input: &mut dyn Input) -> Result<Outputs, Error> {
        let mut out = Vec::with_capacity(self.module.outputs().len());
        match self.outputs_into(input, &mut out) {
            Ok(()) => Ok(out),
            Err(e) => {
                self.partial = out;
                Err(e)
            }
        }
    }

    /// The columns of a failed record computed before the error: rcalc has printed
    /// them by the time it stops.
    pub fn take_partial(&mut self) -> Outputs {
        std::mem::take(&mut self.partial)
    }

    /// Warnings raised since the last call, in order (rcalc prints them as they come).
    pub fn take_warnings(&mut self) -> Vec<Warning> {
        std::mem::take(&mut self.ev.warnings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use radc_lang::FileId;
    use radc_lang::cal::Env;

    fn run(src: &str, line: &str) -> (String, Vec<String>) {
        let mut m = Module::new(&Env::rcalc());
        let d = m.add_source(FileId(0), src);
        assert!(d.iter().all(|d| !d.is_error()), "{d:?}");
        m.optimize();
        let mut it = Interpreter::new(&m, MathErrors::default()).expect("interpreter");
        let mut rec = Record::new(line, '\t');
        let out = it.record(&mut rec).expect("record").unwrap_or_default();
        let warns = it.take_warnings().iter().map(|w| w.to_string()).collect();
        (format_outputs(&out, '\t'), warns)
    }

    #[test]
    fn errors_propagate_through_library_calls_only() {
        // Checked against rcalc: `echo 0 | rcalc -e 'z=$1;$1=max(1/z,5);$2=1+max(1,2);$3=1+1/z'`
        let (out, w) = run("z=$1;$1=max(1/z,5);$2=1+max(1,2);$3=1+1/z", "0\n");
        assert_eq!(out, "0\t3\t1\n");
        assert_eq!(
            w,
            ["Division by zero", "max(): range error", "Division by zero"]
        );
    }

    #[test]
    fn cached_values_do_not_reraise() {
        let (out, _) = run("z=$1; a=1/z; $1=a; $2=sqrt(a+4)", "0\n");
        assert_eq!(out, "0\t2\n");
    }

    #[test]
    fn flattening_combines_constants() {
        let (out, _) = run("$1=$1+1e20-1e20;$2=-$1+-$1;$3=-$1", "0\n");
        assert_eq!(out, "0\t0\t-0\n");
        let (out, _) = run("$1=$1+1e20-1e20", "1\n");
        assert_eq!(out, "1\n");
    }

    #[test]
    fn cond_filters_and_recno_counts() {
        let mut m = Module::new(&Env::rcalc());
        m.add_source(FileId(0), "cond=$1-1; $1=$1");
        m.optimize();
        let mut it = Interpreter::new(&m, MathErrors::default()).expect("interpreter");
        assert_eq!(it.record(&mut Record::new("1", '\t')), Ok(None));
        assert_eq!(
            it.record(&mut Record::new("2", '\t')),
            Ok(Some(vec![(1, 2.0)]))
        );
    }

    #[test]
    fn undefined_is_an_error_only_when_evaluated() {
        let (out, _) = run("a = nosuch; $1 = 1", "\n");
        assert_eq!(out, "1\n");
        let mut m = Module::new(&Env::rcalc());
        m.add_source(FileId(0), "$1 = nosuch");
        let mut it = Interpreter::new(&m, MathErrors::default()).expect("interpreter");
        assert_eq!(
            it.single(),
            Err(Error::Eval(EvalError::UndefinedVariable("nosuch".into())))
        );
    }
}
