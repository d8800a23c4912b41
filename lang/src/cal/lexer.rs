//! calcomp tokens. Radiance scans calcomp one character at a time (`escan` in
//! calexpr.c); these rules reproduce where its tokens begin and end: whitespace and
//! `{ }` comments end a name or a number, comments nest and may sit between any two
//! tokens, and names may hold letters, digits, `_`, `.` and the back-quote context mark.

use logos::Logos;
use std::fmt;

/// Why a piece of text is not a token.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LexError {
    /// A character calcomp has no use for (`#`, `%`, `&`, ...).
    #[default]
    UnexpectedChar,
    /// `{` without its matching `}`: Radiance stops with "'}' expected".
    UnterminatedComment,
    /// A lone `.`, `.e1`: Radiance's "badly formed number".
    BadNumber,
    /// `1e`, `2.5E+`: Radiance's "missing exponent".
    MissingExponent,
}

impl LexError {
    pub fn message(self) -> &'static str {
        match self {
            LexError::UnexpectedChar => "unexpected character",
            LexError::UnterminatedComment => "comment is not closed: '}' expected",
            LexError::BadNumber => "badly formed number",
            LexError::MissingExponent => "number has an exponent mark but no exponent digits",
        }
    }
}

#[derive(Logos, Clone, Copy, Debug, PartialEq)]
#[logos(error = LexError)]
#[logos(skip r"[ \t\r\n\f\v]+")]
pub enum Token<'a> {
    #[token("{", skip_comment)]
    Comment,

    /// `digits[.digits][(e|E)[+-]digits]`, `.5` and `5.`, read as C's `atof` would.
    #[regex(r"[0-9]+(\.[0-9]*)?([eE][+-]?[0-9]+)?", parse_number)]
    #[regex(r"\.[0-9]+([eE][+-]?[0-9]+)?", parse_number)]
    Number(f64),

    #[regex(r"[0-9]+(\.[0-9]*)?[eE][+-]?", missing_exponent)]
    #[regex(r"\.[0-9]+[eE][+-]?", missing_exponent)]
    #[token(".", bad_number)]
    BadNumber,

    /// A name starts with a letter or a back-quote (calexpr.c `getE5`, `isid`).
    #[regex(r"[A-Za-z`][A-Za-z0-9_.`]*")]
    Name(&'a str),

    /// `$N`: an input column on the right of `=`, an output column on the left.
    /// Radiance reads the digits after `$` with `getinum`, so `$` alone is column 0,
    /// and its scanner skips white space after the `$` (`$ 1` is column 1).
    #[regex(r"\$[ \t\r\n\f\v]*[0-9]*", parse_channel)]
    Channel(u32),

    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("^")]
    Caret,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token(",")]
    Comma,
    #[token(";")]
    Semi,
    #[token("=")]
    Eq,
    #[token(":")]
    Colon,
    /// Stands in for a lexing error so the parser can report it and move on.
    Error,
}

fn missing_exponent<'a>(_: &mut logos::Lexer<'a, Token<'a>>) -> Result<(), LexError> {
    Err(LexError::MissingExponent)
}

fn bad_number<'a>(_: &mut logos::Lexer<'a, Token<'a>>) -> Result<(), LexError> {
    Err(LexError::BadNumber)
}

fn parse_number<'a>(lex: &mut logos::Lexer<'a, Token<'a>>) -> Option<f64> {
    lex.slice().parse::<f64>().ok()
}

/// Channel numbers beyond `u32` saturate; Radiance's `int` would overflow instead,
/// and no input has that many columns.
fn parse_channel<'a>(lex: &mut logos::Lexer<'a, Token<'a>>) -> u32 {
    lex.slice()
        .bytes()
        .filter(u8::is_ascii_digit)
        .fold(0u32, |n, b| {
            n.saturating_mul(10).saturating_add(u32::from(b - b'0'))
        })
}

/// Comments nest (`escan` recurses on `{`), so a regex cannot match them.
fn skip_comment<'a>(lex: &mut logos::Lexer<'a, Token<'a>>) -> logos::FilterResult<(), LexError> {
    let mut depth = 1usize;
    for (i, b) in lex.remainder().bytes().enumerate() {
        match b {
            b'{' => depth += 1,
            b'}' => {
                depth -= 1;
                if depth == 0 {
                    lex.bump(i + 1);
                    return logos::FilterResult::Skip;
                }
            }
            _ => {}
        }
    }
    lex.bump(lex.remainder().len());
    logos::FilterResult::Error(LexError::UnterminatedComment)
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Comment => write!(f, "comment"),
            Token::Number(n) => write!(f, "{n}"),
            Token::BadNumber => write!(f, "bad number"),
            Token::Name(s) => write!(f, "{s}"),
            Token::Channel(n) => write!(f, "${n}"),
            Token::Plus => write!(f, "+"),
            Token::Minus => write!(f, "-"),
            Token::Star => write!(f, "*"),
            Token::Slash => write!(f, "/"),
            Token::Caret => write!(f, "^"),
            Token::LParen => write!(f, "("),
            Token::RParen => write!(f, ")"),
            Token::Comma => write!(f, ","),
            Token::Semi => write!(f, ";"),
            Token::Eq => write!(f, "="),
            Token::Colon => write!(f, ":"),
            Token::Error => write!(f, "invalid text"),
        }
    }
}

/// A token or an error with its byte range.
pub type Spanned<T> = (T, std::ops::Range<usize>);

/// Every token with its byte range; lexing errors become [`Token::Error`] plus an
/// entry in the error list so one bad character does not stop the scan.
pub fn tokenize(text: &str) -> (Vec<Spanned<Token<'_>>>, Vec<Spanned<LexError>>) {
    let mut toks = Vec::new();
    let mut errs = Vec::new();
    for (tok, span) in Token::lexer(text).spanned() {
        match tok {
            Ok(t) => toks.push((t, span)),
            Err(e) => {
                errs.push((e, span.clone()));
                toks.push((Token::Error, span));
            }
        }
    }
    (toks, errs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(s: &str) -> Vec<Token<'_>> {
        tokenize(s).0.into_iter().map(|(t, _)| t).collect()
    }

    #[test]
    fn numbers_in_every_form() {
        assert_eq!(
            kinds("1 2.5 .5 5. 1e3 2.5E-2 3e+1"),
            [1.0, 2.5, 0.5, 5.0, 1000.0, 0.025, 30.0]
                .map(Token::Number)
                .to_vec()
        );
    }

    #[test]
    fn malformed_numbers_are_errors() {
        for s in [".", "1e", "2.5E+", ".5e"] {
            let (_, errs) = tokenize(s);
            assert_eq!(errs.len(), 1, "{s}");
        }
    }

    #[test]
    fn comments_nest_and_end_names() {
        assert_eq!(
            kinds("ab{ x { y } z }cd"),
            vec![Token::Name("ab"), Token::Name("cd")]
        );
        let (_, errs) = tokenize("a { { }");
        assert_eq!(errs[0].0, LexError::UnterminatedComment);
    }

    #[test]
    fn names_and_channels() {
        assert_eq!(
            kinds("A.b_1`ctx `x $12 $"),
            vec![
                Token::Name("A.b_1`ctx"),
                Token::Name("`x"),
                Token::Channel(12),
                Token::Channel(0)
            ]
        );
        assert_eq!(
            kinds("$ 3 $\t4"),
            vec![Token::Channel(3), Token::Channel(4)]
        );
    }
}
