//! Radiance's `rsplit` (src/cal/rsplit.c): one input split field by field into several
//! outputs in turn. Each output takes N fields a record (`-oa[N]`, text up to its
//! terminator `-tC`, a newline by default, blanks for `-t` followed by a space) or N
//! binary values (`-of -od -oi -ow -ob`); `.` discards its share. `-ih`/`-iH` read the
//! input's header and resolution line; `-oh`/`-oH` write them to an output (the header's
//! lines but its format and counts, the command line, `NCOMP=`, the byte order and the
//! format). `-on N` (or `-x -y`) stops after N records.

use std::io::{self, BufRead, Write};

/// One output: where its share goes (`None`: discarded), what it takes, and whether it
/// gets a header and a resolution line.
pub struct SplitOutput<'a> {
    pub output: Option<Box<dyn Write + 'a>>,
    pub components: usize,
    /// Bytes a binary value (0: text fields).
    pub bytes: usize,
    pub terminator: u8,
    pub format: &'static str,
    pub header: bool,
    pub resolution: bool,
    /// Standard output, whose `NCOMP=` counts every field sent there.
    pub stdout: bool,
    /// Where the output starts in its file (`ftell`), for the `FORMAT=` line's padding.
    pub start: Option<u64>,
}

/// The run's settings.
pub struct Split<'a> {
    pub outputs: Vec<SplitOutput<'a>>,
    pub read_header: bool,
    pub read_resolution: bool,
    /// `-x -y`, or what the input's resolution line says.
    pub resolution: (i64, i64),
    pub records: i64,
    /// The command line each header records (`printargs`), newline included.
    pub command_line: String,
    /// `fputformat`: the `FORMAT=` line for a format, an output's start and the header
    /// bytes before the line.
    pub format_line: &'a dyn Fn(&str, Option<u64>, usize) -> String,
}

/// How a run ended.
#[derive(Debug, PartialEq, Eq)]
pub enum SplitEnd {
    Done,
    /// The input ended before `-on` records (rsplit's "premature EOD").
    Premature,
}

/// A problem rsplit reports by name (its exit status is 1).
#[derive(Debug, PartialEq, Eq)]
pub enum SplitError {
    Header,
    Resolution,
    NeedsResolution,
    Write,
}

impl std::fmt::Display for SplitError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SplitError::Header => "cannot read header from standard input",
            SplitError::Resolution => "bad resolution string on standard input",
            SplitError::NeedsResolution => "-oH option requires -iH or -x and -y options",
            SplitError::Write => "write error on one or more outputs",
        })
    }
}

const FIELD_MAX: usize = 16384;

/// rsplit.c `scanOK`: one field up to and including its terminator; `None` at the end
/// of the input (or past the field size limit).
fn field(input: &mut dyn BufRead, term: u8, buf: &mut Vec<u8>) -> io::Result<Option<()>> {
    buf.clear();
    let space = |c: u8| radc_lang::c_number::is_c_space(c);
    let mut skip_white = term == b' ';
    loop {
        let c = {
            let b = input.fill_buf()?;
            let Some(&c) = b.first() else {
                return Ok(None);
            };
            input.consume(1);
            c
        };
        if skip_white && space(c) {
            continue;
        }
        skip_white = false;
        let c = if c == b'\n' && space(term) { term } else { c };
        buf.push(c);
        if buf.len() >= FIELD_MAX {
            return Ok(None);
        }
        if if term == b' ' { space(c) } else { c == term } {
            return Ok(Some(()));
        }
    }
}

/// Runs the split of `input`, warnings to `warn` (`-on` disagreeing with the resolution).
pub fn split(
    s: &mut Split<'_>,
    input: &mut dyn BufRead,
    warn: &mut dyn FnMut(&str),
) -> Result<SplitEnd, SplitError> {
    let binary = s.outputs.iter().any(|o| o.bytes > 0);
    let mut swapped = false;
    let mut header_lines: Vec<Vec<u8>> = Vec::new();
    if s.read_header {
        loop {
            let mut line = Vec::new();
            if input
                .read_until(b'\n', &mut line)
                .map_err(|_| SplitError::Header)?
                == 0
            {
                return Err(SplitError::Header);
            }
            if line == b"\n" {
                break;
            }
            let skip = ["FORMAT=", "NROWS=", "NCOLS=", "NCOMP="]
                .iter()
                .any(|p| line.starts_with(p.as_bytes()));
            if let Some(v) = line.strip_prefix(b"BigEndian=") {
                let big = v.trim_ascii_start().first() == Some(&b'1');
                swapped = big != cfg!(target_endian = "big");
                continue;
            }
            if !skip {
                header_lines.push(line);
            }
        }
    }
    if s.read_resolution {
        let mut line = Vec::new();
        let _ = input.read_until(b'\n', &mut line);
        match radc_picture_resolution(&line) {
            Some(r) => s.resolution = r,
            None => return Err(SplitError::Resolution),
        }
    }
    let needs = s.outputs.iter().any(|o| o.resolution);
    if needs && (s.resolution.0 <= 0 || s.resolution.1 <= 0) {
        return Err(SplitError::NeedsResolution);
    }
    if s.resolution.0 > 0 && s.resolution.1 > 0 {
        let n = s.resolution.0 * s.resolution.1;
        if s.records <= 0 {
            s.records = n;
        } else if s.records != n {
            warn("warning: -on option does not agree with resolution");
        }
    }
    let stdout_components: usize = s
        .outputs
        .iter()
        .filter(|o| o.stdout)
        .map(|o| o.components)
        .sum();
    let (xr, yr) = s.resolution;
    for o in &mut s.outputs {
        let Some(out) = o.output.as_mut() else {
            continue;
        };
        let mut head = Vec::new();
        if o.header {
            if !s.read_header {
                head.extend_from_slice(b"#?RADIANCE\n");
            }
            header_lines.iter().for_each(|l| head.extend_from_slice(l));
            head.extend_from_slice(s.command_line.as_bytes());
            let n = if o.stdout {
                stdout_components
            } else {
                o.components
            };
            head.extend_from_slice(format!("NCOMP={n}\n").as_bytes());
            if o.bytes > 1 {
                let big = cfg!(target_endian = "big") ^ swapped;
                head.extend_from_slice(if big {
                    b"BigEndian=1\n"
                } else {
                    b"BigEndian=0\n"
                });
            }
            let line = (s.format_line)(o.format, o.start, head.len());
            head.extend_from_slice(line.as_bytes());
            head.push(b'\n');
        }
        if o.resolution {
            head.extend_from_slice(format!("-Y {yr:8} +X {xr:8}\n").as_bytes());
        }
        out.write_all(&head).map_err(|_| SplitError::Write)?;
    }
    let last_term = s.outputs.last().map_or(b'\n', |o| o.terminator);
    let mut left = s.records;
    let mut buf = Vec::new();
    let mut value = Vec::new();
    'records: loop {
        for o in &mut s.outputs {
            if o.bytes > 0 {
                value.resize(o.bytes * o.components, 0);
                if input.read_exact(&mut value).is_err() {
                    break 'records;
                }
                if let Some(out) = o.output.as_mut()
                    && out.write_all(&value).is_err()
                {
                    break 'records;
                }
            } else {
                for _ in 0..o.components {
                    if field(input, o.terminator, &mut buf)
                        .ok()
                        .flatten()
                        .is_none()
                    {
                        break 'records;
                    }
                    if let Some(out) = o.output.as_mut()
                        && out.write_all(&buf).is_err()
                    {
                        break 'records;
                    }
                }
                if o.terminator != b'\n'
                    && let Some(out) = o.output.as_mut()
                    && out.write_all(b"\n").is_err()
                {
                    break 'records;
                }
            }
            // rsplit skips an input newline after each output when the last output's
            // fields end otherwise.
            if !binary
                && last_term != b'\n'
                && let Ok(b) = input.fill_buf()
                && b.first() == Some(&b'\n')
            {
                input.consume(1);
            }
        }
        left -= 1;
        if left == 0 {
            break;
        }
    }
    for o in &mut s.outputs {
        if let Some(out) = o.output.as_mut() {
            out.flush().map_err(|_| SplitError::Write)?;
        }
    }
    Ok(if left > 0 {
        SplitEnd::Premature
    } else {
        SplitEnd::Done
    })
}

/// `fgetsresolu` on one line: the x and y sizes of a standard or any other orientation.
fn radc_picture_resolution(line: &[u8]) -> Option<(i64, i64)> {
    let text = std::str::from_utf8(line).ok()?;
    let w: Vec<&str> = text.split_whitespace().collect();
    if w.len() != 4 {
        return None;
    }
    let num = |s: &str| s.parse::<i64>().ok().filter(|v| *v > 0);
    let (a, b) = (num(w[1])?, num(w[3])?);
    match (
        w[0].trim_start_matches(['-', '+']),
        w[2].trim_start_matches(['-', '+']),
    ) {
        ("Y", "X") => Some((b, a)),
        ("X", "Y") => Some((a, b)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use std::cell::RefCell;
    use std::rc::Rc;

    #[derive(Clone, Default)]
    struct Shared(Rc<RefCell<Vec<u8>>>);

    impl Write for Shared {
        fn write(&mut self, b: &[u8]) -> io::Result<usize> {
            self.0.borrow_mut().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    fn text_output(n: usize, term: u8, to: &Shared) -> SplitOutput<'static> {
        SplitOutput {
            output: Some(Box::new(to.clone())),
            components: n,
            bytes: 0,
            terminator: term,
            format: "ascii",
            header: false,
            resolution: false,
            stdout: false,
            start: None,
        }
    }

    #[test]
    fn fields_go_to_each_output_in_turn() {
        let (a, b) = (Shared::default(), Shared::default());
        let line = |f: &str, _: Option<u64>, _: usize| format!("FORMAT={f}\n");
        let mut s = Split {
            outputs: vec![text_output(1, b' ', &a), text_output(2, b' ', &b)],
            read_header: false,
            read_resolution: false,
            resolution: (0, 0),
            records: 0,
            command_line: String::new(),
            format_line: &line,
        };
        let mut input: &[u8] = b"1 2 3\n4 5 6\n";
        let end = split(&mut s, &mut input, &mut |_| {}).expect("split");
        assert_eq!(end, SplitEnd::Done);
        assert_eq!(String::from_utf8_lossy(&a.0.borrow()), "1 \n4 \n");
        // The newline ending a record is taken for the blank terminator.
        assert_eq!(String::from_utf8_lossy(&b.0.borrow()), "2 3 \n5 6 \n");
    }

    proptest::proptest! {
        /// Any input split among a text and a binary output: no panic.
        #[test]
        fn any_input_is_split(
            data in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..400),
            header in proptest::prelude::any::<bool>(),
        ) {
            let (a, b) = (Shared::default(), Shared::default());
            let line = |f: &str, _: Option<u64>, _: usize| format!("FORMAT={f}\n");
            let mut binary = text_output(1, b' ', &b);
            binary.bytes = 4;
            binary.header = header;
            let mut s = Split {
                outputs: vec![text_output(2, b',', &a), binary],
                read_header: header,
                read_resolution: false,
                resolution: (0, 0),
                records: 0,
                command_line: String::new(),
                format_line: &line,
            };
            let mut input: &[u8] = &data;
            let _ = split(&mut s, &mut input, &mut |_| {});
        }
    }
}
