//! rtrace's text I/O on the hot path: real numbers in Radiance's syntax in, C's `%e`
//! out. Both have a fast exact path for the common case (up to 19 digits and a small
//! power of ten in; 7 significant digits not near a rounding tie out) and fall back on
//! Rust's exactly rounded conversions otherwise, so the results are those conversions'
//! bit for bit.

/// The powers of ten an `f64` holds exactly.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Bytes Rust's `char::is_whitespace` accepts among ASCII (`split_whitespace` on an
/// ASCII line): also the vertical tab, which `u8::is_ascii_whitespace` leaves out.
pub fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\x0b' | b'\x0c' | b'\r')
}

/// A word in Radiance's real-number syntax (`[+-]digits[.digits][e[+-]digits]`, or
/// starting with the point): no `inf`, `nan` or hex, which Rust would otherwise accept.
pub fn radiance_number(w: &[u8]) -> Option<f64> {
    number_prefix(w).and_then(|(x, n)| (n == w.len()).then_some(x))
}

/// The longest prefix of `w` in Radiance's real-number syntax, if one starts `w`, with
/// its length. The word is a number when that prefix is all of it (`radiance_number`);
/// the line scanner checks instead that a space follows.
pub fn number_prefix(w: &[u8]) -> Option<(f64, usize)> {
    let (negative, start) = match w.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let (mut mantissa, mut at) = digit_run(w, start, 0);
    let mut digits = at - start;
    let mut scale = 0i64;
    if w.get(at) == Some(&b'.') {
        let from = at + 1;
        (mantissa, at) = digit_run(w, from, mantissa);
        digits += at - from;
        scale = -((at - from) as i64);
    }
    if digits == 0 {
        return None;
    }
    if matches!(w.get(at), Some(b'e' | b'E')) {
        at += 1;
        let negative_exp = match w.get(at) {
            Some(b'-') => {
                at += 1;
                true
            }
            Some(b'+') => {
                at += 1;
                false
            }
            _ => false,
        };
        let from = at;
        let mut exp = 0i64;
        while let Some(&b) = w.get(at).filter(|b| b.is_ascii_digit()) {
            exp = (exp * 10 + i64::from(b - b'0')).min(1 << 20);
            at += 1;
        }
        if at == from {
            return None;
        }
        scale += if negative_exp { -exp } else { exp };
    }
    // Clinger's fast path: an exact integer and an exact power of ten, one rounding.
    let v = if digits <= 19 && mantissa <= 1 << 53 && scale.unsigned_abs() <= 22 {
        let m = mantissa as f64;
        if scale >= 0 {
            m * POW10[scale as usize]
        } else {
            m / POW10[(-scale) as usize]
        }
    } else {
        std::str::from_utf8(&w[start..at])
            .ok()?
            .parse::<f64>()
            .ok()?
    };
    Some((if negative { -v } else { v }, at))
}

/// The number at the start of `w` when it has the usual shape of ray input
/// (`[-]digits[.digits]`: fewer than 8 digits before the point, at most 8 after) and a
/// space follows, with its length; `None` for anything else, which `number_prefix`
/// decides. Two eight-byte loads instead of a loop per byte; the value is
/// `number_prefix`'s (the same integer, at most 15 digits, over the same power of ten).
#[inline(always)]
pub fn spaced_number(w: &[u8]) -> Option<(f64, usize)> {
    let negative = w.first() == Some(&b'-');
    let start = usize::from(negative);
    let int = load8(w, start)?;
    let int_digits = leading_digits(int);
    if int_digits == 8 {
        return None;
    }
    let (mantissa, digits, fraction_digits, point) = if (int >> (8 * int_digits)) as u8 == b'.' {
        let fraction = load8(w, start + int_digits + 1)?;
        let n = leading_digits(fraction);
        let digits = int_digits + n;
        let mantissa = if digits <= 8 {
            // Both runs side by side in one word.
            let below = (1u64 << (8 * int_digits)) - 1;
            eight_digits_value((int & below) | (fraction << (8 * int_digits)), digits)
        } else if int_digits == 1 && int as u8 == b'0' {
            eight_digits_value(fraction, n)
        } else {
            eight_digits_value(int, int_digits) * POW10_U64[n] + eight_digits_value(fraction, n)
        };
        (mantissa, digits, n, 1)
    } else {
        (eight_digits_value(int, int_digits), int_digits, 0, 0)
    };
    let end = start + digits + point;
    if digits == 0 || !w.get(end).is_some_and(|&b| is_space(b)) {
        return None;
    }
    // Below 1e15: exact either way, and a signed conversion is one instruction.
    let v = mantissa as i64 as f64 / POW10[fraction_digits];
    Some((if negative { -v } else { v }, end))
}

/// The eight bytes of `w` from `at`, the first lowest.
#[inline(always)]
fn load8(w: &[u8], at: usize) -> Option<u64> {
    let mut word = [0u8; 8];
    word.copy_from_slice(w.get(at..at + 8)?);
    Some(u64::from_le_bytes(word))
}

/// The decimal digits of `w` from `at` on, appended to `mantissa` (wrapping: a long
/// run only counts its digits, the value goes to Rust's parser), and where they end.
/// Eight bytes at a time where `w` has them: digits found and combined with a few
/// multiplications instead of a loop per digit.
#[inline(always)]
fn digit_run(w: &[u8], mut at: usize, mut mantissa: u64) -> (u64, usize) {
    while let Some(v) = load8(w, at) {
        let n = leading_digits(v);
        if n == 0 {
            return (mantissa, at);
        }
        mantissa = mantissa
            .wrapping_mul(POW10_U64[n])
            .wrapping_add(eight_digits_value(v, n));
        at += n;
        if n < 8 {
            return (mantissa, at);
        }
    }
    while let Some(&b) = w.get(at).filter(|b| b.is_ascii_digit()) {
        mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(b - b'0'));
        at += 1;
    }
    (mantissa, at)
}

/// How many of the eight bytes of `v` (little-endian: the first byte lowest) are ASCII
/// digits before the first that is not. A byte below `0` borrows in the subtraction and
/// one above `9` carries into its top bit in the addition; either sets its top bit, and
/// a borrow or carry only starts at such a byte, so the bytes before it are untouched.
#[inline(always)]
fn leading_digits(v: u64) -> usize {
    let not_digit = (v.wrapping_sub(0x3030_3030_3030_3030) | v.wrapping_add(0x4646_4646_4646_4646))
        & 0x8080_8080_8080_8080;
    if not_digit == 0 {
        8
    } else {
        not_digit.trailing_zeros() as usize / 8
    }
}

/// The value of the first `n` (0 to 8) bytes of `v`, all digits: they move to the top,
/// the bytes below become `0`s (leading zeros), and the eight digits combine pairwise.
#[inline(always)]
fn eight_digits_value(v: u64, n: usize) -> u64 {
    if n == 0 {
        return 0;
    }
    let shift = (8 - n) * 8;
    let zeros = 0x3030_3030_3030_3030 & !(u64::MAX << shift);
    let v = ((v << shift) | zeros) - 0x3030_3030_3030_3030;
    // Bytes d0..d7 (d0 lowest, the most significant digit): pairs, then quads, then all.
    let pairs = (v * 10 + (v >> 8)) & 0x00ff_00ff_00ff_00ff;
    let quads = (pairs * 100 + (pairs >> 16)) & 0x0000_ffff_0000_ffff;
    (quads & 0xffff_ffff) * 10_000 + (quads >> 32)
}

/// `10^n` for the runs of digits `digit_run` takes at once.
const POW10_U64: [u64; 9] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
];

/// C's `%e` of `x` (six decimals, an exponent of at least two digits:
/// `1.000000e+10`) into `buf`, returning the length (at most 14).
#[inline]
pub fn c_exp_into(x: f64, buf: &mut [u8; 16]) -> usize {
    fast_exp(x, buf).unwrap_or_else(|| slow_exp(x, buf))
}

/// `"00"` to `"99"`.
const PAIRS: [[u8; 2]; 100] = {
    let mut t = [[0u8; 2]; 100];
    let mut i = 0;
    while i < 100 {
        t[i] = [b'0' + (i / 10) as u8, b'0' + (i % 10) as u8];
        i += 1;
    }
    t
};

/// The common case: `x * 10^k` for an exact power of ten, rounded once, lies within
/// 1e-9 of the exact product (half an ulp below 1e7); unless that is within 1e-6 of a
/// half its rounding to an integer is the exactly rounded seven digits. `None` leaves
/// the rest to `slow_exp`.
#[inline(always)]
fn fast_exp(x: f64, buf: &mut [u8; 16]) -> Option<usize> {
    let a = x.abs();
    if !(1e-15..1e19).contains(&a) {
        // Zero is common (rays that meet nothing lit).
        if a != 0.0 {
            return None;
        }
        let text: &[u8] = if x.is_sign_negative() {
            b"-0.000000e+00"
        } else {
            b"0.000000e+00"
        };
        buf[..text.len()].copy_from_slice(text);
        return Some(text.len());
    }
    // floor(log10 a) is e or e + 1 for e = floor(binary exponent * log10 2) (no libm
    // calls: without SSE4.1, floor and round are function calls).
    let binary = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let mut e = (binary * 78_913) >> 18;
    // The truncation (saturating) is at least 1e7 exactly when s is, and so on.
    let mut s = scaled(a, 6 - e)?;
    let mut whole = s as u32;
    if whole >= 10_000_000 {
        e += 1;
        s = scaled(a, 6 - e)?;
        whole = s as u32;
    }
    // Outside only when a rounded product crossed a power of ten.
    if !(1_000_000..10_000_000).contains(&whole) {
        return None;
    }
    // 1e6 <= s < 1e7: the truncation is exact.
    let fraction = s - f64::from(whole);
    if (fraction - 0.5).abs() < 1e-6 {
        return None;
    }
    let mut n = whole + u32::from(fraction > 0.5);
    if n == 10_000_000 {
        n = 1_000_000;
        e += 1;
    }
    // "d.dddddd" and "e+dd", each in one store; the sign before them.
    let lead = n / 1_000_000;
    let rest = n - lead * 1_000_000;
    let high = rest / 10_000;
    let low = rest - high * 10_000;
    let middle = low / 100;
    let last = low - middle * 100;
    let pair = |i: u32| u64::from(u16::from_le_bytes(PAIRS[i as usize]));
    let digits = u64::from(b'0' + lead as u8)
        | u64::from(b'.') << 8
        | pair(high) << 16
        | pair(middle) << 32
        | pair(last) << 48;
    let sign = if e < 0 { b'-' } else { b'+' };
    // |e| <= 19 in this range.
    let exponent = u32::from(b'e') | u32::from(sign) << 8 | (pair(e.unsigned_abs()) as u32) << 16;
    buf[0] = b'-';
    let at = usize::from(x < 0.0);
    buf[at..at + 8].copy_from_slice(&digits.to_le_bytes());
    buf[at + 8..at + 12].copy_from_slice(&exponent.to_le_bytes());
    Some(at + 12)
}

/// `a * 10^k`, rounded once (`None` when `10^k` or `10^-k` is not an exact `f64`).
fn scaled(a: f64, k: i32) -> Option<f64> {
    let p = *POW10.get(k.unsigned_abs() as usize)?;
    Some(if k >= 0 { a * p } else { a / p })
}

/// `%e` by Rust's exactly rounded `{:.6e}`, the exponent rewritten; no allocation.
#[cold]
#[inline(never)]
fn slow_exp(x: f64, buf: &mut [u8; 16]) -> usize {
    use std::io::Write;
    let special: &[u8] = if x.is_nan() {
        if x.is_sign_negative() {
            b"-nan"
        } else {
            b"nan"
        }
    } else if x.is_infinite() {
        if x < 0.0 { b"-inf" } else { b"inf" }
    } else {
        b""
    };
    if !special.is_empty() {
        buf[..special.len()].copy_from_slice(special);
        return special.len();
    }
    let mut cursor = std::io::Cursor::new(&mut buf[..]);
    // At most "-d.dddddde-324": 14 bytes, so the write cannot fail.
    let _ = write!(cursor, "{x:.6e}");
    let len = cursor.position() as usize;
    let Some(e) = buf[..len].iter().position(|&b| b == b'e') else {
        return len;
    };
    let (negative, digits) = match buf[e + 1] {
        b'-' => (true, e + 2),
        _ => (false, e + 1),
    };
    let exp: u32 = buf[digits..len]
        .iter()
        .fold(0, |v, d| v * 10 + u32::from(d - b'0'));
    let mut at = e + 1;
    buf[at] = if negative { b'-' } else { b'+' };
    at += 1;
    if exp >= 100 {
        buf[at] = b'0' + (exp / 100) as u8;
        at += 1;
    }
    buf[at] = b'0' + (exp / 10 % 10) as u8;
    buf[at + 1] = b'0' + (exp % 10) as u8;
    at + 2
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c_exp(x: f64) -> String {
        let mut buf = [0u8; 16];
        let n = c_exp_into(x, &mut buf);
        String::from_utf8_lossy(&buf[..n]).into_owned()
    }

    fn c_exp_reference(x: f64) -> String {
        if x.is_nan() {
            return if x.is_sign_negative() { "-nan" } else { "nan" }.into();
        }
        if x.is_infinite() {
            return if x < 0.0 { "-inf" } else { "inf" }.into();
        }
        let s = format!("{x:.6e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let exp: i32 = exp.parse().unwrap_or(0);
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{mantissa}e{sign}{:02}", exp.unsigned_abs())
    }

    #[test]
    fn c_exp_matches_printf() {
        assert_eq!(c_exp(0.5), "5.000000e-01");
        assert_eq!(c_exp(0.0), "0.000000e+00");
        assert_eq!(c_exp(-0.0), "-0.000000e+00");
        assert_eq!(c_exp(1e10), "1.000000e+10");
        assert_eq!(c_exp(3.141718), "3.141718e+00");
        assert_eq!(c_exp(-1.5e-120), "-1.500000e-120");
        assert_eq!(c_exp(9.9999999e9), "1.000000e+10");
        assert_eq!(c_exp(f64::MIN_POSITIVE / 8.0), "2.781342e-309");
        assert_eq!(c_exp(f64::NAN), "nan");
        assert_eq!(c_exp(f64::NEG_INFINITY), "-inf");
    }

    /// The fast formatter equals the straightforward one everywhere: a sweep over the
    /// whole range, values at and near rounding ties and powers of ten, and random
    /// bit patterns.
    #[test]
    fn c_exp_into_matches_the_reference() {
        let mut x = 1.234_567_891e-300_f64;
        while x < 1e300 {
            for v in [x, -x, x * 0.999_999_95, x * 1.000_000_5] {
                assert_eq!(c_exp(v), c_exp_reference(v), "{v:e}");
            }
            x *= 7.77;
        }
        for v in [
            0.0,
            -0.0,
            f64::MAX,
            f64::MIN,
            5e-324,
            1.0,
            9.9999995,
            0.5,
            1e-15,
            1e19,
        ] {
            assert_eq!(c_exp(v), c_exp_reference(v), "{v:e}");
        }
        for e in -16..20 {
            let p = 10f64.powi(e);
            for m in [
                1.0, 9.9999995, 9.99999949, 9.99999951, 1.0000005, 1.00000049, 2.5,
            ] {
                for v in [m * p, (m * p).next_up(), (m * p).next_down()] {
                    assert_eq!(c_exp(v), c_exp_reference(v), "{v:e}");
                    assert_eq!(c_exp(-v), c_exp_reference(-v), "{v:e}");
                }
            }
        }
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let v = f64::from_bits(seed);
            assert_eq!(c_exp(v), c_exp_reference(v), "{v:e}");
            // Values in the range radiance outputs, with few digits (near ties).
            let w = ((seed >> 11) % 100_000_000) as f64 / 10f64.powi((seed % 17) as i32);
            assert_eq!(c_exp(w), c_exp_reference(w), "{w:e}");
        }
    }

    fn reference_number(w: &str) -> Option<f64> {
        let body = w.strip_prefix(['+', '-']).unwrap_or(w);
        let (mantissa, exponent) = match body.find(['e', 'E']) {
            Some(i) => (&body[..i], Some(&body[i + 1..])),
            None => (body, None),
        };
        let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
        let digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
        let ok_mantissa = digits(int) && digits(frac) && !(int.is_empty() && frac.is_empty());
        let ok_exponent = exponent.is_none_or(|e| {
            let e = e.strip_prefix(['+', '-']).unwrap_or(e);
            !e.is_empty() && digits(e)
        });
        (ok_mantissa && ok_exponent)
            .then(|| w.parse().ok())
            .flatten()
    }

    #[test]
    fn numbers_in_radiance_syntax_only() {
        for (w, v) in [
            ("1", 1.0),
            ("-2.5", -2.5),
            (".5", 0.5),
            ("5.", 5.0),
            ("1e3", 1e3),
            ("+1.5E-2", 0.015),
        ] {
            assert_eq!(radiance_number(w.as_bytes()), Some(v), "{w}");
        }
        for w in [
            "nan",
            "inf",
            "-infinity",
            "0x10",
            ".",
            "e5",
            "1e",
            "1.2.3",
            "",
            "-",
            "+.",
            "1e+",
            "1.5x",
            "--1",
            "1e5e5",
        ] {
            assert_eq!(radiance_number(w.as_bytes()), None, "{w}");
        }
    }

    /// The fast parser gives Rust's exactly rounded value, bit for bit (and the sign of
    /// zero), on the shapes of number rtrace input has and on long or extreme ones.
    #[test]
    fn numbers_parse_as_rust_parses_them() {
        let mut words: Vec<String> = [
            "-0",
            "0.0",
            "-0.000",
            "9007199254740993",
            "9007199254740992",
            "123456789012345678901",
            "1e22",
            "1e23",
            "1e-22",
            "1e-23",
            "4.9e-324",
            "1.7976931348623157e308",
            "1e400",
            "-1e-400",
            "0.1",
            "0.30000000000000004",
            "00000000000000000000001.5",
            "1e0000000000000003",
            "1.00000000000000000000001",
            ".000001",
            "2.2250738585072014e-308",
            "1e999999999999",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..100_000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let x = f64::from_bits(seed >> 2) % 1e6;
            let sign = if seed & 1 == 1 { "-" } else { "" };
            let precision = (seed >> 40) as usize % 12;
            words.push(format!("{sign}{:.precision$}", x.abs()));
            words.push(format!(
                "{sign}{:.precision$e}",
                f64::from_bits(seed & !(1 << 63))
            ));
        }
        for w in &words {
            let fast = radiance_number(w.as_bytes());
            let reference = reference_number(w);
            assert_eq!(fast.map(f64::to_bits), reference.map(f64::to_bits), "{w}");
        }
    }

    /// The eight-byte digit helpers against a byte loop: every count of leading digits,
    /// followed by each kind of byte that is not a digit (just below `0`, just above
    /// `9`, and bytes whose addition or subtraction carries or borrows).
    #[test]
    fn eight_digit_words() {
        let mut seed = 0x1234_5678_9abc_def0u64;
        for stop in [
            b'/', b':', b'.', b' ', b'\n', 0, 0x7f, 0x80, 0xb9, 0xba, 0xcf, 0xd0, 0xff,
        ] {
            for n in 0..=8 {
                for _ in 0..200 {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    let mut bytes = [0u8; 8];
                    for (k, b) in bytes.iter_mut().enumerate() {
                        let r = (seed >> (8 * k)) as u8;
                        *b = if k < n {
                            b'0' + r % 10
                        } else if k == n {
                            stop
                        } else {
                            r
                        };
                    }
                    let v = u64::from_le_bytes(bytes);
                    assert_eq!(leading_digits(v), n, "{bytes:?}");
                    let want = bytes[..n]
                        .iter()
                        .fold(0u64, |m, d| m * 10 + u64::from(d - b'0'));
                    assert_eq!(eight_digits_value(v, n), want, "{bytes:?}");
                }
            }
        }
    }

    /// Words followed by more text, as the line scanner sees them: the fast reading of
    /// the usual shapes gives `number_prefix`'s value and length bit for bit, and a
    /// space must follow; the usual shapes do take it.
    #[test]
    fn spaced_numbers_read_as_number_prefix_reads_them() {
        let mut words: Vec<String> = [
            "0",
            "-0",
            "1",
            "5.",
            ".5",
            "-.5",
            "10.925434",
            "-0.46798942",
            "0.00000001",
            "9999999.99999999",
            "1234567.12345678",
            "0.12345678",
            "12.12345678",
            "00000001.5",
            "0.123456789",
            "12345678",
            "1e5",
            "+1",
            "-",
            ".",
            "-.",
            "1.5x",
            "1.2.3",
            "--1",
            "9007199254740993",
            "1234567.1234567",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..50_000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let int = (seed >> 8) % 10u64.pow((seed % 9) as u32);
            let precision = (seed >> 40) as usize % 10;
            let fraction = (seed >> 20) % 10u64.pow(precision as u32);
            let sign = if seed & 1 == 1 { "-" } else { "" };
            words.push(if precision == 0 {
                format!("{sign}{int}")
            } else {
                format!("{sign}{int}.{fraction:0precision$}")
            });
        }
        let mut fast = 0;
        for w in &words {
            for tail in [
                " ",
                "\t1 2 3\n",
                "\n",
                "\r\n",
                "x",
                "5",
                "\u{a0}",
                "",
                "        ",
            ] {
                let text = format!("{w}{tail}");
                let b = text.as_bytes();
                let Some((x, n)) = spaced_number(b) else {
                    continue;
                };
                fast += 1;
                assert!(is_space(b[n]), "{text:?}");
                let reference = number_prefix(b).map(|(x, n)| (x.to_bits(), n));
                assert_eq!(Some((x.to_bits(), n)), reference, "{text:?}");
                assert_eq!(
                    radiance_number(&b[..n]).map(f64::to_bits),
                    Some(x.to_bits())
                );
            }
        }
        assert!(fast > 100_000, "{fast}");
        for w in [
            "10.925434 ",
            "-0.46798942\n",
            "0 1",
            "5.\t",
            ".5 ",
            "-1234567.12345678 ",
        ] {
            // Eight bytes are read at a time: the buffer goes on after the word.
            let text = format!("{w}1 2 3 4 5 6");
            assert!(spaced_number(text.as_bytes()).is_some(), "{w:?}");
        }
        for w in [
            "1e5     ",
            "+1      ",
            "-       ",
            ".       ",
            "12345678.5 ",
            "0.123456789 ",
            "1.5x    ",
            "1 ",
        ] {
            assert!(spaced_number(w.as_bytes()).is_none(), "{w:?}");
        }
    }

    #[test]
    fn number_prefix_stops_where_the_syntax_does() {
        for (w, v, n) in [
            ("1.5x", 1.5, 3),
            ("-2e3.5", -2e3, 4),
            ("7 8", 7.0, 1),
            ("12345678901234567890123 ", 12345678901234567890123.0, 23),
            (".5e-1e", 0.05, 5),
        ] {
            let got = number_prefix(w.as_bytes());
            assert_eq!(
                got.map(|(x, n)| (x.to_bits(), n)),
                Some((f64::to_bits(v), n)),
                "{w}"
            );
        }
        // An exponent marker without digits: no number (no word starting so is one).
        for w in ["x1", "e5", "-x", "+.e1", "", "3e", "3e+ 1"] {
            assert_eq!(number_prefix(w.as_bytes()), None, "{w}");
        }
    }

    /// The fast `%e` answers the usual values itself, gives way near rounding ties and
    /// at the ends of its range, and agrees with the reference at carries into the
    /// next power of ten.
    #[test]
    fn fast_exp_takes_the_usual_values_and_leaves_ties() {
        let fast = |x: f64| {
            let mut buf = [0u8; 16];
            fast_exp(x, &mut buf).map(|n| String::from_utf8_lossy(&buf[..n]).into_owned())
        };
        for (x, want) in [
            (0.0, "0.000000e+00"),
            (-0.0, "-0.000000e+00"),
            (1.0, "1.000000e+00"),
            (-2.5, "-2.500000e+00"),
            (0.123_456_74, "1.234567e-01"),
            (123_456.76, "1.234568e+05"),
            (9.999_999_6, "1.000000e+01"),
            (-9.999_999_6e-10, "-1.000000e-09"),
            (1e-15, "1.000000e-15"),
            (9.99e18, "9.990000e+18"),
        ] {
            assert_eq!(fast(x).as_deref(), Some(want), "{x:e}");
        }
        // Exact halves between seven-digit neighbours, and values within 1e-6 of one.
        for x in [
            1.234_567_5,
            2.000_000_5e3,
            1.250_000_5e-7,
            1.234_567_500_000_1,
        ] {
            assert_eq!(fast(x), None, "{x:e}");
            assert_eq!(c_exp(x), c_exp_reference(x), "{x:e}");
        }
        for x in [1e19, 9.99e-16, f64::MIN_POSITIVE, f64::INFINITY, f64::NAN] {
            assert_eq!(fast(x), None, "{x:e}");
        }
        for e in -15..19 {
            let p = 10f64.powi(e);
            for x in [
                p,
                p.next_up(),
                p.next_down(),
                9.999_999_5 * p,
                9.999_999_4 * p,
            ] {
                assert_eq!(c_exp(x), c_exp_reference(x), "{x:e}");
            }
        }
    }
}
