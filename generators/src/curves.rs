//! The calcomp side of genworm and genrev: `-e` statements and `-f` files, then one
//! function of `t` per curve (`X`SYS`(t)=...`), evaluated with `radc_lang::cal` at the
//! parameter values the generator asks for.
//!
//! As in Radiance, `PI` and the spline functions `hermite`, `bezier` and `bspline`
//! are predefined, constants fold while parsing, and everything is evaluated within
//! one evaluation clock (so `=` variables keep their first value).

use crate::GenError;
use radc_lang::FileId;
use radc_lang::cal::eval::{Evaluator, NoInput};
use radc_lang::cal::ir::DefId;
use radc_lang::cal::{Env, Module};

/// The generators' C spline functions (`l_hermite`, `l_bezier`, `l_bspline`), in
/// calcomp, defined constant (`:`) as their `funset(..., ':', ...)` does. The oracle
/// compiles them with `-ffast-math`, which regroups the arithmetic; these formulas
/// follow its compiled order, read from the disassembly, so results agree to the bit.
/// `I`SYS`` is the identity: a call is never spliced into the enclosing sum or
/// product by `doptimize`, so it keeps a grouping that flattening would undo.
const SPLINES: &str = "\
I`SYS`(x) : x;
hermite(p0,p1,r0,r1,t) : t*(((t-1)*r1 + (3-2*t)*p1)*t + ((t-2)*t+1)*r0) + p0*(1+(2*t-3)*I`SYS`(t*t));
bezier(p0,p1,p2,p3,t) : t*(t*(p3*t + (1-t)*I`SYS`(3*p2)) + ((t-2)*t+1)*I`SYS`(3*p1)) + p0*(1+((3-t)*t-3)*t);
bspline(p0,p1,p2,p3,t) : I`SYS`(p3*t)*I`SYS`(I`SYS`(t*t)*(1/6)) + p1*((0.5*t-1)*I`SYS`(t*t)+2/3) + I`SYS`(p0*(((0.5-(1/6)*t)*t-0.5)*t+1/6) + p2*((1+(1-t)*t)*I`SYS`(0.5*t)+1/6));
";

pub(crate) struct CurveProgram {
    module: Module,
    /// The parameters' variables (`S`SYS``, `T`SYS``), set before each evaluation.
    parameters: Vec<DefId>,
    /// Output channels 1..=curves hold the curves at the parameters.
    curves: u32,
    /// Channels of expressions evaluated once (segment counts).
    next_channel: u32,
}

/// Channels from here on hold one-off expressions; curves use 1, 2, ...
const FIRST_EXPRESSION_CHANNEL: u32 = 1000;

impl CurveProgram {
    pub fn new() -> Result<Self, GenError> {
        let mut module = Module::new(&Env::bare());
        module.set_constant("PI", std::f64::consts::PI);
        let mut p = CurveProgram {
            module,
            parameters: Vec::new(),
            curves: 0,
            next_channel: FIRST_EXPRESSION_CHANNEL,
        };
        p.compile(SPLINES, "the spline functions")?;
        Ok(p)
    }

    /// `scompile()`/`fcompile()`: statements in order.
    pub fn compile(&mut self, text: &str, what: &str) -> Result<(), GenError> {
        let diagnostics = self.module.add_source(FileId(0), text);
        match diagnostics.iter().find(|d| d.is_error()) {
            None => Ok(()),
            Some(d) => Err(GenError::Invalid(format!("in {what}: {}", d.message))),
        }
    }

    /// The generators' `-e expr` and `-f file` options: definitions from the command
    /// line or from a file read through `host`.
    pub fn load_option(
        &mut self,
        option: &str,
        value: &str,
        host: &mut dyn crate::Host,
    ) -> Result<(), GenError> {
        if option == "-e" {
            self.compile(value, value)
        } else {
            let text = host.read_file(value)?;
            self.compile(&text, value)
        }
    }

    /// `eval(text)`: an expression's value with the definitions made so far.
    pub fn eval(&mut self, text: &str) -> Result<f64, GenError> {
        let channel = self.next_channel;
        self.next_channel += 1;
        self.compile(&format!("${channel}={text};"), text)?;
        self.evaluator().channel(channel)
    }

    /// Defines `<name>`SYS`(<parameters>)` for each curve, plus output channels that
    /// evaluate them (and any `extra` functions of the same parameters) at the
    /// parameter variables.
    pub fn define(
        &mut self,
        parameters: &[&str],
        curves: &[(&str, &str)],
        extra: &[&str],
    ) -> Result<(), GenError> {
        let list = parameters.join(",");
        for (name, body) in curves {
            self.compile(&format!("{name}`SYS`({list})={body};"), body)?;
        }
        let variables: Vec<String> = parameters
            .iter()
            .map(|p| format!("{}`SYS`", p.to_uppercase()))
            .collect();
        for v in &variables {
            self.module.set_variable(v, 0.0);
        }
        let call_args = variables.join(",");
        let mut outputs = String::new();
        let names = curves
            .iter()
            .map(|(name, _)| format!("{name}`SYS`"))
            .chain(extra.iter().map(|e| e.to_string()));
        for (k, name) in names.enumerate() {
            outputs.push_str(&format!("${}={name}({call_args});", k + 1));
        }
        self.compile(&outputs, "the curves")?;
        self.curves = (curves.len() + extra.len()) as u32;
        self.parameters = variables
            .iter()
            .filter_map(|v| {
                self.module
                    .lookup(v)
                    .and_then(|s| self.module.current_def(s))
            })
            .collect();
        Ok(())
    }

    /// The number of parameters of a user function, if `name` is one (`fundefined`).
    pub fn function_arity(&self, name: &str) -> Option<usize> {
        let sym = self.module.lookup(name)?;
        let def = self.module.current_def(sym)?;
        self.module.def(def).params.as_ref().map(Vec::len)
    }

    /// `doptimize(1)`: flatten sums and products, folding their numbers. The
    /// generators call it after reading their counts, before evaluating the curves.
    pub fn optimize(&mut self) {
        self.module.optimize();
    }

    pub fn evaluator(&self) -> CurveEval<'_> {
        CurveEval {
            program: self,
            ev: Evaluator::new(&self.module),
        }
    }
}

pub(crate) struct CurveEval<'m> {
    program: &'m CurveProgram,
    ev: Evaluator<'m>,
}

impl CurveEval<'_> {
    fn channel(&mut self, channel: u32) -> Result<f64, GenError> {
        let out = self
            .program
            .module
            .outputs()
            .get(&channel)
            .ok_or_else(|| GenError::Invalid("missing curve output".into()))?;
        self.ev
            .eval_top(&out.body, &mut NoInput)
            .map_err(|e| GenError::Invalid(format!("calcomp: {e}")))
    }

    /// Every curve at the given parameter values (`funvalue(name, n, args)` for each).
    pub fn at(&mut self, parameters: &[f64]) -> Result<Vec<f64>, GenError> {
        if parameters.len() != self.program.parameters.len() {
            return Err(GenError::Invalid("curves not defined".into()));
        }
        for (&def, &value) in self.program.parameters.iter().zip(parameters) {
            self.ev.set_value(def, value);
        }
        (1..=self.program.curves).map(|c| self.channel(c)).collect()
    }

    /// Only curve `k` (1-based) at the parameters last set by [`CurveEval::at`] or
    /// [`CurveEval::set`].
    pub fn curve(&mut self, k: u32) -> Result<f64, GenError> {
        self.channel(k)
    }

    /// Sets the parameters without evaluating.
    pub fn set(&mut self, parameters: &[f64]) {
        for (&def, &value) in self.program.parameters.iter().zip(parameters) {
            self.ev.set_value(def, value);
        }
    }
}
