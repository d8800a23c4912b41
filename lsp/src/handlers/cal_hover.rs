//! `textDocument/hover` in a calcomp file: on a name, its definition in force (the
//! file's last: a later definition replaces an earlier one), its arity and, for a
//! variable that folds to a constant, its value; on a parameter, which function it
//! belongs to; on a library name (calcomp's, rcalc's, the renderer's, rayinit.cal's),
//! its documentation.

use radc_lang::cal::syntax::DefKind;
use radc_lang::db::{self, CalDef, CalName};
use tower_lsp_server::ls_types::{Hover, HoverContents, MarkupContent, MarkupKind, Position};

use crate::calcomp;
use crate::document::Document;

/// Definitions longer than this are cut in hover text.
const MAX_LINES: usize = 12;

pub fn hover(doc: &Document<'_>, pos: Position) -> Option<Hover> {
    let index = db::cal_index(doc.db, doc.file);
    let at = index.at(doc.offset(pos))?;
    let text = match &at.name {
        CalName::Param { def, index: i } => {
            let d = index.defs.get(*def)?;
            let p = d.params.as_ref()?.get(*i)?;
            format!("**{}** — parameter {} of **{}**", p.name, i + 1, d.name)
        }
        CalName::Global(name) => match index.definition(name) {
            Some(d) => definition(doc, d),
            None => calcomp::library()
                .into_iter()
                .find(|l| l.name == name)
                .map(|l| format!("**{}** — {}", l.name, l.doc))?,
        },
    };
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: text,
        }),
        range: Some(doc.range(at.span)),
    })
}

/// How a definition of the file reads in hover text (also used from scenes).
pub fn definition_text(
    name: &str,
    d: &CalDef,
    source: &str,
    line: u32,
    place: &str,
    value: Option<f64>,
) -> String {
    let what = match &d.params {
        Some(p) => format!(
            "function of {} parameter{}",
            p.len(),
            if p.len() == 1 { "" } else { "s" }
        ),
        None if d.kind == DefKind::Constant => "constant".to_string(),
        None => "variable".to_string(),
    };
    let mut lines: Vec<&str> = source.lines().take(MAX_LINES).collect();
    if source.lines().count() > MAX_LINES {
        lines.push("...");
    }
    let mut text = format!(
        "**{name}** — {what} (`{}`), defined on line {}{place}\n\n```calcomp\n{}\n```",
        d.kind.symbol(),
        line + 1,
        lines.join("\n")
    );
    if let Some(v) = value {
        text.push_str(&format!("\n\nvalue: `{v}`"));
    }
    text
}

fn definition(doc: &Document<'_>, d: &CalDef) -> String {
    let source = doc.text().get(d.span.range()).unwrap_or("");
    let line = doc.position(d.span.start as usize).line;
    let value = db::cal_values(doc.db, doc.file).get(&d.name).copied();
    definition_text(&d.name, d, source, line, "", value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_cal_document;

    fn hover_text(text: &str, line: u32, character: u32) -> Option<String> {
        with_cal_document(text, |doc| {
            hover(doc, Position::new(line, character)).map(|h| match h.contents {
                HoverContents::Markup(m) => m.value,
                _ => String::new(),
            })
        })
    }

    #[test]
    fn names_parameters_and_builtins() {
        let text = "k : 2 * 3;\nf(x) = x * k;\ng = sin(f(k));\n";
        assert_eq!(
            hover_text(text, 1, 11).as_deref(),
            Some(
                "**k** — constant (`:`), defined on line 1\n\n```calcomp\nk : 2 * 3\n```\n\nvalue: `6`"
            )
        );
        assert_eq!(
            hover_text(text, 1, 7).as_deref(),
            Some("**x** — parameter 1 of **f**")
        );
        assert_eq!(
            hover_text(text, 2, 5).as_deref(),
            Some("**sin** — sin(x): sine of x radians (calcomp library)")
        );
        let f = hover_text(text, 2, 8).unwrap_or_default();
        assert!(
            f.starts_with("**f** — function of 1 parameter (`=`), defined on line 2"),
            "{f}"
        );
        assert_eq!(hover_text(text, 0, 9), None);
    }
}
