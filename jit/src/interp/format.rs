//! rcalc's output: `printf("%.9g")` per column, columns separated by the separator
//! character, a missing column left empty (rcalc.c `chanset`).

/// C's `%.{precision}g`, including glibc's `nan`, `-nan`, `inf` and `-0`.
pub fn format_g(v: f64, precision: usize) -> String {
    if v.is_nan() {
        return if v.is_sign_negative() { "-nan" } else { "nan" }.to_string();
    }
    if v.is_infinite() {
        return if v < 0.0 { "-inf" } else { "inf" }.to_string();
    }
    let p = precision.max(1);
    if v == 0.0 {
        return if v.is_sign_negative() { "-0" } else { "0" }.to_string();
    }
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

fn strip_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// One output line, with its newline; empty when there are no outputs.
pub fn format_outputs(values: &[(u32, f64)], sep: char) -> String {
    let mut line = String::new();
    let mut col = 0u32;
    for &(n, v) in values {
        if col == 0 {
            col = 1;
        }
        while col < n {
            line.push(sep);
            col += 1;
        }
        line.push_str(&format_g(v, 9));
    }
    if col > 0 {
        line.push('\n');
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_printf_g() {
        let cases: &[(f64, &str)] = &[
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
        ];
        for (v, s) in cases {
            assert_eq!(format_g(*v, 9), *s, "{v}");
        }
    }

    #[test]
    fn missing_columns_stay_empty() {
        assert_eq!(format_outputs(&[(1, 1.0), (3, 2.0)], '\t'), "1\t\t2\n");
        assert_eq!(format_outputs(&[], '\t'), "");
    }
}
