//! rcalc's record loop over compiled code: the same driver as
//! [`crate::interp::Interpreter`] (a new clock per record, `cond`, `recno`/`outno`,
//! outputs in ascending column order, the columns computed before a fatal error),
//! with `cond` and each `-o` field compiled as an entry point, and the output columns
//! as one (`$*`, [`super::Compiled::eval_outputs`]).

use super::{Compiled, Context, Entry, Jit, JitError};
use crate::engine::RecordNumbering;
use crate::interp::{Error, Outputs, Record};
use radc_lang::cal::Module;
use radc_lang::cal::eval::{Input, MathErrors, NoInput, Warning};
use radc_lang::cal::ir::Expr;
use radc_lang::cal::syntax::DefKind;
use std::fmt;
use std::sync::Arc;

/// Why a [`JitProgram`] could not start: an error rcalc itself reports, or a program
/// the JIT declines (run it with the interpreter instead).
#[derive(Clone, Debug, PartialEq)]
pub enum StartError {
    Program(Error),
    Jit(JitError),
}

impl fmt::Display for StartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StartError::Program(e) => e.fmt(f),
            StartError::Jit(e) => e.fmt(f),
        }
    }
}

pub struct JitProgram {
    /// Shared by the engines [`JitProgram::fork`] makes.
    compiled: Arc<Compiled>,
    ctx: Context,
    cond: Option<Entry>,
    /// The output columns, ascending, and the entry computing them all.
    columns: Vec<u32>,
    outputs: Entry,
    values: Vec<f64>,
    /// The expressions given to [`JitProgram::with_fields`], as entries.
    fields: Vec<Entry>,
    recno: Option<usize>,
    outno: Option<usize>,
    numbering: RecordNumbering,
    partial: Outputs,
}

impl JitProgram {
    /// As [`crate::Interpreter::new`]: `recno` and `outno` are host variables.
    pub fn new(module: &Module, policy: MathErrors) -> Result<Self, StartError> {
        Self::with_fields(module, policy, &[], &[])
    }

    /// As [`JitProgram::new`], also compiling `fields` (an `-o` format's number fields,
    /// see [`JitProgram::field`]) and making `named` variables settable per record
    /// ([`JitProgram::set_named`], an `-i` format's fields).
    pub fn with_fields(
        module: &Module,
        policy: MathErrors,
        fields: &[&Expr],
        named: &[&str],
    ) -> Result<Self, StartError> {
        let cond = module.lookup("cond").and_then(|s| {
            module
                .current_def(s)
                .filter(|&d| !module.def(d).is_function())
        });
        if cond.is_some_and(|d| module.def(d).kind == DefKind::Constant) {
            return Err(StartError::Program(Error::ConstantCond));
        }
        let columns: Vec<u32> = module.outputs().keys().copied().collect();
        let mut entries: Vec<String> = vec!["$*".into()];
        if cond.is_some() {
            entries.push("cond".into());
        }
        let names: Vec<&str> = entries.iter().map(String::as_str).collect();
        let mut hosts = vec!["recno", "outno"];
        // A format may name a variable twice (`${a} ${a}`): one host slot each name.
        for n in named {
            if !hosts.contains(n) {
                hosts.push(n);
            }
        }
        let compiled = Jit::new()
            .with_policy(policy)
            .with_host_variables(&hosts)
            .compile_with_expressions(module, &names, fields)
            .map_err(StartError::Jit)?;
        let entry = |name: &str| {
            compiled
                .entry(name)
                .ok_or_else(|| StartError::Jit(JitError::UnknownEntry(name.to_string())))
        };
        let outputs = entry("$*")?;
        let cond = match cond {
            Some(_) => Some(entry("cond")?),
            None => None,
        };
        let fields = (0..fields.len())
            .map(|k| entry(&format!("#{k}")))
            .collect::<Result<Vec<_>, StartError>>()?;
        let ctx = compiled.context();
        let compiled = Arc::new(compiled);
        Ok(JitProgram {
            recno: compiled.host_index("recno"),
            outno: compiled.host_index("outno"),
            compiled,
            ctx,
            cond,
            columns,
            outputs,
            values: Vec::new(),
            fields,
            numbering: RecordNumbering::default(),
            partial: Vec::new(),
        })
    }

    /// Another engine running the same compiled code (for another thread), with its
    /// own context, and record counts from 0: no second compilation.
    pub fn fork(&self) -> Self {
        let mut ctx = self.compiled.context();
        ctx.set_stack_budget(self.ctx.stack_budget());
        JitProgram {
            compiled: Arc::clone(&self.compiled),
            ctx,
            cond: self.cond,
            columns: self.columns.clone(),
            outputs: self.outputs,
            values: Vec::new(),
            fields: self.fields.clone(),
            recno: self.recno,
            outno: self.outno,
            numbering: RecordNumbering::default(),
            partial: Vec::new(),
        }
    }

    /// Native stack the compiled code may use (see [`Context::set_stack_budget`]).
    pub fn set_stack_budget(&mut self, bytes: usize) {
        self.ctx.set_stack_budget(bytes);
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

    /// Start rcalc's single `-n` record.
    pub fn begin_single(&mut self) {
        self.ctx.next_record();
    }

    /// One input record: `None` when `cond` rejects it.
    pub fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        if !self.begin_record(record)? {
            return Ok(None);
        }
        self.outputs(record).map(Some)
    }

    /// As [`crate::Interpreter::begin_record`].
    pub fn begin_record(&mut self, input: &mut dyn Input) -> Result<bool, Error> {
        let n = self.numbering.begin();
        if let Some(k) = self.recno {
            self.ctx.set_host(k, n.recno);
        }
        if let Some(k) = self.outno {
            self.ctx.set_host(k, n.outno);
        }
        self.ctx.next_record();
        match self.cond {
            Some(c) => {
                let cond = self.compiled.eval(c, &mut self.ctx, input)?;
                Ok(self.numbering.accept(cond))
            }
            None => {
                self.numbering.accept_all();
                Ok(true)
            }
        }
    }

    /// Set a variable named to [`JitProgram::with_fields`] for this record; false if
    /// the program has no such variable.
    pub fn set_named(&mut self, name: &str, value: f64) -> bool {
        match self.compiled.host_index(name) {
            Some(k) => {
                self.ctx.set_host(k, value);
                true
            }
            None => false,
        }
    }

    /// The value of the `k`th field given to [`JitProgram::with_fields`].
    pub fn field(&mut self, k: usize, input: &mut dyn Input) -> Result<f64, Error> {
        let Some(&entry) = self.fields.get(k) else {
            return Err(Error::Eval(radc_lang::cal::eval::EvalError::NotAvailable(
                format!("format field #{k}"),
            )));
        };
        Ok(self.compiled.eval(entry, &mut self.ctx, input)?)
    }

    /// The `$N` columns of the record begun, appended to `out`; on an error `out`
    /// holds the columns computed before it.
    pub fn outputs_into(&mut self, input: &mut dyn Input, out: &mut Outputs) -> Result<(), Error> {
        let mut values = std::mem::take(&mut self.values);
        values.clear();
        let result = self
            .compiled
            .eval_outputs(self.outputs, &mut self.ctx, input, &mut values);
        out.extend(self.columns.iter().copied().zip(values.iter().copied()));
        self.values = values;
        Ok(result?)
    }

    fn outputs(&mut self, input: &mut dyn Input) -> Result<Outputs, Error> {
        let mut out = Vec::with_capacity(self.columns.len());
        match self.outputs_into(input, &mut out) {
            Ok(()) => Ok(out),
            Err(e) => {
                self.partial = out;
                Err(e)
            }
        }
    }

    pub fn take_partial(&mut self) -> Outputs {
        std::mem::take(&mut self.partial)
    }

    pub fn take_warnings(&mut self) -> Vec<Warning> {
        self.ctx.take_warnings()
    }
}
