//! Radiance pictures (`src/common/color.c header.c resolu.c`): a text header, then RGBE
//! pixels, top scanline first, each scanline run-length encoded by byte plane.

use std::io::{self, Write};

use crate::math::Color;

/// Shared exponent colour: three 8-bit mantissas and an exponent biased by 128.
pub fn rgbe(c: Color) -> [u8; 4] {
    let d = c.max_element();
    if d.is_nan() || d <= 1e-32 {
        return [0; 4];
    }
    let d = d.min(f64::MAX);
    // d = m * 2^e with m in [0.5, 1) (C's frexp, read from the exponent bits; d is a
    // normal number here): the largest component maps to [128, 256).
    let e = ((d.to_bits() >> 52) & 0x7ff) as i32 - 1022;
    let scale = 256.0 / 2f64.powi(e);
    let q = |x: f64| (x.max(0.0) * scale).min(255.0) as u8;
    if !(-128..=127).contains(&e) {
        return if e > 127 {
            [255, 255, 255, 255]
        } else {
            [0; 4]
        };
    }
    [q(c.x), q(c.y), q(c.z), (e + 128) as u8]
}

/// Decodes one RGBE pixel (the centre of its quantization step).
pub fn from_rgbe(p: [u8; 4]) -> Color {
    if p[3] == 0 {
        return Color::ZERO;
    }
    let f = 2f64.powi(i32::from(p[3]) - (128 + 8));
    Color::new(
        (f64::from(p[0]) + 0.5) * f,
        (f64::from(p[1]) + 0.5) * f,
        (f64::from(p[2]) + 0.5) * f,
    )
}

/// Writes a picture: `header` lines (without the magic line and format), then `width`
/// by `height` pixels given top row first.
pub fn write(
    out: &mut impl Write,
    header: &[String],
    width: u32,
    height: u32,
    pixels: &[Color],
) -> io::Result<()> {
    writeln!(out, "#?RADIANCE")?;
    for line in header {
        writeln!(out, "{line}")?;
    }
    writeln!(out, "FORMAT=32-bit_rle_rgbe")?;
    writeln!(out)?;
    writeln!(out, "-Y {height} +X {width}")?;
    let mut buf = Vec::new();
    for row in pixels.chunks(width.max(1) as usize).take(height as usize) {
        buf.clear();
        let scan: Vec<[u8; 4]> = row.iter().map(|c| rgbe(*c)).collect();
        encode_scanline(&scan, &mut buf);
        out.write_all(&buf)?;
    }
    Ok(())
}

/// One scanline: new-style run-length encoding for widths 8..=32767, flat otherwise.
pub fn encode_scanline(scan: &[[u8; 4]], out: &mut Vec<u8>) {
    let n = scan.len();
    if !(8..=0x7fff).contains(&n) {
        for p in scan {
            out.extend_from_slice(p);
        }
        return;
    }
    out.extend_from_slice(&[2, 2, (n >> 8) as u8, (n & 0xff) as u8]);
    let mut plane = vec![0u8; n];
    for c in 0..4 {
        for (b, p) in plane.iter_mut().zip(scan) {
            *b = p[c];
        }
        encode_plane(&plane, out);
    }
}

/// Runs of 4 or more equal bytes as (128 + count, byte); everything else as literal
/// blocks of up to 128 bytes (count, bytes...).
fn encode_plane(p: &[u8], out: &mut Vec<u8>) {
    const MIN_RUN: usize = 4;
    let run_at = |i: usize| p[i..].iter().take(127).take_while(|&&b| b == p[i]).count();
    let mut i = 0;
    while i < p.len() {
        let run = run_at(i);
        if run >= MIN_RUN {
            out.push(128 + run as u8);
            out.push(p[i]);
            i += run;
            continue;
        }
        // Literals up to the next long run.
        let start = i;
        while i < p.len() && i - start < 128 && run_at(i) < MIN_RUN {
            i += 1;
        }
        out.push((i - start) as u8);
        out.extend_from_slice(&p[start..i]);
    }
}

/// Reads back a picture written by [`write`] (new-style RLE or flat scanlines): width,
/// height and pixels top row first. For tests and tools; not a general reader.
pub fn read(data: &[u8]) -> Option<(u32, u32, Vec<[u8; 4]>)> {
    let header_end = data.windows(2).position(|w| w == b"\n\n")? + 2;
    let rest = &data[header_end..];
    let line_end = rest.iter().position(|&b| b == b'\n')?;
    let res = std::str::from_utf8(&rest[..line_end]).ok()?;
    let words: Vec<&str> = res.split_whitespace().collect();
    let (height, width): (u32, u32) = match words.as_slice() {
        ["-Y", h, "+X", w] => (h.parse().ok()?, w.parse().ok()?),
        _ => return None,
    };
    let mut pos = line_end + 1;
    let mut pixels = Vec::with_capacity((width * height) as usize);
    for _ in 0..height {
        let w = width as usize;
        if (8..=0x7fff).contains(&w) && rest.get(pos..pos + 2) == Some(&[2, 2]) {
            pos += 4;
            let mut planes = vec![[0u8; 4]; w];
            for c in 0..4 {
                let mut x = 0;
                while x < w {
                    let code = *rest.get(pos)? as usize;
                    pos += 1;
                    if code > 128 {
                        let v = *rest.get(pos)?;
                        pos += 1;
                        for p in planes.get_mut(x..x + code - 128)? {
                            p[c] = v;
                        }
                        x += code - 128;
                    } else {
                        for p in planes.get_mut(x..x + code)? {
                            p[c] = *rest.get(pos)?;
                            pos += 1;
                        }
                        x += code;
                    }
                }
            }
            pixels.extend(planes);
        } else {
            for _ in 0..w {
                let p = rest.get(pos..pos + 4)?;
                pixels.push([p[0], p[1], p[2], p[3]]);
                pos += 4;
            }
        }
    }
    Some((width, height, pixels))
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
