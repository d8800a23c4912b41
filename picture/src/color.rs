//! Shared-exponent colours (`src/common/color.c`: `setcolr`, `colr_color`) and
//! Radiance's brightness weights (`color.h`: `bright`, `CIE_rf` ...).

/// One pixel as stored: three 8-bit mantissas and an exponent biased by 128 (RGBE, or
/// XYZE in an XYZ picture: the bytes do not say which).
pub type Colr = [u8; 4];

/// Encodes a colour as `setcolr` does: the largest component `d = m * 2^e` (`frexp`,
/// `m` in [0.5, 1)) sets the exponent, each component is scaled by `256 / 2^e` and
/// truncated. Below 1e-32 the pixel is black. Radiance lets the exponent byte wrap for
/// values beyond 2^127; radc saturates to the largest pixel instead (and to black below
/// 2^-128), and negative or NaN components become 0 as `(r > 0) * (int)(r*d)` makes them.
pub fn encode(r: f64, g: f64, b: f64) -> Colr {
    let d = r.max(g).max(b);
    if d.is_nan() || d <= 1e-32 {
        return [0; 4];
    }
    let d = d.min(f64::MAX);
    // The exponent of frexp, read from the bits: d is a normal number here.
    let e = ((d.to_bits() >> 52) & 0x7ff) as i32 - 1022;
    if !(-128..=127).contains(&e) {
        return if e > 127 { [255; 4] } else { [0; 4] };
    }
    // 256 / 2^e is exact, as is Radiance's frexp(d) * 256 / d.
    let scale = 256.0 / 2f64.powi(e);
    let q = |x: f64| (x.max(0.0) * scale).min(255.0) as u8;
    [q(r), q(g), q(b), (e + 128) as u8]
}

/// The multiplier of exponent byte `e` (`cxponent[e]`): 2^(e - 136) in single
/// precision, 0 for `e = 0`.
pub fn exponent_scale(e: u8) -> f32 {
    if e == 0 {
        0.0
    } else {
        // 2^(e-136) for e in 1..=255 lies in 2^-135 ..= 2^119: exact in f32 (the
        // smallest are subnormal but still powers of two).
        2f64.powi(i32::from(e) - 136) as f32
    }
}

/// Decodes a pixel as `colr_color` does, in single precision: `(m + 0.5) * 2^(e-136)`,
/// black when the exponent byte is 0.
pub fn decode(c: Colr) -> [f32; 3] {
    let f = exponent_scale(c[3]);
    [
        (f32::from(c[0]) + 0.5) * f,
        (f32::from(c[1]) + 0.5) * f,
        (f32::from(c[2]) + 0.5) * f,
    ]
}

// Radiance's standard primaries and equal-energy white (`color.h`, the default branch).
const XR: f64 = 0.640;
const YR: f64 = 0.330;
const XG: f64 = 0.290;
const YG: f64 = 0.600;
const XB: f64 = 0.150;
const YB: f64 = 0.060;
const XW: f64 = 1. / 3.;
const YW: f64 = 1. / 3.;
const D: f64 = XR * (YG - YB) + XG * (YB - YR) + XB * (YR - YG);
const C_RD: f64 = (1. / YW) * (XW * (YG - YB) - YW * (XG - XB) + XG * YB - XB * YG);
const C_GD: f64 = (1. / YW) * (XW * (YB - YR) - YW * (XB - XR) - XR * YB + XB * YR);
const C_BD: f64 = (1. / YW) * (XW * (YR - YG) - YW * (XR - XG) + XR * YG - XG * YR);

/// The weights of `bright()`, computed from the primaries by the same expressions as
/// `color.h`'s `CIE_rf CIE_gf CIE_bf` (not the rounded values its comment quotes), so
/// `pvalue -b` prints the same numbers.
pub const CIE_RF: f64 = YR * C_RD / D;
pub const CIE_GF: f64 = YG * C_GD / D;
pub const CIE_BF: f64 = YB * C_BD / D;

/// The photometric brightness of an RGB colour (`bright()`): Y for Radiance's primaries.
pub fn bright(c: [f32; 3]) -> f64 {
    CIE_RF * f64::from(c[0]) + CIE_GF * f64::from(c[1]) + CIE_BF * f64::from(c[2])
}

/// Lumens per watt of equal-energy white (`WHTEFFICACY`).
pub const WHITE_EFFICACY: f64 = 179.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_matches_setcolr() {
        assert_eq!(encode(0.0, 0.0, 0.0), [0; 4]);
        assert_eq!(encode(1.0, 1.0, 1.0), [128, 128, 128, 129]);
        assert_eq!(encode(1.0, 0.5, 0.25), [128, 64, 32, 129]);
        assert_eq!(encode(-1.0, 0.5, f64::NAN), [0, 128, 0, 128]);
        assert_eq!(encode(1e-40, 0.0, 0.0), [0; 4]);
        assert_eq!(encode(1e300, 0.0, 0.0), [255; 4]);
    }

    #[test]
    fn decode_is_the_centre_of_the_step() {
        assert_eq!(
            decode([128, 64, 0, 129]),
            [1.0 + 1.0 / 256.0, 0.5 + 1.0 / 256.0, 1.0 / 256.0]
        );
        assert_eq!(decode([200, 1, 2, 0]), [0.0; 3]);
        assert_eq!(exponent_scale(136), 1.0);
        assert_eq!(exponent_scale(1), 2f64.powi(-135) as f32);
    }

    #[test]
    fn brightness_weights_are_color_h_values() {
        // What the expressions give (pvalue -b -dd prints these sums); color.h's comment
        // quotes other, older values.
        assert_eq!(CIE_RF, 0.26510582010582007);
        assert_eq!(CIE_GF, 0.6701058201058199);
        assert_eq!(CIE_BF, 0.06478835978835978);
        assert_eq!(
            bright([1.0 + 1.0 / 256.0, 1.0 / 256.0, 1.0 / 256.0]),
            0.26901207010582007
        );
    }

    #[test]
    fn round_trip_is_within_a_step() {
        for c in [[1.0, 0.5, 0.25], [1e-3, 2e-3, 0.0], [1234.0, 1.0, 0.0]] {
            let d = decode(encode(c[0], c[1], c[2]));
            let step = c.iter().copied().fold(0.0, f64::max) / 128.0;
            for i in 0..3 {
                assert!((f64::from(d[i]) - c[i]).abs() <= step, "{c:?} -> {d:?}");
            }
        }
    }
}
