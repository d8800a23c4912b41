//! Rays from a stream in rtrace's input formats: text lines of six numbers (scanned
//! in the input's buffer where they can be), or binary floats and doubles; a zero
//! direction asks for a flush, and a word that is not a number ends the input, as
//! rtrace reads them.

use std::io::BufRead;

use radc_lang::c_number::{is_c_space, real_prefix, real_word};

use super::RayEncoding;
use super::ray_text::spaced_number;
use crate::math::Vec3;

/// Rays from stdin in rtrace's input formats.
pub struct RayReader<R> {
    input: R,
    format: RayEncoding,
    /// Lines are scanned in the input's buffer where they can be (`scan_line`); the
    /// others are copied here and split (`read_line`).
    fast: bool,
    line: Vec<u8>,
    /// The numbers of the current line and the next to return; `stop`: after them
    /// comes a word that is not a number, which ends the input.
    words: Vec<f64>,
    at: usize,
    stop: bool,
    eof: bool,
}

impl<R: BufRead> RayReader<R> {
    pub fn new(input: R, format: RayEncoding) -> Self {
        RayReader {
            input,
            format,
            fast: true,
            line: Vec::new(),
            words: Vec::new(),
            at: 0,
            stop: false,
            eof: false,
        }
    }

    /// Up to `n` rays into `out` (cleared first). Returns whether it stopped early
    /// after a zero-direction ray (a flush request, not returned) and whether the
    /// input ended (or came to a word that is not a number).
    pub fn batch(&mut self, n: usize, out: &mut Vec<(Vec3, Vec3)>) -> (bool, bool) {
        out.clear();
        while out.len() < n {
            let Some(v) = self.next_six() else {
                return (false, true);
            };
            let org = Vec3::new(v[0], v[1], v[2]);
            let dir = Vec3::new(v[3], v[4], v[5]);
            if dir == Vec3::ZERO {
                return (true, false);
            }
            out.push((org, dir));
        }
        (false, false)
    }

    fn next_six(&mut self) -> Option<[f64; 6]> {
        if self.format == RayEncoding::Ascii && !self.eof {
            // Six numbers of the current line at once (the usual case: one ray a line).
            if self.at == self.words.len() {
                self.next_line()?;
            }
            if let Some(w) = self.words.get(self.at..self.at + 6)
                && !(self.stop && self.at + 6 == self.words.len())
            {
                let mut v = [0.0; 6];
                v.copy_from_slice(w);
                self.at += 6;
                return Some(v);
            }
        }
        let mut v = [0.0; 6];
        for x in &mut v {
            *x = self.next_number()?;
        }
        Some(v)
    }

    fn next_number(&mut self) -> Option<f64> {
        if self.eof {
            return None;
        }
        let r = match self.format {
            // Refused by the option parser: nothing to read.
            RayEncoding::Color => None,
            RayEncoding::Ascii => self.next_word(),
            RayEncoding::Float => {
                let mut b = [0u8; 4];
                self.input
                    .read_exact(&mut b)
                    .ok()
                    .map(|_| f64::from(f32::from_ne_bytes(b)))
            }
            RayEncoding::Double => {
                let mut b = [0u8; 8];
                self.input
                    .read_exact(&mut b)
                    .ok()
                    .map(|_| f64::from_ne_bytes(b))
            }
        };
        if r.is_none() {
            self.eof = true;
        }
        r
    }

    fn next_word(&mut self) -> Option<f64> {
        if self.at == self.words.len() {
            self.next_line()?;
        }
        let x = self.words[self.at];
        self.at += 1;
        (!(self.stop && self.at == self.words.len())).then_some(x)
    }

    /// Reads lines until one has a word; `None` at the end of the input (sets `eof`).
    #[inline(always)]
    fn next_line(&mut self) -> Option<()> {
        while self.at == self.words.len() {
            if self.stop {
                self.eof = true;
                return None;
            }
            self.words.clear();
            self.at = 0;
            if !(self.fast && self.scan_line()) && self.read_line().is_none() {
                self.eof = true;
                return None;
            }
        }
        Some(())
    }

    /// The next line's numbers, read in place in the input's buffer, when the whole
    /// line is there and is nothing but ASCII spaces and numbers (so splitting it would
    /// find the same words); false leaves the line to `read_line`.
    fn scan_line(&mut self) -> bool {
        let Ok(buf) = self.input.fill_buf() else {
            return false;
        };
        let mut at = 0;
        while let Some(&b) = buf.get(at) {
            if b == b'\n' {
                self.input.consume(at + 1);
                return true;
            }
            if is_c_space(b) {
                at += 1;
                continue;
            }
            let word = &buf[at..];
            let number = spaced_number(word).or_else(|| {
                real_prefix(word).filter(|&(_, n)| word.get(n).is_some_and(|&b| is_c_space(b)))
            });
            let Some((x, n)) = number else {
                break;
            };
            self.words.push(x);
            // A space follows the number: the line's end, or skipped.
            if word[n] == b'\n' {
                self.input.consume(at + n + 1);
                return true;
            }
            at += n + 1;
        }
        self.words.clear();
        false
    }

    /// The next line, copied and split into words, as rtrace reads it; `None` at the
    /// end of the input or at a line that is not UTF-8.
    #[cold]
    #[inline(never)]
    fn read_line(&mut self) -> Option<()> {
        self.line.clear();
        if self.input.read_until(b'\n', &mut self.line).ok()? == 0 {
            return None;
        }
        if self.line.is_ascii() {
            for w in self
                .line
                .split(|&b| is_c_space(b))
                .filter(|w| !w.is_empty())
            {
                // rtrace stops at the first word that is not a number.
                let Some(x) = real_word(w) else {
                    self.words.push(f64::NAN);
                    self.stop = true;
                    break;
                };
                self.words.push(x);
            }
        } else {
            // Unicode spaces separate words too; a line that is not UTF-8 ends the
            // input.
            let line = std::str::from_utf8(&self.line).ok()?;
            for w in line.split_whitespace() {
                let Some(x) = real_word(w.as_bytes()) else {
                    self.words.push(f64::NAN);
                    self.stop = true;
                    break;
                };
                self.words.push(x);
            }
        }
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::BufReader;

    /// Every batch a reader returns, until the input ends: rays as bits, then the flush
    /// and end flags.
    fn read_all(
        text: &[u8],
        capacity: usize,
        fast: bool,
        n: usize,
    ) -> Vec<(Vec<[u64; 6]>, bool, bool)> {
        let mut reader =
            RayReader::new(BufReader::with_capacity(capacity, text), RayEncoding::Ascii);
        reader.fast = fast;
        let mut rays = Vec::new();
        let mut batches = Vec::new();
        loop {
            let (flush, done) = reader.batch(n, &mut rays);
            let bits = rays
                .iter()
                .map(|(o, d)| {
                    let v = [o.x, o.y, o.z, d.x, d.y, d.z];
                    v.map(f64::to_bits)
                })
                .collect();
            batches.push((bits, flush, done));
            if done || batches.len() > 100_000 {
                return batches;
            }
        }
    }

    /// Reading lines in place in the input's buffer finds the same rays, flushes and
    /// end as copying and splitting every line, on random text with the usual numbers,
    /// odd ones, Unicode spaces, bytes that are not UTF-8, blank and long lines, words
    /// that are not numbers, and lines cut by the buffer's end (small buffers).
    #[test]
    fn lines_read_in_place_as_when_copied() {
        let tokens: [&[u8]; 24] = [
            b"10.925434",
            b"-0.46798942",
            b"0",
            b"-0",
            b"1",
            b"5.",
            b".5",
            b"-.25",
            b"+2",
            b"1e3",
            b"-2.5E-2",
            b"123456789012345678901234567890",
            b"0.1234567890123",
            b"12345678.5",
            b"0.000000001",
            b"1234567.12345678",
            b"9007199254740993",
            b"00000001.5",
            b"7",
            b"3.25",
            b"-1",
            b"0.5",
            b"2",
            b"-3",
        ];
        let spaces: [&[u8]; 9] = [
            b" ",
            b" ",
            b" ",
            b"\t",
            b"  ",
            b"\r",
            b"\x0b",
            b"\x0c",
            "\u{a0}".as_bytes(),
        ];
        let odd: [&[u8]; 7] = [
            b"abc",
            b"1.5x",
            b"\xff",
            "\u{2003}".as_bytes(),
            b"1e",
            b"-",
            "\u{e9}".as_bytes(),
        ];
        let mut seed = 0x5851_f42d_4c95_7f2du64;
        let mut next = |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        let mut compared = 0;
        for case in 0..300 {
            let mut text = Vec::new();
            for _ in 0..next(60) + 1 {
                match next(20) {
                    0 => {}
                    1 => text.extend_from_slice(b"1 2 3 0 0 0"),
                    2 => text.extend_from_slice(b"4 5 6 7 8"),
                    _ => {
                        for k in 0..6 {
                            if k > 0 || next(4) == 0 {
                                text.extend_from_slice(spaces[next(9) as usize]);
                            }
                            text.extend_from_slice(tokens[next(24) as usize]);
                        }
                    }
                }
                if next(8) == 0 {
                    text.extend_from_slice(spaces[next(9) as usize]);
                }
                if case % 3 == 0 && next(40) == 0 {
                    text.extend_from_slice(odd[next(7) as usize]);
                }
                text.push(b'\n');
            }
            if next(2) == 0 {
                text.pop();
            }
            for n in [1, 3, 4096] {
                let want = read_all(&text, 1 << 16, false, n);
                for capacity in [1, 7, 16, 64, 1 << 16] {
                    let got = read_all(&text, capacity, true, n);
                    assert_eq!(
                        got,
                        want,
                        "{:?} capacity {capacity} batch {n}",
                        String::from_utf8_lossy(&text)
                    );
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 300 * 3 * 5);
    }

    /// The fast path is the one the usual input takes.
    #[test]
    fn usual_lines_are_scanned_in_place() {
        let text =
            b"10.925434 13.039251 1.057157 -0.46798942 0.81813978 -0.33411556\n1 2 3 0 0 1\n";
        let mut reader = RayReader::new(BufReader::new(&text[..]), RayEncoding::Ascii);
        assert!(reader.scan_line());
        assert_eq!(reader.words.len(), 6);
        assert_eq!(reader.words[3], -0.46798942);
        reader.words.clear();
        assert!(reader.scan_line());
        assert_eq!(reader.words, [1.0, 2.0, 3.0, 0.0, 0.0, 1.0]);
        reader.words.clear();
        for text in [&b"1 2 abc\n"[..], b"1 2\xc2\xa0 3\n", b"1 2 3"] {
            let mut reader = RayReader::new(BufReader::new(text), RayEncoding::Ascii);
            assert!(!reader.scan_line(), "{text:?}");
            assert!(reader.words.is_empty());
        }
    }
}
