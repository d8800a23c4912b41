//! `radc pflip`: Radiance's pflip. `-h` flips the picture left to right, `-v` top to
//! bottom; the resolution line's orientation changes with the flip (so programs that
//! honour it see the same picture laid out the other way), unless `-c` keeps it, which
//! corrects a picture whose orientation was wrong. `pflip [-h][-v][-c] [in [out]]`;
//! `-v` needs a named input, as pflip seeks in it.

use std::process::ExitCode;

use radc_picture::{Orientation, Picture};

use super::{command_line, fail, format_line, read_input};

const NAME: &str = "pflip";
const USAGE: &str = "usage: radc pflip [-h][-v][-c] infile [outfile]";

pub fn run(args: &[String]) -> ExitCode {
    let (mut horizontal, mut vertical, mut correct) = (false, false, false);
    let mut i = 0;
    while let Some(a) = args.get(i) {
        match a.as_str() {
            "-h" => horizontal = true,
            "-v" => vertical = true,
            "-c" => correct = true,
            _ => break,
        }
        i += 1;
    }
    let files = &args[i..];
    if files.len() > 2 {
        return fail(NAME, USAGE);
    }
    if !horizontal && !vertical {
        eprintln!("radc pflip: warning - no operation");
    }
    let input = files.first().filter(|f| !f.starts_with('-'));
    if input.is_none() && vertical {
        return fail(NAME, format!("-v needs an input file\n{USAGE}"));
    }
    let data = match read_input(input.map(String::as_str)) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let what = input.map_or("standard input", |s| s.as_str());
    let picture = match Picture::read(&data) {
        Ok(p) => p,
        Err(e) => return fail(NAME, format!("{what}: {e}")),
    };
    let flipped = flip(&picture, horizontal, vertical, correct);
    let mut out = header_bytes(&picture, &command_line(NAME, &args[..i]));
    out.extend_from_slice(flipped.resolution.line().as_bytes());
    if flipped.write_pixels(&mut out).is_err() {
        return fail(NAME, "write error");
    }
    super::write_output(NAME, files.get(1).map(String::as_str), &out)
}

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
