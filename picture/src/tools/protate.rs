//! Radiance's protate. Turns a picture a quarter turn clockwise (`-r`:
//! counter-clockwise) in its scanlines; the orientation changes so programs that honour
//! it see the turned picture, unless `-c` keeps it. `protate [-r][-c] infile [outfile]`.

use crate::{Orientation, Picture, Resolution};

/// protate's `ordercw`: the orientation after a clockwise quarter turn.
fn clockwise(o: u8) -> u8 {
    const Y: u8 = Orientation::YMAJOR;
    const XD: u8 = Orientation::XDECR;
    const YD: u8 = Orientation::YDECR;
    match o {
        o if o == Y | YD => 0,
        0 => Y | XD,
        o if o == Y | XD => XD | YD,
        o if o == XD | YD => Y | YD,
        o if o == Y | XD | YD => XD,
        o if o == XD => Y,
        o if o == Y => YD,
        _ => Y | XD | YD,
    }
}

/// The scanlines turned: clockwise, output scanline `k` is input column `k` read from
/// the last scanline up; counter-clockwise, output scanline `k` is input column
/// `len - 1 - k` read from the first scanline down.
pub fn rotate(picture: &Picture, ccw: bool, correct: bool) -> Picture {
    let r = picture.resolution;
    let (len, scans) = (r.scan_length(), r.scan_count());
    let o = if correct {
        r.orientation.0
    } else if ccw {
        (0..8)
            .find(|&i| clockwise(i) == r.orientation.0)
            .unwrap_or(0)
    } else {
        clockwise(r.orientation.0)
    };
    let mut pixels = Vec::with_capacity(picture.pixels.len());
    for k in 0..len {
        for j in 0..scans {
            let (s, p) = if ccw {
                (j, len - 1 - k)
            } else {
                (scans - 1 - j, k)
            };
            pixels.push(picture.pixels[(s * len + p) as usize]);
        }
    }
    // New scanlines are `scans` long and there are `len` of them.
    let orientation = Orientation(o);
    let (x, y) = if orientation.y_major() {
        (scans, len)
    } else {
        (len, scans)
    };
    let mut out = picture.clone();
    out.resolution = Resolution { orientation, x, y };
    out.pixels = pixels;
    out
}

/// protate's output: the header (the input's, with `command_line`), the new
/// resolution line and the turned pixels.
pub fn convert(picture: &Picture, ccw: bool, correct: bool, command_line: &str) -> Vec<u8> {
    let turned = rotate(picture, ccw, correct);
    let mut out = super::pflip::header_bytes(picture, command_line);
    out.extend_from_slice(turned.resolution.line().as_bytes());
    for s in 0..turned.resolution.scan_count() {
        crate::scanline::write(turned.scanline(s), &mut out);
    }
    out
}
