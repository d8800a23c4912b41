//! Radiance's pfilt: a picture resampled to a new size (`-x -y`, `/N` for a fraction)
//! through a box filter, or a Gaussian (`-r`), after an exposure (`-e`, with `+N`/`-N`
//! stops and `-er -eg -eb` per primary). In two passes (the default) the first finds
//! the exposure that brings the average brightness of the pixels below the hot level
//! (`-h`, times the header's exposure; `-a` averages the hot ones too) to 0.5; `-1`
//! skips it. `-p` fits the output to a pixel aspect ratio, `-c` corrects the aspect
//! instead of recording it. A 360-degree cylindrical view wraps around horizontally.
//!
//! Arithmetic is pfilt's: single-precision colours summed in single precision,
//! weights and factors in double, scanlines and coordinates in file order. Not
//! modelled (refused by the command): star patterns (`-n`, drawn at random), lamp
//! colour tables (`-t -f`), the threshold filter (`-m`), spectral pictures.

use super::Run;
use crate::color::{CIE_BF, CIE_GF, CIE_RF, decode, encode};
use crate::{Format, Picture, Resolution, scanline};
use radc_lang::c_number::{atof, format_e};

const FTINY: f64 = 1e-6;
const CHECKRAD: f64 = 2.0;
/// Target mean brightness of the first pass.
const AVGLVL: f64 = 0.5;

/// An output size: pixels, or a fraction of the input's (`-x /2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Size {
    Pixels(i64),
    Fraction(f64),
}

/// pfilt's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct Options {
    pub x: Size,
    pub y: Size,
    /// The exposure, a single-precision colour (`-e`, `-er -eg -eb`).
    pub exposure: [f32; 3],
    pub single_pass: bool,
    pub average_hot: bool,
    pub hot_level: f64,
    /// Gaussian filter radius in output pixels (0: box filter).
    pub radius: f64,
    pub correct_aspect: bool,
    /// `-p`: the output pixel aspect ratio (0: none asked for).
    pub output_aspect: f64,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            x: Size::Fraction(1.0),
            y: Size::Fraction(1.0),
            exposure: [1.0; 3],
            single_pass: false,
            average_hot: false,
            hot_level: 100.0,
            radius: 0.0,
            correct_aspect: false,
            output_aspect: 0.0,
        }
    }
}

/// `scalecolor`: each primary times a double, rounded back to single precision.
fn scale(c: [f32; 3], d: f64) -> [f32; 3] {
    c.map(|v| (f64::from(v) * d) as f32)
}

/// `scalescolor`: the factor made single precision first (`const float _f = sf`).
fn scale_s(c: [f32; 3], d: f64) -> [f32; 3] {
    let f = d as f32;
    c.map(|v| v * f)
}

fn add(a: &mut [f32; 3], b: [f32; 3]) {
    for i in 0..3 {
        a[i] += b[i];
    }
}

fn rgb_bright(c: [f32; 3]) -> f64 {
    CIE_RF * f64::from(c[0]) + CIE_GF * f64::from(c[1]) + CIE_BF * f64::from(c[2])
}

/// `FEQ`: within 2%.
fn feq(a: f64, b: f64) -> bool {
    a >= 0.98 * b && a <= 1.02 * b
}

/// What `sscanview` finds in the VIEW lines that matters here: a cylindrical view and
/// its horizontal angle (the last of each wins).
fn wraps_around(picture: &Picture) -> bool {
    let mut seen = false;
    let mut cylindrical = false;
    let mut horizontal = 45.0;
    for v in picture.header.values("VIEW=") {
        let words: Vec<&str> = v.split_whitespace().collect();
        let mut i = 0;
        while i < words.len() {
            let w = words[i];
            if let Some(t) = w.strip_prefix("-vt") {
                cylindrical = t == "c";
                seen = true;
            } else if w == "-vh" && i + 1 < words.len() {
                horizontal = atof(words[i + 1]);
                seen = true;
                i += 1;
            }
            i += 1;
        }
    }
    seen && cylindrical && horizontal >= 360.0 - FTINY
}

/// The filtered picture, header and all; `what` names the input in messages.
pub fn filter(o: &Options, run: &Run, data: &[u8], what: &str) -> Result<Vec<u8>, String> {
    let picture = Picture::read(data).map_err(|e| format!("{what}: {e}"))?;
    let xyz = match picture.format_name.as_deref() {
        None | Some(Format::RGBE) => false,
        Some(Format::XYZE) => true,
        Some(_) => return Err("input must be a Radiance picture".into()),
    };
    if picture.header.values("NCOMP=").any(|v| atof(&v) as i64 > 3) {
        return Err("spectral pictures are not supported by radc pfilt".into());
    }
    let bright = |c: [f32; 3]| if xyz { f64::from(c[1]) } else { rgb_bright(c) };
    let mut out = Vec::new();
    let mut in_aspect = 1.0;
    let mut hot_level = o.hot_level;
    for line in &picture.header.lines {
        out.extend_from_slice(&line.0);
        if let Some(v) = line.value_after("PIXASPECT=") {
            in_aspect *= atof(&v);
        } else if let Some(v) = line.value_after("EXPOSURE=") {
            hot_level *= atof(&v);
        }
    }
    out.extend_from_slice(run.command_line.as_bytes());
    let res = picture.resolution;
    let order = res.orientation;
    let (xres, yres) = (res.scan_length() as i64, res.scan_count() as i64);
    if !order.y_major() {
        in_aspect = 1.0 / in_aspect;
    }
    let wrap = wraps_around(&picture) && order.y_major();
    let (mut ncols, mut x_c) = match o.x {
        Size::Pixels(n) => (n, 1.0),
        Size::Fraction(f) => (0, f),
    };
    let (mut nrows, mut y_r) = match o.y {
        Size::Pixels(n) => (n, 1.0),
        Size::Fraction(f) => (0, f),
    };
    if ncols <= 0 {
        ncols = (x_c * xres as f64 + 0.5) as i64;
    }
    if nrows <= 0 {
        nrows = (y_r * yres as f64 + 0.5) as i64;
    }
    if o.output_aspect > 0.01 {
        let d = in_aspect * yres as f64 / xres as f64 / o.output_aspect;
        if d * ncols as f64 > nrows as f64 {
            ncols = (nrows as f64 / d) as i64;
        } else {
            nrows = (ncols as f64 * d) as i64;
        }
    }
    if ncols <= 0 || nrows <= 0 || ncols > i64::from(i32::MAX) || nrows > i64::from(i32::MAX) {
        return Err(format!("bad output resolution {ncols} by {nrows}"));
    }
    if (ncols as u64) * (nrows as u64) > crate::DEFAULT_MAX_PIXELS {
        return Err(format!("a {ncols} by {nrows} output is too large"));
    }
    x_c = ncols as f64 / xres as f64;
    y_r = nrows as f64 / yres as f64;
    // The input as single-precision colours, in file order.
    let mut pixels: Vec<[f32; 3]> = picture.pixels.iter().map(|&p| decode(p)).collect();
    let mut exposure = o.exposure;
    // Pass one: the average brightness below the hot level.
    let (mut avg, mut npix) = (0.0f64, 0u64);
    if o.single_pass {
        (avg, npix) = (AVGLVL, 1);
    } else {
        for &c in &pixels {
            let b = bright(c);
            if b <= 0.0 {
                continue;
            }
            if o.average_hot || b < hot_level {
                avg += b;
                npix += 1;
            }
        }
    }
    if npix == 0 {
        return Err("picture too dark or too bright".into());
    }
    avg /= npix as f64;
    exposure = scale(exposure, AVGLVL / avg);
    for c in &mut pixels {
        for i in 0..3 {
            c[i] *= exposure[i];
        }
    }
    // Pass two.
    let xbrad = xres / ncols / 2 + 1;
    let ybrad = yres / nrows / 2 + 1;
    let mut rad = o.radius;
    let (xrad, yrad, gauss) = if rad > FTINY {
        if nrows >= yres && ncols >= xres {
            rad *= (y_r + x_c) / 2.0;
        }
        let xrad = (CHECKRAD * rad / x_c + 1.0) as i64;
        let yrad = (CHECKRAD * rad / y_r + 1.0) as i64;
        (xrad, yrad, Some(gauss_table(x_c, y_r, rad)))
    } else {
        (xbrad, ybrad, None)
    };
    let _ = (xrad, yrad);
    if !o.correct_aspect {
        let d = if order.y_major() {
            x_c / y_r
        } else {
            y_r / x_c
        };
        if !(0.995..=1.005).contains(&d) {
            out.extend_from_slice(format!("PIXASPECT={d:.6}\n").as_bytes());
        }
    }
    let d = rgb_bright(exposure);
    if !feq(d, 1.0) {
        out.extend_from_slice(format!("EXPOSURE={}\n", format_e(d, 4)).as_bytes());
    }
    let cc = scale(exposure, 1.0 / d);
    if !feq(f64::from(cc[0]), f64::from(cc[1])) || !feq(f64::from(cc[1]), f64::from(cc[2])) {
        out.extend_from_slice(
            format!("COLORCORR= {:.6} {:.6} {:.6}\n", cc[0], cc[1], cc[2]).as_bytes(),
        );
    }
    out.push(b'\n');
    let out_res = if order.y_major() {
        Resolution {
            orientation: order,
            x: ncols as u32,
            y: nrows as u32,
        }
    } else {
        Resolution {
            orientation: order,
            x: nrows as u32,
            y: ncols as u32,
        }
    };
    out.extend_from_slice(out_res.line().as_bytes());
    let at = |x: i64, y: i64| pixels[(y * xres + x) as usize];
    // One output scanline, encoded; rows are independent, so blocks of them are
    // filtered on every core and joined in order (the bytes never depend on it).
    let row = |r: i64, out: &mut Vec<u8>| {
        let mut scan = Vec::with_capacity(ncols as usize);
        let ycent = ((r as f64 + 0.5) * yres as f64 / nrows as f64) as i64;
        for c in 0..ncols {
            let xcent = ((c as f64 + 0.5) * xres as f64 / ncols as f64) as i64;
            let v = match &gauss {
                None => {
                    // dobox
                    let mut sum = [0f32; 3];
                    let mut wsum = 0i64;
                    for y in ycent + 1 - ybrad..=ycent + ybrad {
                        if y < 0 {
                            continue;
                        }
                        if y >= yres {
                            break;
                        }
                        let d = if y_r < 1.0 {
                            y_r * y as f64 - (r as f64 + 0.5)
                        } else {
                            (y - ycent) as f64
                        };
                        if d < -0.5 {
                            continue;
                        }
                        if d >= 0.5 {
                            break;
                        }
                        for x in xcent + 1 - xbrad..=xcent + xbrad {
                            let offs = if x < 0 {
                                xres
                            } else if x >= xres {
                                -xres
                            } else {
                                0
                            };
                            if offs != 0 && !wrap {
                                continue;
                            }
                            let d = if x_c < 1.0 {
                                x_c * x as f64 - (c as f64 + 0.5)
                            } else {
                                (x - xcent) as f64
                            };
                            if d < -0.5 {
                                continue;
                            }
                            if d >= 0.5 {
                                break;
                            }
                            wsum += 1;
                            add(&mut sum, at(x + offs, y));
                        }
                    }
                    if wsum > 1 {
                        sum = scale_s(sum, 1.0 / wsum as f64);
                    }
                    sum
                }
                Some(table) => {
                    // dogauss
                    let mut sum = [0f32; 3];
                    let mut wsum = FTINY;
                    let inv_rad = 1.0 / rad;
                    for y in ycent - yrad..=ycent + yrad {
                        if y < 0 {
                            continue;
                        }
                        if y >= yres {
                            break;
                        }
                        let dy = (y_r * (y as f64 + 0.5) - (r as f64 + 0.5)) / rad;
                        for x in xcent - xrad..=xcent + xrad {
                            let offs = if x < 0 {
                                xres
                            } else if x >= xres {
                                -xres
                            } else {
                                0
                            };
                            if offs != 0 && !wrap {
                                continue;
                            }
                            // The reference build multiplies by the reciprocal here.
                            let dx = (x_c * (x as f64 + 0.5) - (c as f64 + 0.5)) * inv_rad;
                            let w = look(table, dx * dx + dy * dy);
                            wsum += w;
                            add(&mut sum, scale_s(at(x + offs, y), w));
                        }
                    }
                    scale_s(sum, 1.0 / wsum)
                }
            };
            scan.push(encode(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])));
        }
        scanline::write(&scan, out);
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as i64;
    let block = (nrows + threads - 1) / threads;
    let parts: Option<Vec<Vec<u8>>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let row = &row;
                s.spawn(move || {
                    let mut part = Vec::new();
                    for r in t * block..((t + 1) * block).min(nrows) {
                        row(r, &mut part);
                    }
                    part
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().ok()).collect()
    });
    let parts = parts.ok_or("a filtering thread failed")?;
    for part in parts {
        out.extend_from_slice(&part);
    }
    Ok(out)
}

/// pf3.c `initmask`: the Gaussian looked up at twentieths of the squared distance,
/// flat inside the radius of a pixel.
fn gauss_table(x_c: f64, y_r: f64, rad: f64) -> Vec<f32> {
    let size = (444.0 * CHECKRAD * CHECKRAD) as usize;
    let d = x_c * y_r * 0.25 / (rad * rad);
    let first = (-d).exp() as f32;
    (0..size)
        .map(|x| {
            if x == 0 || x as f64 * 0.05 <= d {
                first
            } else {
                (-(x as f64) * 0.05).exp() as f32
            }
        })
        .collect()
}

/// `lookgauss`.
fn look(table: &[f32], x: f64) -> f64 {
    let i = (20.0 * x + 0.5) as usize;
    f64::from(table.get(i).copied().unwrap_or(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(w: u32, h: u32, v: f64) -> Vec<u8> {
        let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n".to_vec();
        bytes.extend_from_slice(Resolution::standard(w, h).line().as_bytes());
        let scan = vec![encode(v, v, v); w as usize];
        for _ in 0..h {
            scanline::write(&scan, &mut bytes);
        }
        bytes
    }

    #[test]
    fn a_flat_picture_halves_to_a_flat_picture_at_the_average_level() {
        let o = Options {
            x: Size::Fraction(0.5),
            y: Size::Fraction(0.5),
            ..Options::default()
        };
        let out = filter(&o, &Run::default(), &flat(8, 6, 2.0), "test").expect("filtered");
        let p = Picture::read(&out).expect("a picture");
        assert_eq!((p.width(), p.height()), (4, 3));
        // Two passes: exposure 0.25 brings the brightness to 0.5.
        let c = decode(p.pixels[0]);
        assert!((c[0] - 0.5).abs() < 0.01, "{c:?}");
        let text = String::from_utf8_lossy(&out);
        let exposure = text
            .lines()
            .find_map(|l| l.strip_prefix("EXPOSURE="))
            .map(atof)
            .expect("an EXPOSURE line");
        assert!((exposure - 0.25).abs() < 0.003, "{exposure}");
    }

    #[test]
    fn one_pass_keeps_the_values_and_a_black_picture_fails_two() {
        let o = Options {
            single_pass: true,
            radius: 0.6,
            ..Options::default()
        };
        let out = filter(&o, &Run::default(), &flat(5, 5, 3.0), "test").expect("filtered");
        let p = Picture::read(&out).expect("a picture");
        assert!((decode(p.pixels[12])[1] - 3.0).abs() < 0.05);
        let err = filter(&Options::default(), &Run::default(), &flat(4, 4, 0.0), "t");
        assert_eq!(err, Err("picture too dark or too bright".into()));
    }
}
