//! rcalc's input columns (rcalc.c `chanvalue`, `l_in`): fields split on runs of
//! blanks (or on a given separator character), read with C's `atof`, so a field that
//! is not a number reads as its longest numeric prefix, or 0.

use radc_lang::cal::eval::{Errno, EvalError, Input};

/// One input record (a line, including its newline).
pub struct Record<'a> {
    line: &'a str,
    sep: char,
    cache: Vec<Option<(f64, Option<Errno>)>>,
}

/// rcalc remembers the first 32 columns of a record (`MAXCOL`).
const MAXCOL: usize = 32;

impl<'a> Record<'a> {
    pub fn new(line: &'a str, sep: char) -> Self {
        Record {
            line,
            sep,
            cache: vec![None; MAXCOL],
        }
    }

    fn blank_separated(&self) -> bool {
        self.sep.is_ascii_whitespace()
    }

    fn field(&self, n: u32) -> &'a str {
        let mut rest = self.line;
        for _ in 1..n {
            if self.blank_separated() {
                rest = rest.trim_start_matches(is_c_space);
                rest = rest.trim_start_matches(|c: char| !is_c_space(c));
            } else {
                rest = match rest.find(self.sep) {
                    Some(i) => &rest[i + self.sep.len_utf8()..],
                    None => "",
                };
            }
        }
        rest
    }
}

fn is_c_space(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\n' | '\r' | '\x0b' | '\x0c')
}

impl Input for Record<'_> {
    fn column(&mut self, n: u32) -> Result<(f64, Option<Errno>), EvalError> {
        let i = n as usize - 1;
        if let Some(Some(v)) = self.cache.get(i) {
            return Ok(*v);
        }
        let v = c_atof(self.field(n));
        if let Some(slot) = self.cache.get_mut(i) {
            *slot = Some(v);
        }
        Ok(v)
    }

    fn column_count(&mut self) -> Result<f64, EvalError> {
        let n = if self.blank_separated() {
            self.line
                .split(is_c_space)
                .filter(|f| !f.is_empty())
                .count()
        } else {
            let mut n = 0;
            let mut rest = self.line;
            while !rest.is_empty() {
                if !rest.starts_with('\n') {
                    n += 1;
                }
                rest = match rest.find(self.sep) {
                    Some(i) => &rest[i + self.sep.len_utf8()..],
                    None => "",
                };
            }
            n
        };
        Ok(n as f64)
    }
}

/// C's `atof`: leading white space, then the longest prefix that is a decimal or
/// hexadecimal number, `inf`, `infinity` or `nan`; 0 if none. Overflow to infinity
/// and underflow to zero set `ERANGE`, as glibc's `strtod` does.
pub fn c_atof(s: &str) -> (f64, Option<Errno>) {
    let s = s.trim_start_matches(is_c_space);
    let b = s.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let negative = b.first() == Some(&b'-');
    let rest = &s[i..];
    let lower = rest.get(..8).unwrap_or(rest).to_ascii_lowercase();
    if lower.starts_with("inf") {
        return (
            if negative {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            },
            None,
        );
    }
    if lower.starts_with("nan") {
        return (if negative { -f64::NAN } else { f64::NAN }, None);
    }
    if lower.starts_with("0x") {
        let v = hex_prefix(&rest[2..]);
        return (if negative { -v } else { v }, None);
    }
    let start = i;
    let digits = |i: &mut usize| {
        let from = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        *i - from
    };
    let mut nd = digits(&mut i);
    if i < b.len() && b[i] == b'.' {
        i += 1;
        nd += digits(&mut i);
    }
    if nd == 0 {
        return (0.0, None);
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        if digits(&mut j) > 0 {
            i = j;
        }
    }
    let text = &s[..i];
    let v: f64 = text.parse().unwrap_or(0.0);
    let nonzero_digits = s[start..i]
        .split(['e', 'E'])
        .next()
        .is_some_and(|m| m.bytes().any(|c| (b'1'..=b'9').contains(&c)));
    let errno = if v.is_infinite() || (v == 0.0 && nonzero_digits) {
        Some(Errno::Range)
    } else {
        None
    };
    (v, errno)
}

fn hex_prefix(s: &str) -> f64 {
    let mut v = 0.0f64;
    let mut scale = None::<f64>;
    let mut chars = s.chars().peekable();
    while let Some(&c) = chars.peek() {
        if let Some(d) = c.to_digit(16) {
            match scale.as_mut() {
                None => v = v * 16.0 + f64::from(d),
                Some(sc) => {
                    *sc /= 16.0;
                    v += f64::from(d) * *sc;
                }
            }
        } else if c == '.' && scale.is_none() {
            scale = Some(1.0);
        } else {
            break;
        }
        chars.next();
    }
    if matches!(chars.peek(), Some('p' | 'P')) {
        chars.next();
        let exp: String = chars
            .take_while(|c| c.is_ascii_digit() || *c == '-' || *c == '+')
            .collect();
        if let Ok(e) = exp.parse::<i32>() {
            v *= 2f64.powi(e);
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atof_reads_prefixes() {
        assert_eq!(c_atof("  12.5abc").0, 12.5);
        assert_eq!(c_atof("abc").0, 0.0);
        assert_eq!(c_atof("-1e3x").0, -1000.0);
        assert_eq!(c_atof("1e").0, 1.0);
        assert_eq!(c_atof(".5").0, 0.5);
        assert_eq!(c_atof("0x10").0, 16.0);
        assert!(c_atof("nan").0.is_nan());
        assert_eq!(c_atof("-inf").0, f64::NEG_INFINITY);
        assert_eq!(c_atof("1e999"), (f64::INFINITY, Some(Errno::Range)));
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
