//! `genworm material name x(t) y(t) z(t) r(t) nseg [-e expr] [-f file]`
//!
//! Reproduces Radiance's `src/gen/genworm.c`: a worm along the curve `(x, y, z)(t)`,
//! `t` from 0 to 1 in `nseg` steps, with radius `r(t)`: a sphere at every step joined
//! by a cylinder (equal radii, within 1e-6) or a cone trimmed to meet the spheres
//! tangentially. The four expressions are calcomp, evaluated with `lang::cal` after
//! the `-e` statements and `-f` files, with `PI` and genworm's `hermite`, `bezier`
//! and `bspline` (same formulas) defined.

use crate::curves::CurveProgram;
use crate::{GenError, Host, command_comment};
use radc_lang::c_number::format_g_width as g;

const USAGE: &str = "genworm material name x(t) y(t) z(t) r(t) nseg [-e expr] [-f file]";
const FTINY: f64 = 1e-6;

/// The scene genworm prints for `args` (the words after `genworm`); `-f` files come
/// through `host`.
/// On failure (a calcomp error at some point of the curve), what was written up to
/// there, as the C program leaves it on standard output.
pub fn genworm(args: &[String], host: &mut dyn Host) -> Result<String, crate::Failure> {
    crate::Failure::keeping_partial("genworm", |out| write(args, host, out))
}

fn write(args: &[String], host: &mut dyn Host, out: &mut String) -> Result<(), GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 7 {
        return Err(usage());
    }
    let mut program = CurveProgram::new()?;
    let mut i = 7;
    while i < args.len() {
        let value = args.get(i + 1).ok_or_else(usage)?;
        match args[i].as_str() {
            option @ ("-e" | "-f") => program.load_option(option, value, host)?,
            _ => return Err(usage()),
        }
        i += 2;
    }
    let curves: Vec<(&str, &str)> = ["X", "Y", "Z", "R"]
        .into_iter()
        .zip(args[2..6].iter().map(String::as_str))
        .collect();
    program.define(&["t"], &curves, &[])?;
    let nseg = (program.eval(&args[6])? + 0.5) as i64;
    if nseg <= 0 {
        return Err(usage());
    }
    if nseg > MAX_SEGMENTS {
        return Err(GenError::Invalid(format!(
            "{nseg} segments: radc makes at most {MAX_SEGMENTS}"
        )));
    }
    program.optimize();
    let mut ev = program.evaluator();
    *out = command_comment("genworm", args);
    let (material, name) = (&args[0], &args[1]);
    let (mut lastp, mut lastr) = ([0.0; 3], 0.0);
    // The oracle's genworm is built with -ffast-math, which turns `i/nseg` into
    // `i * (1/nseg)`; the last bit of t shows in cos(6*PI*t) near its zeros.
    let step = 1.0 / nseg as f64;
    for i in 0..=nseg {
        let t = i as f64 * step;
        let v = ev.at(&[t])?;
        let (p, r) = ([v[0], v[1], v[2]], v[3]);
        if i > 0 {
            if lastr <= r + FTINY && lastr >= r - FTINY {
                out.push_str(&format!("\n{material} cylinder {name}.c{i}\n0\n0\n7\n"));
                line(out, &lastp);
                line(out, &p);
                out.push_str(&format!("{}\n", g(r, 18, 12)));
            } else {
                out.push_str(&format!("\n{material} cone {name}.c{i}\n0\n0\n8\n"));
                let f = (lastr - r) / dist2(&lastp, &p);
                let along = |base: &[f64; 3], radius: f64| -> [f64; 3] {
                    std::array::from_fn(|k| base[k] + f * radius * (p[k] - lastp[k]))
                };
                line(out, &along(&lastp, lastr));
                line(out, &along(&p, r));
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
    Ok(())
}

/// More segments than this are refused rather than filling memory.
const MAX_SEGMENTS: i64 = 1_000_000;

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
