//! Radiance's pvalue. Prints a picture's pixels as numbers (`x y r g b`
//! lines in the picture's frame, or data only with `-d`), brightness with `-b`, one
//! primary with `-pr -pg -pb`, undoing the header's exposure with `-o`, in ASCII, `-di`
//! integers, `-db` bytes, `-df` floats or `-dd` doubles; `-r` converts such numbers back
//! to a picture. `-h`/`-H` leave out the header/resolution line (`+h`/`+H` put them
//! back), `-u` prints only values that differ from the one before, `-e` scales by an
//! exposure (`+N`/`-N`: stops), `-R` reverses the channel order, `-x -y` give the
//! resolution of headerless input. Arithmetic is pvalue's: single-precision colours.

use radc_lang::c_number::{atof, format_e};

use super::{Run, c_exp_width, format_line};
use crate::color::{CIE_BF, CIE_GF, CIE_RF};
use crate::{
    Format, Header, HeaderLine, Orientation, Picture, Resolution, decode, encode, scanline,
};

/// What each value is (`putprim`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Put {
    All,
    Bright,
    Primary(usize),
}

/// The number format (`format`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Number {
    Ascii,
    Int,
    Byte,
    Float,
    Double,
}

/// pvalue's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct Options {
    pub header: bool,
    pub resolution: bool,
    pub uniq: bool,
    pub original: bool,
    pub put: Put,
    pub reverse: bool,
    pub number: Number,
    pub format_id: String,
    pub data_only: bool,
    pub exposure: [f32; 3],
    pub do_exposure: bool,
    /// The product of `-e` values, for the EXPOSURE line.
    pub exposure_value: f64,
    pub order: [usize; 3],
    /// `-x -y`: orientation flags and sizes (0 when not given).
    pub orientation: u8,
    pub x: i64,
    pub y: i64,
}

/// `isbigendian`: `BigEndian`, blanks, `=`, blanks, then whether it is `1`.
fn big_endian(line: &[u8]) -> Option<bool> {
    let rest = line.strip_prefix(b"BigEndian")?;
    let rest = rest.trim_ascii_start().strip_prefix(b"=")?;
    Some(rest.trim_ascii_start().first() == Some(&b'1'))
}

/// The header lines pvalue reads itself (`checkhead`) and so does not copy.
fn consumed(o: &mut Options, line: &HeaderLine) -> bool {
    let b = &line.0;
    if line.format().is_some()
        || b.starts_with(b"NROWS=")
        || b.starts_with(b"NCOLS=")
        || b.starts_with(b"NCOMP=")
        || b.starts_with(b"WAVELENGTH_SPLITS=")
        || big_endian(b).is_some()
    {
        return true;
    }
    if o.original
        && let Some(v) = line.value_after("EXPOSURE=")
    {
        let d = 1.0 / atof(&v);
        o.exposure = o.exposure.map(|e| (f64::from(e) * d) as f32);
        o.do_exposure = true;
        return true;
    }
    if o.original
        && let Some(v) = line.value_after("COLORCORR=")
    {
        let n: Vec<f32> = v.split_whitespace().map_while(|w| w.parse().ok()).collect();
        let c = [0, 1, 2].map(|i| n.get(i).copied().unwrap_or(0.0));
        o.exposure = [0, 1, 2].map(|i| o.exposure[i] / c[i]);
        o.do_exposure = true;
        return true;
    }
    false
}

fn endian_line() -> &'static str {
    if cfg!(target_endian = "big") {
        "BigEndian=1\n"
    } else {
        "BigEndian=0\n"
    }
}

/// Picture to numbers.
/// A picture to numbers; `what` names the input in messages.
pub fn to_values(o: &Options, run: &Run, data: &[u8], what: &str) -> Result<Vec<u8>, String> {
    let o = &mut o.clone();
    let picture = Picture::read(data).map_err(|e| format!("{what}: {e}"))?;
    let xyz = match picture.format_name.as_deref() {
        None | Some(Format::RGBE) => false,
        Some(Format::XYZE) => true,
        Some(f) => {
            return Err(format!(
                "{what}: input not a Radiance RGBE picture (FORMAT={f})"
            ));
        }
    };
    let mut out = Vec::new();
    for line in &picture.header.lines {
        if !consumed(o, line) && o.header {
            out.extend_from_slice(&line.0);
        }
    }
    let res = picture.resolution;
    if o.header {
        out.extend_from_slice(run.command_line.as_bytes());
        if o.data_only {
            let n = if o.put == Put::All { 3 } else { 1 };
            out.extend_from_slice(format!("NCOMP={n}\n").as_bytes());
        }
        if o.data_only && !o.resolution && !o.uniq {
            out.extend_from_slice(
                format!("NCOLS={}\nNROWS={}\n", res.scan_length(), res.scan_count()).as_bytes(),
            );
        }
        exposure_line(o, &mut out);
        if !matches!(o.number, Number::Ascii | Number::Int | Number::Byte) {
            out.extend_from_slice(endian_line().as_bytes());
        }
        out.extend_from_slice(format_line(&o.format_id, run.output_start, out.len()).as_bytes());
        out.push(b'\n');
    }
    if o.resolution {
        out.extend_from_slice(res.line().as_bytes());
    }
    let bright = |c: [f32; 3]| -> f64 {
        if xyz {
            f64::from(c[1])
        } else {
            CIE_RF * f64::from(c[0]) + CIE_GF * f64::from(c[1]) + CIE_BF * f64::from(c[2])
        }
    };
    let mut last = [0f32; 3];
    for s in 0..res.scan_count() {
        for (p, &colr) in picture.scanline(s).iter().enumerate() {
            let mut c = decode(colr);
            if o.uniq {
                if c == last {
                    continue;
                }
                last = c;
            }
            if o.do_exposure {
                c = [0, 1, 2].map(|i| c[i] * o.exposure[i]);
            }
            if !o.data_only {
                let (x, y) = res.frame_position(s, p as u32);
                let (xr, yr) = (f64::from(res.x), f64::from(res.y));
                let lx = (f64::from(x) + 0.5) / xr;
                let ly = (f64::from(y) + 0.5) / yr;
                let line = format!("{:7} {:7} ", (lx * xr) as i32, (ly * yr) as i32);
                out.extend_from_slice(line.as_bytes());
            }
            put_value(o, c, bright, &mut out);
        }
    }
    Ok(out)
}

fn exposure_line(o: &Options, out: &mut Vec<u8>) {
    if o.exposure_value < 0.99 || o.exposure_value > 1.01 {
        out.extend_from_slice(format!("EXPOSURE={}\n", format_e(o.exposure_value, 4)).as_bytes());
    }
}

/// One pixel's value(s) in the chosen format (`putcascii`, `putbfloat`, ...).
fn put_value(o: &Options, c: [f32; 3], bright: impl Fn([f32; 3]) -> f64, out: &mut Vec<u8>) {
    let values: Vec<f64> = match o.put {
        Put::All => o.order.iter().map(|&i| f64::from(c[i])).collect(),
        Put::Bright => vec![bright(c)],
        Put::Primary(i) => vec![f64::from(c[i])],
    };
    match o.number {
        Number::Ascii => {
            let words: Vec<String> = values.iter().map(|&v| c_exp_width(v, 15, 3)).collect();
            out.extend_from_slice(words.join(" ").as_bytes());
            out.push(b'\n');
        }
        Number::Int => {
            let words: Vec<String> = values
                .iter()
                .map(|&v| ((v * 256.0) as i32).to_string())
                .collect();
            out.extend_from_slice(words.join(" ").as_bytes());
            out.push(b'\n');
        }
        Number::Byte => values
            .iter()
            .for_each(|&v| out.push(((v * 256.0) as i64).min(255) as u8)),
        Number::Float => values
            .iter()
            .for_each(|&v| out.extend_from_slice(&(v as f32).to_ne_bytes())),
        Number::Double => values
            .iter()
            .for_each(|&v| out.extend_from_slice(&v.to_ne_bytes())),
    }
}

/// `fscanf` on text: blanks skipped, then an integer or a floating-point number.
struct Scanner<'a> {
    b: &'a [u8],
    pos: usize,
}

impl Scanner<'_> {
    fn skip_blanks(&mut self) {
        while self
            .b
            .get(self.pos)
            .is_some_and(|c| c.is_ascii_whitespace())
        {
            self.pos += 1;
        }
    }

    fn int(&mut self) -> Option<i64> {
        self.skip_blanks();
        let start = self.pos;
        if matches!(self.b.get(self.pos), Some(b'-' | b'+')) {
            self.pos += 1;
        }
        let digits = self.pos;
        while self.b.get(self.pos).is_some_and(u8::is_ascii_digit) {
            self.pos += 1;
        }
        if self.pos == digits {
            self.pos = start;
            return None;
        }
        std::str::from_utf8(&self.b[start..self.pos])
            .ok()?
            .parse::<i64>()
            .ok()
            .map(|v| v.clamp(i32::MIN.into(), i32::MAX.into()))
    }

    fn float(&mut self) -> Option<f64> {
        self.skip_blanks();
        let start = self.pos;
        let rest = &self.b[start..];
        // The longest prefix that is a number, as strtod takes it.
        let mut best = None;
        let limit = rest
            .iter()
            .position(|c| !(c.is_ascii_alphanumeric() || matches!(c, b'+' | b'-' | b'.')))
            .unwrap_or(rest.len());
        for end in (1..=limit).rev() {
            if let Some(v) = std::str::from_utf8(&rest[..end])
                .ok()
                .and_then(|t| t.parse::<f64>().ok())
            {
                best = Some((v, end));
                break;
            }
        }
        let (v, n) = best?;
        self.pos += n;
        Some(v)
    }
}

/// Numbers to a picture (`-r`); `what` names the input in messages.
pub fn to_picture(o: &Options, run: &Run, data: &[u8], what: &str) -> Result<Vec<u8>, String> {
    let o = &mut o.clone();
    let mut out = Vec::new();
    let mut pos = 0;
    let (mut xr, mut yr) = (o.x, o.y);
    let mut ncomp = 3;
    if o.header {
        let (header, end) = Header::parse(data).map_err(|e| format!("{what}: {e}"))?;
        pos = end;
        for line in &header.lines {
            if let Some(f) = line.format() {
                let id = match f.as_str() {
                    "ascii" => Some(Number::Ascii),
                    "float" => Some(Number::Float),
                    "double" => Some(Number::Double),
                    "byte" => Some(Number::Byte),
                    _ => None,
                };
                let wrong = if o.number == Number::Ascii {
                    match id {
                        Some(n) => {
                            o.number = n;
                            o.format_id = f.clone();
                            false
                        }
                        None => true,
                    }
                } else {
                    f != o.format_id
                };
                if wrong {
                    return Err(format!(
                        "{what}: wrong input format (expected {})",
                        o.format_id
                    ));
                }
                continue;
            }
            if let Some(v) = line.value_after("NROWS=") {
                yr = atof(&v) as i64;
                continue;
            }
            if let Some(v) = line.value_after("NCOLS=") {
                xr = atof(&v) as i64;
                continue;
            }
            if let Some(v) = line.value_after("NCOMP=") {
                ncomp = atof(&v) as i64;
                o.data_only = true;
                continue;
            }
            if let Some(big) = big_endian(&line.0) {
                if big != cfg!(target_endian = "big") {
                    return Err(format!(
                        "{what}: byte-swapped input (BigEndian=) is not supported by radc pvalue"
                    ));
                }
                continue;
            }
            if !consumed(o, line) {
                out.extend_from_slice(&line.0);
            }
        }
        o.resolution &= xr <= 0 || yr <= 0;
    } else {
        out.extend_from_slice(b"#?RADIANCE\n");
    }
    let mut orientation = Orientation(o.orientation);
    if o.resolution {
        let (r, n) =
            Resolution::parse(&data[pos..]).ok_or(format!("{what}: missing resolution"))?;
        pos += n;
        orientation = r.orientation;
        (xr, yr) = (i64::from(r.x), i64::from(r.y));
    }
    if xr <= 0 || yr <= 0 || xr > i64::from(i32::MAX) || yr > i64::from(i32::MAX) {
        return Err(format!("{what}: missing resolution"));
    }
    let res = Resolution {
        orientation,
        x: xr as u32,
        y: yr as u32,
    };
    if u64::from(res.x) * u64::from(res.y) > crate::DEFAULT_MAX_PIXELS {
        return Err(format!("{what}: a {xr} by {yr} picture is too large"));
    }
    out.extend_from_slice(run.command_line.as_bytes());
    exposure_line(o, &mut out);
    if !o.header && o.put != Put::All {
        // No header to say otherwise: the user's word for one component.
    } else if ncomp == 1 {
        if o.put == Put::All {
            o.put = Put::Bright;
        }
    } else if ncomp != 3 {
        return Err(format!("{what}: input NCOMP must be 1 or 3"));
    } else if o.put != Put::All {
        return Err(format!("{what}: NCOMP mismatch"));
    }
    out.extend_from_slice(format_line(Format::RGBE, None, 0).as_bytes());
    out.push(b'\n');
    out.extend_from_slice(res.line().as_bytes());
    let mut input = Input {
        scan: Scanner { b: data, pos },
        number: o.number,
    };
    let len = res.scan_length() as usize;
    let mut scan = Vec::with_capacity(len);
    for _ in 0..res.scan_count() {
        scan.clear();
        for _ in 0..len {
            if !o.data_only {
                let _ = input.scan.int().and_then(|_| input.scan.int());
            }
            let mut c = match o.put {
                Put::All => {
                    let v = [input.value(), input.value(), input.value()];
                    let [Some(a), Some(b), Some(c)] = v else {
                        return Err(format!("{what}: read error"));
                    };
                    let v = [a, b, c];
                    // rord: value k of the line is channel order[k].
                    let mut col = [0f32; 3];
                    for (k, &ch) in o.order.iter().enumerate() {
                        col[ch] = v[k];
                    }
                    col
                }
                _ => [input.value().ok_or(format!("{what}: read error"))?; 3],
            };
            if o.do_exposure {
                c = [0, 1, 2].map(|i| c[i] * o.exposure[i]);
            }
            let colr = encode(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]));
            if o.uniq {
                out.extend_from_slice(&colr);
            } else {
                scan.push(colr);
            }
        }
        if !o.uniq {
            scanline::write(&scan, &mut out);
        }
    }
    Ok(out)
}

/// The numbers of `-r` input in their format, each as pvalue's `get...` makes a
/// single-precision value of it.
struct Input<'a> {
    scan: Scanner<'a>,
    number: Number,
}

impl Input<'_> {
    fn value(&mut self) -> Option<f32> {
        let s = &mut self.scan;
        let mut bytes = |n: usize| {
            let b = s.b.get(s.pos..s.pos + n)?;
            s.pos += n;
            Some(b)
        };
        match self.number {
            Number::Ascii => s.float().map(|v| v as f32),
            Number::Int => s.int().map(|v| ((v as f64 + 0.5) / 256.0) as f32),
            Number::Byte => bytes(1).map(|b| ((f64::from(b[0]) + 0.5) / 256.0) as f32),
            Number::Float => bytes(4).map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]])),
            Number::Double => bytes(8).map(|b| {
                let a: [u8; 8] = b.try_into().unwrap_or([0; 8]);
                f64::from_ne_bytes(a) as f32
            }),
        }
    }
}
