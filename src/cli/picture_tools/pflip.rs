//! `radc pflip`: Radiance's pflip. `-h` flips the picture left to right, `-v` top to
//! bottom; the resolution line's orientation changes with the flip (so programs that
//! honour it see the same picture laid out the other way), unless `-c` keeps it, which
//! corrects a picture whose orientation was wrong. `pflip [-h][-v][-c] [in [out]]`;
//! `-v` needs a named input, as pflip seeks in it.
use radc_picture::Picture;
use radc_picture::tools::{command_line, pflip};
use std::process::ExitCode;

use super::{fail, read_input};
const NAME: &str = "pflip";
const USAGE: &str = "usage: radc pflip [-h][-v][-c] infile [outfile]";
pub fn run(args: &[String]) -> ExitCode {
    let (mut horizontal, mut vertical, mut correct) = (false, false, false);
    let mut i = 0;
    while let Some(a) = args.get(i) {
        match a.as_str() {
            "-h" => horizontal = true,
            "-v" => vertical = true,
            "-c" => correct = true,
            _ => break,
        }
        i += 1;
    }
    let files = &args[i..];
    if files.len() > 2 {
        return fail(NAME, USAGE);
    }
    if !horizontal && !vertical {
        eprintln!("radc pflip: warning - no operation");
    }
    let input = files.first().filter(|f| !f.starts_with('-'));
    if input.is_none() && vertical {
        return fail(NAME, format!("-v needs an input file\n{USAGE}"));
    }
    let data = match read_input(input.map(String::as_str)) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let what = input.map_or("standard input", |s| s.as_str());
    let picture = match Picture::read(&data) {
        Ok(p) => p,
        Err(e) => return fail(NAME, format!("{what}: {e}")),
    };
    let command = command_line(&crate::cli::programs::printed_name(NAME), &args[..i]);
    let out = pflip::convert(&picture, horizontal, vertical, correct, &command);
    super::write_output(NAME, files.get(1).map(String::as_str), &out)
}
