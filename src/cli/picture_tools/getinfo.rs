//! `radc getinfo`: Radiance's getinfo. Prints the information header of each file
//! (`file:` then each line after a tab), `-d` the resolution line instead (`+d` both),
//! `-` copies standard input without its header (`-d -`: without its resolution line
//! too), `-a line...` adds lines to the header of standard input, `-r var...` removes
//! the lines setting them (adding those given values), `-c command...` runs a
//! command on the data after the header and writes the header with the command added.
//! Works on any Radiance file (pictures, octrees, matrices), as getinfo does.
use super::{FAILURE, fail, format_line, read_input, stdout_position, words_line, write_stdout};
use radc_picture::tools::getinfo;
use radc_picture::{Header, Resolution};
use std::io::{BufRead, Read, Write};
use std::process::{ExitCode, Stdio};
const NAME: &str = "getinfo";
pub fn run(args: &[String]) -> ExitCode {
    // A first argument of -d or +d (getinfo looks at its first two characters only).
    let (dim, args) = match args.first().map(String::as_bytes) {
        Some([s @ (b'-' | b'+'), b'd', ..]) => (if *s == b'-' { -1 } else { 1 }, &args[1..]),
        _ => (0, args),
    };
    match args.first().map(String::as_str) {
        Some("-c") if args.len() > 1 => run_command(dim, &args[1..]),
        Some("-a") if args.len() > 1 => add_lines(&args[1..]),
        Some("-r") if args.len() > 1 => replace_lines(&args[1..]),
        Some("-") if args.len() == 1 => strip_header(dim),
        None => standard_input(dim),
        Some(_) => files(dim, args),
    }
}
fn files(dim: i32, names: &[String]) -> ExitCode {
    let mut out = Vec::new();
    for name in names {
        let Ok(data) = std::fs::read(name) else {
            out.extend_from_slice(name.as_bytes());
            out.extend_from_slice(b": cannot open\n");
            continue;
        };
        if let Err(e) = getinfo::file_listing(name, &data, dim, &mut out) {
            let _ = write_stdout(NAME, &out);
            eprintln!("{e}");
            return ExitCode::from(FAILURE);
        }
    }
    finish(write_stdout(NAME, &out))
}

/// No file names: the header of standard input, as is.
fn standard_input(dim: i32) -> ExitCode {
    let data = match read_input(None) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let mut out = Vec::new();
    let listed = getinfo::input_listing(&data, dim, &mut out);
    let written = write_stdout(NAME, &out);
    match listed {
        Ok(()) => finish(written),
        Err(e) => fail(NAME, e),
    }
}

/// `getinfo -`: standard input after its header (and after its resolution line, `-d`).
fn strip_header(dim: i32) -> ExitCode {
    let data = match read_input(None) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    match getinfo::strip_header(&data, dim) {
        Ok(rest) => finish(write_stdout(NAME, rest)),
        Err(e) => fail(NAME, e),
    }
}

/// `getinfo -a line...`: the header of standard input with the lines added before its
/// format line, then the rest of the input.
fn add_lines(lines: &[String]) -> ExitCode {
    let data = match read_input(None) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    match getinfo::add_lines(&data, lines, stdout_position()) {
        Ok(out) => finish(write_stdout(NAME, &out)),
        Err(e) => fail(NAME, e),
    }
}

/// `getinfo -r VAR...`: standard input with the named header lines removed and the
/// arguments that set values added.
fn replace_lines(args: &[String]) -> ExitCode {
    let data = match read_input(None) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    match getinfo::replace_lines(&data, args, stdout_position()) {
        Ok(out) => finish(write_stdout(NAME, &out)),
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(FAILURE)
        }
    }
}

fn finish(written: Result<(), ExitCode>) -> ExitCode {
    written.err().unwrap_or(ExitCode::SUCCESS)
}

/// `getinfo -c command...`: the header of standard input with the command line added,
/// then what the command writes given the rest of the input (`-d`: without the
/// resolution line; `+d`: the line is passed on, normalized). The exit status is the
/// command's. The command runs directly (no shell), as getinfo's `execvp`.
fn run_command(dim: i32, command: &[String]) -> ExitCode {
    let stdin = std::io::stdin();
    let mut input = stdin.lock();
    let mut head = Vec::new();
    // Read line by line up to the empty line, so the rest goes to the command untouched.
    loop {
        let mut line = Vec::new();
        match input.read_until(b'\n', &mut line) {
            Ok(0) | Err(_) => return fail(NAME, "bad header on standard input"),
            Ok(_) => {}
        }
        let end = line == b"\n" || line == b"\r\n";
        head.extend_from_slice(&line);
        if end {
            break;
        }
        if head.len() == line.len() && !line.first().is_some_and(|c| (0x20..0x7f).contains(c)) {
            return fail(NAME, "bad header on standard input");
        }
    }
    let header = match Header::parse(&head) {
        Ok((h, _)) => h,
        Err(e) => return fail(NAME, format!("bad header on standard input: {e}")),
    };
    let (mut out, format) = getinfo::header_without_format(&header.lines);
    out.extend_from_slice(words_line(command).as_bytes());
    if let Some(f) = format {
        out.extend_from_slice(format_line(&f, stdout_position(), out.len()).as_bytes());
    }
    out.push(b'\n');
    let mut first = Vec::new();
    if dim != 0 {
        let mut line = Vec::new();
        let _ = input.by_ref().take(31).read_until(b'\n', &mut line);
        let Some((res, _)) = Resolution::parse(&line) else {
            return fail(NAME, "no resolution string on standard input");
        };
        if dim > 0 {
            out.extend_from_slice(res.line().as_bytes());
        }
    }
    if let Err(code) = write_stdout(NAME, &out) {
        return code;
    }
    first.extend_from_slice(input.fill_buf().unwrap_or(&[]));
    let mut child = match std::process::Command::new(&command[0])
        .args(&command[1..])
        .stdin(Stdio::piped())
        .spawn()
    {
        Ok(c) => c,
        Err(e) => return fail(NAME, format!("{}: {e}", command[0])),
    };
    if let Some(mut to) = child.stdin.take() {
        // What is already buffered, then the rest of standard input.
        let n = first.len();
        let _ = to.write_all(&first);
        input.consume(n);
        let _ = std::io::copy(&mut input, &mut to);
    }
    match child.wait() {
        Ok(status) => ExitCode::from(status.code().unwrap_or(FAILURE as i32) as u8),
        Err(e) => fail(NAME, format!("{}: {e}", command[0])),
    }
}
