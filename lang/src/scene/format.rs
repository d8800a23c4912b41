//! Lays a scene out in Radiance's conventional form, the shape `oconv`-era tools and
//! the reference manual use:
//!
//! ```text
//! modifier type name
//! N str1 str2 ...
//! 0
//! N real1 real2 ...
//! ```
//!
//! Words are copied from the source exactly (quotes and number spellings included:
//! a formatter must never change what a scene means). Argument lists with a repeating
//! group in the schema (polygon vertices) put the count on its own line and one group
//! per indented line. Comments and `!` commands are kept verbatim; runs of blank lines
//! between statements shrink to one. The output formats to itself.

use super::syntax::{ArgGroup, Item, Primitive, SceneFile};
use crate::diagnostic::Diagnostic;
use crate::schema::{self, ArgList};

/// Indentation of continuation lines of a long argument list.
const INDENT: &str = "    ";

/// The formatted text, or `None` if the file has syntax errors: a misread statement
/// could silently move words from one primitive to another.
pub fn format(text: &str, syntax: &SceneFile, diagnostics: &[Diagnostic]) -> Option<String> {
    let has_syntax_errors = diagnostics
        .iter()
        .any(|d| d.is_error() && d.code.id.starts_with("E01"));
    if has_syntax_errors || syntax.items.iter().any(|i| matches!(i, Item::Error(_))) {
        return None;
    }
    let mut out = String::with_capacity(text.len() + text.len() / 8);
    let mut prev_end: Option<usize> = None;
    for item in &syntax.items {
        let span = item.span();
        if let Some(end) = prev_end {
            let gap = text.get(end..span.start as usize).unwrap_or("\n");
            match gap.matches('\n').count() {
                // A comment after a statement on its own last line stays there.
                0 if matches!(item, Item::Comment(_)) => out.push_str("  "),
                0 | 1 => out.push('\n'),
                _ => out.push_str("\n\n"),
            }
        }
        write_item(&mut out, text, item);
        prev_end = Some(span.end as usize);
    }
    if !out.is_empty() {
        out.push('\n');
    }
    Some(out)
}

fn write_item(out: &mut String, text: &str, item: &Item) {
    let src = |s: crate::Span| text.get(s.range()).unwrap_or("").trim_end();
    match item {
        Item::Primitive(p) => write_primitive(out, text, p),
        Item::Alias(a) => {
            let words = [a.modifier.span, a.keyword, a.name.span, a.target.span];
            out.push_str(&join(&words.map(src)));
        }
        Item::Command(c) => {
            // A command ending in a continuation goes on to its next line, blank or
            // not: trimming that away would join what follows to the command.
            let raw = text.get(c.span.range()).unwrap_or("");
            let trimmed = raw.trim_end();
            if trimmed.ends_with('\\') {
                out.push_str(raw.strip_suffix('\n').unwrap_or(raw));
            } else {
                out.push_str(trimmed);
            }
        }
        Item::Comment(s) | Item::Error(s) => out.push_str(src(*s)),
    }
}

fn write_primitive(out: &mut String, text: &str, p: &Primitive) {
    let src = |s: crate::Span| text.get(s.range()).unwrap_or("");
    let layout = schema::lookup(&p.kind.text);
    out.push_str(
        &[p.modifier.span, p.kind.span, p.name.span]
            .map(src)
            .join(" "),
    );
    out.push('\n');
    let strings: Vec<&str> = p.strings.items.iter().map(|w| src(w.span)).collect();
    write_group(
        out,
        src(p.strings.count_span),
        &p.strings,
        &strings,
        layout.map(|t| t.strings),
    );
    out.push('\n');
    let ints: Vec<&str> = p.ints.items.iter().map(|w| src(w.span)).collect();
    write_group(out, src(p.ints.count_span), &p.ints, &ints, None);
    out.push('\n');
    let reals: Vec<&str> = p.reals.items.iter().map(|r| src(r.span)).collect();
    write_group(
        out,
        src(p.reals.count_span),
        &p.reals,
        &reals,
        layout.map(|t| t.reals),
    );
}

/// `N a b c` on one line, or for a repeating layout `N`, then the fixed arguments and
/// each repeated group on indented lines of their own.
fn write_group<T>(
    out: &mut String,
    count: &str,
    group: &ArgGroup<T>,
    words: &[&str],
    layout: Option<ArgList>,
) {
    out.push_str(count);
    let repeat = layout.map_or(0, |l| l.repeat.len());
    let fixed = layout.map_or(0, |l| l.fixed.len());
    if repeat == 0 || group.len() <= fixed + repeat {
        if !words.is_empty() {
            out.push(' ');
            out.push_str(&join(words));
        }
        return;
    }
    let (head, tail) = words.split_at(fixed.min(words.len()));
    let lines = std::iter::once(head)
        .filter(|h| !h.is_empty())
        .chain(tail.chunks(repeat));
    for line in lines {
        out.push('\n');
        out.push_str(INDENT);
        out.push_str(&join(line));
    }
}

/// Words separated by spaces, except that a word starting with `#` or `!` ends its
/// line: Radiance reads it as one argument only when nothing follows it on the line
/// (otherwise it is a comment or a command), so the formatter must never join
/// another word onto it.
fn join(words: &[&str]) -> String {
    let mut out = String::new();
    for (i, w) in words.iter().enumerate() {
        if i > 0 {
            let prev = words[i - 1];
            if prev.starts_with(['#', '!']) {
                out.push('\n');
                out.push_str(INDENT);
            } else {
                out.push(' ');
            }
        }
        out.push_str(w);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;

    fn fmt(text: &str) -> Option<String> {
        let (syntax, diags) = crate::scene::parse(FileId(0), text);
        format(text, &syntax, &diags)
    }

    #[test]
    fn lays_out_primitives_conventionally() {
        let text = "# paint\nvoid   plastic  red 0 0 5 .5 .1 .1\n  0 0 # glossy?\n\n\n\nred polygon \"floor\" 0 0 12 0 0 0 1 0 0 1 1 0 0 1 0\n!genbox red box 1 1 1\n";
        let expected = "# paint\nvoid plastic red\n0\n0\n5 .5 .1 .1 0 0  # glossy?\n\nred polygon \"floor\"\n0\n0\n12\n    0 0 0\n    1 0 0\n    1 1 0\n    0 1 0\n!genbox red box 1 1 1\n";
        assert_eq!(fmt(text).as_deref(), Some(expected));
    }

    #[test]
    fn is_idempotent() {
        for text in [
            "void plastic red 0 0 5 .5 .1 .1 0 0\nred sphere s 0 0 4 0 0 0 1\n",
            "# a\n\n\nvoid plastic red\n0\n0\n5 .5 .1 .1 0 0  # b\nred alias other red\n",
            "void unknowntype x 2 a b 0 3 1 2 3\n",
            "red polygon p 0 0 9 0 0 0 1 0 0 1 1 0\n",
            "",
        ] {
            let once = fmt(text).unwrap_or_else(|| panic!("refused {text:?}"));
            assert_eq!(fmt(&once).as_deref(), Some(once.as_str()), "{text:?}");
        }
    }

    #[test]
    fn refuses_files_with_syntax_errors() {
        assert_eq!(fmt("void plastic red 0 0 5 1 1"), None);
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::scene::lexer::lex;
    use crate::source::FileId;
    use proptest::prelude::*;

    /// Scene-like text: real words, counts, numbers, comments, quotes and line breaks.
    fn scene_text() -> impl Strategy<Value = String> {
        let word = prop_oneof![
            Just("void"),
            Just("plastic"),
            Just("polygon"),
            Just("sphere"),
            Just("antimatter"),
            Just("mixfunc"),
            Just("alias"),
            Just("red"),
            Just("0"),
            Just("1"),
            Just("2"),
            Just("3"),
            Just("4"),
            Just("5"),
            Just("9"),
            Just(".5"),
            Just("-1e2"),
            Just("#"),
            Just("#x"),
            Just("!genbox"),
            Just("\"a b\""),
            Just("\n"),
            Just("\n\n\n"),
            Just("\\\n"),
        ];
        prop::collection::vec(word, 0..60).prop_map(|w| w.join(" "))
    }

    /// Well-formed primitives with random spacing, strings and comments between them.
    fn valid_scene() -> impl Strategy<Value = String> {
        let space = prop_oneof![Just(" "), Just("\n"), Just("  \t"), Just("\n\n\n")];
        let string = prop_oneof![
            Just("a"),
            Just("#x"),
            Just("-t"),
            Just("\"q r\""),
            Just("!y")
        ];
        let real = prop_oneof![Just("0"), Just(".5"), Just("-1e2"), Just("3.")];
        let kind = prop_oneof![
            Just("polygon"),
            Just("plastic"),
            Just("antimatter"),
            Just("texfunc"),
            Just("zz")
        ];
        let primitive = (
            kind,
            prop::collection::vec(string, 0..5),
            prop::collection::vec(real, 0..13),
            prop::collection::vec(space, 8),
            prop::bool::ANY,
        )
            .prop_map(|(kind, strings, reals, ws, comment)| {
                let mut out = format!("m{}{kind}{}n{}{}", ws[0], ws[1], ws[2], strings.len());
                for s in &strings {
                    out.push_str(ws[3]);
                    out.push_str(s);
                }
                out.push_str(&format!("{}0{}{}", ws[4], ws[5], reals.len()));
                for r in &reals {
                    out.push_str(ws[6]);
                    out.push_str(r);
                }
                if comment {
                    out.push_str(" # note");
                }
                out.push_str(ws[7]);
                out
            });
        prop::collection::vec(primitive, 0..6).prop_map(|p| p.concat())
    }

    fn words(text: &str) -> Vec<String> {
        lex(text)
            .into_iter()
            .map(|(t, _)| t.text.trim_end().to_string())
            .collect()
    }

    proptest! {
        #[test]
        fn formatting_keeps_every_word_and_is_idempotent(text in prop_oneof![scene_text(), valid_scene()]) {
            let (syntax, diags) = crate::scene::parse(FileId(0), &text);
            if let Some(once) = format(&text, &syntax, &diags) {
                prop_assert_eq!(words(&once), words(&text));
                let (again_syntax, again_diags) = crate::scene::parse(FileId(0), &once);
                prop_assert_eq!(&again_syntax.items.len(), &syntax.items.len());
                let twice = format(&once, &again_syntax, &again_diags);
                prop_assert_eq!(twice.as_deref(), Some(once.as_str()));
            }
        }
    }
}
