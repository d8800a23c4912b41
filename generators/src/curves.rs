//! The calcomp side of genworm and genrev: `-e` statements and `-f` files, then one
//! function of `t` per curve (`X`SYS`(t)=...`), evaluated with `radc_lang::cal` at the
//! parameter values the generator asks for: compiled by the Cranelift JIT (`radc_jit`),
//! or interpreted when the JIT declines the program.
//!
//! As in Radiance, `PI` and the spline functions `hermite`, `bezier` and `bspline`
//! are predefined, constants fold while parsing, and everything is evaluated within
//! one evaluation clock (so `=` variables keep their first value).

use crate::GenError;
use radc_jit::compile::Entry;
use radc_jit::{Compiled, Context, Jit, JitError};
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
    /// Their names, the JIT's host variables.
    parameter_names: Vec<String>,
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
            parameter_names: Vec::new(),
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
        self.parameter_names = variables;
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

    /// Evaluation of the curves: compiled by the JIT when it accepts the program,
    /// else through the interpreter. Both compute the same bits (the JIT is built to
    /// agree with the interpreter), so the choice never shows in the output.
    pub fn evaluator(&self) -> CurveEval<'_> {
        let engine = match self.jit_compile() {
            Ok((compiled, entries, hosts)) => {
                let ctx = compiled.context();
                Engine::Jit(Box::new(JitCurves {
                    compiled,
                    ctx,
                    entries,
                    hosts,
                }))
            }
            Err(_) => return self.interpreted(),
        };
        CurveEval {
            program: self,
            engine,
            parameters: vec![0.0; self.parameters.len()],
        }
    }

    /// Evaluation through the interpreter only.
    pub fn interpreted(&self) -> CurveEval<'_> {
        CurveEval {
            program: self,
            engine: Engine::Interpreter(Evaluator::new(&self.module)),
            parameters: vec![0.0; self.parameters.len()],
        }
    }

    /// The curves' output channels as JIT entries, the parameter variables as host
    /// variables (the interpreter's `set_value` overrides).
    #[allow(clippy::type_complexity)]
    fn jit_compile(&self) -> Result<(Compiled, Vec<Entry>, Vec<usize>), JitError> {
        let names: Vec<String> = (1..=self.curves).map(|c| format!("${c}")).collect();
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let parameters: Vec<&str> = self.parameter_names.iter().map(String::as_str).collect();
        let compiled = Jit::new()
            .with_host_variables(&parameters)
            .compile(&self.module, &names)?;
        let entries = names
            .iter()
            .map(|n| {
                compiled
                    .entry(n)
                    .ok_or(JitError::UnknownEntry(n.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let hosts = parameters
            .iter()
            .map(|n| {
                compiled
                    .host_index(n)
                    .ok_or(JitError::UnknownEntry(n.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok((compiled, entries, hosts))
    }
}

/// What evaluates the curves.
enum Engine<'m> {
    Jit(Box<JitCurves>),
    Interpreter(Evaluator<'m>),
}

struct JitCurves {
    compiled: Compiled,
    ctx: Context,
    /// Curve `k` is `entries[k - 1]`.
    entries: Vec<Entry>,
    /// The context's host slot of each parameter.
    hosts: Vec<usize>,
}

pub(crate) struct CurveEval<'m> {
    program: &'m CurveProgram,
    engine: Engine<'m>,
    /// The parameters last set, to replay into the interpreter if the JIT fails.
    parameters: Vec<f64>,
}

impl<'m> CurveEval<'m> {
    fn channel(&mut self, channel: u32) -> Result<f64, GenError> {
        if let Engine::Jit(jit) = &mut self.engine {
            let entry = jit.entries.get(channel as usize - 1).copied();
            match entry.map(|e| jit.compiled.eval_no_input(e, &mut jit.ctx)) {
                Some(Ok(v)) => return Ok(v),
                // A failure (a calcomp error, or the JIT's own stack budget running
                // out before the interpreter's depth limit) is reported as the
                // interpreter reports it: from here on the interpreter evaluates.
                _ => self.fall_back(),
            }
        }
        let out = self
            .program
            .module
            .outputs()
            .get(&channel)
            .ok_or_else(|| GenError::Invalid("missing curve output".into()))?;
        match &mut self.engine {
            Engine::Interpreter(ev) => ev
                .eval_top(&out.body, &mut NoInput)
                .map_err(|e| GenError::Plain(e.to_string())),
            Engine::Jit(_) => Err(GenError::Invalid("missing curve output".into())),
        }
    }

    fn fall_back(&mut self) {
        let mut ev = Evaluator::new(&self.program.module);
        for (&def, &value) in self.program.parameters.iter().zip(&self.parameters) {
            ev.set_value(def, value);
        }
        self.engine = Engine::Interpreter(ev);
    }

    /// Every curve at the given parameter values (`funvalue(name, n, args)` for each).
    pub fn at(&mut self, parameters: &[f64]) -> Result<Vec<f64>, GenError> {
        if parameters.len() != self.program.parameters.len() {
            return Err(GenError::Invalid("curves not defined".into()));
        }
        self.set(parameters);
        (1..=self.program.curves).map(|c| self.channel(c)).collect()
    }

    /// Only curve `k` (1-based) at the parameters last set by [`CurveEval::at`] or
    /// [`CurveEval::set`].
    pub fn curve(&mut self, k: u32) -> Result<f64, GenError> {
        self.channel(k)
    }

    /// Sets the parameters without evaluating.
    pub fn set(&mut self, parameters: &[f64]) {
        for (slot, &value) in self.parameters.iter_mut().zip(parameters) {
            *slot = value;
        }
        match &mut self.engine {
            Engine::Jit(jit) => {
                for (&k, &value) in jit.hosts.iter().zip(parameters) {
                    jit.ctx.set_host(k, value);
                }
            }
            Engine::Interpreter(ev) => {
                for (&def, &value) in self.program.parameters.iter().zip(parameters) {
                    ev.set_value(def, value);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn program(defs: &str, curves: &[(&str, &str)]) -> CurveProgram {
        let mut p = CurveProgram::new().expect("splines compile");
        p.compile(defs, "-e").expect("definitions compile");
        p.define(&["s", "t"], curves, &[]).expect("curves compile");
        p.optimize();
        p
    }

    fn is_jit(ev: &CurveEval<'_>) -> bool {
        matches!(ev.engine, Engine::Jit(_))
    }

    #[test]
    fn the_jit_evaluates_curves_and_agrees_with_the_interpreter() {
        let p = program(
            "f(x) = if(x - .5, bspline(0, 1, 3, 2, x), hermite(1, 2, x, -x, x*x));\
             k(s, t) = sin(PI*s) * exp(-t); fact(n) = if(n - 1.5, n * fact(n - 1), 1);",
            &[
                ("X", "f(s) + k(s, t)"),
                ("Y", "bezier(s, t, 1, 2, t)/t"),
                ("Z", "fact(s*9)"),
            ],
        );
        let (mut jit, mut interp) = (p.evaluator(), p.interpreted());
        assert!(is_jit(&jit));
        assert!(!is_jit(&interp));
        for i in 0..=20 {
            let (s, t) = (i as f64 / 20.0, 1.0 - i as f64 / 20.0);
            let a = jit.at(&[s, t]).expect("jit evaluates");
            let b = interp.at(&[s, t]).expect("interpreter evaluates");
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "at s={s} t={t}");
        }
    }

    #[test]
    fn a_jit_failure_is_the_interpreters_error() {
        let p = program("", &[("X", "s"), ("Y", "undefined_thing(t)"), ("Z", "1")]);
        let mut jit = p.evaluator();
        let got = jit.at(&[0.5, 0.5]);
        let want = p.interpreted().at(&[0.5, 0.5]);
        assert!(want.is_err());
        assert_eq!(got, want);
        assert!(!is_jit(&jit), "the interpreter takes over after a failure");
    }

    #[test]
    fn the_interpreter_takes_over_when_the_jit_runs_out_of_stack() {
        // Recursion 15,000 deep (within the interpreter's 20,000-call limit) outgrows
        // the JIT's 1 MB native stack budget: the interpreter, on a thread with a deep
        // stack as the CLI gives it, finishes the evaluation.
        let worker = std::thread::Builder::new().stack_size(512 << 20).spawn(|| {
            let p = program(
                "r(n) = if(n, 1 + r(n - 1), 0);",
                &[("X", "r(s)"), ("Y", "t"), ("Z", "0")],
            );
            let mut ev = p.evaluator();
            let small = ev.at(&[20.0, 1.0]);
            let jit_after_small = is_jit(&ev);
            let deep = ev.at(&[15000.0, 1.0]);
            (small, jit_after_small, deep, is_jit(&ev))
        });
        let (small, jit_after_small, deep, jit_after_deep) =
            worker.expect("thread starts").join().expect("no panic");
        assert_eq!(small, Ok(vec![20.0, 1.0, 0.0]));
        assert!(jit_after_small);
        assert_eq!(deep, Ok(vec![15000.0, 1.0, 0.0]));
        assert!(!jit_after_deep);
    }
}
