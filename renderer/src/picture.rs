//! The renderer's colours in and out of Radiance pictures. The format itself (header,
//! resolution line, RGBE scanlines exactly as Radiance writes them) lives in
//! `radc-picture`, the one home of pictures; this module only converts the renderer's
//! `f64` colours (glam vectors) to and from it.

use std::io::{self, Write};

use crate::math::Color;

/// Shared exponent colour (`setcolr`): see [`radc_picture::encode`].
pub fn rgbe(c: Color) -> [u8; 4] {
    radc_picture::encode(c.x, c.y, c.z)
}

/// Decodes one RGBE pixel (the centre of its quantization step).
pub fn from_rgbe(p: [u8; 4]) -> Color {
    let [r, g, b] = radc_picture::decode(p);
    Color::new(f64::from(r), f64::from(g), f64::from(b))
}

/// Writes a picture as rpict does: `header` lines (without the magic line and format),
/// then `width` by `height` pixels given top row first.
pub fn write(
    out: &mut impl Write,
    header: &[String],
    width: u32,
    height: u32,
    pixels: &[Color],
) -> io::Result<()> {
    let px: Vec<[f64; 3]> = pixels.iter().map(|c| c.to_array()).collect();
    radc_picture::write_rgb(out, header, width, height, &px)
}

/// Reads a picture: width, height and pixels top row first whatever the file's
/// orientation; `None` if it is not a picture `radc_picture` can read.
pub fn read(data: &[u8]) -> Option<(u32, u32, Vec<[u8; 4]>)> {
    let p = radc_picture::Picture::read(data).ok()?;
    Some((p.width(), p.height(), p.standard_pixels()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgbe_round_trip_is_within_a_step() {
        for c in [
            Color::new(1.0, 0.5, 0.25),
            Color::new(1e-3, 2e-3, 0.0),
            Color::new(1234.0, 1.0, 0.0),
        ] {
            let d = from_rgbe(rgbe(c));
            let step = c.max_element() / 128.0;
            assert!((d - c).abs().max_element() <= step, "{c:?} -> {d:?}");
        }
        assert_eq!(rgbe(Color::ZERO), [0; 4]);
        assert_eq!(rgbe(Color::new(1.0, 1.0, 1.0)), [128, 128, 128, 129]);
    }

    #[test]
    fn scanlines_round_trip() {
        let w = 300u32;
        let pixels: Vec<Color> = (0..w * 3)
            .map(|i| {
                let x = f64::from(i % w);
                if x < 100.0 {
                    Color::splat(0.5)
                } else {
                    Color::new(x / 300.0, 0.1, (x % 7.0) / 7.0)
                }
            })
            .collect();
        let mut out = Vec::new();
        write(&mut out, &["SOFTWARE= test".into()], w, 3, &pixels).unwrap();
        assert!(out.starts_with(b"#?RADIANCE\n"));
        let (rw, rh, back) = read(&out).unwrap();
        assert_eq!((rw, rh), (w, 3));
        let want: Vec<[u8; 4]> = pixels.iter().map(|c| rgbe(*c)).collect();
        assert_eq!(back, want);
    }
}
