//! Number text as Radiance's C programs read and write it, in one place.
//!
//! Reading: C's `isspace` in the "C" locale ([`is_c_space`]), glibc's `strtod` and
//! `atof` ([`strtod`], [`atof`]: the longest numeric prefix, decimal or hexadecimal,
//! `inf`, `infinity`, `nan`; 0 when there is none), `strtol`'s digits ([`atol`]), and
//! Radiance's own number words (`isint`, `isflt` in `src/common/words.c`:
//! [`is_int`], [`is_flt`], and [`real_prefix`], the value and length of the longest
//! prefix in that syntax). Writing: [`format`], C's `%g`, `%e` and a fast `%.9g`.
//!
//! Matching these keeps every output identical to Radiance's: rcalc reads its columns
//! with `atof`, the generators their arguments, data files are checked with `isflt`,
//! rtrace reads rays in `isflt`'s syntax.

pub mod digits;
pub mod format;

pub use format::{format_e, format_g, format_g_width, write_g9};

use digits::{POW10, digit_run};

/// C's `isspace` in the "C" locale: also the vertical tab and form feed, which
/// `u8::is_ascii_whitespace` leaves out (the bytes `char::is_whitespace` accepts among
/// ASCII).
#[inline(always)]
pub const fn is_c_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\x0b' | b'\x0c' | b'\r')
}

/// `s` after its leading C white space.
pub fn skip_c_spaces(s: &[u8]) -> &[u8] {
    let n = s.iter().position(|&c| !is_c_space(c)).unwrap_or(s.len());
    &s[n..]
}

/// What `strtod` read from the start of a text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strtod {
    pub value: f64,
    /// Bytes read, leading white space included; 0 when no number starts the text
    /// (and then `value` is 0).
    pub len: usize,
    /// glibc sets `ERANGE`: a decimal that overflowed to infinity or underflowed to
    /// zero from non-zero digits.
    pub out_of_range: bool,
}

impl Strtod {
    fn new(value: f64, len: usize) -> Self {
        Strtod {
            value,
            len,
            out_of_range: false,
        }
    }
}

/// glibc's `strtod`: leading white space, then the longest prefix that is a decimal or
/// hexadecimal number, `inf`, `infinity` or `nan` (any case, signed). Decimals are
/// correctly rounded, as glibc rounds them (Clinger's fast path where it is exact).
pub fn strtod(s: &[u8]) -> Strtod {
    let lead = s.len() - skip_c_spaces(s).len();
    let b = &s[lead..];
    let signed = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let negative = b.first() == Some(&b'-');
    let sign = |v: f64| if negative { -v } else { v };
    let rest = &b[signed..];
    let starts =
        |word: &[u8]| rest.len() >= word.len() && rest[..word.len()].eq_ignore_ascii_case(word);
    // Words only start with a letter: a digit or point goes straight on (rcalc reads
    // every column through here).
    if rest.first().is_some_and(u8::is_ascii_alphabetic) {
        for word in [&b"infinity"[..], b"inf"] {
            if starts(word) {
                return Strtod::new(sign(f64::INFINITY), lead + signed + word.len());
            }
        }
        if starts(b"nan") {
            return Strtod::new(sign(f64::NAN), lead + signed + 3);
        }
        return Strtod::new(0.0, 0);
    }
    if rest.len() > 1 && rest[0] == b'0' && (rest[1] == b'x' || rest[1] == b'X') {
        return match hex(&rest[2..]) {
            Some((v, n)) => Strtod::new(sign(v), lead + signed + 2 + n),
            // "0x" without hexadecimal digits: the "0" alone.
            None => Strtod::new(sign(0.0), lead + signed + 1),
        };
    }
    let Some(d) = decimal(rest) else {
        return Strtod::new(0.0, 0);
    };
    let len = lead + signed + d.len;
    if let Some(v) = d.exact() {
        return Strtod::new(sign(v), len);
    }
    // The prefix is ASCII: sign, digits, point, exponent.
    let text = std::str::from_utf8(&b[..signed + d.len]).unwrap_or("0");
    let v: f64 = text.parse().unwrap_or(0.0);
    let nonzero = rest[..d.mantissa_len]
        .iter()
        .any(|c| (b'1'..=b'9').contains(c));
    Strtod {
        value: v,
        len,
        out_of_range: v.is_infinite() || (v == 0.0 && nonzero),
    }
}

/// C's `atof`: [`strtod`]'s value, 0 when no number starts `s`.
pub fn atof(s: &str) -> f64 {
    strtod(s.as_bytes()).value
}

/// glibc's `strtol` in base 10 (as `atoi`/`atol` use it): leading white space, an
/// optional sign and digits, saturating at the ends of a 64-bit `long`; 0 for none.
pub fn atol(s: impl AsRef<[u8]>) -> i64 {
    let b = skip_c_spaces(s.as_ref());
    let (negative, digits) = match b.first() {
        Some(b'-') => (true, &b[1..]),
        Some(b'+') => (false, &b[1..]),
        _ => (false, b),
    };
    let magnitude = digits
        .iter()
        .take_while(|c| c.is_ascii_digit())
        .fold(0i128, |acc, &c| {
            (acc * 10 + i128::from(c - b'0')).min(i128::from(i64::MAX) + 1)
        });
    let long = if negative { -magnitude } else { magnitude };
    long.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
}

/// C's `atoi`: [`atol`] converted to `int` as glibc does (`(int) strtol(...)`, which
/// keeps the low 32 bits of a value past `int`'s range).
pub fn atoi(s: impl AsRef<[u8]>) -> i32 {
    atol(s) as i32
}

/// Radiance's `isint()`: leading white space, an optional sign, digits, nothing after.
pub fn is_int(s: &str) -> bool {
    let b = skip_c_spaces(s.as_bytes());
    let digits = b
        .strip_prefix(b"+")
        .or_else(|| b.strip_prefix(b"-"))
        .unwrap_or(b);
    !digits.is_empty() && digits.iter().all(u8::is_ascii_digit)
}

/// Radiance's `isflt()`: leading white space, then a whole [`real_word`].
pub fn is_flt(s: &str) -> bool {
    real_word(skip_c_spaces(s.as_bytes())).is_some()
}

/// A word in Radiance's real-number syntax (`isflt`'s, without leading white space:
/// `[+-](digits[.digits]|.digits)[(e|E)[+-]digits]`, `5.` included), and its value:
/// no `inf`, `nan` or hex, which `strtod` and Rust would otherwise accept.
pub fn real_word(w: &[u8]) -> Option<f64> {
    real_prefix(w).and_then(|(x, n)| (n == w.len()).then_some(x))
}

/// The longest prefix of `w` in Radiance's real-number syntax, if one starts `w`, with
/// its length; an exponent marker without digits makes it none (no word starting so
/// is a number). The value is `strtod`'s, bit for bit.
pub fn real_prefix(w: &[u8]) -> Option<(f64, usize)> {
    let (negative, start) = match w.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let d = decimal(&w[start..])?;
    if d.exponent_without_digits {
        return None;
    }
    let at = start + d.len;
    let v = match d.exact() {
        Some(v) => v,
        None => std::str::from_utf8(&w[start..at])
            .ok()?
            .parse::<f64>()
            .ok()?,
    };
    Some((if negative { -v } else { v }, at))
}

/// An unsigned decimal at the start of a text: `digits[.digits][(e|E)[+-]digits]` or
/// `.digits...`, the exponent only when it has digits.
struct Decimal {
    /// The digits as an integer, wrapping past 19 of them (then `exact` is `None`).
    mantissa: u64,
    digits: usize,
    /// The power of ten the mantissa is scaled by (clamped far beyond any double).
    scale: i64,
    len: usize,
    /// The length of the digits and point before any exponent.
    mantissa_len: usize,
    /// An `e` follows the mantissa but no exponent digits do.
    exponent_without_digits: bool,
}

impl Decimal {
    /// Clinger's fast path: a mantissa of at most 2^53 and a power of ten up to 10^22
    /// are both exact doubles, so one multiplication or division rounds correctly, as
    /// strtod does.
    fn exact(&self) -> Option<f64> {
        if self.digits > 19 || self.mantissa > 1 << 53 || self.scale.unsigned_abs() > 22 {
            return None;
        }
        let m = self.mantissa as f64;
        Some(if self.scale >= 0 {
            m * POW10[self.scale as usize]
        } else {
            m / POW10[(-self.scale) as usize]
        })
    }
}

fn decimal(w: &[u8]) -> Option<Decimal> {
    let (mut mantissa, mut at) = digit_run(w, 0, 0);
    let mut digits = at;
    let mut scale = 0i64;
    if w.get(at) == Some(&b'.') {
        let from = at + 1;
        (mantissa, at) = digit_run(w, from, mantissa);
        digits += at - from;
        scale = -((at - from).min(1 << 20) as i64);
    }
    if digits == 0 {
        return None;
    }
    let mantissa_len = at;
    let mut exponent_without_digits = false;
    if matches!(w.get(at), Some(b'e' | b'E')) {
        let mut j = at + 1;
        let negative_exp = match w.get(j) {
            Some(b'-') => {
                j += 1;
                true
            }
            Some(b'+') => {
                j += 1;
                false
            }
            _ => false,
        };
        let from = j;
        let mut exp = 0i64;
        while let Some(&b) = w.get(j).filter(|b| b.is_ascii_digit()) {
            exp = (exp * 10 + i64::from(b - b'0')).min(1 << 20);
            j += 1;
        }
        if j == from {
            exponent_without_digits = true;
        } else {
            at = j;
            scale += if negative_exp { -exp } else { exp };
        }
    }
    Some(Decimal {
        mantissa,
        digits,
        scale,
        len: at,
        mantissa_len,
        exponent_without_digits,
    })
}

/// A hexadecimal mantissa `h[.h]` or `.h` and an optional binary exponent `p[+-]d`,
/// summed digit by digit in doubles; its value and length, `None` without digits.
fn hex(b: &[u8]) -> Option<(f64, usize)> {
    let mut v = 0.0f64;
    let mut scale = None::<f64>;
    let mut digits = 0;
    let mut i = 0;
    while let Some(&c) = b.get(i) {
        if let Some(d) = char::from(c).to_digit(16) {
            digits += 1;
            match scale.as_mut() {
                None => v = v * 16.0 + f64::from(d),
                Some(sc) => {
                    *sc /= 16.0;
                    v += f64::from(d) * *sc;
                }
            }
        } else if c == b'.' && scale.is_none() {
            scale = Some(1.0);
        } else {
            break;
        }
        i += 1;
    }
    if digits == 0 {
        return None;
    }
    if matches!(b.get(i), Some(b'p' | b'P')) {
        let mut j = i + 1;
        let negative = b.get(j) == Some(&b'-');
        j += usize::from(matches!(b.get(j), Some(b'+' | b'-')));
        let from = j;
        let mut e = 0i32;
        while let Some(&c) = b.get(j).filter(|c| c.is_ascii_digit()) {
            e = e.saturating_mul(10).saturating_add(i32::from(c - b'0'));
            j += 1;
        }
        if j > from {
            v *= 2f64.powi(if negative { -e } else { e });
            i = j;
        }
    }
    Some((v, i))
}

#[cfg(test)]
mod tests;
