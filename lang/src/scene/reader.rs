//! The scene reader's fast path: Radiance's own count-driven reading (`readobj.c`) as
//! a straight loop over the tokens, one statement at a time, with no backtracking
//! beyond a statement and no allocation once its buffers have grown.
//!
//! It handles statements that are well formed, which are nearly all of them: an
//! unknown type or integer arguments are reported and reading goes on, as the
//! recovering parser does. At the first statement it cannot read it stops and says
//! where that statement begins; the recovering parser (`parser.rs`) takes over from
//! there. Both make the same choices for a clean statement (comment, command,
//! alias, then primitive, as `parser::scene_parser` orders them), so the items and
//! diagnostics are exactly those of the recovering parser run on the whole file: the
//! tests in `parser.rs` check this on random scenes.

use super::lexer::{Lexer, Token, TokenKind, unquote};
use super::parser::{
    SyntaxError, command_text, nonzero_ints, parse_count, parse_real, to_diagnostic, unknown_type,
};
use super::syntax::{Alias, ArgGroup, Command, Item, Primitive, Real, Word};
use crate::diagnostic::Diagnostic;
use crate::schema;
use crate::source::{FileId, Span};
use chumsky::span::SimpleSpan;
use std::ops::ControlFlow;

/// How a run of the reader ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Outcome {
    /// It read every statement to the end of the text.
    End,
    /// The statement it could not read cleanly starts after this byte offset (the
    /// end of the last statement it did read, or where it started).
    Stopped(usize),
    /// The visitor asked it to stop after the statement it was handed.
    Halted,
}

/// Reads statements from byte `start` of `text` (a statement boundary: the start or
/// the end of a statement), handing each to `visit` with its diagnostics (which
/// `visit` may take), until the end, the first statement it cannot read, or `visit`
/// breaks.
pub(super) fn read(
    file: FileId,
    text: &str,
    start: usize,
    visit: &mut dyn FnMut(&Item, &mut Vec<Diagnostic>) -> ControlFlow<()>,
) -> Outcome {
    let mut diags = Vec::new();
    let mut reader = Reader {
        file,
        lexer: Lexer::starting_at(text, start),
        last_type: None,
        errors: Vec::new(),
    };
    let mut prim = Some(empty_primitive(file));
    loop {
        let resume = reader.lexer.position();
        let statement_lexer = reader.lexer.clone();
        let Some((first, range)) = reader.lexer.next() else {
            return Outcome::End;
        };
        let span = Span::new(file, range.clone());
        diags.clear();
        let flow = match first.kind {
            TokenKind::Comment => visit(&Item::Comment(span), &mut diags),
            TokenKind::Command => visit(
                &Item::Command(Command {
                    text: command_text(first.text),
                    span,
                }),
                &mut diags,
            ),
            TokenKind::Word | TokenKind::Unterminated => {
                reader.lexer = statement_lexer.clone();
                if let Some(alias) = reader.alias() {
                    visit(&Item::Alias(alias), &mut diags)
                } else {
                    reader.lexer = statement_lexer;
                    let mut p = prim.take().unwrap_or_else(|| empty_primitive(file));
                    reader.errors.clear();
                    if reader.primitive(&mut p).is_none() {
                        return Outcome::Stopped(resume);
                    }
                    diags.extend(
                        reader
                            .errors
                            .drain(..)
                            .map(|e| to_diagnostic(file, text, e)),
                    );
                    let item = Item::Primitive(p);
                    let flow = visit(&item, &mut diags);
                    if let Item::Primitive(p) = item {
                        prim = Some(p);
                    }
                    flow
                }
            }
        };
        if flow.is_break() {
            return Outcome::Halted;
        }
    }
}

struct Reader<'src> {
    file: FileId,
    lexer: Lexer<'src>,
    /// The last type keyword looked up: scenes repeat one type for long runs.
    last_type: Option<&'static str>,
    /// Problems in the current statement that do not stop it being read.
    errors: Vec<SyntaxError>,
}

impl<'src> Reader<'src> {
    fn token(&mut self) -> Option<(Token<'src>, Span)> {
        let (t, r) = self.lexer.next()?;
        Some((t, Span::new(self.file, r)))
    }

    /// A word where Radiance calls `fgetword`, as `parser::word` accepts it, written
    /// into `out` (reusing its buffer).
    fn word_into(&mut self, out: &mut Word) -> Option<()> {
        let (t, span) = self.token()?;
        out.text.clear();
        match t.kind {
            TokenKind::Word => out.text.push_str(&unquote(t.text)),
            TokenKind::Comment | TokenKind::Command
                if !t.text.contains(|c: char| c.is_ascii_whitespace()) =>
            {
                out.text.push_str(t.text)
            }
            _ => return None,
        }
        out.span = span;
        Some(())
    }

    fn word(&mut self) -> Option<Word> {
        let mut w = Word {
            text: String::new(),
            span: Span::default(),
        };
        self.word_into(&mut w)?;
        Some(w)
    }

    /// `modifier alias name target`.
    fn alias(&mut self) -> Option<Alias> {
        let modifier = self.word()?;
        let keyword = self.word()?;
        if keyword.text != "alias" {
            return None;
        }
        let name = self.word()?;
        let target = self.word()?;
        let span = modifier.span.to(target.span);
        Some(Alias {
            modifier,
            keyword: keyword.span,
            name,
            target,
            span,
        })
    }

    /// `modifier type name` and the three argument lists, into `p`'s buffers.
    fn primitive(&mut self, p: &mut Primitive) -> Option<()> {
        self.word_into(&mut p.modifier)?;
        self.word_into(&mut p.kind)?;
        if !self.is_known_type(&p.kind.text) {
            let span = SimpleSpan::from(p.kind.span.range());
            self.errors.extend(unknown_type(&p.kind, span));
        }
        self.word_into(&mut p.name)?;
        self.words_into(&mut p.strings)?;
        self.words_into(&mut p.ints)?;
        self.errors.extend(nonzero_ints(&p.ints));
        let n = self.count(&mut p.reals.count_span)?;
        p.reals.items.clear();
        let mut end = p.reals.count_span;
        for _ in 0..n {
            let (t, span) = self.token()?;
            if t.kind != TokenKind::Word {
                return None;
            }
            // A number holds no quotes, so the raw text is tried first: unquoting
            // only matters for the odd `"1.5"`.
            let value = parse_real(t.text).or_else(|| parse_real(&unquote(t.text)))?;
            p.reals.items.push(Real { value, span });
            end = span;
        }
        p.span = p.modifier.span.to(end);
        Some(())
    }

    /// A count and that many words, into `group`'s buffers.
    fn words_into(&mut self, group: &mut ArgGroup<Word>) -> Option<()> {
        let n = self.count(&mut group.count_span)?;
        let mut kept = 0;
        for _ in 0..n {
            if kept == group.items.len() {
                group.items.push(Word {
                    text: String::new(),
                    span: Span::default(),
                });
            }
            self.word_into(&mut group.items[kept])?;
            kept += 1;
        }
        group.items.truncate(kept);
        Some(())
    }

    /// A count word, as `parser::group` reads it.
    fn count(&mut self, span: &mut Span) -> Option<u32> {
        let (t, s) = self.token()?;
        *span = s;
        match t.kind {
            TokenKind::Word => parse_count(t.text).or_else(|| parse_count(&unquote(t.text))),
            TokenKind::Comment | TokenKind::Command => None,
            TokenKind::Unterminated => None,
        }
    }

    fn is_known_type(&mut self, name: &str) -> bool {
        if self.last_type == Some(name) {
            return true;
        }
        match schema::lookup(name) {
            Some(t) => {
                self.last_type = Some(t.name);
                true
            }
            None => false,
        }
    }
}

fn empty_primitive(file: FileId) -> Primitive {
    let word = || Word {
        text: String::new(),
        span: Span::new(file, 0..0),
    };
    let group = || ArgGroup {
        count_span: Span::new(file, 0..0),
        items: Vec::new(),
    };
    Primitive {
        modifier: word(),
        kind: word(),
        name: word(),
        strings: group(),
        ints: group(),
        reals: ArgGroup {
            count_span: Span::new(file, 0..0),
            items: Vec::new(),
        },
        span: Span::new(file, 0..0),
    }
}
