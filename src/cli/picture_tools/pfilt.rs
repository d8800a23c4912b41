//! `radc pfilt`: Radiance's pfilt (see `radc_picture::tools::pfilt`). `pfilt [options]
//! [picture]`, the picture from standard input when not named; the result on standard
//! output.

use std::process::ExitCode;

use radc_lang::c_number::{atof, atoi};
use radc_picture::tools::pfilt::{self, Options, Size};
use radc_picture::tools::{Run, command_line};

use super::{fail, read_input, write_output};

const NAME: &str = "pfilt";
const FTINY: f64 = 1e-6;

/// The options and the index of the first file argument.
fn parse(args: &[String]) -> Result<(Options, usize), String> {
    let mut o = Options::default();
    let mut i = 0;
    let value = |i: usize| {
        args.get(i + 1)
            .map(String::as_str)
            .ok_or_else(|| format!("{} needs a value", args[i]))
    };
    let unsupported = |what: &str| format!("{what} is not supported by radc pfilt");
    let mut stars = 0;
    let mut lamp = false;
    while let Some(a) = args.get(i).filter(|a| a.starts_with('-')) {
        let b = a.as_bytes();
        match b.get(1) {
            Some(b'x' | b'y') => {
                let v = value(i)?;
                let size = match v.strip_prefix('/') {
                    Some(n) => Size::Fraction(1.0 / atof(n)),
                    None => Size::Pixels(i64::from(atoi(v))),
                };
                if b[1] == b'x' {
                    o.x = size;
                } else {
                    o.y = size;
                }
                i += 1;
            }
            Some(b'c') => o.correct_aspect = !o.correct_aspect,
            Some(b'p') => {
                o.output_aspect = atof(value(i)?);
                i += 1;
            }
            Some(b'e') => {
                let v = value(i)?;
                let d = if v.starts_with(['+', '-']) {
                    2f64.powf(atof(v))
                } else {
                    atof(v)
                };
                if !(1e-20..=1e20).contains(&d) {
                    return Err("exposure out of range".into());
                }
                let channel = match b.get(2) {
                    None => None,
                    Some(b'r') => Some(0),
                    Some(b'g') => Some(1),
                    Some(b'b') => Some(2),
                    Some(_) => return Err(format!("unknown option: {a}")),
                };
                match channel {
                    None => o.exposure = o.exposure.map(|e| (f64::from(e) * d) as f32),
                    Some(k) => o.exposure[k] = (f64::from(o.exposure[k]) * d) as f32,
                }
                i += 1;
            }
            // The lamp table matters only with -t; the spread only with stars.
            Some(b'f' | b's') => {
                value(i)?;
                i += 1;
            }
            Some(b't') => {
                value(i)?;
                lamp = true;
                i += 1;
            }
            Some(b'1') => o.single_pass = true,
            Some(b'2') => o.single_pass = false,
            Some(b'n') => {
                stars = atoi(value(i)?) / 2;
                i += 1;
            }
            Some(b'a') => o.average_hot = !o.average_hot,
            Some(b'h') => {
                o.hot_level = atof(value(i)?);
                i += 1;
            }
            Some(b'r') => {
                o.radius = atof(value(i)?);
                i += 1;
            }
            Some(b'm') => {
                if atof(value(i)?) > FTINY {
                    return Err(unsupported("the threshold filter (-m)"));
                }
                if o.radius <= FTINY {
                    o.radius = 0.6;
                }
                i += 1;
            }
            Some(b'b') => o.radius = 0.0,
            _ => return Err(format!("unknown option: {a}")),
        }
        i += 1;
    }
    if stars > 0 {
        return Err(unsupported(
            "star patterns (-n), which pfilt draws at random,",
        ));
    }
    if lamp {
        return Err(unsupported("lamp colour correction (-t)"));
    }
    Ok((o, i))
}

pub fn run(args: &[String]) -> ExitCode {
    let (o, files_at) = match parse(args) {
        Ok(o) => o,
        Err(e) => return fail(NAME, e),
    };
    let files = &args[files_at..];
    if files.len() > 1 {
        return fail(NAME, "bad # file arguments");
    }
    let path = files.first().map(String::as_str);
    let data = match read_input(path) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let run = Run {
        command_line: command_line(&crate::cli::programs::printed_name(NAME), &args[..files_at]),
        output_start: None,
    };
    match pfilt::filter(&o, &run, &data, path.unwrap_or("standard input")) {
        Ok(out) => write_output(NAME, None, &out),
        Err(e) => fail(NAME, e),
    }
}
