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

/// The parameter's name: a context-qualified name no user file can define.
const PARAMETER: &str = "T`SYS`";

pub(crate) struct CurveProgram {
    module: Module,
    parameter: Option<DefId>,
    curves: u32,
}

impl CurveProgram {
    pub fn new() -> Result<Self, GenError> {
        let mut module = Module::new(&Env::bare());
        module.set_constant("PI", std::f64::consts::PI);
        let mut p = CurveProgram {
            module,
            parameter: None,
            curves: 0,
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

    /// Defines `<name>`SYS`(t)` for each curve, then the segment-count expression.
    pub fn finish(&mut self, curves: &[(&str, &str)], count: &str) -> Result<(), GenError> {
        for (name, body) in curves {
            self.compile(&format!("{name}`SYS`(t)={body};"), body)?;
        }
        self.module.set_variable(PARAMETER, 0.0);
        let mut outputs = String::new();
        for (k, (name, _)) in curves.iter().enumerate() {
            outputs.push_str(&format!("${}={name}`SYS`({PARAMETER});", k + 1));
        }
        self.compile(&outputs, "the curves")?;
        self.curves = curves.len() as u32;
        self.compile(&format!("${}={count};", self.curves + 1), count)?;
        self.parameter = self
            .module
            .lookup(PARAMETER)
            .and_then(|s| self.module.current_def(s));
        Ok(())
    }

    /// The segment count expression's value (`eval(argv[n])`), computed before the
    /// program is optimized, as the C generators do.
    pub fn count(&self) -> Result<f64, GenError> {
        self.evaluator().count()
    }

    /// `doptimize(1)`: flatten sums and products, folding their numbers. The
    /// generators call it after reading the segment count, before the curves.
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

    /// The segment count expression's value (`eval(argv[n])`).
    pub fn count(&mut self) -> Result<f64, GenError> {
        self.channel(self.program.curves + 1)
    }

    /// Every curve at `t` (`funvalue(name, 1, &t)` for each).
    pub fn at(&mut self, t: f64) -> Result<Vec<f64>, GenError> {
        let parameter = self
            .program
            .parameter
            .ok_or_else(|| GenError::Invalid("curves not defined".into()))?;
        self.ev.set_value(parameter, t);
        (1..=self.program.curves).map(|c| self.channel(c)).collect()
    }
}
