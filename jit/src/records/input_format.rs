//! rcalc's `-i` record formats (rcalc.c `getrec`, `getfield`): a pattern of literal
//! text, `${name}` numbers and `$(name)` strings matched against the input; where it
//! fails to match, one character is dropped (and, if the attempt began inside a line,
//! the rest of that line) and matching starts again.

use super::format::Field;
use radc_lang::c_number::{is_c_space, strtod};
use std::collections::HashMap;

/// A matched record: number and string variables.
#[derive(Debug, Default, PartialEq)]
pub struct Matched {
    pub numbers: Vec<(String, f64)>,
    pub strings: HashMap<String, String>,
    /// The matched input, for `-P` to pass through when `cond` rejects it.
    pub text: Vec<u8>,
}

pub struct Matcher<'a> {
    fields: Vec<Field>,
    text: &'a [u8],
    /// Start of the unconsumed input (rcalc's `ipb.beg`).
    home: usize,
    blanks_equal: bool,
    presets: &'a HashMap<String, String>,
    /// Input dropped while looking for a match, for `-p`/`-P` to pass through.
    pub skipped: Vec<u8>,
    /// rcalc's `-l`: newlines are blanks like any other.
    ignore_eol: bool,
}

/// rcalc.c `isblnk`: space and tab, or any white space under `-l`.
fn blank(c: u8, ignore_eol: bool) -> bool {
    if ignore_eol {
        is_c_space(c)
    } else {
        c == b' ' || c == b'\t'
    }
}

/// rcalc.c `isnum`: characters that may continue a number.
fn is_num(c: u8) -> bool {
    c.is_ascii_digit() || matches!(c, b'-' | b'.' | b'+' | b'e' | b'E')
}

impl<'a> Matcher<'a> {
    /// `nbsynch`: with blanks equal, leading blanks of a first literal do not count.
    pub fn new(
        mut fields: Vec<Field>,
        text: &'a [u8],
        blanks_equal: bool,
        ignore_eol: bool,
        presets: &'a HashMap<String, String>,
    ) -> Self {
        if blanks_equal && let Some(Field::Literal(l)) = fields.first_mut() {
            let trimmed = l
                .trim_start_matches(|c: char| c.is_ascii() && blank(c as u8, ignore_eol))
                .to_string();
            if trimmed.is_empty() {
                fields.remove(0);
            } else {
                *l = trimmed;
            }
        }
        Matcher {
            fields,
            text,
            home: 0,
            blanks_equal,
            presets,
            skipped: Vec::new(),
            ignore_eol,
        }
    }

    fn is_blank(&self, c: u8) -> bool {
        blank(c, self.ignore_eol)
    }

    fn at(&self, i: usize) -> Option<u8> {
        self.text.get(i).copied()
    }

    /// The next record, or `None` at the end of the input.
    pub fn next_record(&mut self) -> Option<Matched> {
        while self.home < self.text.len() {
            if self.blanks_equal {
                while self.at(self.home).is_some_and(|c| self.is_blank(c)) {
                    self.skip();
                }
                self.at(self.home)?;
            }
            let eatline = !self.ignore_eol && self.at(self.home) != Some(b'\n');
            let mut m = Matched::default();
            if let Some(end) = self.try_match(self.home, &mut m) {
                m.text = self.text[self.home..end].to_vec();
                self.home = end;
                return Some(m);
            }
            self.skip();
            if eatline {
                loop {
                    match self.at(self.home) {
                        None => return None,
                        Some(b'\n') => break,
                        Some(_) => self.skip(),
                    }
                }
                self.skip();
            }
        }
        None
    }

    /// rcalc.c `skipinp`: drop one character (kept for passive mode).
    fn skip(&mut self) {
        if let Some(c) = self.at(self.home) {
            self.skipped.push(c);
        }
        self.home += 1;
    }

    fn try_match(&self, mut pos: usize, m: &mut Matched) -> Option<usize> {
        for (i, f) in self.fields.iter().enumerate() {
            let delim = match self.fields.get(i + 1) {
                Some(Field::Literal(l)) => l.bytes().next(),
                _ => None,
            };
            pos = match f {
                Field::Literal(l) => self.literal(l.as_bytes(), pos)?,
                Field::Number { expr: name, width } => self.number(name, *width, delim, pos, m)?,
                Field::Text { name, width } => self.string(name, *width, delim, pos, m)?,
            };
        }
        Some(pos)
    }

    fn literal(&self, lit: &[u8], mut pos: usize) -> Option<usize> {
        let mut k = 0;
        while k < lit.len() {
            if self.blanks_equal && self.is_blank(lit[k]) {
                if !self.at(pos).is_some_and(|c| self.is_blank(c)) {
                    return None;
                }
                while k < lit.len() && self.is_blank(lit[k]) {
                    k += 1;
                }
                while self.at(pos).is_some_and(|c| self.is_blank(c)) {
                    pos += 1;
                }
            } else if self.at(pos) == Some(lit[k]) {
                k += 1;
                pos += 1;
            } else {
                return None;
            }
        }
        Some(pos)
    }

    /// Whether the character at `pos` continues a field ending at `delim`.
    fn in_word(&self, c: u8, delim: Option<u8>, len: usize, width: usize) -> bool {
        match delim {
            Some(d) if self.blanks_equal => {
                if self.is_blank(d) {
                    !self.is_blank(c)
                } else {
                    c != d
                }
            }
            _ => len < width,
        }
    }

    fn number(
        &self,
        name: &str,
        width: usize,
        delim: Option<u8>,
        mut pos: usize,
        m: &mut Matched,
    ) -> Option<usize> {
        let mut word = Vec::new();
        let mut start = None;
        while word.len() < 127 {
            let Some(c) = self.at(pos) else { break };
            if !((start.is_none() && self.is_blank(c)) || is_num(c))
                || !self.in_word(c, delim, word.len(), width)
            {
                break;
            }
            if start.is_none() && !self.is_blank(c) {
                start = Some(word.len());
            }
            word.push(c);
            pos += 1;
        }
        let d = match start {
            Some(s) => strtod(&word[s..]).value,
            None => 0.0,
        };
        match m.numbers.iter().find(|(n, _)| n == name) {
            None => m.numbers.push((name.to_string(), d)),
            Some(&(_, prev)) => {
                let rel = (prev - d) / if d == 0.0 { 1.0 } else { d };
                if !(-0.001..=0.001).contains(&rel) {
                    return None;
                }
            }
        }
        Some(pos)
    }

    fn string(
        &self,
        name: &str,
        width: usize,
        delim: Option<u8>,
        mut pos: usize,
        m: &mut Matched,
    ) -> Option<usize> {
        let mut word = Vec::new();
        while word.len() < 127 {
            let Some(c) = self.at(pos).filter(|&c| c != b'\n') else {
                break;
            };
            if !self.in_word(c, delim, word.len(), width) {
                break;
            }
            word.push(c);
            pos += 1;
        }
        let got = String::from_utf8_lossy(&word).into_owned();
        let known = m
            .strings
            .get(name)
            .or_else(|| self.presets.get(name))
            .cloned();
        match known {
            Some(v) if v != got => return None,
            Some(_) => {}
            None => {
                m.strings.insert(name.to_string(), got);
            }
        }
        Some(pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::records::format;

    #[test]
    fn numbers_between_literals() {
        let fields = format::parse("x=${a} y=${b}\n", false).unwrap_or_default();
        let presets = HashMap::new();
        let text = b"junk\nx=1.5 y=2\nx=3 y=-4e1\n";
        let mut m = Matcher::new(fields, text, true, false, &presets);
        let r1 = m.next_record().map(|r| r.numbers);
        assert_eq!(r1, Some(vec![("a".into(), 1.5), ("b".into(), 2.0)]));
        let r2 = m.next_record().map(|r| r.numbers);
        assert_eq!(r2, Some(vec![("a".into(), 3.0), ("b".into(), -40.0)]));
        assert_eq!(m.next_record(), None);
    }
}
