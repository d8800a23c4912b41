//! Radiance's ra_rgbe. Copies pictures from the input (a stream of them:
//! each is a frame) with flat scanlines, or run-length encoded with `-r`, each pixel's
//! exponent shifted by `-e +N`/`-e -N` stops; `-n N` takes only frame N (the `FRAME=`
//! header line numbers them). `ra_rgbe [-r][-e +/-stops][-f][-n frame] [input [outspec]]`:
//! outspec may hold a `%d` for the frame number, and an existing file is not
//! overwritten without `-f`. An outspec starting with `!` (a command to pipe into) is
//! refused: radc runs no shell.

use radc_lang::c_number::{atoi, format_e};

use super::format_line;
use crate::{Header, Picture, scanline};

/// ra_rgbe's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct Options {
    /// Flat scanlines (the default; `-r` run-length encodes them).
    pub flat: bool,
    /// `-e`: exponent shift in stops.
    pub stops: i32,
    /// `-n`: the one frame to convert (0: all).
    pub frame: i64,
    /// The name each frame's header gives the program (`ra_rgbe`, or `radc ra_rgbe`).
    pub program: String,
}

/// One converted frame: its number (`FRAME=`, 0 when the header gives none) and bytes.
#[derive(Clone, Debug)]
pub struct Frame {
    pub number: i64,
    pub bytes: Vec<u8>,
}

/// The frames of `data` converted, in order, and the message that stopped the
/// conversion early, if one did (the frames before it stand, as ra_rgbe has written
/// them by then). `what` names the input in messages.
pub fn frames(o: &Options, data: &[u8], what: &str) -> (Vec<Frame>, Option<String>) {
    let mut done = Vec::new();
    let mut pos = 0;
    // Header lines are kept across frames as ra_rgbe keeps them: the second frame adds
    // to the first's, later ones to the first's again (its `headlen1`).
    let mut first_len = 0;
    let mut lines: Vec<u8> = Vec::new();
    let mut format: Option<String> = None;
    loop {
        if Header::parse(&data[pos..]).is_err() {
            break;
        }
        if first_len == 0 {
            first_len = lines.len();
        } else {
            lines.truncate(first_len);
        }
        let (picture, used) = match Picture::read_prefix(&data[pos..], crate::DEFAULT_MAX_PIXELS) {
            Ok(p) => p,
            Err(e) => return (done, Some(format!("{what}: {e}"))),
        };
        pos += used;
        let mut frame = 0;
        for l in &picture.header.lines {
            let b = &l.0;
            if b.starts_with(b"#?") || b.starts_with(b"WAVELENGTH_SPLITS=") {
                continue;
            }
            if let Some(v) = l.value_after("FRAME=") {
                frame = i64::from(atoi(&v));
                continue;
            }
            if let Some(f) = l.format() {
                format = Some(f);
                continue;
            }
            if let Some(v) = l.value_after("NCOMP=") {
                match atoi(&v) {
                    3 => continue,
                    // getheader gives up on the header: ra_rgbe stops, as at the end.
                    n if n < 3 => return (done, None),
                    _ => {
                        let why =
                            "spectral pictures (NCOMP= above 3) are not supported by radc ra_rgbe";
                        return (done, Some(why.into()));
                    }
                }
            }
            lines.extend_from_slice(b);
        }
        if o.frame != 0 && o.frame < frame {
            break;
        }
        if o.frame > frame {
            continue;
        }
        let mut out = b"#?RADIANCE\n".to_vec();
        out.extend_from_slice(&lines);
        out.extend_from_slice(o.program.as_bytes());
        if o.stops != 0 {
            out.extend_from_slice(format!(" -e {:+}", o.stops).as_bytes());
        }
        if !o.flat {
            out.extend_from_slice(b" -r");
        }
        out.push(b'\n');
        if o.stops != 0 {
            let e = 2f64.powi(o.stops);
            out.extend_from_slice(format!("EXPOSURE={}\n", format_e(e, 4)).as_bytes());
        }
        if frame != 0 {
            out.extend_from_slice(format!("FRAME={frame}\n").as_bytes());
        }
        if let Some(f) = &format {
            out.extend_from_slice(format_line(f, None, 0).as_bytes());
        }
        out.push(b'\n');
        out.extend_from_slice(picture.resolution.line().as_bytes());
        let mut scan = Vec::new();
        for s in 0..picture.resolution.scan_count() {
            scan.clear();
            scan.extend_from_slice(picture.scanline(s));
            shift(&mut scan, o.stops);
            if o.flat {
                scan.iter().for_each(|p| out.extend_from_slice(p));
            } else {
                scanline::write(&scan, &mut out);
            }
        }
        done.push(Frame {
            number: frame,
            bytes: out,
        });
    }
    (done, None)
}

/// `shiftcolrs`: exponents moved by `stops`; pixels at or below the smallest exponent a
/// downward shift allows become black (the exponent byte wraps above 255, as in C).
fn shift(scan: &mut [[u8; 4]], stops: i32) {
    if stops == 0 {
        return;
    }
    let min = if stops < 0 { -stops } else { 0 };
    for p in scan {
        if i32::from(p[3]) <= min {
            *p = [0; 4];
        } else {
            p[3] = (i32::from(p[3]) + stops) as u8;
        }
    }
}
