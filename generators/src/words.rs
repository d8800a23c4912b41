//! Reading and writing words the way Radiance's C library does.
//!
//! `fgetword()` (`src/common/fgetword.c`) splits on C whitespace, honours quotes that
//! may start anywhere in a word, and truncates at a buffer size (dropping the character
//! that overflowed); `fputword()` quotes only when needed. Matching these keeps
//! outputs identical. Numbers are read as `radc_lang::c_number` reads them.

use radc_lang::c_number::{atol, is_c_space};

/// A cursor over scene text that hands out words and lines as the C reader would.
pub struct Stream<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Stream<'a> {
    pub fn new(text: &'a str) -> Self {
        Stream {
            bytes: text.as_bytes(),
            pos: 0,
        }
    }

    pub fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    pub fn next_byte(&mut self) -> Option<u8> {
        let b = self.peek()?;
        self.pos += 1;
        Some(b)
    }

    /// `fgetword(s, size, fp)`: `None` at end of input with nothing read.
    pub fn word(&mut self, size: usize) -> Option<String> {
        let mut c = self.next_byte();
        while c.is_some_and(is_c_space) {
            c = self.next_byte();
        }
        let is_quote = |b: u8| b == b'"' || b == b'\'';
        let mut quote = None;
        if let Some(q) = c.filter(|&b| is_quote(b)) {
            quote = Some(q);
            c = self.next_byte();
        }
        let mut out = Vec::new();
        let mut room = size;
        while let Some(b) = c {
            if Some(b) == quote {
                quote = None;
            } else if quote.is_none() && is_quote(b) {
                quote = Some(b);
            } else {
                if quote.is_none() && is_c_space(b) {
                    break;
                }
                room = room.saturating_sub(1);
                if room == 0 {
                    break;
                }
                out.push(b);
            }
            c = self.next_byte();
        }
        if c.is_none() && out.is_empty() {
            return None;
        }
        Some(String::from_utf8_lossy(&out).into_owned())
    }

    /// The rest of the line through its newline (or the end), unchanged: xform copies
    /// comments this way.
    pub fn comment(&mut self) -> String {
        let rest = &self.bytes[self.pos..];
        let len = rest
            .iter()
            .position(|&b| b == b'\n')
            .map_or(rest.len(), |i| i + 1);
        self.pos += len;
        String::from_utf8_lossy(&rest[..len]).into_owned()
    }

    /// `fgetline()`: one line without its newline; a newline after a backslash is kept
    /// and continues the line; `\r\n` and a lone `\r` end a line.
    pub fn line(&mut self, size: usize) -> Option<String> {
        let mut out: Vec<u8> = Vec::new();
        let mut room = size;
        let mut hit_end = false;
        loop {
            room = room.saturating_sub(1);
            if room == 0 {
                break;
            }
            let Some(mut c) = self.next_byte() else {
                hit_end = true;
                break;
            };
            if c == b'\r' {
                if self.peek() == Some(b'\n') {
                    self.pos += 1;
                }
                c = b'\n';
            }
            if c == b'\n' && out.last() != Some(&b'\\') {
                break;
            }
            out.push(c);
        }
        if out.is_empty() && hit_end {
            return None;
        }
        Some(String::from_utf8_lossy(&out).into_owned())
    }
}

/// `fputword()`: quote a word that is empty, holds whitespace, or holds a quote
/// character (not in first or last place), choosing the other kind of quote.
pub fn put_word(out: &mut String, s: &str) {
    let b = s.as_bytes();
    let mut has_space = false;
    let mut quote = None;
    for (i, &c) in b.iter().enumerate() {
        let not_last = i + 1 < b.len();
        if is_c_space(c) {
            has_space = true;
        } else if i > 0 && c == b'"' && not_last {
            quote = Some('\'');
        } else if i > 0 && c == b'\'' && not_last {
            quote = Some('"');
        }
    }
    if s.is_empty() || has_space || quote.is_some() {
        let q = quote.unwrap_or('"');
        out.push(q);
        out.push_str(s);
        out.push(q);
    } else {
        out.push_str(s);
    }
}

/// `atoi` as the generators have always read integers: `strtol`'s digits, clamped to
/// the range of an `int` (C's conversion would keep the low 32 bits instead; no
/// golden reaches the difference).
pub fn atoi(s: &str) -> i64 {
    atol(s).clamp(i64::from(i32::MIN), i64::from(i32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_split_and_quote_like_fgetword() {
        let mut s = Stream::new("  a \"b c\"d 'e'  x\"y z\"\n");
        let words: Vec<_> = std::iter::from_fn(|| s.word(512)).collect();
        assert_eq!(words, ["a", "b cd", "e", "xy z"]);
        let mut s = Stream::new("abcdef");
        assert_eq!(s.word(4).as_deref(), Some("abc"));
        assert_eq!(s.word(4).as_deref(), Some("ef"));
    }

    #[test]
    fn lines_continue_after_backslash() {
        let mut s = Stream::new("!a \\\nb\r\nc");
        assert_eq!(s.line(2048).as_deref(), Some("!a \\\nb"));
        assert_eq!(s.line(2048).as_deref(), Some("c"));
        assert_eq!(s.line(2048), None);
    }

    #[test]
    fn put_word_quotes_when_needed() {
        let mut out = String::new();
        for w in ["plain", "", "my light", "it's", "'x'"] {
            put_word(&mut out, w);
            out.push('|');
        }
        assert_eq!(out, "plain|\"\"|\"my light\"|\"it's\"|'x'|");
    }

    #[test]
    fn atoi_reads_prefixes() {
        assert_eq!(atoi("12abc"), 12);
        assert_eq!(atoi("99999999999"), i64::from(i32::MAX));
        assert_eq!(atoi("-7"), -7);
        assert_eq!(atoi("x"), 0);
    }
}
