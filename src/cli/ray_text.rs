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
    let (negative, body) = match w.first() {
        Some(b'-') => (true, &w[1..]),
        Some(b'+') => (false, &w[1..]),
        _ => (false, w),
    };
    let mut at = 0;
    let mut mantissa = 0u64;
    let mut digits = 0u32;
    let mut scale = 0i64;
    let mut any = false;
    while let Some(&b) = body.get(at).filter(|b| b.is_ascii_digit()) {
        mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(b - b'0'));
        digits += 1;
        any = true;
        at += 1;
    }
    if body.get(at) == Some(&b'.') {
        at += 1;
        while let Some(&b) = body.get(at).filter(|b| b.is_ascii_digit()) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(b - b'0'));
            digits += 1;
            scale -= 1;
            any = true;
            at += 1;
        }
    }
    if !any {
        return None;
    }
    if matches!(body.get(at), Some(b'e' | b'E')) {
        at += 1;
        let negative_exp = match body.get(at) {
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
        let start = at;
        let mut exp = 0i64;
        while let Some(&b) = body.get(at).filter(|b| b.is_ascii_digit()) {
            exp = (exp * 10 + i64::from(b - b'0')).min(1 << 20);
            at += 1;
        }
        if at == start {
            return None;
        }
        scale += if negative_exp { -exp } else { exp };
    }
    if at != body.len() {
        return None;
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
        std::str::from_utf8(body).ok()?.parse::<f64>().ok()?
    };
    Some(if negative { -v } else { v })
}

/// C's `%e` of `x` (six decimals, an exponent of at least two digits:
/// `1.000000e+10`) into `buf`, returning the length.
pub fn c_exp_into(x: f64, buf: &mut [u8; 40]) -> usize {
    fast_exp(x, buf).unwrap_or_else(|| slow_exp(x, buf))
}

/// The common case: `x * 10^k` for an exact power of ten, rounded once, lies within
/// 1.2e-9 of the exact product; unless that is within 1e-6 of a half its rounding to an
/// integer is the exactly rounded seven digits. `None` leaves the rest to `slow_exp`.
fn fast_exp(x: f64, buf: &mut [u8; 40]) -> Option<usize> {
    let a = x.abs();
    if !(1e-15..1e19).contains(&a) {
        return None;
    }
    // floor(log10 a) within one, from the binary exponent (no libm calls: without
    // SSE4.1, floor and round are function calls).
    let binary = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let mut e = (binary * 78_913) >> 18;
    for _ in 0..4 {
        let k = 6 - e;
        let p = *POW10.get(k.unsigned_abs() as usize)?;
        let s = if k >= 0 { a * p } else { a / p };
        if s >= 1e7 {
            e += 1;
            continue;
        }
        if s < 1e6 {
            e -= 1;
            continue;
        }
        // 1e6 <= s < 1e7: the truncation is exact.
        let whole = s as u32;
        let fraction = s - f64::from(whole);
        if (fraction - 0.5).abs() < 1e-6 {
            return None;
        }
        let mut n = whole + u32::from(fraction > 0.5);
        if n >= 10_000_000 {
            n /= 10;
            e += 1;
        }
        let mut at = 0;
        if x < 0.0 {
            buf[0] = b'-';
            at = 1;
        }
        buf[at] = b'0' + (n / 1_000_000) as u8;
        buf[at + 1] = b'.';
        let mut rest = n % 1_000_000;
        for i in (0..6).rev() {
            buf[at + 2 + i] = b'0' + (rest % 10) as u8;
            rest /= 10;
        }
        at += 8;
        buf[at] = b'e';
        buf[at + 1] = if e < 0 { b'-' } else { b'+' };
        let m = e.unsigned_abs();
        buf[at + 2] = b'0' + (m / 10) as u8;
        buf[at + 3] = b'0' + (m % 10) as u8;
        return Some(at + 4);
    }
    None
}

/// `%e` by Rust's exactly rounded `{:.6e}`, the exponent rewritten; no allocation.
fn slow_exp(x: f64, buf: &mut [u8; 40]) -> usize {
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
        let mut buf = [0u8; 40];
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
}
