//! Radiance's portable binary numbers and strings (portio.c), and the text header that
//! opens its binary files (header.c), read from bytes with the offset of every damage.
//!
//! Integers are big-endian, `size` bytes, the first byte sign-extended (`getint`);
//! reals are a 4-byte mantissa of `frexp(x) * 0x7fffffff` and a 1-byte exponent
//! (`getflt`, `putflt`: 31 bits, so a real read back differs from the one written in
//! its last bits, exactly as Radiance's readers see it); strings end in a NUL.

use std::fmt;

/// What is wrong with a binary file, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BinaryError {
    /// Byte offset of the damage in the file.
    pub offset: usize,
    pub message: String,
}

impl fmt::Display for BinaryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (at byte {})", self.message, self.offset)
    }
}

impl std::error::Error for BinaryError {}

pub type Result<T> = std::result::Result<T, BinaryError>;

/// A cursor over a binary file's bytes. `truncated` names what a premature end cuts
/// short, as Radiance's readers word it ("truncated mesh file", "truncated octree").
pub struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    truncated: &'static str,
}

impl<'a> Reader<'a> {
    pub fn new(bytes: &'a [u8], truncated: &'static str) -> Reader<'a> {
        Reader {
            bytes,
            pos: 0,
            truncated,
        }
    }

    pub fn offset(&self) -> usize {
        self.pos
    }

    pub fn error<T>(&self, at: usize, message: impl Into<String>) -> Result<T> {
        Err(BinaryError {
            offset: at,
            message: message.into(),
        })
    }

    fn end<T>(&self) -> Result<T> {
        self.error(self.bytes.len(), self.truncated)
    }

    /// The next byte (`getc`), or `None` at the end.
    pub fn byte(&mut self) -> Option<u8> {
        let b = self.bytes.get(self.pos).copied()?;
        self.pos += 1;
        Some(b)
    }

    /// `getint(size)`: big-endian, the first byte sign-extended.
    pub fn int(&mut self, size: usize) -> Result<i64> {
        let Some(first) = self.byte() else {
            return self.end();
        };
        let mut r = i64::from(first as i8);
        for _ in 1..size {
            let Some(b) = self.byte() else {
                return self.end();
            };
            r = (r << 8) | i64::from(b);
        }
        Ok(r)
    }

    /// `getflt`: `(m + .5 - (m < 0)) / 0x7fffffff * 2^e`, exactly zero for `m = 0`.
    pub fn real(&mut self) -> Result<f64> {
        let m = self.int(4)?;
        let e = self.int(1)?;
        if m == 0 {
            return Ok(0.0);
        }
        let d = (m as f64 + 0.5 - f64::from(u8::from(m < 0))) * (1.0 / 2147483647.0);
        Ok(d * pow2(e))
    }

    /// `getstr`: bytes up to a NUL (lossy UTF-8: Radiance's names are ASCII).
    pub fn string(&mut self) -> Result<String> {
        let rest = self.bytes.get(self.pos..).unwrap_or_default();
        let Some(n) = rest.iter().position(|&b| b == 0) else {
            self.pos = self.bytes.len();
            return self.end();
        };
        let s = String::from_utf8_lossy(&rest[..n]).into_owned();
        self.pos += n + 1;
        Ok(s)
    }

    /// Skips `n` bytes, failing at the end of the file.
    pub fn skip(&mut self, n: usize) -> Result<()> {
        match self.pos.checked_add(n) {
            Some(end) if end <= self.bytes.len() => {
                self.pos = end;
                Ok(())
            }
            _ => self.end(),
        }
    }

    /// The information header (`getheader`): text lines up to an empty one. Returns
    /// the lines (without their newlines) and the value of the last `FORMAT=` line.
    /// `None` when the first byte is not printable or the file ends inside the
    /// header, as `getheader` fails then.
    pub fn header(&mut self) -> Option<(Vec<String>, Option<String>)> {
        let first = *self.bytes.get(self.pos)?;
        if !(0x20..0x7f).contains(&first) {
            return None;
        }
        let mut lines = Vec::new();
        let mut format = None;
        loop {
            let rest = self.bytes.get(self.pos..)?;
            let n = rest.iter().position(|&b| b == b'\n')?;
            let line = &rest[..n];
            self.pos += n + 1;
            if line.is_empty() || line == b"\r" {
                return Some((lines, format));
            }
            let text = String::from_utf8_lossy(line).into_owned();
            if let Some(f) = text.strip_prefix("FORMAT=") {
                format = Some(f.trim_end().to_string());
            }
            lines.push(text);
        }
    }
}

/// `2^e` exactly, for the exponents a 1-byte field holds.
fn pow2(e: i64) -> f64 {
    f64::from_bits(((1023 + e.clamp(-1022, 1023)) as u64) << 52)
}

/// Radiance's writers (`putint`, `putflt`, `putstr`), appending to a byte vector.
#[derive(Default)]
pub struct Writer {
    pub bytes: Vec<u8>,
}

impl Writer {
    /// `putint(i, size)`: the low `size` bytes, big-endian.
    pub fn int(&mut self, i: i64, size: usize) {
        for k in (0..size).rev() {
            self.bytes.push((i >> (8 * k)) as u8);
        }
    }

    /// `putflt`: `frexp` mantissa times `0x7fffffff` (truncated toward zero), and the
    /// exponent; overflow saturates, underflow is zero.
    pub fn real(&mut self, f: f64) {
        let (mut m, mut e) = if f == 0.0 || !f.is_finite() {
            (0i64, 0i64)
        } else {
            let (fr, ex) = frexp(f);
            ((fr * 2147483647.0) as i64, ex)
        };
        if e > 127 {
            m = if m > 0 { 0x7fffffff } else { -0x7fffffff };
            e = 127;
        } else if e < -128 {
            m = 0;
            e = 0;
        }
        self.int(m, 4);
        self.int(e, 1);
    }

    /// `putstr`: the bytes and a NUL.
    pub fn string(&mut self, s: &str) {
        self.bytes.extend_from_slice(s.as_bytes());
        self.bytes.push(0);
    }
}

/// C's `frexp` for finite, non-zero `x`: `x = fr * 2^e` with `0.5 <= |fr| < 1`.
fn frexp(x: f64) -> (f64, i64) {
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    if exp == 0 {
        // Subnormal: scale into the normal range first.
        let (fr, e) = frexp(x * pow2(64));
        return (fr, e - 64);
    }
    let fr = f64::from_bits((bits & !(0x7ff << 52)) | (1022 << 52));
    (fr, exp - 1022)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_sign_extend_their_first_byte() {
        let bytes = [0xff, 0xfe, 0x01, 0x00, 0x7f];
        let mut r = Reader::new(&bytes, "truncated");
        assert_eq!(r.int(2).unwrap(), -2);
        assert_eq!(r.int(2).unwrap(), 256);
        assert_eq!(r.int(1).unwrap(), 127);
        assert_eq!(r.int(1).unwrap_err().offset, 5);
    }

    #[test]
    fn reals_round_trip_to_31_bits() {
        for x in [1.0, -1.0, 0.1, 3.5e-7, -123456.789, 1e30, 0.0] {
            let mut w = Writer::default();
            w.real(x);
            let mut r = Reader::new(&w.bytes, "truncated");
            let y = r.real().unwrap();
            assert!((x - y).abs() <= x.abs() * 1e-9, "{x} -> {y}");
        }
    }

    #[test]
    fn a_real_reads_as_getflt_computes_it() {
        // m = 0x40000000, e = 1: (m + .5) / 0x7fffffff * 2.
        let bytes = [0x40, 0, 0, 0, 1];
        let y = Reader::new(&bytes, "t").real().unwrap();
        assert_eq!(y, (1073741824.0 + 0.5) * (1.0 / 2147483647.0) * 2.0);
    }

    #[test]
    fn headers_end_at_an_empty_line() {
        let bytes = b"#?RADIANCE\nFORMAT=Radiance_tmesh\n\nrest";
        let mut r = Reader::new(bytes, "t");
        let (lines, format) = r.header().unwrap();
        assert_eq!(lines.len(), 2);
        assert_eq!(format.as_deref(), Some("Radiance_tmesh"));
        assert_eq!(r.offset(), bytes.len() - 4);
        assert!(Reader::new(b"\x01abc", "t").header().is_none());
        assert!(Reader::new(b"abc\n", "t").header().is_none());
    }

    #[test]
    fn strings_end_in_nul() {
        let mut r = Reader::new(b"ab\0c", "cut");
        assert_eq!(r.string().unwrap(), "ab");
        let e = r.string().unwrap_err();
        assert_eq!((e.offset, e.message.as_str()), (4, "cut"));
    }
}
