//! `genworm material name x(t) y(t) z(t) r(t) nseg [-e expr] [-f file]`
//!
//! Reproduces Radiance's `src/gen/genworm.c`: a worm along the curve `(x, y, z)(t)`,
//! `t` from 0 to 1 in `nseg` steps, with radius `r(t)`: a sphere at every step joined
//! by a cylinder (equal radii, within 1e-6) or a cone trimmed to meet the spheres
//! tangentially. The four expressions are calcomp, evaluated with `lang::cal` after
//! the `-e` statements and `-f` files, with `PI` and genworm's `hermite`, `bezier`
//! and `bspline` (same formulas) defined.

use crate::printf::g;
use crate::{GenError, Host, command_comment};
use radc_lang::FileId;
use radc_lang::cal::eval::{Evaluator, NoInput};
use radc_lang::cal::{Env, Module};

const USAGE: &str = "genworm material name x(t) y(t) z(t) r(t) nseg [-e expr] [-f file]";
const FTINY: f64 = 1e-6;

/// genworm's C library functions, written in calcomp with the C code's operation
/// order, defined constant (`:`) as `funset(..., ':', ...)` does.
const SPLINES: &str = "\
hermite(p0,p1,r0,r1,t) : p0*((2*t-3)*t*t+1) + p1*(-2*t+3)*t*t + r0*((t-2)*t+1)*t + r1*(t-1)*t*t;
bezier(p0,p1,p2,p3,t) : p0*(1+t*(-3+t*(3-t))) + p1*3*t*(1+t*(-2+t)) + p2*3*t*t*(1-t) + p3*t*t*t;
bspline(p0,p1,p2,p3,t) : p0*(1/6+t*(-1/2+t*(1/2-1/6*t))) + p1*(2/3+t*t*(-1+1/2*t)) + p2*(1/6+t*(1/2+t*(1/2-1/2*t))) + p3*(1/6*t*t*t);
";

/// The scene genworm prints for `args` (the words after `genworm`); `-f` files come
/// through `host`.
pub fn genworm(args: &[String], host: &mut dyn Host) -> Result<String, GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 7 {
        return Err(usage());
    }
    let mut module = Module::new(&Env::bare());
    module.set_constant("PI", std::f64::consts::PI);
    compile(&mut module, SPLINES, "genworm's splines")?;
    let mut i = 7;
    while i < args.len() {
        let value = args.get(i + 1).ok_or_else(usage)?;
        match args[i].as_str() {
            "-e" => compile(&mut module, value, value)?,
            "-f" => {
                let text = host.read_file(value)?;
                compile(&mut module, &text, value)?;
            }
            _ => return Err(usage()),
        }
        i += 2;
    }
    for (name, body) in ["X", "Y", "Z", "R"].iter().zip(&args[2..6]) {
        compile(&mut module, &format!("{name}`SYS`(t)={body};"), body)?;
    }
    // The curve is evaluated through output channels of a variable the loop sets;
    // channel 5 is the segment count, read once as genworm's `eval(nseg)` does.
    module.set_variable("T`SYS`", 0.0);
    let outputs = "$1=X`SYS`(T`SYS`);$2=Y`SYS`(T`SYS`);$3=Z`SYS`(T`SYS`);$4=R`SYS`(T`SYS`);";
    compile(&mut module, outputs, "genworm")?;
    compile(&mut module, &format!("$5={};", args[6]), &args[6])?;
    let t_def = module
        .lookup("T`SYS`")
        .and_then(|s| module.current_def(s))
        .ok_or_else(|| GenError::Invalid("cannot define the curve parameter".into()))?;
    let module = &module;
    let mut ev = Evaluator::new(module);
    let nseg = (output(module, &mut ev, 5)? + 0.5) as i64;
    if nseg <= 0 {
        return Err(usage());
    }
    if nseg > MAX_SEGMENTS {
        return Err(GenError::Invalid(format!(
            "{nseg} segments: radc makes at most {MAX_SEGMENTS}"
        )));
    }
    let mut out = command_comment("genworm", args);
    let (material, name) = (&args[0], &args[1]);
    let (mut lastp, mut lastr) = ([0.0; 3], 0.0);
    // The oracle's genworm is built with -ffast-math, which turns `i/nseg` into
    // `i * (1/nseg)`; the last bit of t shows in cos(6*PI*t) near its zeros.
    let step = 1.0 / nseg as f64;
    for i in 0..=nseg {
        let t = i as f64 * step;
        ev.set_value(t_def, t);
        let p = [
            output(module, &mut ev, 1)?,
            output(module, &mut ev, 2)?,
            output(module, &mut ev, 3)?,
        ];
        let r = output(module, &mut ev, 4)?;
        if i > 0 {
            if lastr <= r + FTINY && lastr >= r - FTINY {
                out.push_str(&format!("\n{material} cylinder {name}.c{i}\n0\n0\n7\n"));
                line(&mut out, &lastp);
                line(&mut out, &p);
                out.push_str(&format!("{}\n", g(r, 18, 12)));
            } else {
                out.push_str(&format!("\n{material} cone {name}.c{i}\n0\n0\n8\n"));
                let f = (lastr - r) / dist2(&lastp, &p);
                let along = |base: &[f64; 3], radius: f64| -> [f64; 3] {
                    std::array::from_fn(|k| base[k] + f * radius * (p[k] - lastp[k]))
                };
                line(&mut out, &along(&lastp, lastr));
                line(&mut out, &along(&p, r));
                let f = 1.0 - (lastr - r) * f;
                let f = if f <= 0.0 { 0.0 } else { f.sqrt() };
                out.push_str(&format!("{} {}\n", g(f * lastr, 18, 12), g(f * r, 18, 12)));
            }
        }
        out.push_str(&format!(
            "\n{material} sphere {name}.s{i}\n0\n0\n4 {} {} {} {}\n",
            g(p[0], 18, 12),
            g(p[1], 18, 12),
            g(p[2], 18, 12),
            g(r, 18, 12)
        ));
        lastp = p;
        lastr = r;
    }
    Ok(out)
}

/// Output channel `channel` of the curve program.
fn output<'m>(module: &'m Module, ev: &mut Evaluator<'m>, channel: u32) -> Result<f64, GenError> {
    let out = module
        .outputs()
        .get(&channel)
        .ok_or_else(|| GenError::Invalid("missing curve output".into()))?;
    ev.eval_top(&out.body, &mut NoInput)
        .map_err(|e| GenError::Invalid(format!("calcomp: {e}")))
}

/// More segments than this are refused rather than filling memory.
const MAX_SEGMENTS: i64 = 10_000_000;

fn compile(module: &mut Module, text: &str, what: &str) -> Result<(), GenError> {
    let diagnostics = module.add_source(FileId(0), text);
    match diagnostics.iter().find(|d| d.is_error()) {
        None => Ok(()),
        Some(d) => Err(GenError::Invalid(format!("in {what}: {}", d.message))),
    }
}

fn line(out: &mut String, p: &[f64; 3]) {
    out.push_str(&format!(
        "{} {} {}\n",
        g(p[0], 18, 12),
        g(p[1], 18, 12),
        g(p[2], 18, 12)
    ));
}

/// `dist2()`: squared distance, summed `x² + (y² + z²)` as the oracle's -ffast-math
/// build compiles it.
fn dist2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    d[0] * d[0] + (d[1] * d[1] + d[2] * d[2])
}
