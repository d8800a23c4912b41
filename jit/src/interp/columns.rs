//! rcalc's input columns (rcalc.c `chanvalue`, `l_in`): fields split on runs of
//! blanks (or on a given separator character), read with C's `atof`, so a field that
//! is not a number reads as its longest numeric prefix, or 0.

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
                rest = skip_blanks(rest);
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

fn is_c_space(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\n' | b'\r' | b'\x0b' | b'\x0c')
}

fn skip_blanks(s: &[u8]) -> &[u8] {
    let n = s.iter().position(|&c| !is_c_space(c)).unwrap_or(s.len());
    &s[n..]
}

impl Input for Record<'_> {
    fn column(&mut self, n: u32) -> Result<(f64, Option<Errno>), EvalError> {
        let i = n as usize - 1;
        if i < CACHED && self.known & (1 << i) != 0 {
            let errno = (self.range & (1 << i) != 0).then_some(Errno::Range);
            return Ok((self.cache[i], errno));
        }
        let v = atof_bytes(self.field(n));
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

/// C's `atof`: leading white space, then the longest prefix that is a decimal or
/// hexadecimal number, `inf`, `infinity` or `nan`; 0 if none. Overflow to infinity
/// and underflow to zero set `ERANGE`, as glibc's `strtod` does.
pub fn c_atof(s: &str) -> (f64, Option<Errno>) {
    atof_bytes(s.as_bytes())
}

fn atof_bytes(s: &[u8]) -> (f64, Option<Errno>) {
    let b = skip_blanks(s);
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let negative = b.first() == Some(&b'-');
    let rest = &b[i..];
    // Words only start with a letter or `0x`; a digit or point goes straight on.
    if let Some(&c) = rest.first()
        && !c.is_ascii_digit()
        && c != b'.'
    {
        let starts =
            |word: &[u8]| rest.len() >= word.len() && rest[..word.len()].eq_ignore_ascii_case(word);
        if starts(b"inf") {
            let v = if negative {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            };
            return (v, None);
        }
        if starts(b"nan") {
            return (if negative { -f64::NAN } else { f64::NAN }, None);
        }
        return (0.0, None);
    }
    if rest.len() > 1 && rest[0] == b'0' && (rest[1] == b'x' || rest[1] == b'X') {
        let v = hex_prefix(&String::from_utf8_lossy(&rest[2..]));
        return (if negative { -v } else { v }, None);
    }
    let start = i;
    // The mantissa's digits as an integer, for Clinger's fast path: exact while
    // there are at most 19 of them (leading zeros included, to keep it simple).
    let mut mantissa = 0u64;
    let mut scale = 0i32;
    let int_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        mantissa = mantissa
            .wrapping_mul(10)
            .wrapping_add(u64::from(b[i] - b'0'));
        i += 1;
    }
    let mut nd = i - int_start;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let frac_start = i;
        while i < b.len() && b[i].is_ascii_digit() {
            mantissa = mantissa
                .wrapping_mul(10)
                .wrapping_add(u64::from(b[i] - b'0'));
            i += 1;
        }
        scale = -((i - frac_start).min(1 << 20) as i32);
        nd += i - frac_start;
    }
    let exact = nd <= 19;
    if nd == 0 {
        return (0.0, None);
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        let mut exp_negative = false;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            exp_negative = b[j] == b'-';
            j += 1;
        }
        let mut e = 0i32;
        let from = j;
        while j < b.len() && b[j].is_ascii_digit() {
            e = e.saturating_mul(10).saturating_add(i32::from(b[j] - b'0'));
            j += 1;
        }
        if j > from {
            i = j;
            scale = scale.saturating_add(if exp_negative { -e } else { e });
        }
    }
    // Clinger: a mantissa below 2^53 and a power of ten below 10^23 are both exact
    // doubles, so one multiplication or division rounds correctly, as strtod does.
    if exact && mantissa < (1 << 53) && (-22..=22).contains(&scale) {
        let m = mantissa as f64;
        let v = if scale < 0 {
            m / POW10[(-scale) as usize]
        } else {
            m * POW10[scale as usize]
        };
        return (if negative { -v } else { v }, None);
    }
    // The prefix is ASCII: sign, digits, point, exponent.
    let text = std::str::from_utf8(&b[..i]).unwrap_or("0");
    let v: f64 = text.parse().unwrap_or(0.0);
    let nonzero_digits = b[start..i]
        .split(|&c| c == b'e' || c == b'E')
        .next()
        .is_some_and(|m| m.iter().any(|c| (b'1'..=b'9').contains(c)));
    let errno = if v.is_infinite() || (v == 0.0 && nonzero_digits) {
        Some(Errno::Range)
    } else {
        None
    };
    (v, errno)
}

const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

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

    /// The fast path must give strtod's correctly rounded value: std's parser is
    /// correctly rounded too, so they must agree on every prefix.
    #[test]
    fn fast_path_rounds_as_strtod() {
        for text in [
            "0.1",
            "1.7976931348623157e308",
            "9007199254740993",
            "123456789012345678901",
            "0.30000000000000004",
            "1e22",
            "1e23",
            "4.35",
            "-0",
            "-0.0e5",
            "12.5e-3",
        ] {
            assert_eq!(
                c_atof(text).0.to_bits(),
                text.parse::<f64>().map_or(0, f64::to_bits),
                "{text}"
            );
        }
    }

    proptest::proptest! {
        #[test]
        fn fast_path_agrees_with_std(m in 0u64..u64::MAX, frac in 0usize..20, e in -40i32..40) {
            let digits = m.to_string();
            let cut = frac.min(digits.len());
            let text = format!("{}.{}e{e}", &digits[..digits.len() - cut], &digits[digits.len() - cut..]);
            let want: f64 = text.parse().unwrap_or(0.0);
            proptest::prop_assert_eq!(c_atof(&text).0.to_bits(), want.to_bits(), "{}", text);
        }
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
