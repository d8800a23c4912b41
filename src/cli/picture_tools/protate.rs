//! `radc protate`: Radiance's protate. Turns a picture a quarter turn clockwise (`-r`:
//! counter-clockwise) in its scanlines; the orientation changes so programs that honour
//! it see the turned picture, unless `-c` keeps it. `protate [-r][-c] infile [outfile]`.
use radc_picture::Picture;
use radc_picture::tools::protate;
use std::process::ExitCode;

use super::{fail, read_input};
const NAME: &str = "protate";
const USAGE: &str = "usage: radc protate [-r][-c] infile [outfile]";
pub fn run(args: &[String]) -> ExitCode {
    let (mut ccw, mut correct) = (false, false);
    let mut i = 0;
    // protate reads options while more than one argument remains, by their second letter.
    while args.len() - i > 1 && args[i].starts_with('-') {
        match args[i].as_bytes().get(1) {
            Some(b'c') => correct = true,
            Some(b'r') => ccw = true,
            _ => return fail(NAME, USAGE),
        }
        i += 1;
    }
    let files = &args[i..];
    if files.is_empty() || files.len() > 2 {
        return fail(NAME, USAGE);
    }
    let data = match read_input(Some(&files[0])) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let picture = match Picture::read(&data) {
        Ok(p) => p,
        Err(e) => return fail(NAME, format!("{}: {e}", files[0])),
    };
    // protate's line names only its options it used, in this order.
    let mut command = crate::cli::programs::printed_name(NAME);
    if ccw {
        command.push_str(" -r");
    }
    if correct {
        command.push_str(" -c");
    }
    command.push('\n');
    let out = protate::convert(&picture, ccw, correct, &command);
    super::write_output(NAME, files.get(1).map(String::as_str), &out)
}
