//! rcalc's record loop over compiled code: the same driver as
//! [`crate::interp::Interpreter`] (a new clock per record, `cond`, `recno`/`outno`,
//! outputs in ascending column order, the columns computed before a fatal error),
//! with each output column and `cond` compiled as an entry point.

use super::{Compiled, Context, Entry, Jit, JitError};
use crate::interp::{Error, Outputs, Record};
use radc_lang::cal::Module;
use radc_lang::cal::eval::{Input, MathErrors, NoInput, Warning};
use radc_lang::cal::syntax::DefKind;
use std::fmt;

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
    compiled: Compiled,
    ctx: Context,
    cond: Option<Entry>,
    outputs: Vec<(u32, Entry)>,
    recno: Option<usize>,
    outno: Option<usize>,
    nrecs: u64,
    nout: u64,
    partial: Outputs,
}

impl JitProgram {
    /// As [`crate::Interpreter::new`]: `recno` and `outno` are host variables.
    pub fn new(module: &Module, policy: MathErrors) -> Result<Self, StartError> {
        let cond = module.lookup("cond").and_then(|s| {
            module
                .current_def(s)
                .filter(|&d| !module.def(d).is_function())
        });
        if cond.is_some_and(|d| module.def(d).kind == DefKind::Constant) {
            return Err(StartError::Program(Error::ConstantCond));
        }
        let columns: Vec<u32> = module.outputs().keys().copied().collect();
        let mut entries: Vec<String> = columns.iter().map(|c| format!("${c}")).collect();
        if cond.is_some() {
            entries.push("cond".into());
        }
        let names: Vec<&str> = entries.iter().map(String::as_str).collect();
        let compiled = Jit::new()
            .with_policy(policy)
            .with_host_variables(&["recno", "outno"])
            .compile(module, &names)
            .map_err(StartError::Jit)?;
        let entry = |name: &str| {
            compiled
                .entry(name)
                .ok_or_else(|| StartError::Jit(JitError::UnknownEntry(name.to_string())))
        };
        let outputs = columns
            .iter()
            .map(|c| Ok((*c, entry(&format!("${c}"))?)))
            .collect::<Result<Vec<_>, StartError>>()?;
        let cond = match cond {
            Some(_) => Some(entry("cond")?),
            None => None,
        };
        let ctx = compiled.context();
        Ok(JitProgram {
            recno: compiled.host_index("recno"),
            outno: compiled.host_index("outno"),
            compiled,
            ctx,
            cond,
            outputs,
            nrecs: 0,
            nout: 0,
            partial: Vec::new(),
        })
    }

    /// Native stack the compiled code may use (see [`Context::set_stack_budget`]).
    pub fn set_stack_budget(&mut self, bytes: usize) {
        self.ctx.set_stack_budget(bytes);
    }

    /// rcalc `-n`: one record with no input.
    pub fn single(&mut self) -> Result<Outputs, Error> {
        self.ctx.next_record();
        self.outputs(&mut NoInput)
    }

    /// One input record: `None` when `cond` rejects it.
    pub fn record(&mut self, record: &mut Record) -> Result<Option<Outputs>, Error> {
        self.nrecs += 1;
        if let Some(k) = self.recno {
            self.ctx.set_host(k, self.nrecs as f64);
        }
        if let Some(k) = self.outno {
            self.ctx.set_host(k, (self.nout + 1) as f64);
        }
        self.ctx.next_record();
        if let Some(c) = self.cond
            && self.compiled.eval(c, &mut self.ctx, record)? <= 0.0
        {
            return Ok(None);
        }
        let out = self.outputs(record)?;
        self.nout += 1;
        Ok(Some(out))
    }

    fn outputs(&mut self, input: &mut dyn Input) -> Result<Outputs, Error> {
        let mut out = Vec::with_capacity(self.outputs.len());
        for &(chan, entry) in &self.outputs {
            match self.compiled.eval(entry, &mut self.ctx, input) {
                Ok(v) => out.push((chan, v)),
                Err(e) => {
                    self.partial = out;
                    return Err(e.into());
                }
            }
        }
        Ok(out)
    }

    pub fn take_partial(&mut self) -> Outputs {
        std::mem::take(&mut self.partial)
    }

    pub fn take_warnings(&mut self) -> Vec<Warning> {
        self.ctx.take_warnings()
    }
}
