//! Radiance's pflip. `-h` flips the picture left to right, `-v` top to
//! bottom; the resolution line's orientation changes with the flip (so programs that
//! honour it see the same picture laid out the other way), unless `-c` keeps it, which
//! corrects a picture whose orientation was wrong. `pflip [-h][-v][-c] [in [out]]`;
//! `-v` needs a named input, as pflip seeks in it.

use super::format_line;
use crate::{Orientation, Picture};

/// The header pflip and protate write: the input's lines but its format, the format
/// line, the command line and the empty line.
pub(super) fn header_bytes(picture: &Picture, command: &str) -> Vec<u8> {
    let mut out = Vec::new();
    for l in &picture.header.lines {
        if l.format().is_none() {
            out.extend_from_slice(&l.0);
        }
    }
    if let Some(f) = &picture.format_name {
        out.extend_from_slice(format_line(f, None, 0).as_bytes());
    }
    out.extend_from_slice(command.as_bytes());
    out.push(b'\n');
    out
}

/// The scanlines reversed (`vertical`) and each reversed (`horizontal`), and the
/// orientation that keeps the picture's frame (pflip's `neworder`) unless `correct`.
pub fn flip(picture: &Picture, horizontal: bool, vertical: bool, correct: bool) -> Picture {
    let r = picture.resolution;
    let mut o = r.orientation.0;
    if !correct {
        let (along, across) = if r.orientation.y_major() {
            (Orientation::XDECR, Orientation::YDECR)
        } else {
            (Orientation::YDECR, Orientation::XDECR)
        };
        if horizontal {
            o ^= along;
        }
        if vertical {
            o ^= across;
        }
    }
    let mut pixels = Vec::with_capacity(picture.pixels.len());
    let scans = r.scan_count();
    for k in 0..scans {
        let s = if vertical { scans - 1 - k } else { k };
        let line = picture.scanline(s);
        if horizontal {
            pixels.extend(line.iter().rev());
        } else {
            pixels.extend_from_slice(line);
        }
    }
    let mut out = picture.clone();
    out.resolution.orientation = Orientation(o);
    out.pixels = pixels;
    out
}

/// pflip's output: the header (the input's, with `command_line`), the new
/// resolution line and the flipped pixels.
pub fn convert(
    picture: &Picture,
    horizontal: bool,
    vertical: bool,
    correct: bool,
    command_line: &str,
) -> Vec<u8> {
    let flipped = flip(picture, horizontal, vertical, correct);
    let mut out = header_bytes(picture, command_line);
    out.extend_from_slice(flipped.resolution.line().as_bytes());
    for s in 0..flipped.resolution.scan_count() {
        crate::scanline::write(flipped.scanline(s), &mut out);
    }
    out
}
