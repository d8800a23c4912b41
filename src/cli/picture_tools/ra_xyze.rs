//! `radc ra_xyze`: Radiance's ra_xyze. Converts an RGBE picture to XYZE (CIE XYZ, with
//! the EXPOSURE that keeps Y in luminance units: 1/179), `-r` an XYZE (or RGBE) picture
//! to RGBE in the standard primaries or `-p rx ry gx gy bx by wx wy`, colours below the
//! gamut's floor desaturated to it (`clipgamut`). `-o` undoes the header's exposure,
//! `-e` scales (`+N`/`-N`: stops), `-c`/`-u` choose run-length or flat scanlines (flat
//! for XYZE, encoded for RGBE by default). `ra_xyze [options] [input [output]]`.
//!
//! The arithmetic is `spec_rgb.c`'s: matrices computed in double from single-precision
//! chromaticities and kept in single precision, colours transformed in single
//! precision. White balancing (a von Kries transform, needed when the input and output
//! whites differ) is not supported and is refused.
use radc_lang::c_number::atof;
use radc_picture::tools::ra_xyze::{self, Options, STD};
use radc_picture::tools::{Run, command_line};
use std::process::ExitCode;

use super::{fail, read_input, write_output};
const NAME: &str = "ra_xyze";
const USAGE: &str =
    "usage: radc ra_xyze [-r][-o][-e exp][-c|-u][-p rx ry gx gy bx by wx wy] [input [output]]";
pub fn run(args: &[String]) -> ExitCode {
    let mut o = Options {
        flat: None,
        rgb_out: false,
        out_prims: STD,
        original: false,
        exposure: 1.0,
    };
    let mut i = 0;
    while let Some(a) = args.get(i).filter(|a| a.starts_with('-')) {
        match a.as_bytes().get(1) {
            Some(b'c') => o.flat = Some(false),
            Some(b'u') => o.flat = Some(true),
            Some(b'r') => o.rgb_out = true,
            Some(b'o') => o.original = true,
            Some(b'p') => {
                if i + 8 >= args.len() {
                    return fail(NAME, USAGE);
                }
                for k in 0..8 {
                    o.out_prims[k / 2][k % 2] = atof(&args[i + 1 + k]) as f32;
                }
                i += 8;
            }
            Some(b'e') => {
                let Some(v) = args.get(i + 1) else {
                    return fail(NAME, USAGE);
                };
                o.exposure = atof(v);
                if v.starts_with(['+', '-']) {
                    o.exposure = 2f64.powf(o.exposure);
                }
                i += 1;
            }
            _ => return fail(NAME, USAGE),
        }
        i += 1;
    }
    let files = &args[i..];
    if files.len() > 2 {
        return fail(NAME, USAGE);
    }
    let data = match read_input(files.first().map(String::as_str)) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let what = files.first().map_or("standard input", String::as_str);
    let run = Run {
        command_line: command_line(&crate::cli::programs::printed_name(NAME), args),
        output_start: None,
    };
    match ra_xyze::convert(&o, &run, &data, what) {
        Ok(out) => write_output(NAME, files.get(1).map(String::as_str), &out),
        Err(e) => fail(NAME, e),
    }
}
