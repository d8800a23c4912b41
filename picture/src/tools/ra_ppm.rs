//! Radiance's ra_ppm. Converts an RGBE picture to a Poskanzer pixmap
//! (binary P6, `-a` ASCII P3, `-b` greyscale P5/P2) through Radiance's integer gamma
//! tables (`colrops.c`: `-g` gamma, 2.2 by default; `-e +N`/`-e -N` stops), and `-r` a
//! pixmap (P2, P3, P5, P6) back to a picture. Scanlines go in file order, as ra_ppm
//! writes them. `ra_ppm [-r][-a][-b][-s maxv][-g gamma][-e +/-stops] [input [output]]`.
//! Pixmaps of more than 8 bits a sample (`-s` or a maxval above 255) take ra_ppm's
//! floating-point path, which radc does not implement: they are refused.

use super::Run;
use crate::color::{CIE_BF, CIE_GF, CIE_RF};
use crate::{Format, Picture, Resolution, scanline};

/// The refusal of deeper pixmaps.
pub const SIXTEEN: &str = "pixmaps of more than 8 bits a sample are not supported by radc ra_ppm";

/// Exponents below 2^-31 leave the gamma table (`MAXGSHIFT`).
const MAX_SHIFT: usize = 31;

/// `setcolrgam`'s tables: RGBE mantissa at each exponent shift to gamma byte, and gamma
/// byte back to a mantissa and an exponent.
struct Gamma {
    to_byte: Vec<[u8; 256]>,
    mantissa: [u8; 256],
    shift: [u8; 256],
}

impl Gamma {
    fn new(g: f64) -> Gamma {
        let mut to_byte = vec![[0u8; 256]; MAX_SHIFT + 1];
        let mut mult = 1.0 / 256.0;
        for row in &mut to_byte {
            for (j, b) in row.iter_mut().enumerate() {
                *b = (256.0 * ((j as f64 + 0.5) * mult).powf(1.0 / g)) as u8;
            }
            mult *= 0.5;
        }
        let (mut mantissa, mut shift) = ([0u8; 256], [0u8; 256]);
        let (mut i, mut mult) = (0u32, 256.0f64);
        for j in (0..256).rev() {
            loop {
                mantissa[j] = (mult * ((j as f64 + 0.5) / 256.0).powf(g)) as u8;
                // A gamma that sends values to 0 would double forever in C; stop.
                if mantissa[j] >= 128 || i >= 255 {
                    break;
                }
                i += 1;
                mult *= 2.0;
            }
            shift[j] = i as u8;
        }
        Gamma {
            to_byte,
            mantissa,
            shift,
        }
    }

    /// `colrs_gambs`: one pixel's mantissas to gamma bytes.
    fn to_bytes(&self, p: [u8; 4]) -> [u8; 3] {
        let expo = i32::from(p[3]) - 128;
        let rgb = [p[0], p[1], p[2]];
        if expo < -(MAX_SHIFT as i32) {
            if expo < -(MAX_SHIFT as i32) - 8 {
                return [0; 3];
            }
            let i = (-(MAX_SHIFT as i32) - 1 - expo) as u32;
            return rgb.map(|m| self.to_byte[MAX_SHIFT][(((u32::from(m) >> i) + 1) >> 1) as usize]);
        }
        if expo > 0 {
            if expo > 8 {
                return [255; 3];
            }
            return rgb.map(|m| {
                let i = (u32::from(m) << 1 | 1) << (expo - 1);
                if i > 255 {
                    255
                } else {
                    self.to_byte[0][i as usize]
                }
            });
        }
        rgb.map(|m| self.to_byte[(-expo) as usize][usize::from(m)])
    }

    /// `gambs_colrs`: gamma bytes to an RGBE pixel.
    fn to_colr(&self, b: [u8; 3]) -> [u8; 4] {
        let n = b.map(|v| self.shift[usize::from(v)]);
        let nexpo = n[0].min(n[1]).min(n[2]);
        let m = [0, 1, 2].map(|c| {
            let v = self.mantissa[usize::from(b[c])];
            if nexpo < n[c] { v >> (n[c] - nexpo) } else { v }
        });
        [m[0], m[1], m[2], 128u8.wrapping_sub(nexpo)]
    }
}

/// `normbright`: integer brightness of an RGBE pixel's mantissas.
fn norm_bright(p: [u8; 4]) -> u8 {
    let w = |f: f64| (f * 256.0 + 0.5) as i64;
    ((w(CIE_RF) * i64::from(p[0]) + w(CIE_GF) * i64::from(p[1]) + w(CIE_BF) * i64::from(p[2])) >> 8)
        as u8
}

/// ra_ppm's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct Options {
    pub grey: bool,
    pub binary: bool,
    pub reverse: bool,
    pub gamma: f64,
    pub stops: i32,
    pub maxval: u32,
}

/// `shiftcolrs` (as in ra_rgbe).
fn shift(p: &mut [u8; 4], stops: i32) {
    if stops == 0 {
        return;
    }
    let min = if stops < 0 { -stops } else { 0 };
    if i32::from(p[3]) <= min {
        *p = [0; 4];
    } else {
        p[3] = (i32::from(p[3]) + stops) as u8;
    }
}

/// A picture to a pixmap, or (`reverse`) a pixmap to a picture.
pub fn convert(o: &Options, run: &Run, data: &[u8]) -> Result<Vec<u8>, String> {
    let gamma = Gamma::new(o.gamma);
    if o.reverse {
        from_pixmap(o, &gamma, &run.command_line, data)
    } else {
        to_pixmap(o, &gamma, data)
    }
}

fn to_pixmap(o: &Options, gamma: &Gamma, data: &[u8]) -> Result<Vec<u8>, String> {
    let picture = Picture::read(data).map_err(|e| format!("bad picture format: {e}"))?;
    if picture
        .format_name
        .as_deref()
        .is_some_and(|f| f != Format::RGBE)
    {
        return Err("bad picture format: not an RGBE picture".into());
    }
    let res = picture.resolution;
    let (len, scans) = (res.scan_length(), res.scan_count());
    let kind = if o.grey { 2 } else { 3 } + if o.binary { 3 } else { 0 };
    let mut out = format!("P{kind}\n{len} {scans}\n{}\n", o.maxval).into_bytes();
    for s in 0..scans {
        for &p in picture.scanline(s) {
            let mut p = p;
            shift(&mut p, o.stops);
            if o.grey {
                p[1] = norm_bright(p);
            }
            let b = gamma.to_bytes(p);
            match (o.grey, o.binary) {
                (true, true) => out.push(b[1]),
                (true, false) => out.extend_from_slice(format!("{}\n", b[1]).as_bytes()),
                (false, true) => out.extend_from_slice(&b),
                (false, false) => {
                    out.extend_from_slice(format!("{} {} {}\n", b[0], b[1], b[2]).as_bytes());
                }
            }
        }
    }
    Ok(out)
}

/// `scanint`: blanks and `#` comments skipped, then digits up to a blank (which is
/// consumed) or the end.
fn scan_int(data: &[u8], pos: &mut usize) -> Result<u32, String> {
    loop {
        while data.get(*pos).is_some_and(u8::is_ascii_whitespace) {
            *pos += 1;
        }
        match data.get(*pos) {
            None => return Err("unexpected end of file".into()),
            Some(b'#') => {
                while data.get(*pos).is_some_and(|&c| c != b'\n') {
                    *pos += 1;
                }
            }
            Some(_) => break,
        }
    }
    let mut v: u32 = 0;
    while let Some(&c) = data.get(*pos) {
        *pos += 1;
        if c.is_ascii_whitespace() {
            break;
        }
        if !c.is_ascii_digit() {
            return Err("error reading integer".into());
        }
        v = v.wrapping_mul(10).wrapping_add(u32::from(c - b'0'));
    }
    Ok(v)
}

fn from_pixmap(o: &Options, gamma: &Gamma, command: &str, data: &[u8]) -> Result<Vec<u8>, String> {
    let (Some(b'P'), Some(&kind)) = (data.first(), data.get(1)) else {
        return Err("input not a Poskanzer Pixmap".into());
    };
    let mut pos = 2;
    let width = scan_int(data, &mut pos)?;
    let height = scan_int(data, &mut pos)?;
    let maxval = scan_int(data, &mut pos)?;
    if maxval >= 256 {
        return Err(SIXTEEN.into());
    }
    if !matches!(kind, b'2' | b'3' | b'5' | b'6') {
        return Err("unsupported Pixmap type".into());
    }
    if width == 0 || height == 0 || u64::from(width) * u64::from(height) > crate::DEFAULT_MAX_PIXELS
    {
        return Err(format!(
            "a {width} by {height} pixmap is not one radc can convert"
        ));
    }
    let norm = |v: u32| -> u8 {
        if v >= maxval {
            255
        } else if maxval == 255 {
            v as u8
        } else {
            (u64::from(v) * 255 / u64::from(maxval)) as u8
        }
    };
    let mut out = b"#?RADIANCE\n".to_vec();
    out.extend_from_slice(command.as_bytes());
    out.extend_from_slice(b"FORMAT=32-bit_rle_rgbe\n\n");
    out.extend_from_slice(Resolution::standard(width, height).line().as_bytes());
    let read_err = || "error reading Pixmap".to_string();
    let mut scan = Vec::with_capacity(width as usize);
    for _ in 0..height {
        scan.clear();
        for _ in 0..width {
            let b = match kind {
                b'2' => [norm(scan_int(data, &mut pos)?); 3],
                b'3' => {
                    let r = norm(scan_int(data, &mut pos)?);
                    let g = norm(scan_int(data, &mut pos)?);
                    [r, g, norm(scan_int(data, &mut pos)?)]
                }
                b'5' => {
                    let c = *data.get(pos).ok_or_else(read_err)?;
                    pos += 1;
                    [if maxval == 255 { c } else { norm(u32::from(c)) }; 3]
                }
                _ => {
                    let px = data.get(pos..pos + 3).ok_or_else(read_err)?;
                    pos += 3;
                    if maxval == 255 {
                        [px[0], px[1], px[2]]
                    } else {
                        [0, 1, 2].map(|c| norm(u32::from(px[c])))
                    }
                }
            };
            let mut p = gamma.to_colr(b);
            shift(&mut p, o.stops);
            scan.push(p);
        }
        scanline::write(&scan, &mut out);
    }
    Ok(out)
}
