//! C's `printf` number conversions, digit for digit.
//!
//! Radiance's generators print reals with `%18.12g` (and xform's material tweaks with
//! `%12.6g`); reproducing their output exactly needs C's `%g` rules: round to P
//! significant digits, use exponent form when the exponent is below -4 or at least P,
//! drop trailing zeros, keep the sign of negative zero, at least two exponent digits.
//! Rust's `{:.*e}` and `{:.*}` round the exact binary value (ties to even) as glibc does.

/// `%W.Pg`: right-aligned in `width` columns.
pub fn g(value: f64, width: usize, precision: usize) -> String {
    let body = g_body(value, precision);
    format!("{body:>width$}")
}

/// `%.Pg` without padding.
pub fn g_body(value: f64, precision: usize) -> String {
    if value.is_nan() {
        return if value.is_sign_negative() {
            "-nan"
        } else {
            "nan"
        }
        .to_string();
    }
    if value.is_infinite() {
        return if value < 0.0 { "-inf" } else { "inf" }.to_string();
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
pub fn e(value: f64, precision: usize) -> String {
    if !value.is_finite() {
        return g_body(value, precision);
    }
    let sci = format!("{value:.precision$e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let x: i64 = exp.parse().unwrap_or(0);
    let sign = if x < 0 { '-' } else { '+' };
    format!("{mantissa}e{sign}{:02}", x.unsigned_abs())
}

fn strip_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
            assert_eq!(g_body(x, 12), want, "{x:e}");
        }
        assert_eq!(g(1.0, 18, 12), "                 1");
        assert_eq!(g(0.05, 12, 6), "        0.05");
        assert_eq!(g_body(2.5, 1), "2");
        assert_eq!(g_body(0.000123456, 3), "0.000123");
        assert_eq!(e(0.0, 6), "0.000000e+00");
        assert_eq!(e(-0.0, 6), "-0.000000e+00");
        assert_eq!(e(123456.789, 6), "1.234568e+05");
        assert_eq!(e(1.5e-300, 2), "1.50e-300");
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
                    assert_eq!(g_body(v, p), want, "{v:e} at {p}");
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
            assert_eq!(g_body(v, 12), two_pass(v, 12).unwrap_or_default(), "{v}");
        }
    }
}
