//! The picture commands (`radc getinfo pvalue pflip protate ra_ppm ra_rgbe ra_xyze`): thin shells over
//! `radc_picture` with the options, outputs and exit codes of Radiance's programs
//! (1 for every error, usage errors included, as those programs exit). Messages name
//! the file and, for damaged pictures, the byte offset.

pub mod getinfo;
pub mod pflip;
pub mod protate;
pub mod pvalue;
pub mod ra_ppm;
pub mod ra_rgbe;
pub mod ra_xyze;

use std::io::{Read, Write};
use std::os::fd::AsFd;
use std::process::ExitCode;

/// Radiance's picture programs exit 1 on any error.
pub const FAILURE: u8 = 1;

/// An error message (`radc <command>: ...`) and exit status 1.
pub fn fail(command: &str, message: impl std::fmt::Display) -> ExitCode {
    eprintln!("radc {command}: {message}");
    ExitCode::from(FAILURE)
}

/// The whole of a file, or of standard input for `None`.
pub fn read_input(path: Option<&str>) -> Result<Vec<u8>, String> {
    match path {
        Some(p) => std::fs::read(p).map_err(|e| format!("cannot open {p}: {e}")),
        None => {
            let mut data = Vec::new();
            std::io::stdin()
                .lock()
                .read_to_end(&mut data)
                .map_err(|e| format!("cannot read standard input: {e}"))?;
            Ok(data)
        }
    }
}

/// One word of a command line as `fputword` writes it: in double quotes when it is
/// empty or has blanks, in the other kind of quote when it holds a quote character
/// (after its first, not last).
pub fn word(s: &str) -> String {
    let b = s.as_bytes();
    let has_space = b.iter().any(|c| c.is_ascii_whitespace());
    let mut quote = None;
    for (i, &c) in b.iter().enumerate() {
        if i > 0 && i + 1 < b.len() {
            if c == b'"' {
                quote = Some('\'');
            } else if c == b'\'' {
                quote = Some('"');
            }
        }
    }
    if b.is_empty() || has_space || quote.is_some() {
        let q = quote.unwrap_or('"');
        format!("{q}{s}{q}")
    } else {
        s.to_string()
    }
}

/// The header line `printargs` writes for this run: `radc <command>` and the arguments
/// given, each as [`word`] quotes it.
pub fn command_line(command: &str, args: &[String]) -> String {
    let mut line = format!("radc {command}");
    for a in args {
        line.push(' ');
        line.push_str(&word(a));
    }
    line.push('\n');
    line
}

/// `printargs` of other words: each quoted by [`word`], blank-separated, a newline.
pub fn words_line(words: &[String]) -> String {
    let mut line = words.iter().map(|w| word(w)).collect::<Vec<_>>().join(" ");
    line.push('\n');
    line
}

/// Where standard output stands in its file: `fputformat` pads binary formats so the
/// data after the header is aligned, measured with `ftell(stdout)`, which fails (no
/// padding) on a pipe or terminal.
pub fn stdout_position() -> Option<u64> {
    use std::io::Seek;
    let fd = std::io::stdout().as_fd().try_clone_to_owned().ok()?;
    let mut f = std::fs::File::from(fd);
    f.stream_position().ok()
}

/// The `FORMAT=` line as `fputformat` writes it when `written` header bytes precede it
/// on an output that started at `start` (`None`: not seekable, no padding): binary
/// number formats are padded with blanks so the data begins on a multiple of their size.
pub fn format_line(format: &str, start: Option<u64>, written: usize) -> String {
    let align: u64 = if radc_picture::Picture::is_format(format) {
        0
    } else if format.starts_with("float") {
        4
    } else if format.starts_with("double") {
        8
    } else if format.starts_with("16-bit") {
        2
    } else if format.starts_with("32-bit") {
        4
    } else if format.starts_with("64-bit") {
        8
    } else {
        0
    };
    let mut line = format!("FORMAT={format}");
    if align > 0
        && let Some(start) = start
    {
        let pos = start + (written + line.len()) as u64;
        let r = (pos + 2) % align;
        if r != 0 {
            line.push_str(&" ".repeat((align - r) as usize));
        }
    }
    line.push('\n');
    line
}

/// C's `%.{prec}e`: a mantissa with `prec` decimals and an exponent of at least two
/// digits (`1.234e+05`), `inf`/`nan` spelled as glibc spells them.
pub fn c_exp(v: f64, prec: usize) -> String {
    if v.is_nan() {
        return if v.is_sign_negative() { "-nan" } else { "nan" }.into();
    }
    if v.is_infinite() {
        return if v < 0.0 { "-inf" } else { "inf" }.into();
    }
    let s = format!("{v:.prec$e}");
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    let (sign, digits) = match e.strip_prefix('-') {
        Some(d) => ('-', d),
        None => ('+', e),
    };
    format!("{m}e{sign}{digits:0>2}")
}

/// `%{width}.{prec}e`, right-aligned.
pub fn c_exp_width(v: f64, width: usize, prec: usize) -> String {
    format!("{:>width$}", c_exp(v, prec))
}

/// Writes `bytes` to standard output, reporting a failed write as the command's error.
pub fn write_stdout(command: &str, bytes: &[u8]) -> Result<(), ExitCode> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)
        .and_then(|_| out.flush())
        .map_err(|e| fail(command, format!("write error: {e}")))
}

/// Writes the finished output to `path`, or to standard output. Called only once the
/// whole output is made, so a failure leaves no partial file behind.
pub fn write_output(command: &str, path: Option<&str>, bytes: &[u8]) -> ExitCode {
    match path {
        Some(p) => match std::fs::write(p, bytes) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(command, format!("cannot write {p}: {e}")),
        },
        None => match write_stdout(command, bytes) {
            Ok(()) => ExitCode::SUCCESS,
            Err(code) => code,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_are_quoted_as_fputword_quotes_them() {
        assert_eq!(word("-h"), "-h");
        assert_eq!(word("a b"), "\"a b\"");
        assert_eq!(word(""), "\"\"");
        assert_eq!(word("it's"), "\"it's\"");
        assert_eq!(word("say\"x\"y"), "'say\"x\"y'");
        assert_eq!(word("x'"), "x'");
    }

    #[test]
    fn exponents_print_as_c_prints_them() {
        assert_eq!(c_exp(0.26901207, 3), "2.690e-01");
        assert_eq!(c_exp(0.0, 3), "0.000e+00");
        assert_eq!(c_exp(1.5e100, 4), "1.5000e+100");
        assert_eq!(c_exp_width(-2.5, 15, 3), "     -2.500e+00");
        assert_eq!(c_exp(f64::INFINITY, 3), "inf");
    }

    #[test]
    fn binary_formats_are_aligned() {
        assert_eq!(format_line("ascii", Some(0), 10), "FORMAT=ascii\n");
        // 10 + "FORMAT=float" (12) + newline and the empty line (2) = 24: aligned.
        assert_eq!(format_line("float", Some(0), 10), "FORMAT=float\n");
        assert_eq!(format_line("float", Some(0), 11), "FORMAT=float   \n");
        assert_eq!(format_line("float", None, 11), "FORMAT=float\n");
        assert_eq!(
            format_line("32-bit_rle_rgbe", Some(0), 11),
            "FORMAT=32-bit_rle_rgbe\n"
        );
    }
}
