//! Radiance's radcompare (src/util/radcompare.c): two files compared for significant
//! differences, the way Radiance's test suite judges its outputs. Headers (when both
//! have one) must set the same variables to equivalent values (`SOFTWARE`, `CAPDATE`,
//! `GMT`, `FRAME`, `TILED` ignored; repeated `EXPOSURE`s multiplied); then the data by its
//! format: text word by word (numbers within the tolerances, other words exactly),
//! RGBE/XYZE pictures pixel by pixel (the mean and the largest primary), 32- and 64-bit
//! floats value by value, anything else byte for byte. Tolerances: relative differences
//! with a floor (`-rel`, 1e-5), a limit on any one difference (`-max`, 0.25) and on the
//! RMS (`-rms`, 0.01). Depth, normal and spectral maps are refused.

use std::collections::HashMap;

use radc_lang::c_number::{atof, is_c_space, is_flt, is_int};

use crate::{Picture, Resolution, decode};

/// radcompare's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct CompareOptions {
    pub ignore_header: bool,
    pub escape_newlines: bool,
    pub comment: Option<u8>,
    /// 0 quiet, 1 errors, 2 warnings (the default), 3 verbose.
    pub report: u8,
    pub rel_min: f64,
    pub rms_limit: f64,
    pub max_limit: f64,
}

impl Default for CompareOptions {
    fn default() -> CompareOptions {
        CompareOptions {
            ignore_header: false,
            escape_newlines: false,
            comment: None,
            report: 2,
            rel_min: 1e-5,
            rms_limit: 0.01,
            max_limit: 0.25,
        }
    }
}

/// One input: its name in messages and its bytes.
pub struct Input<'a> {
    pub name: &'a str,
    pub data: &'a [u8],
}

/// The verdict: radcompare's exit status (0 same, 1 different, 2 trouble) and what it
/// printed on standard output.
pub struct Verdict {
    pub status: u8,
    pub report: String,
}

const IGNORED: [&str; 5] = ["SOFTWARE", "CAPDATE", "GMT", "FRAME", "TILED"];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Unknown,
    Text,
    Ascii,
    Rgbe,
    Xyze,
    Spectral,
    Depth,
    Normal,
    Float,
    Double,
    Binary,
    Other(&'static str),
}

fn kind_name(k: Kind) -> &'static str {
    match k {
        Kind::Unknown => "Unrecognized",
        Kind::Text => "TEXT_generic",
        Kind::Ascii => "ascii",
        Kind::Rgbe => "32-bit_rle_rgbe",
        Kind::Xyze => "32-bit_rle_xyze",
        Kind::Spectral => "Radiance_spectra",
        Kind::Depth => "16-bit_encoded_depth",
        Kind::Normal => "32-bit_encoded_normal",
        Kind::Float => "float",
        Kind::Double => "double",
        Kind::Binary => "BINARY_unknown",
        Kind::Other(n) => n,
    }
}

fn kind_of(format: Option<&str>) -> Kind {
    match format {
        Some("ascii") => Kind::Ascii,
        Some("32-bit_rle_rgbe") => Kind::Rgbe,
        Some("32-bit_rle_xyze") => Kind::Xyze,
        Some("Radiance_spectra") => Kind::Spectral,
        Some("16-bit_encoded_depth") => Kind::Depth,
        Some("32-bit_encoded_normal") => Kind::Normal,
        Some("float") => Kind::Float,
        Some("double") => Kind::Double,
        Some(
            n @ ("BSDF_RBFmesh"
            | "Radiance_octree"
            | "Radiance_tmesh"
            | "8-bit_indexed_name"
            | "16-bit_indexed_name"
            | "24-bit_indexed_name"),
        ) => Kind::Other(match n {
            "BSDF_RBFmesh" => "BSDF_RBFmesh",
            "Radiance_octree" => "Radiance_octree",
            "Radiance_tmesh" => "Radiance_tmesh",
            "8-bit_indexed_name" => "8-bit_indexed_name",
            "16-bit_indexed_name" => "16-bit_indexed_name",
            _ => "24-bit_indexed_name",
        }),
        _ => Kind::Unknown,
    }
}

/// A file's header variables, its header line count, byte order and where the data
/// starts.
struct Parsed {
    vars: HashMap<String, String>,
    lines: usize,
    swapped: bool,
    kind: Kind,
    body: usize,
}

struct Comparer<'o> {
    o: &'o CompareOptions,
    prog: String,
    out: String,
    diff2sum: f64,
    nsum: u64,
}

impl Comparer<'_> {
    fn say(&mut self, s: &str) {
        self.out.push_str(s);
    }

    /// `real_check`.
    fn real(&mut self, r1: f64, r2: f64) -> bool {
        let mut diff2 = (r1 - r2) * (r1 - r2);
        if self.o.rel_min > 0.0 {
            let mut av2 = 0.25 * (r1 * r1 + 2.0 * (r1 * r2).abs() + r2 * r2);
            if av2 < self.o.rel_min * self.o.rel_min {
                av2 = self.o.rel_min * self.o.rel_min;
            }
            diff2 /= av2;
        }
        if self.o.max_limit >= 0.0 && diff2 > self.o.max_limit * self.o.max_limit {
            if self.o.report != 0 {
                let rel = if self.o.rel_min > 0.0 {
                    "relative "
                } else {
                    ""
                };
                let line = format!(
                    "{}: {rel}difference between {} and {} exceeds epsilon of {}\n",
                    self.prog,
                    radc_lang::c_number::format_g(r1, 8),
                    radc_lang::c_number::format_g(r2, 8),
                    radc_lang::c_number::format_g(self.o.max_limit, 8)
                );
                self.say(&line);
            }
            return false;
        }
        self.diff2sum += diff2;
        self.nsum += 1;
        true
    }

    fn good_rms(&mut self, n1: &str, n2: &str) -> bool {
        if self.nsum == 0 {
            return true;
        }
        let ms = self.diff2sum / self.nsum as f64;
        let rel = if self.o.rel_min > 0.0 {
            "relative "
        } else {
            ""
        };
        if ms > self.o.rms_limit * self.o.rms_limit {
            if self.o.report != 0 {
                let line = format!(
                    "{}: {rel}RMS difference between '{n1}' and '{n2}' of {} exceeds limit of {}\n",
                    self.prog,
                    radc_lang::c_number::format_g(ms.sqrt(), 5),
                    radc_lang::c_number::format_g(self.o.rms_limit, 5)
                );
                self.say(&line);
            }
            return false;
        }
        if self.o.report >= 3 {
            let line = format!(
                "{}: {rel}RMS difference of reals in '{n1}' and '{n2}' is {}\n",
                self.prog,
                radc_lang::c_number::format_g(ms.sqrt(), 5)
            );
            self.say(&line);
        }
        true
    }

    /// `equiv_string`: word by word.
    fn equivalent(&mut self, s1: &[u8], s2: &[u8]) -> bool {
        let (mut i, mut j) = (0, 0);
        let skip = |s: &[u8], mut k: usize| {
            while k < s.len() && is_c_space(s[k]) {
                k += 1;
            }
            k
        };
        i = skip(s1, i);
        j = skip(s2, j);
        while i < s1.len() {
            if j >= s2.len() {
                return false;
            }
            let q = s1[i];
            if q == b'\'' || q == b'"' {
                // Quoted text must match exactly.
                if s2[j] != q {
                    return false;
                }
                i += 1;
                j += 1;
                loop {
                    let Some(&c) = s1.get(i) else { return false };
                    if c == q {
                        break;
                    }
                    if s2.get(j) != Some(&c) {
                        return false;
                    }
                    i += 1;
                    j += 1;
                }
                i += 1;
                if s2.get(j) != Some(&q) {
                    return false;
                }
                j += 1;
            } else {
                let word_end = |s: &[u8], mut k: usize| {
                    while k < s.len() && !is_c_space(s[k]) {
                        k += 1;
                    }
                    k
                };
                let (e1, e2) = (word_end(s1, i), word_end(s2, j));
                let w1 = String::from_utf8_lossy(&s1[i..e1]).into_owned();
                let w2 = String::from_utf8_lossy(&s2[j..e2]).into_owned();
                let numeric = if is_int(&w1) {
                    !is_int(&w2) && is_flt(&w2)
                } else if is_flt(&w1) {
                    if !is_flt(&w2) {
                        return false;
                    }
                    true
                } else {
                    false
                };
                if numeric {
                    if !self.real(atof(&w1), atof(&w2)) {
                        return false;
                    }
                } else if w1 != w2 {
                    return false;
                }
                i = e1;
                j = e2;
            }
            i = skip(s1, i);
            j = skip(s2, j);
        }
        j >= s2.len()
    }
}

/// `setheadvar` over a header; `None` when the file has no header.
fn parse(data: &[u8]) -> Result<Option<Parsed>, String> {
    if !data.starts_with(b"#?") {
        return Ok(None);
    }
    let mut vars: HashMap<String, String> = HashMap::new();
    let mut pos = 0;
    let mut lines = 0;
    let mut swapped = false;
    let mut first = true;
    loop {
        let Some(n) = data[pos..].iter().position(|&c| c == b'\n') else {
            return Err("unexpected end-of-file".into());
        };
        let line = &data[pos..pos + n];
        pos += n + 1;
        lines += 1;
        if first {
            first = false;
            continue;
        }
        if line.is_empty() {
            break;
        }
        let text = String::from_utf8_lossy(line);
        if !text.starts_with(|c: char| c.is_ascii_alphabetic()) {
            continue;
        }
        if let Some(v) = text.strip_prefix("BigEndian=") {
            let big = v.trim_start().starts_with('1');
            if big != cfg!(target_endian = "big") {
                swapped = true;
            }
            continue;
        }
        let key_end = text
            .find(|c: char| c == '=' || c.is_ascii_whitespace())
            .unwrap_or(text.len());
        let key = &text[..key_end];
        let rest = text[key_end..].trim_start();
        let Some(value) = rest.strip_prefix('=') else {
            continue;
        };
        let value = value.trim();
        if value.is_empty() || IGNORED.contains(&key) {
            continue;
        }
        let value = match vars.get(key) {
            Some(old) if key == "EXPOSURE" => {
                radc_lang::c_number::format_e(atof(old) * atof(value), 6)
            }
            _ => value.to_string(),
        };
        vars.insert(key.to_string(), value);
    }
    let kind = kind_of(vars.get("FORMAT").map(String::as_str));
    Ok(Some(Parsed {
        vars,
        lines,
        swapped,
        kind,
        body: pos,
    }))
}

/// Compares `reference` with `test`.
pub fn compare(o: &CompareOptions, prog: &str, a: &Input, b: &Input) -> Verdict {
    let mut c = Comparer {
        o,
        prog: prog.to_string(),
        out: String::new(),
        diff2sum: 0.0,
        nsum: 0,
    };
    let ident = |input: &Input| -> Result<Parsed, String> {
        match parse(input.data)? {
            Some(p) => Ok(p),
            None => {
                let head = &input.data[..input.data.len().min(10240)];
                let binary = head.iter().any(|&b| b == 0 || b > 127);
                if input.data.is_empty() {
                    return Err("read/seek error".into());
                }
                Ok(Parsed {
                    vars: HashMap::new(),
                    lines: 0,
                    swapped: false,
                    kind: if binary { Kind::Binary } else { Kind::Text },
                    body: 0,
                })
            }
        }
    };
    let trouble = |c: Comparer, name: &str, e: String| Verdict {
        status: 2,
        report: format!("{}{name}: {e}\n", c.out),
    };
    let p1 = match ident(a) {
        Ok(p) => p,
        Err(e) => return trouble(c, a.name, e),
    };
    let p2 = match ident(b) {
        Ok(p) => p,
        Err(e) => return trouble(c, b.name, e),
    };
    if p1.kind != p2.kind {
        if o.report != 0 {
            let line = format!(
                "{prog}: '{}' format is {} and '{}' is {}\n",
                a.name,
                kind_name(p1.kind),
                b.name,
                kind_name(p2.kind)
            );
            c.say(&line);
        }
        return Verdict {
            status: 1,
            report: c.out,
        };
    }
    let has_header = !matches!(p1.kind, Kind::Text | Kind::Binary);
    let check_header = !o.ignore_header && has_header;
    if check_header {
        let mut keys: Vec<&String> = p1.vars.keys().collect();
        keys.sort();
        for k in keys {
            let v1 = &p1.vars[k];
            let Some(v2) = p2.vars.get(k) else {
                if o.report != 0 {
                    let line = format!("{prog}: variable '{k}' missing in '{}'\n", b.name);
                    c.say(&line);
                }
                return Verdict {
                    status: 1,
                    report: c.out,
                };
            };
            if !c.equivalent(v1.as_bytes(), v2.as_bytes()) {
                if o.report != 0 {
                    let line = format!("{prog}: header variable '{k}' has different values\n");
                    c.say(&line);
                }
                return Verdict {
                    status: 1,
                    report: c.out,
                };
            }
        }
        let extra = p2.vars.len().saturating_sub(p1.vars.len());
        if o.report >= 2 && extra > 0 {
            let line = format!(
                "{prog}: warning - '{}' has {extra} extra header setting(s)\n",
                b.name
            );
            c.say(&line);
        }
        if o.report >= 2 {
            if p1.lines != p2.lines {
                let line = format!("{prog}: warning - headers are different lengths\n");
                c.say(&line);
            }
            if p1.kind == Kind::Unknown {
                let line = format!("{prog}: warning - unrecognized format\n");
                c.say(&line);
            }
        }
    }
    let (d1, d2) = (&a.data[p1.body..], &b.data[p2.body..]);
    let same = match p1.kind {
        Kind::Text | Kind::Ascii => text(&mut c, (a.name, b.name), (d1, d2), (p1.lines, p2.lines)),
        Kind::Rgbe | Kind::Xyze => pictures(&mut c, a, b),
        Kind::Float => binary_values(&mut c, d1, d2, 4, (p1.swapped, p2.swapped), a.name, b.name),
        Kind::Double => binary_values(&mut c, d1, d2, 8, (p1.swapped, p2.swapped), a.name, b.name),
        Kind::Spectral | Kind::Depth | Kind::Normal => {
            return Verdict {
                status: 2,
                report: format!(
                    "{}{prog}: comparing {} files is not supported by radc radcompare\n",
                    c.out,
                    kind_name(p1.kind)
                ),
            };
        }
        Kind::Unknown | Kind::Binary | Kind::Other(_) => {
            bytes(&mut c, a.name, b.name, d1, d2, p1.body, p2.body)
        }
    };
    Verdict {
        status: u8::from(!same),
        report: c.out,
    }
}

/// `read_line` over a text: lines with their newline, `\r\n` made `\n`, escaped
/// newlines joined, comment lines emptied.
fn lines(o: &CompareOptions, data: &[u8]) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    let mut pos = 0;
    while pos < data.len() {
        let mut line = Vec::new();
        loop {
            let end = data[pos..]
                .iter()
                .position(|&c| c == b'\n')
                .map_or(data.len(), |n| pos + n + 1);
            line.extend_from_slice(&data[pos..end]);
            pos = end;
            if line.ends_with(b"\r\n") {
                line.truncate(line.len() - 2);
                line.push(b'\n');
            }
            if o.escape_newlines && line.ends_with(b"\\\n") && pos < data.len() {
                line.truncate(line.len() - 2);
                line.push(b' ');
                continue;
            }
            break;
        }
        if let Some(cc) = o.comment {
            let k = line
                .iter()
                .position(|&c| !is_c_space(c))
                .unwrap_or(line.len());
            if line.get(k) == Some(&cc) {
                line.truncate(k);
                line.push(b'\n');
            }
        }
        out.push(line);
    }
    out
}

fn blank(l: &[u8]) -> bool {
    l.iter().all(|&c| is_c_space(c))
}

/// `compare_text`; line numbers count from the header lines (`lin1cnt`, `lin2cnt`).
fn text(
    c: &mut Comparer,
    (n1, n2): (&str, &str),
    (d1, d2): (&[u8], &[u8]),
    (mut c1, mut c2): (usize, usize),
) -> bool {
    let (l1, l2) = (lines(c.o, d1), lines(c.o, d2));
    let mut j = 0;
    for line in &l1 {
        c1 += 1;
        if blank(line) {
            continue;
        }
        let mut other = None;
        while j < l2.len() {
            c2 += 1;
            j += 1;
            if !blank(&l2[j - 1]) {
                other = Some(&l2[j - 1]);
                break;
            }
        }
        let Some(other) = other else {
            if c.o.report != 0 {
                c.say(&format!("{n2}: unexpected end-of-file\n"));
            }
            return false;
        };
        if !c.equivalent(line, other) {
            if c.o.report != 0 {
                let mut s = format!("{}: inputs '{n1}' and '{n2}' differ at line {c1}", c.prog);
                if c1 != c2 {
                    s.push_str(&format!("|{c2}\n"));
                } else {
                    s.push('\n');
                }
                c.say(&s);
            }
            return false;
        }
    }
    if l2[j..].iter().any(|l| !blank(l)) {
        if c.o.report != 0 {
            c.say(&format!("{n1}: unexpected end-of-file\n"));
        }
        return false;
    }
    c.good_rms(n1, n2)
}

fn pictures(c: &mut Comparer, a: &Input, b: &Input) -> bool {
    let (p1, p2) = match (Picture::read(a.data), Picture::read(b.data)) {
        (Ok(p1), Ok(p2)) => (p1, p2),
        _ => {
            if c.o.report != 0 {
                let line = format!("{}: unexpected end-of-file\n", c.prog);
                c.say(&line);
            }
            return false;
        }
    };
    let (r1, r2): (Resolution, Resolution) = (p1.resolution, p2.resolution);
    if r1.orientation != r2.orientation {
        if c.o.report != 0 {
            let line = format!(
                "{}: HDR images '{}' and '{}' have different pixel ordering\n",
                c.prog, a.name, b.name
            );
            c.say(&line);
        }
        return false;
    }
    if r1.x != r2.x || r1.y != r2.y {
        if c.o.report != 0 {
            let line = format!(
                "{}: HDR images '{}' and '{}' are different sizes\n",
                c.prog, a.name, b.name
            );
            c.say(&line);
        }
        return false;
    }
    for y in 0..r1.scan_count() {
        for (x, (&q1, &q2)) in p1.scanline(y).iter().zip(p2.scanline(y)).enumerate() {
            let (v1, v2) = (decode(q1), decode(q2));
            let mean =
                |v: [f32; 3]| (f64::from(v[0]) + f64::from(v[1]) + f64::from(v[2])) * (1. / 3.);
            let mut ok = c.real(mean(v1), mean(v2));
            if ok {
                let mut p = if v1[1] > v1[0] { 1 } else { 0 };
                if v1[2] > v1[p] {
                    p = 2;
                }
                ok = c.real(f64::from(v1[p]), f64::from(v2[p]));
            }
            if !ok {
                if c.o.report != 0 {
                    let line = format!("{}: pixels at scanline {y} offset {x} differ\n", c.prog);
                    c.say(&line);
                }
                return false;
            }
        }
    }
    c.good_rms(a.name, b.name)
}

fn suffix(n: u64) -> &'static str {
    ["th", "st", "nd", "rd", "th", "th", "th", "th", "th", "th"][(n % 10) as usize]
}

fn binary_values(
    c: &mut Comparer,
    d1: &[u8],
    d2: &[u8],
    size: usize,
    swapped: (bool, bool),
    n1: &str,
    n2: &str,
) -> bool {
    let value = |d: &[u8], k: usize, swap: bool| -> Option<f64> {
        let b = d.get(k * size..(k + 1) * size)?;
        let mut v = b.to_vec();
        if swap {
            v.reverse();
        }
        Some(if size == 4 {
            f64::from(f32::from_ne_bytes([v[0], v[1], v[2], v[3]]))
        } else {
            f64::from_ne_bytes(v.try_into().unwrap_or([0; 8]))
        })
    };
    let what = if size == 4 { "float" } else { "double" };
    let mut k = 0;
    while let Some(v1) = value(d1, k, swapped.0) {
        let Some(v2) = value(d2, k, swapped.1) else {
            if c.o.report != 0 {
                let line = format!("{}: unexpected end-of-file\n", c.prog);
                c.say(&line);
            }
            return false;
        };
        k += 1;
        if !c.real(v1, v2) {
            if c.o.report != 0 {
                let line = format!("{}: {k}{} {what} values differ\n", c.prog, suffix(k as u64));
                c.say(&line);
            }
            return false;
        }
    }
    if value(d2, k, swapped.1).is_some() {
        if c.o.report != 0 {
            let line = format!("{}: unexpected end-of-file\n", c.prog);
            c.say(&line);
        }
        return false;
    }
    c.good_rms(n1, n2)
}

fn bytes(c: &mut Comparer, n1: &str, n2: &str, d1: &[u8], d2: &[u8], o1: usize, o2: usize) -> bool {
    let n = d1.iter().zip(d2).position(|(x, y)| x != y);
    match n {
        None if d1.len() == d2.len() => true,
        None => {
            if c.o.report != 0 {
                let name = if d1.len() < d2.len() { n1 } else { n2 };
                c.say(&format!("{name}: unexpected end-of-file\n"));
            }
            false
        }
        Some(k) => {
            if c.o.report != 0 {
                let line = format!(
                    "{}: binary files '{n1}' and '{n2}' differ at byte offset {}|{}\n",
                    c.prog,
                    o1 + k + 1,
                    o2 + k + 1
                );
                c.say(&line);
            }
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(a: &[u8], b: &[u8]) -> Verdict {
        compare(
            &CompareOptions::default(),
            "radcompare",
            &Input { name: "a", data: a },
            &Input { name: "b", data: b },
        )
    }

    #[test]
    fn text_numbers_compare_within_the_tolerances_and_words_exactly() {
        assert_eq!(run(b"1 2.5 x\n\n3\n", b"1 2.5000001 x\n3\n").status, 0);
        let v = run(b"1 2.5 x\n", b"1 3.5 x\n");
        assert_eq!(v.status, 1);
        assert!(
            v.report.contains("relative difference between 2.5 and 3.5"),
            "{}",
            v.report
        );
        assert_eq!(run(b"1 2 x\n", b"1 2 y\n").status, 1);
        let v = run(b"1\n2\n", b"1\n");
        assert_eq!(
            (v.status, v.report.as_str()),
            (1, "b: unexpected end-of-file\n")
        );
        // Integers compare as text, unless the other side is a real number.
        assert_eq!(run(b"10\n", b"10.0000001\n").status, 0);
        assert_eq!(run(b"10\n", b"11\n").status, 1);
    }

    #[test]
    fn headers_must_agree_and_formats_match() {
        let a = b"#?RADIANCE\nFORMAT=ascii\nSOFTWARE= a\nVIEW= -vh 40\n\n1 2\n";
        let b = b"#?RADIANCE\nSOFTWARE= b\nFORMAT=ascii\nVIEW= -vh 40.00001\n\n1 2\n";
        assert_eq!(run(a, b).status, 0);
        let c = b"#?RADIANCE\nFORMAT=ascii\nVIEW= -vh 50\n\n1 2\n";
        let v = run(a, c);
        assert_eq!(v.status, 1);
        assert!(
            v.report
                .contains("header variable 'VIEW' has different values")
        );
        let v = run(a, b"1 2\n");
        assert!(
            v.report.contains("format is ascii and 'b' is TEXT_generic"),
            "{}",
            v.report
        );
    }

    #[test]
    fn pictures_compare_pixel_by_pixel() {
        let picture = |v: f64| {
            let mut p = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n".to_vec();
            p.extend_from_slice(crate::Resolution::standard(3, 2).line().as_bytes());
            let scan = vec![crate::encode(v, v, v); 3];
            for _ in 0..2 {
                crate::scanline::write(&scan, &mut p);
            }
            p
        };
        assert_eq!(run(&picture(1.0), &picture(1.0)).status, 0);
        let v = run(&picture(1.0), &picture(2.0));
        assert_eq!(v.status, 1);
        assert!(
            v.report.contains("pixels at scanline 0 offset 0 differ"),
            "{}",
            v.report
        );
    }

    proptest::proptest! {
        /// Any two inputs get a verdict, never a panic: headers cut anywhere, binary
        /// junk, pictures with damaged scanlines.
        #[test]
        fn any_inputs_get_a_verdict(
            a in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..300),
            b in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..300),
            head in 0usize..4,
        ) {
            let heads: [&[u8]; 4] = [
                b"",
                b"#?RADIANCE\nFORMAT=ascii\n\n",
                b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 3\n",
                b"#?RADIANCE\nFORMAT=float\nBigEndian=1\n\n",
            ];
            let (mut x, mut y) = (heads[head].to_vec(), heads[head].to_vec());
            x.extend_from_slice(&a);
            y.extend_from_slice(&b);
            let v = run(&x, &y);
            proptest::prop_assert!(v.status <= 2);
        }
    }
}
