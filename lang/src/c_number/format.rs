//! C's `printf` number conversions, digit for digit: `%g` ([`format_g`],
//! [`format_g_width`]), `%e` ([`format_e`]) and `%.9g` without allocating
//! ([`write_g9`], rcalc's output).
//!
//! Radiance's generators print reals with `%18.12g` (and xform's material tweaks with
//! `%12.6g`), rcalc with `%.9g` (and `%g`, `%.Ne` in `-o` formats), rtrace with `%e`;
//! reproducing their output exactly needs C's rules: round to P significant digits,
//! use exponent form when the exponent is below -4 or at least P, drop trailing zeros,
//! keep the sign of negative zero, at least two exponent digits, glibc's `nan`, `-nan`,
//! `inf`, `-inf`. Rust's `{:.*e}` and `{:.*}` round the exact binary value (ties to
//! even) as glibc does.

use super::digits::POW10;

/// `%W.Pg`: right-aligned in `width` columns.
pub fn format_g_width(value: f64, width: usize, precision: usize) -> String {
    let body = format_g(value, precision);
    format!("{body:>width$}")
}

/// `%.Pg` without padding.
pub fn format_g(value: f64, precision: usize) -> String {
    if let Some(s) = nonfinite(value) {
        return s.to_string();
    }
    let p = precision.max(1);
    // Round once, to p significant digits; the exponent after rounding decides the
    // style, and `%f` with p-1-x decimals would round at the very same digit, so the
    // fixed form is built from these digits.
    let sci = format!("{:.*e}", p - 1, value);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let x: i64 = exp.parse().unwrap_or(0);
    if x < -4 || x >= p as i64 {
        let mantissa = strip_zeros(mantissa);
        let sign = if x < 0 { '-' } else { '+' };
        return format!("{mantissa}e{sign}{:02}", x.unsigned_abs());
    }
    let (sign, unsigned) = match mantissa.strip_prefix('-') {
        Some(rest) => ("-", rest),
        None => ("", mantissa),
    };
    let digits: String = unsigned.chars().filter(char::is_ascii_digit).collect();
    let mut out = String::with_capacity(digits.len() + 8);
    out.push_str(sign);
    if x >= 0 {
        let (int, frac) = digits.split_at((x as usize + 1).min(digits.len()));
        out.push_str(int);
        out.push('.');
        out.push_str(frac);
    } else {
        out.push_str("0.");
        out.extend(std::iter::repeat_n('0', (-x - 1) as usize));
        out.push_str(&digits);
    }
    strip_zeros(&out).to_string()
}

/// `%.Pe`: mantissa with P decimals, exponent signed with at least two digits.
pub fn format_e(value: f64, precision: usize) -> String {
    if let Some(s) = nonfinite(value) {
        return s.to_string();
    }
    let sci = format!("{value:.precision$e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let x: i64 = exp.parse().unwrap_or(0);
    let sign = if x < 0 { '-' } else { '+' };
    format!("{mantissa}e{sign}{:02}", x.unsigned_abs())
}

/// glibc's text for NaNs (with their sign) and infinities.
fn nonfinite(v: f64) -> Option<&'static str> {
    if v.is_nan() {
        Some(if v.is_sign_negative() { "-nan" } else { "nan" })
    } else if v.is_infinite() {
        Some(if v < 0.0 { "-inf" } else { "inf" })
    } else {
        None
    }
}

/// `%g`'s special forms: [`nonfinite`], and zero with its sign.
fn special(v: f64) -> Option<&'static str> {
    if v == 0.0 {
        Some(if v.is_sign_negative() { "-0" } else { "0" })
    } else {
        nonfinite(v)
    }
}

/// `%g` drops the trailing zeros of a fraction, and the point if nothing is left.
fn strip_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// Appends C's `%.9g` of `v` to `out`: the same bytes as `format_g(v, 9)`, without
/// allocating: scales by an exact power of ten and hands the cases it cannot
/// decide to `format_g` (property-tested to give the same bytes on any double).
pub fn write_g9(out: &mut Vec<u8>, v: f64) {
    if let Some(s) = special(v) {
        out.extend_from_slice(s.as_bytes());
        return;
    }
    match nine_digits(v) {
        Some(d) => d.write_g9(out),
        None => out.extend_from_slice(format_g(v, 9).as_bytes()),
    }
}

/// `v` rounded to 9 significant digits by scaling it into `[1e8, 1e9)` with one
/// exact power of ten (one rounding, at most half an ulp of the scaled value, about
/// 6e-8) and rounding to an integer; `None` where that cannot be trusted: powers of
/// ten beyond 1e22 (not exact doubles) and scaled values within 1e-6 of a halfway
/// point, which only the exact digits can settle.
fn nine_digits(v: f64) -> Option<NineDigits> {
    let a = v.abs();
    let e2 = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    // floor(log10(a)) or one less: floor(e2 * log10(2)) in fixed point (exact for
    // |e2| < 1650, as 78913 / 2^18 approximates log10(2) to 2e-7).
    let mut x = (e2 * 78913) >> 18;
    let scaled = |x: i32| -> Option<f64> {
        let k = 8 - x;
        let p = *POW10.get(k.unsigned_abs() as usize)?;
        Some(if k >= 0 { a * p } else { a / p })
    };
    let mut t = scaled(x)?;
    if t >= 1e9 {
        x += 1;
        t = scaled(x)?;
    } else if t < 1e8 {
        x -= 1;
        t = scaled(x)?;
    }
    // t is positive and below about 1e9: truncation is floor (and no libm call).
    let whole = t as u64;
    let frac = t - whole as f64;
    if (frac - 0.5).abs() < 1e-6 {
        return None;
    }
    // After one correction t is in [1e8, 1e9) but for the rounding of the scaling
    // itself, which can only carry m to 1e9.
    let mut m = whole + u64::from(frac > 0.5);
    if m == 1_000_000_000 {
        m = 100_000_000;
        x += 1;
    } else if !(100_000_000..1_000_000_000).contains(&m) {
        return None;
    }
    let mut d = NineDigits {
        negative: v < 0.0,
        digits: [b'0'; 9],
        len: 9,
        exp: x,
    };
    // Two digits at a time.
    let (mut hi, lo) = ((m / 10) as u32, (m % 10) as u8);
    d.digits[8] = b'0' + lo;
    for k in (0..4).rev() {
        let pair = (hi % 100) as usize;
        hi /= 100;
        d.digits[2 * k] = b'0' + (pair / 10) as u8;
        d.digits[2 * k + 1] = b'0' + (pair % 10) as u8;
    }
    while d.len > 1 && d.digits[d.len - 1] == b'0' {
        d.len -= 1;
    }
    Some(d)
}

/// `d1.d2... x 10^exp`, digits without trailing zeros.
struct NineDigits {
    negative: bool,
    digits: [u8; 9],
    len: usize,
    exp: i32,
}

impl NineDigits {
    fn write_g9(&self, out: &mut Vec<u8>) {
        // At most "-d.dddddddde-308": laid out here, appended once.
        let mut buf = [0u8; 24];
        let mut n = 0;
        let mut put = |bytes: &[u8]| {
            buf[n..n + bytes.len()].copy_from_slice(bytes);
            n += bytes.len();
        };
        if self.negative {
            put(b"-");
        }
        let digits = &self.digits[..self.len];
        let x = self.exp;
        if !(-4..9).contains(&x) {
            put(&digits[..1]);
            if digits.len() > 1 {
                put(b".");
                put(&digits[1..]);
            }
            put(if x < 0 { b"e-" } else { b"e+" });
            let e = x.unsigned_abs();
            if e >= 100 {
                put(&[b'0' + (e / 100) as u8]);
            }
            put(&[b'0' + (e / 10 % 10) as u8, b'0' + (e % 10) as u8]);
        } else if x >= 0 {
            let int = x as usize + 1;
            if digits.len() <= int {
                put(digits);
                put(&[b'0'; 9][..int - digits.len()]);
            } else {
                put(&digits[..int]);
                put(b".");
                put(&digits[int..]);
            }
        } else {
            put(b"0.");
            put(&[b'0'; 4][..(-x - 1) as usize]);
            put(digits);
        }
        out.extend_from_slice(&buf[..n]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    // Expected strings are Python's `'%18.12g' % x`, which follows C.
    #[test]
    fn matches_c_g_format() {
        let cases: &[(f64, &str)] = &[
            (0.0, "0"),
            (-0.0, "-0"),
            (1.0, "1"),
            (0.1, "0.1"),
            (2.220_446_049_250_313e-16, "2.22044604925e-16"),
            (std::f64::consts::SQRT_2, "1.41421356237"),
            (123456789012.0, "123456789012"),
            (1234567890123.0, "1.23456789012e+12"),
            (0.0001, "0.0001"),
            (0.00001234, "1.234e-05"),
            (-2.5e100, "-2.5e+100"),
            (0.5, "0.5"),
            (999999999999.5, "1e+12"),
            (1e-300, "1e-300"),
        ];
        for &(x, want) in cases {
            assert_eq!(format_g(x, 12), want, "{x:e}");
        }
        assert_eq!(format_g_width(1.0, 18, 12), "                 1");
        assert_eq!(format_g_width(0.05, 12, 6), "        0.05");
        assert_eq!(format_g(2.5, 1), "2");
        assert_eq!(format_g(0.000123456, 3), "0.000123");
        assert_eq!(format_e(0.0, 6), "0.000000e+00");
        assert_eq!(format_e(-0.0, 6), "-0.000000e+00");
        assert_eq!(format_e(123456.789, 6), "1.234568e+05");
        assert_eq!(format_e(1.5e-300, 2), "1.50e-300");
    }

    /// The digit-reusing fixed form agrees with formatting twice, as C does.
    #[test]
    fn fixed_form_matches_two_pass_formatting() {
        let two_pass = |v: f64, p: usize| {
            let sci = format!("{:.*e}", p - 1, v);
            let x: i64 = sci
                .split_once('e')
                .map_or(0, |(_, e)| e.parse().unwrap_or(0));
            if x < -4 || x >= p as i64 {
                return None;
            }
            let d = (p as i64 - 1 - x).max(0) as usize;
            Some(strip_zeros(&format!("{v:.d$}")).to_string())
        };
        let mut state: u64 = 0x1234_5678_9abc_def0;
        for _ in 0..20000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mantissa = (state >> 11) as f64 / (1u64 << 53) as f64;
            let exponent = ((state % 23) as i32) - 8;
            let sign = if state & 1 == 1 { -1.0 } else { 1.0 };
            let v = sign * mantissa * 10f64.powi(exponent);
            for p in [1, 3, 6, 12] {
                if let Some(want) = two_pass(v, p) {
                    assert_eq!(format_g(v, p), want, "{v:e} at {p}");
                }
            }
        }
        for v in [
            0.5,
            9.5,
            99.5,
            0.00015,
            999999.5,
            0.0001,
            123456789012.0,
            -0.0,
        ] {
            assert_eq!(format_g(v, 12), two_pass(v, 12).unwrap_or_default(), "{v}");
        }
    }

    const CASES: &[(f64, &str)] = &[
        (1.0, "1"),
        (0.1, "0.1"),
        (1.0 / 3.0, "0.333333333"),
        (2.0 / 3.0, "0.666666667"),
        (1e9, "1e+09"),
        (123456789.0, "123456789"),
        (1234567890.0, "1.23456789e+09"),
        (1e-5, "1e-05"),
        (0.0001, "0.0001"),
        (0.00012345678912, "0.000123456789"),
        (-2.5e-300, "-2.5e-300"),
        (std::f64::consts::PI, "3.14159265"),
        (1e100, "1e+100"),
        (999999999.5, "1e+09"),
        (-0.0, "-0"),
        (f64::NAN, "nan"),
        (-f64::NAN, "-nan"),
        (f64::NEG_INFINITY, "-inf"),
        (5e-324, "4.94065646e-324"),
        (1234567895.0, "1.2345679e+09"),
        (1234567885.0, "1.23456788e+09"),
        (100.0, "100"),
        (1e16, "1e+16"),
        (123.456, "123.456"),
        (0.000099999999996, "0.0001"),
    ];

    #[test]
    fn matches_printf_g() {
        for (v, s) in CASES {
            assert_eq!(format_g(*v, 9), *s, "{v}");
        }
    }

    fn g9(v: f64) -> String {
        let mut out = Vec::new();
        write_g9(&mut out, v);
        String::from_utf8(out).expect("ascii")
    }

    #[test]
    fn fast_route_matches_printf_g() {
        for (v, s) in CASES {
            assert_eq!(g9(*v), *s, "{v}");
        }
    }

    /// Decimals of ten digits ending in 5 are the fast route's hard case: the
    /// shortest digits sit on the midpoint and only the exact value can round them.
    #[test]
    fn fast_route_on_midpoints() {
        for m in (1_000_000_005u64..1_000_100_000).step_by(10) {
            for e in [-12, -5, -1, 0, 3, 9, 20] {
                let v = m as f64 * 10f64.powi(e);
                assert_eq!(g9(v), format_g(v, 9), "{v:e}");
                assert_eq!(g9(-v), format_g(-v, 9), "{v:e}");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20000))]
        #[test]
        fn fast_route_equals_exact_on_any_bits(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assert_eq!(g9(v), format_g(v, 9));
        }

        #[test]
        fn fast_route_equals_exact_on_computed_values(x in -1e6f64..1e6, k in -20i32..25) {
            let v = x.sin() * 10f64.powi(k);
            prop_assert_eq!(g9(v), format_g(v, 9));
        }

        #[test]
        fn fast_route_equals_exact_on_short_decimals(m in 0i64..10_000_000_000, e in -30i32..30) {
            let v: f64 = format!("{m}e{e}").parse().unwrap_or(0.0);
            prop_assert_eq!(g9(v), format_g(v, 9));
        }
    }

    /// The one-pass `%g` against the two-pass form the interpreter used (`{:.*e}` for
    /// the exponent, then `{:.*}` with the decimals it implies), on any bits and
    /// precision.
    fn two_pass_g(v: f64, precision: usize) -> String {
        if let Some(s) = special(v) {
            return s.to_string();
        }
        let p = precision.max(1);
        let sci = format!("{:.*e}", p - 1, v);
        let (mantissa, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
        let x: i32 = exp.parse().unwrap_or(0);
        if x < -4 || x >= p as i32 {
            let m = strip_zeros(mantissa);
            let sign = if x < 0 { '-' } else { '+' };
            format!("{m}e{sign}{:02}", x.unsigned_abs())
        } else {
            let decimals = (p as i32 - 1 - x).max(0) as usize;
            strip_zeros(&format!("{v:.decimals$}")).to_string()
        }
    }

    proptest! {
        #[test]
        fn one_pass_g_equals_two_pass_g(bits in any::<u64>(), p in 0usize..20) {
            let v = f64::from_bits(bits);
            prop_assert_eq!(format_g(v, p), two_pass_g(v, p));
        }

        #[test]
        fn one_pass_g_equals_two_pass_g_on_short_decimals(m in -100_000i64..100_000, e in -8i32..14, p in 1usize..13) {
            let v: f64 = format!("{m}e{e}").parse().unwrap_or(0.0);
            prop_assert_eq!(format_g(v, p), two_pass_g(v, p));
        }
    }
}
