//! `radc ra_rgbe`: Radiance's ra_rgbe. Copies pictures from the input (a stream of them:
//! each is a frame) with flat scanlines, or run-length encoded with `-r`, each pixel's
//! exponent shifted by `-e +N`/`-e -N` stops; `-n N` takes only frame N (the `FRAME=`
//! header line numbers them). `ra_rgbe [-r][-e +/-stops][-f][-n frame] [input [outspec]]`:
//! outspec may hold a `%d` for the frame number, and an existing file is not
//! overwritten without `-f`. An outspec starting with `!` (a command to pipe into) is
//! refused: radc runs no shell.

use std::path::Path;
use std::process::ExitCode;

use radc_picture::{Picture, scanline};

use super::{FAILURE, c_exp, fail, format_line, read_input};

const NAME: &str = "ra_rgbe";
const USAGE: &str = "usage: radc ra_rgbe [-r][-e +/-stops][-f][-n frame] [input [outspec]]";

struct Options {
    flat: bool,
    stops: i32,
    frame: i64,
    force: bool,
}

pub fn run(args: &[String]) -> ExitCode {
    let mut o = Options {
        flat: true,
        stops: 0,
        frame: 0,
        force: false,
    };
    let mut i = 0;
    while let Some(a) = args.get(i).filter(|a| a.starts_with('-')) {
        match a.as_bytes().get(1) {
            Some(b'r') => o.flat = !o.flat,
            Some(b'e') => match args.get(i + 1).filter(|v| v.starts_with(['+', '-'])) {
                Some(v) => {
                    o.stops = atoi(v) as i32;
                    i += 1;
                }
                None => return fail(NAME, USAGE),
            },
            Some(b'n') => match args.get(i + 1) {
                Some(v) => {
                    o.frame = atoi(v);
                    i += 1;
                }
                None => return fail(NAME, USAGE),
            },
            Some(b'f') => o.force = true,
            None => break,
            Some(_) => return fail(NAME, USAGE),
        }
        i += 1;
    }
    let files = &args[i..];
    if files.len() > 2 {
        return fail(NAME, USAGE);
    }
    let input = files.first().map(String::as_str).filter(|f| *f != "-");
    let data = match read_input(input) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let spec = files.get(1).map(String::as_str);
    if spec.is_some_and(|s| s.starts_with('!')) {
        return fail(
            NAME,
            "an output starting with '!' is a command to run, which radc does not do",
        );
    }
    let mut stdout = Vec::new();
    let mut pos = 0;
    // Header lines are kept across frames as ra_rgbe keeps them: the second frame adds
    // to the first's, later ones to the first's again (its `headlen1`).
    let mut first_len = 0;
    let mut lines: Vec<u8> = Vec::new();
    let mut format: Option<String> = None;
    loop {
        if radc_picture::Header::parse(&data[pos..]).is_err() {
            break;
        }
        if first_len == 0 {
            first_len = lines.len();
        } else {
            lines.truncate(first_len);
        }
        let (picture, used) =
            match Picture::read_prefix(&data[pos..], radc_picture::DEFAULT_MAX_PIXELS) {
                Ok(p) => p,
                Err(e) => return fail(NAME, format!("{}: {e}", input.unwrap_or("standard input"))),
            };
        pos += used;
        let mut frame = 0;
        for l in &picture.header.lines {
            let b = &l.0;
            if b.starts_with(b"#?") || b.starts_with(b"WAVELENGTH_SPLITS=") {
                continue;
            }
            if let Some(v) = l.value_after("FRAME=") {
                frame = atoi(&v);
                continue;
            }
            if let Some(f) = l.format() {
                format = Some(f);
                continue;
            }
            if let Some(v) = l.value_after("NCOMP=") {
                match atoi(&v) {
                    3 => continue,
                    // getheader gives up on the header: ra_rgbe stops, as at the end.
                    n if n < 3 => return write_all(&stdout),
                    _ => {
                        return fail(
                            NAME,
                            "spectral pictures (NCOMP= above 3) are not supported by radc ra_rgbe",
                        );
                    }
                }
            }
            lines.extend_from_slice(b);
        }
        if o.frame != 0 && o.frame < frame {
            break;
        }
        if o.frame > frame {
            continue;
        }
        let mut out = b"#?RADIANCE\n".to_vec();
        out.extend_from_slice(&lines);
        out.extend_from_slice(b"radc ra_rgbe");
        if o.stops != 0 {
            out.extend_from_slice(format!(" -e {:+}", o.stops).as_bytes());
        }
        if !o.flat {
            out.extend_from_slice(b" -r");
        }
        out.push(b'\n');
        if o.stops != 0 {
            let e = 2f64.powi(o.stops);
            out.extend_from_slice(format!("EXPOSURE={}\n", c_exp(e, 4)).as_bytes());
        }
        if frame != 0 {
            out.extend_from_slice(format!("FRAME={frame}\n").as_bytes());
        }
        if let Some(f) = &format {
            out.extend_from_slice(format_line(f, None, 0).as_bytes());
        }
        out.push(b'\n');
        out.extend_from_slice(picture.resolution.line().as_bytes());
        let mut scan = Vec::new();
        for s in 0..picture.resolution.scan_count() {
            scan.clear();
            scan.extend_from_slice(picture.scanline(s));
            shift(&mut scan, o.stops);
            if o.flat {
                scan.iter().for_each(|p| out.extend_from_slice(p));
            } else {
                scanline::write(&scan, &mut out);
            }
        }
        match spec {
            None => stdout.extend_from_slice(&out),
            Some(spec) => {
                let name = spec.replacen("%d", &frame.to_string(), 1);
                if !o.force && Path::new(&name).exists() {
                    return fail(NAME, format!("output file \"{name}\" exists"));
                }
                if let Err(e) = std::fs::write(&name, &out) {
                    return fail(NAME, format!("cannot write {name}: {e}"));
                }
            }
        }
    }
    write_all(&stdout)
}

fn write_all(stdout: &[u8]) -> ExitCode {
    if stdout.is_empty() {
        return ExitCode::SUCCESS;
    }
    match super::write_stdout(NAME, stdout) {
        Ok(()) => ExitCode::SUCCESS,
        Err(_) => ExitCode::from(FAILURE),
    }
}

/// `shiftcolrs`: exponents moved by `stops`; pixels at or below the smallest exponent a
/// downward shift allows become black (the exponent byte wraps above 255, as in C).
fn shift(scan: &mut [[u8; 4]], stops: i32) {
    if stops == 0 {
        return;
    }
    let min = if stops < 0 { -stops } else { 0 };
    for p in scan {
        if i32::from(p[3]) <= min {
            *p = [0; 4];
        } else {
            p[3] = (i32::from(p[3]) + stops) as u8;
        }
    }
}

/// C's `atoi`: blanks, a sign, digits; 0 without digits.
fn atoi(s: &str) -> i64 {
    let s = s.trim_start();
    let (neg, digits) = match s.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, s.strip_prefix('+').unwrap_or(s)),
    };
    let n = digits
        .bytes()
        .take_while(u8::is_ascii_digit)
        .fold(0i64, |v, d| {
            (v * 10 + i64::from(d - b'0')).min(i64::from(i32::MAX))
        });
    if neg { -n } else { n }
}
