//! The tone map for 8-bit pictures (`radc render -o x.png`): one global exposure, a
//! clamp, and the sRGB transfer curve. Deliberately simple and predictable (no local
//! adaptation as `pcond` does): the Radiance picture keeps the real values.
//!
//! Exposure: chosen so the mean brightness (`pbright`, the luminance weights of
//! Radiance's primaries) of the picture's non-black pixels maps to 0.5, the idea of
//! pfilt's automatic exposure; black pixels (a sky that is not modelled, the outside of
//! a fisheye's circle) are left out so they do not overexpose the rest. Each channel is
//! multiplied by it, clamped to [0, 1] and encoded with the sRGB curve (IEC 61966-2-1:
//! linear below 0.0031308, else `1.055 v^(1/2.4) - 0.055`), then rounded to 8 bits.
//! Radiance's primaries are close enough to sRGB's that no colour matrix is applied.

/// The brightness weights as `color.h`'s comment rounds them: the PNGs radc has always
/// written use these, so they stay.
fn brightness(c: [f64; 3]) -> f64 {
    0.265074126 * c[0] + 0.670114631 * c[1] + 0.064811243 * c[2]
}

/// The exposure that maps the mean brightness of the non-black `pixels` to 0.5 (1 for
/// a black or empty picture). Non-finite pixels are left out.
pub fn auto_exposure(pixels: &[[f64; 3]]) -> f64 {
    let (sum, n) = pixels
        .iter()
        .map(|c| brightness(c.map(|v| v.max(0.0))))
        .filter(|b| b.is_finite() && *b > 0.0)
        .fold((0.0, 0usize), |(s, n), b| (s + b, n + 1));
    let mean = if n > 0 { sum / n as f64 } else { 0.0 };
    if mean > 1e-30 { 0.5 / mean } else { 1.0 }
}

/// One channel, linear to 8-bit sRGB.
pub fn srgb8(v: f64) -> u8 {
    // NaN compares false: it ends up 0.
    let v = if v > 0.0 { v.min(1.0) } else { 0.0 };
    let e = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0 + 0.5) as u8
}

/// `pixels` as 8-bit RGB triples, in the same order.
pub fn to_srgb8(pixels: &[[f64; 3]], exposure: f64) -> Vec<u8> {
    pixels
        .iter()
        .flat_map(|c| c.map(|v| srgb8(v * exposure)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_curve_end_points_and_middle() {
        assert_eq!(srgb8(0.0), 0);
        assert_eq!(srgb8(1.0), 255);
        assert_eq!(srgb8(7.0), 255, "clamped");
        assert_eq!(srgb8(-1.0), 0);
        assert_eq!(srgb8(f64::NAN), 0);
        // sRGB mid grey: linear 0.2140 encodes as 0.5 (127.5).
        assert!((127..=128).contains(&srgb8(0.2140)));
        // The linear toe: 0.002 * 12.92 * 255 = 6.59.
        assert_eq!(srgb8(0.002), 7);
    }

    #[test]
    fn auto_exposure_maps_the_mean_to_half() {
        let px = vec![[2.0; 3], [0.0; 3], [6.0; 3]];
        let e = auto_exposure(&px);
        assert!((e - 0.125).abs() < 1e-9, "{e}");
        assert_eq!(auto_exposure(&[[0.0; 3]]), 1.0);
        assert_eq!(auto_exposure(&[]), 1.0);
        assert_eq!(to_srgb8(&px, e).len(), 9);
    }
}
