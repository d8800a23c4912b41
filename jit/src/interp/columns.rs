//! rcalc's input columns (rcalc.c `chanvalue`, `l_in`): fields split on runs of
//! blanks (or on a given separator character), read with C's `atof`
//! (`radc_lang::c_number::strtod`), so a field that is not a number reads as its
//! longest numeric prefix, or 0, and overflow raises `ERANGE`.

use radc_lang::c_number::{is_c_space, skip_c_spaces, strtod};
use radc_lang::cal::eval::{Errno, EvalError, Input};

/// One input record (a line, including its newline).
pub struct Record<'a> {
    line: &'a [u8],
    sep: char,
    /// Columns read so far: bit `i` of `known` says `cache[i]` holds column `i + 1`
    /// (and bit `i` of `range` that reading it overflowed).
    known: u8,
    range: u8,
    cache: [f64; CACHED],
}

/// Columns kept once read. rcalc keeps 32 (`MAXCOL`); reading a column is pure, so
/// the number only matters to speed, and records rarely have more than a few.
const CACHED: usize = 8;

impl<'a> Record<'a> {
    pub fn new(line: &'a str, sep: char) -> Self {
        Self::from_bytes(line.as_bytes(), sep)
    }

    /// A record straight from input bytes: fields split on ASCII blanks or on the
    /// separator's bytes and numbers are ASCII, so bytes that are not UTF-8 read as
    /// they would after a lossy conversion.
    pub fn from_bytes(line: &'a [u8], sep: char) -> Self {
        Record {
            line,
            sep,
            known: 0,
            range: 0,
            cache: [0.0; CACHED],
        }
    }

    /// Column `n` to the end of the line.
    fn field(&self, n: u32) -> &'a [u8] {
        let mut rest = self.line;
        if self.sep.is_ascii_whitespace() {
            for _ in 1..n {
                rest = skip_c_spaces(rest);
                let word = rest
                    .iter()
                    .position(|&c| is_c_space(c))
                    .unwrap_or(rest.len());
                rest = &rest[word..];
            }
        } else {
            let mut sep = [0u8; 4];
            let sep = self.sep.encode_utf8(&mut sep).as_bytes();
            for _ in 1..n {
                rest = match find(rest, sep) {
                    Some(i) => &rest[i + sep.len()..],
                    None => &[],
                };
            }
        }
        rest
    }
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    match *needle {
        [b] => haystack.iter().position(|&c| c == b),
        _ => haystack.windows(needle.len()).position(|w| w == needle),
    }
}

impl Input for Record<'_> {
    fn column(&mut self, n: u32) -> Result<(f64, Option<Errno>), EvalError> {
        let i = n as usize - 1;
        if i < CACHED && self.known & (1 << i) != 0 {
            let errno = (self.range & (1 << i) != 0).then_some(Errno::Range);
            return Ok((self.cache[i], errno));
        }
        let v = c_atof(self.field(n));
        if i < CACHED {
            self.cache[i] = v.0;
            self.known |= 1 << i;
            if v.1.is_some() {
                self.range |= 1 << i;
            }
        }
        Ok(v)
    }

    fn column_count(&mut self) -> Result<f64, EvalError> {
        let n = if self.sep.is_ascii_whitespace() {
            self.line
                .split(|&c| is_c_space(c))
                .filter(|f| !f.is_empty())
                .count()
        } else {
            let mut sep = [0u8; 4];
            let sep = self.sep.encode_utf8(&mut sep).as_bytes();
            let mut n = 0;
            let mut rest = self.line;
            while !rest.is_empty() {
                if !rest.starts_with(b"\n") {
                    n += 1;
                }
                rest = match find(rest, sep) {
                    Some(i) => &rest[i + sep.len()..],
                    None => &[],
                };
            }
            n
        };
        Ok(n as f64)
    }
}

/// C's `atof` with the `errno` it leaves.
fn c_atof(field: &[u8]) -> (f64, Option<Errno>) {
    let n = strtod(field);
    (n.value, n.out_of_range.then_some(Errno::Range))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_raise_range_errors() {
        let mut r = Record::new("1e999 2\n", ' ');
        assert_eq!(r.column(1), Ok((f64::INFINITY, Some(Errno::Range))));
        assert_eq!(r.column(1), Ok((f64::INFINITY, Some(Errno::Range))));
        assert_eq!(r.column(2), Ok((2.0, None)));
    }

    #[test]
    fn fields_split_on_blank_runs() {
        let mut r = Record::new("  1 \t 2   3\n", '\t');
        assert_eq!(r.column(2).map(|v| v.0), Ok(2.0));
        assert_eq!(r.column(3).map(|v| v.0), Ok(3.0));
        assert_eq!(r.column(4).map(|v| v.0), Ok(0.0));
        assert_eq!(r.column_count(), Ok(3.0));
    }

    #[test]
    fn fields_split_on_a_separator() {
        let mut r = Record::new("1,,3\n", ',');
        assert_eq!(r.column(2).map(|v| v.0), Ok(0.0));
        assert_eq!(r.column(3).map(|v| v.0), Ok(3.0));
        assert_eq!(r.column_count(), Ok(3.0));
    }
}
