//! `genrev material name z(t) r(t) nseg [-e expr] [-f file] [-s]`
//!
//! Reproduces Radiance's `src/gen/genrev.c`: the surface swept by rotating the curve
//! `(z(t), r(t))`, `t` from 0 to 1, about the z axis, as cones, cups, cylinders, tubes
//! and rings, one per segment. The normal points outward where z increases, inward
//! where it decreases. `-s` adds a `rev.cal` Phong texture per segment that
//! interpolates the normal between neighbouring segments.

use crate::curves::CurveProgram;
use crate::{GenError, Host, command_comment};
use radc_lang::c_number::format_g_width as g;

const USAGE: &str = "genrev material name z(t) r(t) nseg [-e expr] [-f file] [-s]";
/// genrev's own tolerance for a coordinate not changing.
const FTINY: f64 = 1e-9;
/// More segments than this are refused rather than filling memory.
const MAX_SEGMENTS: i64 = 1_000_000;

/// Which way a segment moves: along z and in radius.
#[derive(Clone, Copy, PartialEq)]
enum Motion {
    Less,
    Same,
    More,
}

fn motion(now: f64, before: f64) -> Motion {
    if now < before - FTINY {
        Motion::Less
    } else if now > before + FTINY {
        Motion::More
    } else {
        Motion::Same
    }
}

/// `computen()`: the unit normal (z, r components) of the segment from (z0, r0) to
/// (z1, r1), at right angles to it.
fn normal(z0: f64, r0: f64, z1: f64, r1: f64) -> (f64, f64) {
    let dz = r0 - r1;
    let dr = z1 - z0;
    let len = (dr * dr + dz * dz).sqrt();
    (dz / len, dr / len)
}

/// The scene genrev prints for `args` (the words after `genrev`); `-f` files come
/// through `host`.
/// On failure (a calcomp error at some point of the curve), what was written up to
/// there, as the C program leaves it on standard output.
pub fn genrev(args: &[String], host: &mut dyn Host) -> Result<String, crate::Failure> {
    crate::Failure::keeping_partial("genrev", |out| write(args, host, out))
}

fn write(args: &[String], host: &mut dyn Host, out: &mut String) -> Result<(), GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 5 {
        return Err(usage());
    }
    let mut program = CurveProgram::new()?;
    let mut smooth = false;
    let mut i = 5;
    while i < args.len() {
        match args[i].as_str() {
            "-s" => smooth = true,
            option @ ("-e" | "-f") => {
                i += 1;
                let value = args.get(i).ok_or_else(usage)?;
                program.load_option(option, value, host)?;
            }
            _ => return Err(usage()),
        }
        i += 1;
    }
    program.define(&["t"], &[("Z", &args[2]), ("R", &args[3])], &[])?;
    let nseg = (program.eval(&args[4])? + 0.5) as i64;
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
    let (material, name) = (&args[0], &args[1]);
    let modifier = if smooth { "Phong" } else { material.as_str() };
    *out = command_comment("genrev", args);
    let at = |ev: &mut crate::curves::CurveEval<'_>, t: f64| -> Result<(f64, f64), GenError> {
        let v = ev.at(&[t])?;
        Ok((v[0], v[1]))
    };
    // The oracle's -ffast-math build computes `(i+1)/nseg` as `(i+1) * (1/nseg)`.
    let step = 1.0 / nseg as f64;
    let (mut lastz, mut lastr) = at(&mut ev, 0.0)?;
    let (mut z, mut r) = at(&mut ev, step)?;
    let (mut lastnz, mut lastnr) = (0.0, 0.0);
    let (mut nz, mut nr) = normal(lastz, lastr, z, r);
    for i in 1..=nseg {
        let (mut nextz, mut nextr, mut nextnz, mut nextnr) = (0.0, 0.0, 0.0, 0.0);
        if i < nseg {
            (nextz, nextr) = at(&mut ev, (i + 1) as f64 * step)?;
            (nextnz, nextnr) = normal(z, r, nextz, nextr);
        }
        let (along, across) = (motion(z, lastz), motion(r, lastr));
        if (along, across) != (Motion::Same, Motion::Same) {
            if smooth {
                out.push_str(&format!(
                    "\n{material} texfunc Phong\n4 rev_dx rev_dy rev_dz rev.cal\n0\n4\n"
                ));
                if along != Motion::Same {
                    let t = (nextnz - lastnz) / (z - lastz);
                    out.push_str(&format!(
                        "\t{}\t{}\n",
                        g(t, 18, 12),
                        g(lastnz - t * lastz, 18, 12)
                    ));
                } else {
                    let sign = if across == Motion::Less { 1 } else { -1 };
                    out.push_str(&format!("\t0\t{sign}\n"));
                }
                if across != Motion::Same {
                    let t = (nextnr - lastnr) / (r - lastr);
                    out.push_str(&format!(
                        "\t{}\t{}\n",
                        g(t, 18, 12),
                        g(lastnr - t * lastr, 18, 12)
                    ));
                } else {
                    let sign = if along == Motion::More { 1 } else { -1 };
                    out.push_str(&format!("\t0\t{sign}\n"));
                }
            }
            let down = along == Motion::Less;
            if across == Motion::Same {
                let kind = if down { "tube" } else { "cylinder" };
                out.push_str(&format!("\n{modifier} {kind} {name}.{i}\n0\n0\n7\n"));
                out.push_str(&format!("\t0\t0\t{}\n", g(lastz, 18, 12)));
                out.push_str(&format!("\t0\t0\t{}\n", g(z, 18, 12)));
                out.push_str(&format!("\t{}\n", g(r, 18, 12)));
            } else if along == Motion::Same {
                let direction = if across == Motion::Less { 1.0 } else { -1.0 };
                out.push_str(&format!("\n{modifier} ring {name}.{i}\n0\n0\n8\n"));
                out.push_str(&format!("\t0\t0\t{}\n", g(z, 18, 12)));
                out.push_str(&format!("\t0\t0\t{}\n", g(direction, 18, 12)));
                out.push_str(&format!("\t{}\t{}\n", g(lastr, 18, 12), g(r, 18, 12)));
            } else {
                let kind = if down { "cup" } else { "cone" };
                out.push_str(&format!("\n{modifier} {kind} {name}.{i}\n0\n0\n8\n"));
                out.push_str(&format!("\t0\t0\t{}\n", g(lastz, 18, 12)));
                out.push_str(&format!("\t0\t0\t{}\n", g(z, 18, 12)));
                out.push_str(&format!("\t{}\t{}\n", g(lastr, 18, 12), g(r, 18, 12)));
            }
        }
        (lastz, lastr) = (z, r);
        (z, r) = (nextz, nextr);
        (lastnz, lastnr) = (nz, nr);
        (nz, nr) = (nextnz, nextnr);
    }
    Ok(())
}
