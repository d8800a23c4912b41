//! The engines of Radiance's picture programs (getinfo, pvalue, pfilt, pflip,
//! protate, ra_ppm, ra_rgbe, ra_xyze): each takes its options and the input's bytes and gives the
//! output's bytes, or a message, as the C program would write them. Reading files,
//! parsing arguments, writing and exit codes are the caller's (the `radc` binary's
//! `cli::picture_tools`), so these never touch the file system or standard streams.

pub mod getinfo;
pub mod pfilt;
pub mod pflip;
pub mod protate;
pub mod pvalue;
pub mod ra_ppm;
pub mod ra_rgbe;
pub mod ra_xyze;
pub mod radcompare;

/// What a picture program writes about its own run into the header it makes.
#[derive(Clone, Debug, Default)]
pub struct Run {
    /// The `printargs` line (see [`command_line`]), newline included.
    pub command_line: String,
    /// Where the output starts in its file (C's `ftell(stdout)`), for the padding of
    /// binary `FORMAT=` lines; `None` on a pipe or terminal, where `ftell` fails.
    pub output_start: Option<u64>,
}

/// C's `%.{prec}e` ([`radc_lang::c_number::format_e`]) right-aligned in `width` columns.
pub fn c_exp_width(v: f64, width: usize, prec: usize) -> String {
    format!("{:>width$}", radc_lang::c_number::format_e(v, prec))
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
pub fn command_line(program: &str, args: &[String]) -> String {
    let mut line = program.to_string();
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

/// The `FORMAT=` line as `fputformat` writes it when `written` header bytes precede it
/// on an output that started at `start` (`None`: not seekable, no padding): binary
/// number formats are padded with blanks so the data begins on a multiple of their size.
pub fn format_line(format: &str, start: Option<u64>, written: usize) -> String {
    let align: u64 = if crate::Picture::is_format(format) {
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
