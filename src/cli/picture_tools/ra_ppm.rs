//! `radc ra_ppm`: Radiance's ra_ppm. Converts an RGBE picture to a Poskanzer pixmap
//! (binary P6, `-a` ASCII P3, `-b` greyscale P5/P2) through Radiance's integer gamma
//! tables (`colrops.c`: `-g` gamma, 2.2 by default; `-e +N`/`-e -N` stops), and `-r` a
//! pixmap (P2, P3, P5, P6) back to a picture. Scanlines go in file order, as ra_ppm
//! writes them. `ra_ppm [-r][-a][-b][-s maxv][-g gamma][-e +/-stops] [input [output]]`.
//! Pixmaps of more than 8 bits a sample (`-s` or a maxval above 255) take ra_ppm's
//! floating-point path, which radc does not implement: they are refused.
use radc_lang::c_number::atof;
use radc_picture::tools::ra_ppm::{self, Options, SIXTEEN};
use radc_picture::tools::{Run, command_line};
use std::process::ExitCode;

use super::{fail, read_input, write_output};
const NAME: &str = "ra_ppm";
const USAGE: &str =
    "usage: radc ra_ppm [-r][-a][-b][-s maxv][-g gamma][-e +/-stops] [input [output]]";
pub fn run(args: &[String]) -> ExitCode {
    let mut o = Options {
        grey: false,
        binary: true,
        reverse: false,
        gamma: 2.2,
        stops: 0,
        maxval: 255,
    };
    let mut i = 0;
    while let Some(a) = args.get(i).filter(|a| a.starts_with('-')) {
        let next = args.get(i + 1);
        match (a.as_bytes().get(1), next) {
            (Some(b's'), Some(v)) => {
                o.maxval = (atof(v) as i64 & 0xffff) as u32;
                i += 1;
            }
            (Some(b'g'), Some(v)) => {
                o.gamma = atof(v);
                i += 1;
            }
            (Some(b'e'), Some(v)) if v.starts_with(['+', '-']) => {
                o.stops = atof(v) as i32;
                i += 1;
            }
            (Some(b'b'), _) => o.grey = true,
            (Some(b'a'), _) => o.binary = false,
            (Some(b'r'), _) => o.reverse = !o.reverse,
            _ => return fail(NAME, USAGE),
        }
        i += 1;
    }
    let files = &args[i..];
    if files.len() > 2 {
        return fail(NAME, USAGE);
    }
    if o.maxval >= 256 {
        return fail(NAME, SIXTEEN);
    }
    let data = match read_input(files.first().map(String::as_str)) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let run = Run {
        command_line: command_line(&crate::cli::programs::printed_name(NAME), &args[..i]),
        output_start: None,
    };
    match ra_ppm::convert(&o, &run, &data) {
        Ok(out) => write_output(NAME, files.get(1).map(String::as_str), &out),
        Err(e) => fail(NAME, e),
    }
}
