//! Data patterns (p_data.c `p_bdata`, `p_cdata`): coordinate expressions, evaluated in
//! the function file's context like a func pattern's, pick a point in one data file
//! (`brightdata`) or three of the same dimensions (`colordata`); the value found there
//! (interpolated as data.c does, by `radc_lang::datafile`) goes through the named
//! function, and that result scales or multiplies `pcol`.

use std::sync::Arc;

use radc_lang::cal::Module;
use radc_lang::cal::ir::Node;
use radc_lang::datafile::DataFile;

use super::channels::{COUNT, Channels};
use super::{Functions, ProgramId, RayInput};

/// The channel number through which a data value reaches the function applied to it:
/// the ones after the ray's own (`$28` .. `$30`). A function file that reads these
/// itself is refused (Radiance calls them an illegal channel).
pub const DATA_CHANNEL: u32 = COUNT as u32 + 1;

/// What a data pattern looks values up in.
#[derive(Clone, Debug)]
pub enum DataSource {
    /// `brightdata`: one file.
    Bright(Arc<DataFile>),
    /// `colordata` and `texdata`: three files.
    Color([Arc<DataFile>; 3]),
    /// `mixdata`: one file, its coordinates evaluated in order (mx_data.c).
    Mix(Arc<DataFile>),
}

/// A `brightdata` or `colordata` pattern's data and the expressions (in its
/// program) that apply its function(s) to the values found.
#[derive(Clone, Debug)]
pub struct DataLookup {
    pub source: DataSource,
    pub functions: Vec<usize>,
}

impl DataLookup {
    /// The pattern's value(s) for the ray; `None` on a compute error (p_data.c warns
    /// and leaves `pcol` alone). `coords` are the coordinate expressions.
    pub fn values(
        &self,
        functions: &Functions,
        pattern: u32,
        program: ProgramId,
        coords: &[usize],
        channels: &Channels,
        args: &[f64],
    ) -> Option<[f64; 3]> {
        let mut pt = vec![0.0; coords.len()];
        let mut input = RayInput {
            channels,
            args,
            data: &[],
        };
        functions.eval(pattern, program, coords, &mut input, &mut pt)?;
        if matches!(self.source, DataSource::Bright(_)) {
            // p_bdata evaluates the last coordinate first (which shows in the warnings
            // met); the scene compiler stored them in that order.
            pt.reverse();
        }
        let data = match &self.source {
            DataSource::Bright(d) | DataSource::Mix(d) => [d.eval(&pt), 0.0, 0.0],
            DataSource::Color(d) => [d[0].eval(&pt), d[1].eval(&pt), d[2].eval(&pt)],
        };
        apply_functions(
            functions,
            pattern,
            program,
            &self.functions,
            data,
            channels,
            args,
        )
    }
}

/// Evaluates the function expressions on `data` (p_data.c `funvalue` after `errno`
/// is cleared: an error there is a compute error too).
pub(super) fn apply_functions(
    functions: &Functions,
    pattern: u32,
    program: ProgramId,
    exprs: &[usize],
    data: [f64; 3],
    channels: &Channels,
    args: &[f64],
) -> Option<[f64; 3]> {
    let mut input = RayInput {
        channels,
        args,
        data: &data,
    };
    let mut v = [0.0; 3];
    let n = exprs.len().min(3);
    functions.eval(pattern, program, exprs, &mut input, &mut v[..n])?;
    Some(v)
}

impl Functions {
    /// The parameter count of function `name` as program `p` would call it, or why it
    /// cannot be called from a pattern or material.
    pub(super) fn callable_arity(&self, p: ProgramId, name: &str) -> Result<usize, String> {
        if !is_function_name(name) {
            return Err(format!("'{name}' is not a function name"));
        }
        let module = &self
            .programs
            .get(p.0 as usize)
            .ok_or_else(|| "no such program".to_string())?
            .module;
        arity(module, name)
            .ok_or_else(|| format!("'{name}' is not a function of fixed arity radc evaluates"))
    }

    /// Adds the call of function `name` on a data value to program `p`: on value
    /// `channel` alone, or, where `name` takes three or more arguments and `triple` is
    /// set, on all three (p_data.c: `fundefined(name) < 3` decides). Returns the
    /// expression's index.
    pub fn add_data_function(
        &mut self,
        p: ProgramId,
        name: &str,
        channel: u32,
        triple: bool,
    ) -> Result<usize, String> {
        let arity = self.callable_arity(p, name)?;
        let text = if triple && arity >= 3 {
            format!(
                "{name}(${DATA_CHANNEL},${},${})",
                DATA_CHANNEL + 1,
                DATA_CHANNEL + 2
            )
        } else {
            format!("{name}(${})", DATA_CHANNEL + channel)
        };
        let k = self.add_expression(p, &text)?;
        let program = self
            .programs
            .get(p.0 as usize)
            .ok_or_else(|| "no such program".to_string())?;
        if let Some(e) = program.exprs.get(k)
            && reads_data_channels(&program.module, e)
        {
            return Err(format!(
                "its function file reads input channel {DATA_CHANNEL} or beyond"
            ));
        }
        Ok(k)
    }
}

/// A name a material or pattern may call: a plain identifier (a context suffix allowed).
pub(super) fn is_function_name(name: &str) -> bool {
    name.chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '`')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '`'))
}

/// calfunc.c `fundefined`: a defined function's parameter count, else the library
/// function's. Library functions of variable arity are not modelled (`None`).
pub(super) fn arity(module: &Module, name: &str) -> Option<usize> {
    if let Some(sym) = module.lookup(name) {
        let s = module.symbol(sym);
        if let Some(params) = s.stack.last().and_then(|&d| module.def(d).params.as_ref()) {
            return Some(params.len());
        }
        if let Some(lib) = &s.lib {
            return (lib.max_args() == Some(lib.min_args())).then(|| lib.min_args());
        }
    }
    radc_lang::cal::builtins::Builtin::ALL
        .iter()
        .find(|b| b.name() == name)
        .and_then(|b| (b.max_args() == Some(b.min_args())).then(|| b.min_args()))
}

/// Whether the call `e`, or anything it reaches, reads a channel past the ray's.
fn reads_data_channels(module: &Module, e: &radc_lang::cal::ir::Expr) -> bool {
    fn reads(e: &radc_lang::cal::ir::Expr) -> bool {
        matches!(e.node, Node::Chan(n) if n > COUNT as u32) || e.children().into_iter().any(reads)
    }
    radc_lang::cal::deps::needed_by_expr(module, e)
        .into_iter()
        .any(|d| reads(&module.def(d).body))
}
