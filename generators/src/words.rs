//! Reading and writing words the way Radiance's C library does.
//!
//! `fgetword()` (`src/common/fgetword.c`) splits on C whitespace, honours quotes that
//! may start anywhere in a word, and truncates at a buffer size (dropping the character
//! that overflowed); `fputword()` quotes only when needed; `atof()`/`atoi()` read the
//! longest numeric prefix and give 0 for none. Matching these keeps outputs identical.

/// C's `isspace` in the "C" locale.
pub fn is_c_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | 0x0b | 0x0c | b'\r')
}

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

/// The length of the longest prefix of `s` (after leading whitespace) that `strtod`
/// would read as a decimal number, and its value. Hex floats are read as their `0`.
pub fn strtod_prefix(s: &str) -> Option<(f64, usize)> {
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && is_c_space(b[i]) {
        i += 1;
    }
    let start = i;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let rest = &s[i..];
    for word in ["infinity", "inf", "nan"] {
        if rest.len() >= word.len() && rest[..word.len()].eq_ignore_ascii_case(word) {
            let neg = b.get(start) == Some(&b'-');
            let v = if word == "nan" {
                f64::NAN
            } else {
                f64::INFINITY
            };
            return Some((if neg { -v } else { v }, i + word.len()));
        }
    }
    let digits_from = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    let int_end = digits_from(i);
    let mut end = int_end;
    let mut any = int_end > i;
    if end < b.len() && b[end] == b'.' {
        let frac_end = digits_from(end + 1);
        any |= frac_end > end + 1;
        end = frac_end;
    }
    if !any {
        return None;
    }
    if end < b.len() && (b[end] == b'e' || b[end] == b'E') {
        let mut j = end + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        let exp_end = digits_from(j);
        if exp_end > j {
            end = exp_end;
        }
    }
    let value = s[start..end].parse::<f64>().ok()?;
    Some((value, end))
}

/// C's `atof`: the numeric prefix, or 0.
pub fn atof(s: &str) -> f64 {
    strtod_prefix(s).map_or(0.0, |(v, _)| v)
}

/// C's `atoi`: optional sign and digits after whitespace, or 0; saturates.
pub fn atoi(s: &str) -> i64 {
    let t = s.trim_start_matches(|c: char| c.is_ascii() && is_c_space(c as u8));
    let (neg, digits) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let mut n: i64 = 0;
    for b in digits.bytes().take_while(u8::is_ascii_digit) {
        n = n.saturating_mul(10).saturating_add(i64::from(b - b'0'));
    }
    let n = if neg { -n } else { n };
    n.clamp(i64::from(i32::MIN), i64::from(i32::MAX))
}

/// Radiance's `isint()`: leading whitespace, optional sign, digits, nothing after.
pub fn is_int(s: &str) -> bool {
    skip_int(s.as_bytes(), 0) == Some(s.len())
}

/// Radiance's `isflt()` (`fskip()` reaching the end): `[+-](d+[.d*]|.d+)[(e|E)[+-]d+]`.
pub fn is_flt(s: &str) -> bool {
    skip_flt(s.as_bytes()) == Some(s.len())
}

fn skip_int(b: &[u8], mut i: usize) -> Option<usize> {
    while i < b.len() && is_c_space(b[i]) {
        i += 1;
    }
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    (i > start).then_some(i)
}

fn skip_flt(b: &[u8]) -> Option<usize> {
    let mut s = 0;
    while s < b.len() && is_c_space(b[s]) {
        s += 1;
    }
    if s < b.len() && (b[s] == b'+' || b[s] == b'-') {
        s += 1;
    }
    let mut cp = s;
    while cp < b.len() && b[cp].is_ascii_digit() {
        cp += 1;
    }
    if cp < b.len() && b[cp] == b'.' {
        cp += 1;
        s += 1;
        while cp < b.len() && b[cp].is_ascii_digit() {
            cp += 1;
        }
    }
    if cp == s {
        return None;
    }
    if cp < b.len() && (b[cp] == b'e' || b[cp] == b'E') {
        cp += 1;
        if cp < b.len() && is_c_space(b[cp]) {
            return None;
        }
        return skip_int(b, cp);
    }
    Some(cp)
}

#[cfg(test)]
mod tests {
    #[test]
    fn number_words_follow_radiance() {
        for ok in ["1", "-1.5", "+.5", "5.", "1e3", "1.5E-2"] {
            assert!(is_flt(ok), "{ok}");
        }
        for bad in ["", ".", "e1", "1e", "1.5.2", "inf", "nan", "1 "] {
            assert!(!is_flt(bad), "{bad}");
        }
        assert!(is_int("-3") && !is_int("3.0") && !is_int("+"));
    }

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
    fn atof_and_atoi_read_prefixes() {
        assert_eq!(atof("1.5x"), 1.5);
        assert_eq!(atof("abc"), 0.0);
        assert_eq!(atof(" -2e3"), -2000.0);
        assert_eq!(atof("1e"), 1.0);
        assert_eq!(atof(".5"), 0.5);
        assert_eq!(atoi("12abc"), 12);
        assert_eq!(atoi("-7"), -7);
        assert_eq!(atoi("x"), 0);
    }
}
