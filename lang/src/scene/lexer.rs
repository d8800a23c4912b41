//! Scene tokens. Radiance reads scenes as whitespace-separated words (`fgetword`), with
//! `'` or `"` quotes starting a quoted segment anywhere in a word; `#` and `!` are only
//! special at the start of a statement. The lexer cannot know where statements start
//! (that needs the argument counts), so it marks words beginning with `#` or `!` as
//! comment and command candidates and records which tokens begin a line; the parser
//! decides what they are.
//!
//! The token language is four regular expressions (kept in the tests as the
//! specification); the scanner below is a hand-written byte loop because scenes of a
//! few hundred megabytes are common and the lexer is the front end's hot loop.

/// What a token is. `Comment` and `Command` are only candidates: inside a primitive's
/// arguments Radiance reads them as ordinary words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TokenKind {
    /// Runs of non-space characters and quoted segments (which may hold spaces).
    Word,
    /// `#` to the end of the line. Radiance skips the rest of the line after a `#`
    /// that starts a statement.
    Comment,
    /// `!` to the end of the line, continued across lines ending in a backslash.
    Command,
    /// A word whose last quote is never closed: it runs to the end of the file.
    Unterminated,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Token<'src> {
    pub kind: TokenKind,
    /// The raw text, quotes included.
    pub text: &'src str,
    /// Whether the token is the first on its line (statement recovery resynchronises there).
    pub line_start: bool,
}

// The whitespace `fgetword` skips: C `isspace` in the C locale.
use crate::c_number::is_c_space as is_space;

/// Ends an unquoted run inside a word: whitespace or the start of a quoted segment.
static WORD_STOP: [bool; 256] = {
    let mut t = [false; 256];
    let mut b = 0;
    while b < 256 {
        t[b] = is_space(b as u8) || b == b'"' as usize || b == b'\'' as usize;
        b += 1;
    }
    t
};

/// Tokens of scene text, one at a time, with their byte ranges. Never fails: every
/// byte is either whitespace or part of some token.
#[derive(Clone, Debug)]
pub struct Lexer<'src> {
    text: &'src str,
    pos: usize,
}

impl<'src> Lexer<'src> {
    pub fn new(text: &'src str) -> Self {
        Lexer { text, pos: 0 }
    }

    /// Starts at byte `start` of `text` (a token boundary), with ranges still
    /// counted from the start of `text`.
    pub fn starting_at(text: &'src str, start: usize) -> Self {
        Lexer {
            text,
            pos: start.min(text.len()),
        }
    }

    /// Where the next token (or the end) is searched from.
    pub fn position(&self) -> usize {
        self.pos
    }

    /// The end of a `!` command: the end of the line, where a backslash escapes the
    /// next byte (so a backslash-newline continues the command).
    fn command_end(bytes: &[u8], mut i: usize) -> usize {
        while i < bytes.len() {
            match bytes[i] {
                b'\n' => break,
                b'\\' => i = (i + 2).min(bytes.len()),
                _ => i += 1,
            }
        }
        i
    }

    /// The end of a word starting at `i`, or `None` if a quote in it is never closed.
    fn word_end(bytes: &[u8], mut i: usize) -> Option<usize> {
        loop {
            // Ordinary bytes go 8 at a time, up to the first that may end the run.
            while let Some(x) = load8(bytes, i) {
                let candidates = stop_candidates(x);
                if candidates != 0 {
                    i += (candidates.trailing_zeros() / 8) as usize;
                    break;
                }
                i += 8;
            }
            let Some(&b) = bytes.get(i) else {
                return Some(i);
            };
            if !WORD_STOP[b as usize] {
                i += 1;
            } else if b == b'"' || b == b'\'' {
                let close = bytes[i + 1..].iter().position(|&c| c == b)?;
                i += close + 2;
            } else {
                return Some(i);
            }
        }
    }
}

impl<'src> Iterator for Lexer<'src> {
    type Item = (Token<'src>, std::ops::Range<usize>);

    fn next(&mut self) -> Option<Self::Item> {
        let bytes = self.text.as_bytes();
        let gap_start = self.pos;
        let mut start = self.pos;
        let mut line_start = gap_start == 0;
        loop {
            // Generated scenes pad numbers into columns: blanks go 8 at a time.
            while let Some(x) = load8(bytes, start) {
                let other = x ^ (ONES * u64::from(b' '));
                if other != 0 {
                    start += (other.trailing_zeros() / 8) as usize;
                    break;
                }
                start += 8;
            }
            match bytes.get(start) {
                Some(&b) if is_space(b) => {
                    line_start |= b == b'\n';
                    start += 1;
                }
                _ => break,
            }
        }
        if start >= bytes.len() {
            self.pos = bytes.len();
            return None;
        }
        let (kind, end) = match bytes[start] {
            b'#' => (
                TokenKind::Comment,
                memchr_newline(bytes, start).unwrap_or(bytes.len()),
            ),
            b'!' => (TokenKind::Command, Self::command_end(bytes, start + 1)),
            _ => match Self::word_end(bytes, start) {
                Some(end) => (TokenKind::Word, end),
                None => (TokenKind::Unterminated, bytes.len()),
            },
        };
        self.pos = end;
        // Token boundaries are ASCII bytes or the ends of the text, so they are
        // character boundaries and the slice cannot fail.
        let text = self.text.get(start..end).unwrap_or("");
        Some((
            Token {
                kind,
                text,
                line_start,
            },
            start..end,
        ))
    }
}

const ONES: u64 = 0x0101_0101_0101_0101;
const HIGHS: u64 = 0x8080_8080_8080_8080;

/// Eight bytes from `i` as a little-endian word (byte `i` lowest), if there are eight.
fn load8(bytes: &[u8], i: usize) -> Option<u64> {
    let chunk: [u8; 8] = bytes.get(i..i.checked_add(8)?)?.try_into().ok()?;
    Some(u64::from_le_bytes(chunk))
}

/// Flags (high bit) the bytes of `x` that are zero. Borrows can flag a byte above a
/// zero byte too, but never below one, so the lowest flag is exact.
const fn zero_bytes(x: u64) -> u64 {
    x.wrapping_sub(ONES) & !x & HIGHS
}

/// Flags bytes that may end an unquoted run: anything below `!` (whitespace and other
/// control bytes) and quotes. The lowest flag is exact; the caller checks the byte.
const fn stop_candidates(x: u64) -> u64 {
    let below_bang = x.wrapping_sub(ONES * 0x21) & !x & HIGHS;
    below_bang | zero_bytes(x ^ (ONES * 0x22)) | zero_bytes(x ^ (ONES * 0x27))
}

fn memchr_newline(bytes: &[u8], from: usize) -> Option<usize> {
    bytes[from..]
        .iter()
        .position(|&b| b == b'\n')
        .map(|i| from + i)
}

/// Splits scene text into tokens with byte ranges.
pub fn lex(text: &str) -> Vec<(Token<'_>, std::ops::Range<usize>)> {
    Lexer::new(text).collect()
}

/// The value of a word as Radiance reads it: quote characters removed, quoted
/// whitespace kept.
pub fn unquote(word: &str) -> std::borrow::Cow<'_, str> {
    // Radiance keeps words in C strings: a NUL ends the word's value, though the
    // characters after it up to the next space are still consumed.
    // Nearly every word has neither a NUL nor a quote: one pass finds out.
    let Some(special) = word.bytes().position(|b| matches!(b, 0 | b'"' | b'\'')) else {
        return std::borrow::Cow::Borrowed(word);
    };
    let word = match word.as_bytes()[special..].iter().position(|&b| b == 0) {
        // A NUL is ASCII, so cutting there keeps the text valid.
        Some(nul) => word.get(..special + nul).unwrap_or(""),
        None => word,
    };
    if !word.bytes().any(|b| b == b'"' || b == b'\'') {
        return std::borrow::Cow::Borrowed(word);
    }
    let mut out = String::with_capacity(word.len());
    let mut quote: Option<char> = None;
    for c in word.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            None if c == '"' || c == '\'' => quote = Some(c),
            _ => out.push(c),
        }
    }
    std::borrow::Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The token language as regular expressions: the specification the scanner is
    /// checked against. Longest match wins; whitespace between tokens is skipped.
    #[derive(logos::Logos, Clone, Copy, Debug, PartialEq, Eq)]
    #[logos(skip r"[ \t\r\n\x0b\x0c]+")]
    enum Spec {
        #[regex(r"#[^\n]*", allow_greedy = true)]
        Comment,
        #[regex(r"!([^\n\\]|\\[^\n]|\\\n)*\\?", allow_greedy = true)]
        Command,
        #[regex(
            r#"([^ \t\r\n\x0b\x0c"'#!]|"[^"]*"|'[^']*')([^ \t\r\n\x0b\x0c"']|"[^"]*"|'[^']*')*"#
        )]
        Word,
        #[regex(r#"(([^ \t\r\n\x0b\x0c"'#!]|"[^"]*"|'[^']*')([^ \t\r\n\x0b\x0c"']|"[^"]*"|'[^']*')*)?("[^"]*|'[^']*)"#, allow_greedy = true)]
        Unterminated,
    }

    fn spec_tokens(text: &str) -> Vec<(TokenKind, std::ops::Range<usize>)> {
        use logos::Logos as _;
        let mut lexer = Spec::lexer(text);
        let mut out = Vec::new();
        while let Some(t) = lexer.next() {
            let kind = match t {
                Ok(Spec::Comment) => TokenKind::Comment,
                Ok(Spec::Command) => TokenKind::Command,
                Ok(Spec::Word) | Err(()) => TokenKind::Word,
                Ok(Spec::Unterminated) => TokenKind::Unterminated,
            };
            out.push((kind, lexer.span()));
        }
        out
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]

        #[test]
        fn scanner_matches_the_regular_expressions(
            text in proptest::string::string_regex(r#"([a-c1.#!"'\\ \t\r\n\x0b\x0cé]|\\\n|        ){0,60}"#).unwrap()
        ) {
            let scanned: Vec<_> = lex(&text).into_iter().map(|(t, r)| (t.kind, r)).collect();
            proptest::prop_assert_eq!(scanned, spec_tokens(&text));
        }
    }

    fn kinds(text: &str) -> Vec<(TokenKind, &str, bool)> {
        lex(text)
            .into_iter()
            .map(|(t, _)| (t.kind, t.text, t.line_start))
            .collect()
    }

    #[test]
    fn words_comments_and_commands() {
        use TokenKind::*;
        assert_eq!(
            kinds("# it's a comment\nvoid plastic red\n!xform -rz 90 \\\n  a.rad\nx"),
            vec![
                (Comment, "# it's a comment", true),
                (Word, "void", true),
                (Word, "plastic", false),
                (Word, "red", false),
                (Command, "!xform -rz 90 \\\n  a.rad", true),
                (Word, "x", true),
            ]
        );
    }

    #[test]
    fn quotes_keep_spaces_and_may_start_mid_word() {
        let toks = kinds(r#"a"b c"d 'e f' "g"#);
        assert_eq!(toks[0].1, r#"a"b c"d"#);
        assert_eq!(toks[1].1, "'e f'");
        assert_eq!(toks[2], (TokenKind::Unterminated, "\"g", false));
        assert_eq!(unquote(r#"a"b c"d"#), "ab cd");
        assert_eq!(unquote(r#"it"'"s"#), "it's");
        assert_eq!(unquote("ab\0cd"), "ab");
        assert_eq!(unquote("'a\0b'"), "a");
        assert_eq!(unquote("\0"), "");
    }

    proptest::proptest! {
        /// The one-pass fast path cuts at the first NUL exactly as splitting does.
        #[test]
        fn unquote_cuts_at_the_first_nul(word in "[ab\"' \u{0}é]{0,12}") {
            let cut = word.split('\0').next().unwrap_or("");
            proptest::prop_assert_eq!(unquote(&word), unquote(cut));
        }
    }

    #[test]
    fn long_runs_match_the_regular_expressions() {
        for text in [
            "                 0               0.25                  5\n  x",
            "abcdefghijklmnopqrstuvwxyz0123456789 \t\t\t\t\t\t\t\t\t\n\n\n\n\n\n\n\n\nw",
            "aaaaaaaa\u{1}bbbbbbbbb\u{7f}cccccccc'ddddd dddd'eeeeeeee\"ff\"gggggggg é\u{0}hhhhhhhh",
            "xxxxxxx\"yyyyyyyyyyyyyyyy",
            "        #comment        \n        !cmd \\\n        more\n        'open",
        ] {
            let scanned: Vec<_> = lex(text).into_iter().map(|(t, r)| (t.kind, r)).collect();
            assert_eq!(scanned, spec_tokens(text), "{text:?}");
        }
    }

    #[test]
    fn hash_inside_a_word_is_not_a_comment() {
        assert_eq!(kinds("mat#1 x!y")[0].1, "mat#1");
        assert_eq!(kinds("mat#1 x!y")[1].1, "x!y");
    }

    #[test]
    fn every_byte_is_covered() {
        for text in ["\"", "'", "#", "!", "\\", "a\"", "\u{0}", "é\"x\ny"] {
            let toks = lex(text);
            let covered: usize = toks.iter().map(|(_, r)| r.len()).sum();
            let spaces = text.chars().filter(|c| c.is_ascii_whitespace()).count();
            assert!(covered + spaces >= text.trim().len(), "{text:?}");
        }
    }
}
