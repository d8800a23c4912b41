//! Radiance's getinfo. Prints the information header of each file
//! (`file:` then each line after a tab), `-d` the resolution line instead (`+d` both),
//! `-` copies standard input without its header (`-d -`: without its resolution line
//! too), `-a line...` adds lines to the header of standard input, `-c command...` runs a
//! command on the data after the header and writes the header with the command added.
//! Works on any Radiance file (pictures, octrees, matrices), as getinfo does.

use super::format_line;
use crate::{Header, HeaderLine, Resolution};

/// What getinfo prints for the data after a header (`getdim`): a picture's resolution
/// line, an octree's boundaries, or "unknown file type".
pub fn dimensions(data: &[u8], out: &mut Vec<u8>) {
    match data.first() {
        Some(b'+' | b'-') => {
            let end = data
                .iter()
                .position(|&b| b == b'\n')
                .map_or(data.len(), |n| n + 1);
            out.extend_from_slice(&data[..end]);
        }
        Some(1) => {
            // An octree: a format byte, then the cube's origin and size as strings.
            let mut zeros = 0;
            for &c in data.iter().skip(2) {
                if c == 0 {
                    zeros += 1;
                    if zeros >= 4 {
                        break;
                    }
                    out.push(b' ');
                } else {
                    out.push(c);
                }
            }
            out.push(b'\n');
        }
        _ => out.extend_from_slice(b"unknown file type\n"),
    }
}

/// The header lines `checkheader` copies (all but `FORMAT=`) and the format found.
pub fn header_without_format(lines: &[HeaderLine]) -> (Vec<u8>, Option<String>) {
    let mut out = Vec::new();
    let mut format = None;
    for l in lines {
        match l.format() {
            Some(f) => format = Some(f),
            None => out.extend_from_slice(&l.0),
        }
    }
    (out, format)
}

/// One named file's part of getinfo's listing (`name:`, then each header line after a
/// tab; `dim < 0`: the dimensions instead, `dim > 0`: both). `Err` after the part
/// listed so far: the header is damaged, and getinfo stops there.
pub fn file_listing(name: &str, data: &[u8], dim: i32, out: &mut Vec<u8>) -> Result<(), String> {
    out.extend_from_slice(name.as_bytes());
    let (lines, end) = Header::parse_partial(data);
    if dim < 0 {
        match end {
            Ok(end) => {
                out.extend_from_slice(b": ");
                dimensions(&data[end..], out);
            }
            Err(_) => out.extend_from_slice(b": bad header!\n"),
        }
        return Ok(());
    }
    out.extend_from_slice(b":\n\t");
    for line in &lines {
        out.extend_from_slice(&line.0);
        if line.0.ends_with(b"\n") {
            out.push(b'\t');
        }
    }
    let end = end.map_err(|e| format!("{name}: bad header! ({e})"))?;
    out.push(b'\n');
    if dim > 0 {
        out.push(b'\t');
        dimensions(&data[end..], out);
    }
    Ok(())
}

/// getinfo without file names: the header of `data` (standard input) as is (`dim <
/// 0`: the dimensions instead, `dim > 0`: both). `Err` after what was listed: a
/// damaged header.
pub fn input_listing(data: &[u8], dim: i32, out: &mut Vec<u8>) -> Result<(), String> {
    let (lines, end) = Header::parse_partial(data);
    if dim >= 0 {
        lines.iter().for_each(|l| out.extend_from_slice(&l.0));
    }
    let end = end.map_err(|e| format!("bad header on standard input: {e}"))?;
    if dim >= 0 {
        out.push(b'\n');
    }
    if dim != 0 {
        dimensions(&data[end..], out);
    }
    Ok(())
}

/// `getinfo -`: the data after the header (and after the resolution line, `dim < 0`).
pub fn strip_header(data: &[u8], dim: i32) -> Result<&[u8], String> {
    let mut at = match Header::parse(data) {
        Ok((_, end)) => end,
        Err(e) => return Err(format!("bad header on standard input: {e}")),
    };
    if dim < 0 {
        match Resolution::parse(&data[at..]) {
            Some((_, n)) => at += n,
            None => return Err("no resolution string on standard input".into()),
        }
    }
    Ok(&data[at..])
}

/// `getinfo -a line...`: the header of `data` with `lines` added before its format
/// line, then the rest of the data; `output_start` as in [`super::Run`].
pub fn add_lines(
    data: &[u8],
    lines: &[String],
    output_start: Option<u64>,
) -> Result<Vec<u8>, String> {
    let (header, end) =
        Header::parse(data).map_err(|e| format!("bad header on standard input: {e}"))?;
    let (mut out, format) = header_without_format(&header.lines);
    for l in lines.iter().filter(|l| !l.is_empty()) {
        out.extend_from_slice(l.as_bytes());
        if !l.ends_with('\n') {
            out.push(b'\n');
        }
    }
    if let Some(f) = format {
        out.extend_from_slice(format_line(&f, output_start, out.len()).as_bytes());
    }
    out.push(b'\n');
    out.extend_from_slice(&data[end..]);
    Ok(out)
}

/// getinfo.c `adjheadline`: whether header line `line` sets the variable `arg` names
/// (`VAR`, `VAR=...`, `VAR value`, leading blanks matched), so `-r` removes it.
fn names_line(line: &[u8], arg: &[u8]) -> bool {
    let space = |c: Option<&u8>| c.is_some_and(|&c| radc_lang::c_number::is_c_space(c));
    let (mut i, mut j) = (0usize, 0usize);
    if space(arg.first()) {
        if !space(line.first()) {
            return false;
        }
        i += 1;
        while space(line.get(i)) {
            i += 1;
        }
        j += 1;
        while space(arg.get(j)) {
            j += 1;
        }
    }
    let start = i;
    while j < arg.len() && line.get(i) == arg.get(j) {
        if line.get(i) == Some(&b'=') && i > 0 {
            return true;
        }
        if space(arg.get(j)) {
            break;
        }
        i += 1;
        j += 1;
    }
    if i == start && start == 0 {
        return false;
    }
    if line.get(i) == Some(&b'=') && j >= arg.len() {
        return true;
    }
    space(line.get(i)) && space(arg.get(j))
}

/// `getinfo -r VAR...`: the header of `data` without the lines the arguments name, then
/// the arguments that set a value (`VAR=value`, `VAR value`) as new lines, the format
/// line and the data; `output_start` as in [`super::Run`].
pub fn replace_lines(
    data: &[u8],
    args: &[String],
    output_start: Option<u64>,
) -> Result<Vec<u8>, String> {
    let (header, end) = Header::parse(data).map_err(|_| "Bad header!".to_string())?;
    let mut out = Vec::new();
    let mut format = None;
    for l in &header.lines {
        if let Some(f) = l.format() {
            format = Some(f);
            continue;
        }
        if !args.iter().any(|a| names_line(&l.0, a.as_bytes())) {
            out.extend_from_slice(&l.0);
        }
    }
    for a in args {
        let b = a.as_bytes();
        let start = b
            .iter()
            .position(|&c| !radc_lang::c_number::is_c_space(c))
            .unwrap_or(b.len());
        if start == b.len() {
            continue;
        }
        let len = b.len()
            - b.iter()
                .rev()
                .take_while(|&&c| radc_lang::c_number::is_c_space(c))
                .count();
        let sets = (start + 1..len.saturating_sub(1))
            .any(|k| b[k] == b'=' || radc_lang::c_number::is_c_space(b[k]));
        if sets {
            out.extend_from_slice(&b[..len]);
            out.push(b'\n');
        }
    }
    if let Some(f) = format {
        out.extend_from_slice(format_line(&f, output_start, out.len()).as_bytes());
    }
    out.push(b'\n');
    out.extend_from_slice(&data[end..]);
    Ok(out)
}
