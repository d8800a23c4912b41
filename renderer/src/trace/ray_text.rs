//! rtrace's text I/O on the hot path: real numbers in Radiance's syntax in, C's `%e`
//! out. The definitions are `radc_lang::c_number`'s (`real_prefix`, `format_e`); here
//! are only the fast paths for the common case (up to 15 digits and no exponent in;
//! 7 significant digits not near a rounding tie out), which stay beside the ray reader
//! and writer because they are specialised to the shapes rays have and must inline
//! into the line loop; everything else falls back on the shared definitions, whose
//! results they equal bit for bit (tested here).

use radc_lang::c_number::digits::{POW10, POW10_U64, eight_digits_value, leading_digits, load8};
use radc_lang::c_number::{format_e, is_c_space};

/// The number at the start of `w` when it has the usual shape of ray input
/// (`[-]digits[.digits]`: fewer than 8 digits before the point, at most 8 after) and a
/// space follows, with its length; `None` for anything else, which `c_number::real_prefix`
/// decides. Two eight-byte loads instead of a loop per byte; the value is
/// `real_prefix`'s (the same integer, at most 15 digits, over the same power of ten).
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
    if digits == 0 || !w.get(end).is_some_and(|&b| is_c_space(b)) {
        return None;
    }
    // Below 1e15: exact either way, and a signed conversion is one instruction.
    let v = mantissa as i64 as f64 / POW10[fraction_digits];
    Some((if negative { -v } else { v }, end))
}

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

/// `%e` by the shared definition, for what `fast_exp` leaves (near ties, far ends).
#[cold]
#[inline(never)]
fn slow_exp(x: f64, buf: &mut [u8; 16]) -> usize {
    // At most "-d.dddddde-324": 14 bytes.
    let text = format_e(x, 6);
    let n = text.len().min(buf.len());
    buf[..n].copy_from_slice(&text.as_bytes()[..n]);
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use radc_lang::c_number::{real_prefix, real_word};

    fn c_exp(x: f64) -> String {
        let mut buf = [0u8; 16];
        let n = c_exp_into(x, &mut buf);
        String::from_utf8_lossy(&buf[..n]).into_owned()
    }

    /// `%e` written the straightforward way, by the shared definition.
    fn c_exp_reference(x: f64) -> String {
        format_e(x, 6)
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

    /// Words followed by more text, as the line scanner sees them: the fast reading of
    /// the usual shapes gives `real_prefix`'s value and length bit for bit, and a
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
                assert!(is_c_space(b[n]), "{text:?}");
                let reference = real_prefix(b).map(|(x, n)| (x.to_bits(), n));
                assert_eq!(Some((x.to_bits(), n)), reference, "{text:?}");
                assert_eq!(real_word(&b[..n]).map(f64::to_bits), Some(x.to_bits()));
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
