//! `radc ra_rgbe`: Radiance's ra_rgbe. Copies pictures from the input (a stream of them:
//! each is a frame) with flat scanlines, or run-length encoded with `-r`, each pixel's
//! exponent shifted by `-e +N`/`-e -N` stops; `-n N` takes only frame N (the `FRAME=`
//! header line numbers them). `ra_rgbe [-r][-e +/-stops][-f][-n frame] [input [outspec]]`:
//! outspec may hold a `%d` for the frame number, and an existing file is not
//! overwritten without `-f`. An outspec starting with `!` (a command to pipe into) is
//! refused: radc runs no shell.

use std::path::Path;
use std::process::ExitCode;

use radc_lang::c_number::atoi;
use radc_picture::tools::ra_rgbe;

use super::{FAILURE, fail, read_input};

const NAME: &str = "ra_rgbe";
const USAGE: &str = "usage: radc ra_rgbe [-r][-e +/-stops][-f][-n frame] [input [outspec]]";

pub fn run(args: &[String]) -> ExitCode {
    let mut options = ra_rgbe::Options {
        flat: true,
        stops: 0,
        frame: 0,
        program: crate::cli::programs::printed_name(NAME),
    };
    let o = &mut options;
    let mut force = false;
    let mut i = 0;
    while let Some(a) = args.get(i).filter(|a| a.starts_with('-')) {
        match a.as_bytes().get(1) {
            Some(b'r') => o.flat = !o.flat,
            Some(b'e') => match args.get(i + 1).filter(|v| v.starts_with(['+', '-'])) {
                Some(v) => {
                    o.stops = atoi(v);
                    i += 1;
                }
                None => return fail(NAME, USAGE),
            },
            Some(b'n') => match args.get(i + 1) {
                Some(v) => {
                    o.frame = i64::from(atoi(v));
                    i += 1;
                }
                None => return fail(NAME, USAGE),
            },
            Some(b'f') => force = true,
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
    let (frames, stopped) = ra_rgbe::frames(&options, &data, input.unwrap_or("standard input"));
    for frame in frames {
        match spec {
            None => stdout.extend_from_slice(&frame.bytes),
            Some(spec) => {
                let name = spec.replacen("%d", &frame.number.to_string(), 1);
                if !force && Path::new(&name).exists() {
                    return fail(NAME, format!("output file \"{name}\" exists"));
                }
                if let Err(e) = std::fs::write(&name, &frame.bytes) {
                    return fail(NAME, format!("cannot write {name}: {e}"));
                }
            }
        }
    }
    match stopped {
        Some(why) => fail(NAME, why),
        None => write_all(&stdout),
    }
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
