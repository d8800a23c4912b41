//! `textDocument/semanticTokens/full`: what each word of a document is, from the
//! parse (not from patterns, so counts decide what is an argument). Scenes: modifier
//! references, type keywords, names being defined, numbers, string arguments (file
//! names among them), comments and `!` commands. Calcomp: functions, variables,
//! parameters (library names marked `defaultLibrary`), numbers and operators.

use radc_lang::Span;
use radc_lang::cal::lexer::{Token, tokenize};
use radc_lang::db::{self, CalName};
use radc_lang::scene::syntax::Item;
use tower_lsp_server::ls_types::{
    SemanticToken, SemanticTokenModifier, SemanticTokenType, SemanticTokens, SemanticTokensLegend,
};

use crate::calcomp;
use crate::document::{Document, Kind};

// Indexes into the legend's token types.
const KEYWORD: u32 = 0;
const TYPE: u32 = 1;
const VARIABLE: u32 = 2;
const NUMBER: u32 = 3;
const STRING: u32 = 4;
const COMMENT: u32 = 5;
const MACRO: u32 = 6;
const FUNCTION: u32 = 7;
const PARAMETER: u32 = 8;
const OPERATOR: u32 = 9;
// Bits of the legend's modifiers.
const DECLARATION: u32 = 1;
const LIBRARY: u32 = 2;

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: vec![
            SemanticTokenType::KEYWORD,
            SemanticTokenType::TYPE,
            SemanticTokenType::VARIABLE,
            SemanticTokenType::NUMBER,
            SemanticTokenType::STRING,
            SemanticTokenType::COMMENT,
            SemanticTokenType::MACRO,
            SemanticTokenType::FUNCTION,
            SemanticTokenType::PARAMETER,
            SemanticTokenType::OPERATOR,
        ],
        token_modifiers: vec![
            SemanticTokenModifier::DECLARATION,
            SemanticTokenModifier::DEFAULT_LIBRARY,
        ],
    }
}

pub fn tokens(doc: &Document<'_>) -> SemanticTokens {
    let mut raw = match doc.kind {
        Kind::Cal => cal_tokens(doc),
        _ => scene_tokens(doc),
    };
    raw.sort_by_key(|t| t.0);
    SemanticTokens {
        result_id: None,
        data: encode(doc, &raw),
    }
}

/// (byte range, token type, modifier bits).
type Raw = ((usize, usize), u32, u32);

fn scene_tokens(doc: &Document<'_>) -> Vec<Raw> {
    let mut out = Vec::new();
    let mut push = |s: Span, ty: u32, m: u32| {
        if s.end > s.start {
            out.push(((s.start as usize, s.end as usize), ty, m));
        }
    };
    for item in &doc.parsed().syntax.items {
        match item {
            Item::Primitive(p) => {
                if p.modifier.text != "void" {
                    push(p.modifier.span, TYPE, 0);
                } else {
                    push(p.modifier.span, KEYWORD, 0);
                }
                push(p.kind.span, KEYWORD, 0);
                push(p.name.span, VARIABLE, DECLARATION);
                push(p.strings.count_span, NUMBER, 0);
                p.strings.items.iter().for_each(|w| push(w.span, STRING, 0));
                push(p.ints.count_span, NUMBER, 0);
                p.ints.items.iter().for_each(|w| push(w.span, NUMBER, 0));
                push(p.reals.count_span, NUMBER, 0);
                p.reals.items.iter().for_each(|r| push(r.span, NUMBER, 0));
            }
            Item::Alias(a) => {
                push(a.modifier.span, TYPE, 0);
                push(a.keyword, KEYWORD, 0);
                push(a.name.span, VARIABLE, DECLARATION);
                push(a.target.span, TYPE, 0);
            }
            Item::Command(c) => push(c.span, MACRO, 0),
            Item::Comment(s) => push(*s, COMMENT, 0),
            Item::Error(_) => {}
        }
    }
    out
}

fn cal_tokens(doc: &Document<'_>) -> Vec<Raw> {
    let index = db::cal_index(doc.db, doc.file);
    let library: Vec<&str> = calcomp::library().iter().map(|l| l.name).collect();
    let mut out: Vec<Raw> = index
        .uses
        .iter()
        .map(|u| {
            let range = (u.span.start as usize, u.span.end as usize);
            let declaration = if u.defining { DECLARATION } else { 0 };
            match &u.name {
                CalName::Param { .. } => (range, PARAMETER, declaration),
                CalName::Global(n) => {
                    let defined = index.definition(n);
                    let function = u.call || defined.is_some_and(|d| d.params.is_some());
                    let lib = if defined.is_none() && library.contains(&n.as_str()) {
                        LIBRARY
                    } else {
                        0
                    };
                    let ty = if function { FUNCTION } else { VARIABLE };
                    (range, ty, declaration | lib)
                }
            }
        })
        .collect();
    for (token, range) in tokenize(doc.text()).0 {
        let ty = match token {
            Token::Number(_) | Token::Channel(_) => NUMBER,
            Token::Plus
            | Token::Minus
            | Token::Star
            | Token::Slash
            | Token::Caret
            | Token::Eq
            | Token::Colon => OPERATOR,
            _ => continue,
        };
        out.push(((range.start, range.end), ty, 0));
    }
    out
}

/// The protocol's relative encoding, one token per line (a multi-line command or
/// comment is cut at line ends), lengths in UTF-16 units.
fn encode(doc: &Document<'_>, raw: &[Raw]) -> Vec<SemanticToken> {
    let text = doc.text();
    let mut data = Vec::with_capacity(raw.len());
    let (mut last_line, mut last_start) = (0u32, 0u32);
    for &((start, end), ty, modifiers) in raw {
        let mut piece_start = start;
        while piece_start < end {
            let line_end = text
                .get(piece_start..end)
                .and_then(|s| s.find('\n'))
                .map_or(end, |i| piece_start + i);
            let piece = text.get(piece_start..line_end).unwrap_or("");
            let piece = piece.strip_suffix('\r').unwrap_or(piece);
            let length: u32 = piece.chars().map(|c| c.len_utf16() as u32).sum();
            if length > 0 {
                let pos = doc.position(piece_start);
                let delta_line = pos.line - last_line;
                let delta_start = if delta_line == 0 {
                    pos.character - last_start
                } else {
                    pos.character
                };
                data.push(SemanticToken {
                    delta_line,
                    delta_start,
                    length,
                    token_type: ty,
                    token_modifiers_bitset: modifiers,
                });
                (last_line, last_start) = (pos.line, pos.character);
            }
            piece_start = line_end + 1;
        }
    }
    data
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::{with_cal_document, with_document};

    fn flat(tokens: SemanticTokens) -> Vec<[u32; 5]> {
        tokens
            .data
            .iter()
            .map(|t| {
                [
                    t.delta_line,
                    t.delta_start,
                    t.length,
                    t.token_type,
                    t.token_modifiers_bitset,
                ]
            })
            .collect()
    }

    #[test]
    fn scene_words_by_role() {
        with_document("# c\nvoid plastic red\n0\n0\n2 .5 1\n", |doc| {
            assert_eq!(
                flat(tokens(doc)),
                [
                    [0, 0, 3, COMMENT, 0],
                    [1, 0, 4, KEYWORD, 0],
                    [0, 5, 7, KEYWORD, 0],
                    [0, 8, 3, VARIABLE, DECLARATION],
                    [1, 0, 1, NUMBER, 0],
                    [1, 0, 1, NUMBER, 0],
                    [1, 0, 1, NUMBER, 0],
                    [0, 2, 2, NUMBER, 0],
                    [0, 3, 1, NUMBER, 0],
                ]
            );
        });
    }

    #[test]
    fn calcomp_names_numbers_and_operators() {
        with_cal_document("f(x) = sin(x)*2;\n", |doc| {
            assert_eq!(
                flat(tokens(doc)),
                [
                    [0, 0, 1, FUNCTION, DECLARATION],
                    [0, 2, 1, PARAMETER, DECLARATION],
                    [0, 3, 1, OPERATOR, 0],
                    [0, 2, 3, FUNCTION, LIBRARY],
                    [0, 4, 1, PARAMETER, 0],
                    [0, 2, 1, OPERATOR, 0],
                    [0, 1, 1, NUMBER, 0],
                ]
            );
        });
    }
}
