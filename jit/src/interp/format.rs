//! rcalc's output: `printf("%.9g")` per column, columns separated by the separator
//! character, a missing column left empty (rcalc.c `chanset`).
//!
//! Two routes to the same digits: [`format_g`] is the exact one (Rust's correctly
//! rounded `{:.*e}`), [`write_g9`] the fast one `radc calc` uses per record, which
//! scales by an exact power of ten and hands the cases it cannot decide to the exact
//! one (property-tested to give the same bytes on any double).

/// C's `%.{precision}g`, including glibc's `nan`, `-nan`, `inf` and `-0`.
pub fn format_g(v: f64, precision: usize) -> String {
    if let Some(s) = special(v) {
        return s.to_string();
    }
    let p = precision.max(1);
    // The exponent after rounding to p significant digits decides the style.
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

fn special(v: f64) -> Option<&'static str> {
    if v.is_nan() {
        Some(if v.is_sign_negative() { "-nan" } else { "nan" })
    } else if v.is_infinite() {
        Some(if v < 0.0 { "-inf" } else { "inf" })
    } else if v == 0.0 {
        Some(if v.is_sign_negative() { "-0" } else { "0" })
    } else {
        None
    }
}

fn strip_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// Appends C's `%.9g` of `v` to `out`: the same bytes as `format_g(v, 9)`, without
/// allocating.
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
fn nine_digits(v: f64) -> Option<Decimal> {
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
    let mut d = Decimal {
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

const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `d1.d2... x 10^exp`, digits without trailing zeros.
struct Decimal {
    negative: bool,
    digits: [u8; 9],
    len: usize,
    exp: i32,
}

impl Decimal {
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

/// Appends one output line, with its newline (nothing when there are no outputs).
pub fn write_outputs(line: &mut Vec<u8>, values: &[(u32, f64)], sep: char) {
    let mut sep_bytes = [0u8; 4];
    let sep = sep.encode_utf8(&mut sep_bytes).as_bytes();
    let mut col = 0u32;
    for &(n, v) in values {
        if col == 0 {
            col = 1;
        }
        while col < n {
            line.extend_from_slice(sep);
            col += 1;
        }
        write_g9(line, v);
    }
    if col > 0 {
        line.push(b'\n');
    }
}

/// One output line, with its newline; empty when there are no outputs.
pub fn format_outputs(values: &[(u32, f64)], sep: char) -> String {
    let mut line = Vec::new();
    write_outputs(&mut line, values, sep);
    String::from_utf8(line).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

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

    #[test]
    fn missing_columns_stay_empty() {
        assert_eq!(format_outputs(&[(1, 1.0), (3, 2.0)], '\t'), "1\t\t2\n");
        assert_eq!(format_outputs(&[], '\t'), "");
    }
}
