//! The scene parser (chumsky over the logos tokens of `lexer.rs`).
//!
//! Radiance's reader (`readobj.c`) is count-driven: after `modifier type identifier`
//! come three count-prefixed lists (strings, integers, reals), so where one statement
//! ends depends on the counts. The argument lists are therefore context-sensitive
//! parsers: the count word configures how many items the list takes. After an error
//! the parser resynchronises at the next line that looks like a statement start (a
//! comment, a command, or `word type-keyword`), so one file yields all its errors.

use chumsky::error::LabelError;
use chumsky::input::{Input as _, MapExtra, ValueInput};
use chumsky::prelude::*;
use chumsky::util::MaybeRef;

use super::lexer::{Lexer, Token, TokenKind, unquote};
use super::reader::{Outcome, read};
use super::syntax::{Alias, ArgGroup, Command, Item, Primitive, Real, SceneFile, Word};
use crate::diagnostic::{self as codes, Code, Diagnostic};
use crate::schema;
use crate::source::{FileId, Span};
use std::ops::ControlFlow;

/// What went wrong, before it becomes a [`Diagnostic`] (which needs the file id).
#[derive(Clone, Debug, PartialEq)]
pub struct SyntaxError {
    span: SimpleSpan,
    kind: SyntaxErrorKind,
}

#[derive(Clone, Debug, PartialEq)]
enum SyntaxErrorKind {
    /// Something other than what the grammar allows here; `None` is end of input.
    Unexpected { found: Option<String> },
    /// A specific, already-worded problem.
    Custom {
        code: Code,
        message: String,
        hint: Option<String>,
    },
}

impl SyntaxError {
    fn custom(span: SimpleSpan, code: Code, message: String, hint: Option<String>) -> Self {
        SyntaxError {
            span,
            kind: SyntaxErrorKind::Custom {
                code,
                message,
                hint,
            },
        }
    }
}

impl<'src, I, L> LabelError<'src, I, L> for SyntaxError
where
    I: chumsky::input::Input<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    fn expected_found<E: IntoIterator<Item = L>>(
        _expected: E,
        found: Option<MaybeRef<'src, Token<'src>>>,
        span: SimpleSpan,
    ) -> Self {
        SyntaxError {
            span,
            kind: SyntaxErrorKind::Unexpected {
                found: found.map(|t| t.text.to_string()),
            },
        }
    }
}

impl<'src, I> chumsky::error::Error<'src, I> for SyntaxError
where
    I: chumsky::input::Input<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    /// A worded error beats a generic "unexpected" one at the same place.
    fn merge(self, other: Self) -> Self {
        match (&self.kind, &other.kind) {
            (SyntaxErrorKind::Unexpected { .. }, SyntaxErrorKind::Custom { .. }) => other,
            _ => self,
        }
    }
}

type Extra<'src, C = ()> = extra::Full<SyntaxError, (), C>;

/// Parses scene text into a syntax tree plus every syntax diagnostic.
pub fn parse(file: FileId, text: &str) -> (SceneFile, Vec<Diagnostic>) {
    let mut items = Vec::new();
    let diagnostics = parse_each(file, text, &mut |item| items.push(item.clone()));
    (SceneFile { items }, diagnostics)
}

/// Parses scene text one statement at a time, handing each item to `visit` in file
/// order, and returns every syntax diagnostic. Nothing of the syntax tree is kept, so
/// a caller that lowers as it goes reads a scene of any size in little memory.
///
/// The fast reader (`reader.rs`) reads the statements that are clean; a statement it
/// cannot read is read by the recovering parser (which resynchronises at the next
/// line that looks like a statement), then the fast reader goes on. The result is the
/// same as parsing it all with the recovering parser (property-tested).
pub fn parse_each(file: FileId, text: &str, visit: &mut dyn FnMut(&Item)) -> Vec<Diagnostic> {
    let mut diagnostics = Vec::new();
    let _ = read_statements(file, text, 0, &mut |item, diags, _| {
        visit(item);
        diagnostics.append(diags);
        ControlFlow::Continue(())
    });
    diagnostics
}

/// What [`read_statements`] hands each statement to: the item, its diagnostics, and
/// for a recovered statement the byte before which its reading looked.
pub(super) type StatementVisitor<'a> =
    dyn FnMut(&Item, &mut Vec<Diagnostic>, Option<usize>) -> ControlFlow<()> + 'a;

/// Reads statements from byte `start` (a statement boundary), handing each to
/// `visit` with its diagnostics (which `visit` may take) and, for a statement the
/// recovering parser read, the byte before which it looked at the text (see
/// [`recover_statement`]); a statement the fast reader read looked at the byte after
/// it. Stops at the end or when `visit` breaks.
pub(super) fn read_statements(
    file: FileId,
    text: &str,
    mut start: usize,
    visit: &mut StatementVisitor<'_>,
) -> ControlFlow<()> {
    loop {
        match read(file, text, start, &mut |item, diags| {
            visit(item, diags, None)
        }) {
            Outcome::End => return ControlFlow::Continue(()),
            Outcome::Halted => return ControlFlow::Break(()),
            Outcome::Stopped(at) => {
                let Some((item, mut diags, looked_to)) = recover_statement(file, text, at) else {
                    return ControlFlow::Continue(());
                };
                visit(&item, &mut diags, Some(looked_to))?;
                start = item.span().end as usize;
            }
        }
    }
}

/// The recovering parser on the statements from byte `start` (a statement boundary)
/// to the end, with spans in the whole text.
#[cfg(test)]
fn parse_recovering(file: FileId, text: &str, start: usize) -> (Vec<Item>, Vec<Diagnostic>) {
    let tokens: Vec<(Token<'_>, SimpleSpan)> = Lexer::starting_at(text, start)
        .map(|(t, r)| (t, SimpleSpan::from(r)))
        .collect();
    let eoi = SimpleSpan::from(text.len()..text.len());
    let input = tokens.as_slice().map(eoi, |(t, s)| (t, s));
    let (items, errors) = scene_parser().parse(input).into_output_errors();
    let mut items = items.unwrap_or_default();
    for item in &mut items {
        set_file(item, file);
    }
    let diagnostics = errors
        .into_iter()
        .map(|e| to_diagnostic(file, text, e))
        .collect();
    (items, diagnostics)
}

/// The parser builds spans in `FileId(0)`; stamp the real file on them.
fn set_file(item: &mut Item, file: FileId) {
    let fix = |s: &mut Span| s.file = file;
    match item {
        Item::Primitive(p) => {
            fix(&mut p.span);
            fix(&mut p.modifier.span);
            fix(&mut p.kind.span);
            fix(&mut p.name.span);
            fix(&mut p.strings.count_span);
            fix(&mut p.ints.count_span);
            fix(&mut p.reals.count_span);
            p.strings.items.iter_mut().for_each(|w| fix(&mut w.span));
            p.ints.items.iter_mut().for_each(|w| fix(&mut w.span));
            p.reals.items.iter_mut().for_each(|r| fix(&mut r.span));
        }
        Item::Alias(a) => {
            fix(&mut a.span);
            fix(&mut a.keyword);
            fix(&mut a.modifier.span);
            fix(&mut a.name.span);
            fix(&mut a.target.span);
        }
        Item::Command(c) => fix(&mut c.span),
        Item::Comment(s) | Item::Error(s) => fix(s),
    }
}

fn span_of(s: SimpleSpan) -> Span {
    Span::new(FileId(0), s.start..s.end)
}

pub(super) fn to_diagnostic(file: FileId, text: &str, e: SyntaxError) -> Diagnostic {
    let span = Span::new(file, e.span.start..e.span.end);
    match e.kind {
        SyntaxErrorKind::Custom {
            code,
            message,
            hint,
        } => {
            let d = Diagnostic::new(code, span, message);
            match hint {
                Some(h) => d.with_hint(h),
                None => d,
            }
        }
        SyntaxErrorKind::Unexpected { found: None } => {
            let end = text.trim_end().len();
            Diagnostic::new(
                codes::E0102,
                Span::new(file, end..end),
                "the file ends in the middle of a primitive",
            )
            .with_hint(
                "a primitive is `modifier type name`, then a count of string arguments and \
                 the strings, a count of integer arguments (always 0), a count of real \
                 arguments and the reals; check the counts",
            )
        }
        SyntaxErrorKind::Unexpected { found: Some(f) } => {
            Diagnostic::new(codes::E0102, span, format!("unexpected '{f}'"))
        }
    }
}

/// Whether a word is what Radiance reads as an integer count (`isint`: optional
/// sign, digits).
pub(super) fn parse_count(s: &str) -> Option<u32> {
    let digits = s.strip_prefix(['+', '-']).unwrap_or(s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let value: u64 = digits.bytes().fold(0u64, |acc, b| {
        acc.saturating_mul(10).saturating_add(u64::from(b - b'0'))
    });
    if s.starts_with('-') && value != 0 {
        return None;
    }
    Some(u32::try_from(value).unwrap_or(u32::MAX))
}

/// Radiance's real syntax (`isflt`): `[+-](digits[.digits]|.digits)[(e|E)[+-]digits]`,
/// where the digits after a point may be absent (`5.`). No `inf`, `nan` or hex. The
/// definition is [`crate::c_number::real_word`]'s.
pub fn parse_real(s: &str) -> Option<f64> {
    crate::c_number::real_word(s.as_bytes())
}

/// A word in a position where Radiance calls `fgetword`. A `#`/`!` token is only a
/// word here if it holds no whitespace (then Radiance reads exactly the same word);
/// otherwise the author clearly meant a comment or command that Radiance would split
/// into argument words.
fn word<'src, I, C>() -> impl Parser<'src, I, Word, Extra<'src, C>> + Clone
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
    C: 'src,
{
    any().try_map(|t: Token<'src>, span: SimpleSpan| match t.kind {
        TokenKind::Word => Ok(Word {
            text: unquote(t.text).into_owned(),
            span: span_of(span),
        }),
        TokenKind::Comment | TokenKind::Command
            if !t.text.contains(|c: char| c.is_ascii_whitespace()) =>
        {
            Ok(Word {
                text: t.text.to_string(),
                span: span_of(span),
            })
        }
        TokenKind::Comment => Err(SyntaxError::custom(
            span,
            codes::E0107,
            "a '#' comment inside a primitive's arguments".into(),
            Some(
                "Radiance only treats '#' as a comment at the start of a statement; \
                 here it reads each word as an argument. Move the comment to its own \
                 line after the primitive"
                    .into(),
            ),
        )),
        TokenKind::Command => Err(SyntaxError::custom(
            span,
            codes::E0102,
            "a '!' command inside a primitive's arguments".into(),
            Some("commands must start a statement: check the argument counts above".into()),
        )),
        TokenKind::Unterminated => Err(SyntaxError::custom(
            SimpleSpan::from(span.start..span.start + 1),
            codes::E0106,
            "this quote is never closed".into(),
            Some(
                "add the closing quote; Radiance would read the rest of the file as one word"
                    .into(),
            ),
        )),
    })
}

/// A count word (`isint`), then exactly that many items.
fn group<'src, I, T>(
    item: impl Parser<'src, I, T, Extra<'src, CountCtx>> + Clone,
    what: &'static str,
) -> impl Parser<'src, I, ArgGroup<T>, Extra<'src>> + Clone
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
    T: 'src,
{
    let count = word().try_map(move |w: Word, span| {
        parse_count(&w.text)
            .map(|n| CountCtx { n, span: w.span })
            .ok_or_else(|| {
                SyntaxError::custom(
                    span,
                    codes::E0103,
                    format!(
                        "expected the number of {what} arguments, found '{}'",
                        w.text
                    ),
                    Some(format!(
                        "the {what} count must be a whole number >= 0 (Radiance rejects '5.0')"
                    )),
                )
            })
    });
    count
        .then_with_ctx(
            item.repeated()
                .configure(|cfg, c: &CountCtx| cfg.exactly(c.n as usize))
                .collect::<Vec<T>>(),
        )
        .map(|(c, items)| ArgGroup {
            count_span: c.span,
            items,
        })
}

/// The count of an argument list, handed to the list's item parser as context.
#[derive(Clone, Copy, Debug)]
struct CountCtx {
    n: u32,
    span: Span,
}

fn real<'src, I>() -> impl Parser<'src, I, Real, Extra<'src, CountCtx>> + Clone
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    word().try_map_with(
        |w: Word, e: &mut MapExtra<'src, '_, I, Extra<'src, CountCtx>>| {
            let n = e.ctx().n;
            parse_real(&w.text)
                .map(|value| Real {
                    value,
                    span: w.span,
                })
                .ok_or_else(|| {
                    SyntaxError::custom(
                        e.span(),
                        codes::E0104,
                        format!("'{}' is not a number", w.text),
                        Some(format!(
                            "the real-argument count says {n}; reals are written like 1, -0.5, \
                         .5, 5. or 1e-3 (no inf, nan or hex)"
                        )),
                    )
                })
        },
    )
}

#[cfg(test)]
fn scene_parser<'src, I>() -> impl Parser<'src, I, Vec<Item>, Extra<'src>>
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    recovering_statement()
        .repeated()
        .collect()
        .then_ignore(end())
}

/// One statement, or (when it cannot be read) an error item up to the next line that
/// looks like a statement start.
fn recovering_statement<'src, I>() -> impl Parser<'src, I, Item, Extra<'src>> + Clone
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    let comment = any()
        .filter(|t: &Token| t.kind == TokenKind::Comment)
        .map_with(|_, e| Item::Comment(span_of(e.span())));
    let command = any()
        .filter(|t: &Token| t.kind == TokenKind::Command)
        .map_with(|t: Token, e| {
            Item::Command(Command {
                text: command_text(t.text),
                span: span_of(e.span()),
            })
        });

    let alias = word()
        .then(word().filter(|w: &Word| w.text == "alias"))
        .then(word())
        .then(word())
        .map_with(|(((modifier, kw), name), target), e| {
            Item::Alias(Alias {
                modifier,
                keyword: kw.span,
                name,
                target,
                span: span_of(e.span()),
            })
        });

    let primitive = word()
        .then(type_word())
        .then(word())
        .then(group(word(), "string"))
        .then(
            group(word(), "integer").validate(|g: ArgGroup<Word>, _, emitter| {
                if let Some(error) = nonzero_ints(&g) {
                    emitter.emit(error);
                }
                g
            }),
        )
        .then(group(real(), "real"))
        .map_with(|(((((modifier, kind), name), strings), ints), reals), e| {
            Item::Primitive(Primitive {
                modifier,
                kind,
                name,
                strings,
                ints,
                reals,
                span: span_of(e.span()),
            })
        });

    let statement = choice((comment, command, alias, primitive));
    let recovery = any()
        .ignore_then(any().and_is(statement_start().not()).repeated())
        .map_with(|_, e| Item::Error(span_of(e.span())));
    statement.recover_with(via_parser(recovery))
}

/// The statement at byte `start` (a statement boundary) as the recovering parser
/// reads it when it gets there parsing the whole file, its diagnostics, and the byte
/// before which it looked at the text (`usize::MAX`: it looked at the end of the
/// text). `None` at the end of the text.
///
/// The parser is handed a window of tokens, widened until its answer cannot depend on
/// what comes after the window: the statement ends at least three tokens before the
/// window's end (recovery looks two tokens past an error item) and no alternative
/// ran into the window's end (that error would be the furthest, so it would be
/// reported), or the window reaches the end of the text.
pub(super) fn recover_statement(
    file: FileId,
    text: &str,
    start: usize,
) -> Option<(Item, Vec<Diagnostic>, usize)> {
    let mut lexer = Lexer::starting_at(text, start);
    let mut tokens: Vec<(Token<'_>, SimpleSpan)> = Vec::new();
    let mut window = WINDOW;
    loop {
        tokens.extend(
            lexer
                .by_ref()
                .take(window - tokens.len())
                .map(|(t, r)| (t, SimpleSpan::from(r))),
        );
        let whole = tokens.len() < window;
        let first = tokens.first()?;
        let last_end = tokens.last().map_or(first.1.end, |t| t.1.end);
        let eoi = if whole {
            SimpleSpan::from(text.len()..text.len())
        } else {
            SimpleSpan::from(last_end..last_end)
        };
        let input = tokens.as_slice().map(eoi, |(t, s)| (t, s));
        let parser = recovering_statement().then_ignore(any().repeated());
        let (item, errors) = parser.parse(input).into_output_errors();
        if let Some(mut item) = item {
            let end = item.span().end as usize;
            let after = tokens.iter().filter(|t| t.1.start >= end).count();
            let ran_out = errors
                .iter()
                .any(|e| matches!(e.kind, SyntaxErrorKind::Unexpected { found: None }));
            if whole || (after >= 3 && !ran_out) {
                set_file(&mut item, file);
                let diagnostics = errors
                    .into_iter()
                    .map(|e| to_diagnostic(file, text, e))
                    .collect();
                let looked_to = if whole { usize::MAX } else { last_end + 1 };
                return Some((item, diagnostics, looked_to));
            }
        } else if whole {
            return None;
        }
        window *= 2;
    }
}

/// Tokens first handed to [`recover_statement`]'s parser (small in tests, so the
/// widening is exercised).
const WINDOW: usize = if cfg!(test) { 8 } else { 64 };

/// The type keyword of a primitive. An unknown type is reported here but parsing goes
/// on, so its arguments are still read and checked for shape.
fn type_word<'src, I>() -> impl Parser<'src, I, Word, Extra<'src>> + Clone
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    word().validate(|w: Word, e, emitter| {
        if let Some(error) = unknown_type(&w, e.span()) {
            emitter.emit(error);
        }
        w
    })
}

/// E0201 for a type keyword Radiance does not know.
pub(super) fn unknown_type(w: &Word, span: SimpleSpan) -> Option<SyntaxError> {
    if schema::lookup(&w.text).is_some() || w.text == "alias" {
        return None;
    }
    let mut message = format!("unknown primitive type '{}'", w.text);
    let hint = codes::suggest(&w.text, schema::type_names())
        .map(|s| format!("did you mean '{s}'?"))
        .or_else(|| Some("see `radc doc types` for the types Radiance knows".into()));
    if w.text.parse::<f64>().is_ok() {
        message.push_str(
            " (a number where the type should be: check the counts of the primitive before)",
        );
    }
    Some(SyntaxError::custom(span, codes::E0201, message, hint))
}

/// E0105 for integer arguments, which no Radiance primitive takes.
pub(super) fn nonzero_ints(g: &ArgGroup<Word>) -> Option<SyntaxError> {
    if g.items.is_empty() {
        return None;
    }
    Some(SyntaxError::custom(
        SimpleSpan::from(g.count_span.start as usize..g.count_span.end as usize),
        codes::E0105,
        format!(
            "the integer-argument count is {}, but it must be 0",
            g.len()
        ),
        Some("no Radiance primitive takes integer arguments; write 0".into()),
    ))
}

/// Lookahead for recovery: a line that begins a comment, a command, or
/// `word known-type`.
fn statement_start<'src, I>() -> impl Parser<'src, I, (), Extra<'src>> + Clone
where
    I: ValueInput<'src, Token = Token<'src>, Span = SimpleSpan>,
{
    let line_start = any().filter(|t: &Token| t.line_start);
    let special = line_start
        .filter(|t: &Token| matches!(t.kind, TokenKind::Comment | TokenKind::Command))
        .ignored();
    let typed = line_start
        .then(any().filter(|t: &Token| {
            t.kind == TokenKind::Word && (t.text == "alias" || schema::lookup(t.text).is_some())
        }))
        .ignored();
    choice((special, typed)).rewind()
}

/// The command as the shell sees it: without the `!`, backslash-newline joined.
pub(super) fn command_text(raw: &str) -> String {
    raw.strip_prefix('!')
        .unwrap_or(raw)
        .replace("\\\r\n", " ")
        .replace("\\\n", " ")
        .trim()
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse0(text: &str) -> (SceneFile, Vec<Diagnostic>) {
        parse(FileId(0), text)
    }

    fn codes_of(text: &str) -> Vec<&'static str> {
        parse0(text).1.iter().map(|d| d.code.id).collect()
    }

    #[test]
    fn reads_primitives_aliases_comments_and_commands() {
        let text = "# a room\nvoid plastic red\n0\n0\n5 .5 5. 1e-3 -1E+2 +.5\n\
                    red alias red2 red\n!genbox red box 1 2 3\nred sphere 'ball one' 0 0 4 0 0 0 1\n";
        let (scene, diags) = parse0(text);
        assert!(diags.is_empty(), "{diags:?}");
        assert_eq!(scene.items.len(), 5);
        let Item::Primitive(p) = &scene.items[1] else {
            panic!("{:?}", scene.items[1])
        };
        assert_eq!(p.kind.text, "plastic");
        let values: Vec<f64> = p.reals.items.iter().map(|r| r.value).collect();
        assert_eq!(values, vec![0.5, 5.0, 1e-3, -100.0, 0.5]);
        assert!(matches!(&scene.items[2], Item::Alias(a) if a.target.text == "red"));
        assert!(matches!(&scene.items[3], Item::Command(c) if c.text == "genbox red box 1 2 3"));
        let Item::Primitive(s) = &scene.items[4] else {
            panic!()
        };
        assert_eq!(s.name.text, "ball one");
        assert_eq!(&text[s.name.span.range()], "'ball one'");
    }

    #[test]
    fn real_syntax_matches_radiance() {
        for ok in [
            "5.",
            ".5",
            "+.5",
            "1.e5",
            "1e5",
            "-.5E-2",
            "007",
            "1e400",
            "-0",
            "5.14980211588",
            "-2.53678628326e-05",
            "9007199254740993",
            "1e23",
            "0.1",
            "123456789012345678901234567890e-10",
            "1e-400",
        ] {
            let v = parse_real(ok).map(f64::to_bits);
            assert_eq!(v, ok.parse::<f64>().ok().map(f64::to_bits), "{ok}");
        }
        for bad in [
            "nan", "inf", "0x10", "1e", "5.5.5", "1,5", ".", ".e1", "", "-", "e5",
        ] {
            assert!(parse_real(bad).is_none(), "{bad}");
        }
    }

    proptest::proptest! {
        /// The fast path gives exactly the standard library's value.
        #[test]
        fn real_values_match_the_full_conversion(
            s in proptest::string::string_regex("[+-]?[0-9]{0,12}\\.?[0-9]{0,12}([eE][+-]?[0-9]{1,3})?").unwrap()
        ) {
            let fast = parse_real(&s).map(f64::to_bits);
            let full = parse_real(&s).and_then(|_| s.parse::<f64>().ok()).map(f64::to_bits);
            proptest::prop_assert_eq!(fast, full);
        }
    }

    #[test]
    fn count_syntax_matches_radiance() {
        assert_eq!(parse_count("+4"), Some(4));
        assert_eq!(parse_count("04"), Some(4));
        assert_eq!(parse_count("-0"), Some(0));
        assert_eq!(parse_count("4.0"), None);
        assert_eq!(parse_count("-1"), None);
        assert_eq!(parse_count("99999999999999999999"), Some(u32::MAX));
    }

    #[test]
    fn recovers_and_reports_every_error() {
        let text = "void plastic a\n0\n0\n5 1 2 x 4 5\n\
                    void plastic b\n0\n0\n5.0 1 2 3 4 5\n\
                    void plastic c\n0\n0\n5 1 2 3 4 5\n";
        let (scene, diags) = parse0(text);
        let codes: Vec<_> = diags.iter().map(|d| d.code.id).collect();
        assert_eq!(codes, vec!["E0104", "E0103"], "{diags:?}");
        assert!(
            scene.primitives().any(|p| p.name.text == "c"),
            "the good primitive after two bad ones is kept"
        );
    }

    #[test]
    fn structural_errors_have_codes() {
        assert_eq!(codes_of("void plastic a 0 1 x 5 1 2 3 4 5"), vec!["E0105"]);
        assert_eq!(codes_of("void plastic a 0 0 5 1 2"), vec!["E0102"]);
        assert_eq!(codes_of("void plastic a 0 0 999999999 1"), vec!["E0102"]);
        assert_eq!(codes_of("void plastc a 0 0 5 1 2 3 4 5"), vec!["E0201"]);
        assert_eq!(codes_of("void plastic a 1 \"open 0 0 0"), vec!["E0106"]);
        assert_eq!(
            codes_of("void plastic a 0 0 5 1 2 # three\n 4 5"),
            vec!["E0107"]
        );
    }

    #[test]
    fn hash_words_in_arguments_are_words_as_radiance_reads_them() {
        // One word per line: the token is exactly the word Radiance reads. (Several
        // words after a `#` inside arguments are reported as a misplaced comment, the
        // one place radc is stricter than Radiance.)
        let (scene, diags) = parse0("void polygon t 2 #x\n!y\n0 0\n");
        assert!(diags.is_empty(), "{diags:?}");
        let p = scene.primitives().next().unwrap();
        assert_eq!(p.strings.items[0].text, "#x");
        assert_eq!(p.strings.items[1].text, "!y");
    }

    /// Statements that are mostly valid, with the ways they go wrong mixed in.
    fn scene_text() -> impl proptest::strategy::Strategy<Value = String> {
        use proptest::prelude::*;
        let word = prop::sample::select(
            &[
                "void", "m", "alias", "inherit", "plastic", "polygon", "sphere", "plastc", "0",
                "1", "3", "5", "9", "12", "-1", "5.0", ".5", "1e400", "x", "\"a b\"", "'q'",
                "\"open", "#", "# c d", "#x", "!cmd", "!a b", "\\", "\n", "\n", "\n", "x\u{0}y",
                "5\u{0}",
            ][..],
        );
        let statement = prop_oneof![
            4 => (0usize..13).prop_map(|n| {
                let reals: Vec<String> = (0..n).map(|i| format!("{i}.5")).collect();
                format!("m polygon p 0 0 {n} {}\n", reals.join(" "))
            }),
            2 => Just("void plastic m 0 0 5 .5 .5 .5 0 0\n".to_string()),
            1 => Just("m alias n m\n".to_string()),
            1 => Just("# comment\n!genbox m b 1 2 3\n".to_string()),
            1 => Just("void plastc q 0 0 5 1 2 3 4 5\n".to_string()),
            1 => Just("void plastic q 0 2 a b 5 1 2 3 4 5\n".to_string()),
            1 => Just("m 5 q 0 0 1 x\n".to_string()),
            3 => prop::collection::vec(word, 1..8).prop_map(|w| w.join(" ")),
        ];
        prop::collection::vec(statement, 0..10).prop_map(|s| s.join(" "))
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]

        /// The fast reader plus recovery is exactly the recovering parser alone.
        #[test]
        fn fast_reader_agrees_with_the_recovering_parser(text in scene_text()) {
            let (scene, diags) = parse(FileId(3), &text);
            let (items, slow_diags) = parse_recovering(FileId(3), &text, 0);
            proptest::prop_assert_eq!(scene.items, items);
            proptest::prop_assert_eq!(diags, slow_diags);
        }
    }

    #[test]
    fn garbage_never_panics() {
        for text in [
            "",
            "\"",
            "'",
            "#",
            "!",
            "\\",
            "a",
            "a b",
            "a b c",
            "a b c 1",
            "\u{0}\u{0}",
            "void alias",
            "x alias y",
            "void plastic a 0 0 5 1 2 3 4 5 6",
        ] {
            let _ = parse0(text);
        }
    }
}
