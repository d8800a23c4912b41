//! Decimal digits eight bytes at a time: the digit runs [`super::real_prefix`] reads,
//! and the pieces rtrace's ray reader (`src/cli/ray_text.rs` `spaced_number`) builds
//! its fast path from. A few multiplications per eight digits instead of a loop per
//! digit: reading rays is dominated by reading numbers.

/// The powers of ten an `f64` holds exactly.
pub const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `10^n` for the runs of digits `digit_run` takes at once.
pub const POW10_U64: [u64; 9] = [
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

/// The eight bytes of `w` from `at`, the first lowest.
#[inline(always)]
pub fn load8(w: &[u8], at: usize) -> Option<u64> {
    let mut word = [0u8; 8];
    word.copy_from_slice(w.get(at..at + 8)?);
    Some(u64::from_le_bytes(word))
}

/// The decimal digits of `w` from `at` on, appended to `mantissa` (wrapping: a long
/// run only counts its digits, the value goes to Rust's parser), and where they end.
/// Eight bytes at a time where `w` has them.
#[inline(always)]
pub fn digit_run(w: &[u8], mut at: usize, mut mantissa: u64) -> (u64, usize) {
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
pub fn leading_digits(v: u64) -> usize {
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
pub fn eight_digits_value(v: u64, n: usize) -> u64 {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
