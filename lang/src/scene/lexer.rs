//! Scene tokens. Radiance reads scenes as whitespace-separated words (`fgetword`), with
//! `'` or `"` quotes starting a quoted segment anywhere in a word; `#` and `!` are only
//! special at the start of a statement. The lexer cannot know where statements start
//! (that needs the argument counts), so it marks words beginning with `#` or `!` as
//! comment and command candidates and records which tokens begin a line; the parser
//! decides what they are.

use logos::Logos;

#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
#[logos(skip r"[ \t\r\n\x0b\x0c]+")]
enum Raw {
    /// `#` to the end of the line. Radiance skips the rest of the line after a `#` that
    /// starts a statement.
    #[regex(r"#[^\n]*", allow_greedy = true)]
    Comment,
    /// `!` to the end of the line, continued across lines ending in a backslash.
    #[regex(r"!([^\n\\]|\\[^\n]|\\\n)*\\?", allow_greedy = true)]
    Command,
    /// A word: runs of non-space characters and quoted segments (which may hold spaces).
    #[regex(r#"([^ \t\r\n\x0b\x0c"'#!]|"[^"]*"|'[^']*')([^ \t\r\n\x0b\x0c"']|"[^"]*"|'[^']*')*"#)]
    Word,
    /// A word whose last quote is never closed: it runs to the end of the file.
    #[regex(r#"(([^ \t\r\n\x0b\x0c"'#!]|"[^"]*"|'[^']*')([^ \t\r\n\x0b\x0c"']|"[^"]*"|'[^']*')*)?("[^"]*|'[^']*)"#, allow_greedy = true)]
    Unterminated,
}

/// What a token is. `Comment` and `Command` are only candidates: inside a primitive's
/// arguments Radiance reads them as ordinary words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TokenKind {
    Word,
    Comment,
    Command,
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

/// Splits scene text into tokens with byte ranges. Never fails: every byte is either
/// whitespace or part of some token.
pub fn lex(text: &str) -> Vec<(Token<'_>, std::ops::Range<usize>)> {
    let mut out = Vec::new();
    let mut lexer = Raw::lexer(text);
    let mut last_end = 0;
    while let Some(raw) = lexer.next() {
        let range = lexer.span();
        let kind = match raw {
            Ok(Raw::Comment) => TokenKind::Comment,
            Ok(Raw::Command) => TokenKind::Command,
            Ok(Raw::Word) => TokenKind::Word,
            Ok(Raw::Unterminated) => TokenKind::Unterminated,
            // Unreachable with the patterns above (every non-space byte starts a
            // token), but a lone byte is still best treated as a word.
            Err(()) => TokenKind::Word,
        };
        let gap = text.get(last_end..range.start).unwrap_or("");
        let line_start = last_end == 0 || gap.contains('\n');
        last_end = range.end;
        out.push((
            Token {
                kind,
                text: &text[range.clone()],
                line_start,
            },
            range,
        ));
    }
    out
}

/// The value of a word as Radiance reads it: quote characters removed, quoted
/// whitespace kept.
pub fn unquote(word: &str) -> std::borrow::Cow<'_, str> {
    // Radiance keeps words in C strings: a NUL ends the word's value, though the
    // characters after it up to the next space are still consumed.
    let word = word.split('\0').next().unwrap_or("");
    if !word.contains(['"', '\'']) {
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
