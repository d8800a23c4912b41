//! `textDocument/completion` in a calcomp file: the parameters of the function being
//! defined at the cursor, the file's definitions, then the library (calcomp's, rcalc's,
//! the renderer's and rayinit.cal's names), each with its documentation.

use radc_lang::cal::syntax::DefKind;
use radc_lang::db;
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, Position, Range,
    TextEdit,
};

use crate::calcomp;
use crate::document::Document;

pub fn completion(doc: &Document<'_>, pos: Position) -> Option<Vec<CompletionItem>> {
    let offset = doc.offset(pos);
    let text = doc.text();
    let before = text.get(..offset)?;
    let start = before
        .rfind(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '`')))
        .map_or(0, |i| i + 1);
    if before[start..].starts_with(|c: char| c.is_ascii_digit()) {
        return None; // inside a number
    }
    let replace = Range {
        start: doc.position(start),
        end: pos,
    };
    let item = |label: String, kind, detail: String, doc: Option<String>| CompletionItem {
        label: label.clone(),
        kind: Some(kind),
        detail: Some(detail),
        documentation: doc.map(Documentation::String),
        text_edit: Some(CompletionTextEdit::Edit(TextEdit {
            range: replace,
            new_text: label,
        })),
        ..CompletionItem::default()
    };
    let index = db::cal_index(doc.db, doc.file);
    let mut items = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let enclosing = index
        .defs
        .iter()
        .find(|d| d.span.start as usize <= offset && offset <= d.span.end as usize);
    if let Some(d) = enclosing {
        for p in d.params.iter().flatten() {
            if seen.insert(p.name.clone()) {
                let detail = format!("parameter of {}", d.name);
                items.push(item(
                    p.name.clone(),
                    CompletionItemKind::VARIABLE,
                    detail,
                    None,
                ));
            }
        }
    }
    for d in index.defs.iter().rev() {
        if !seen.insert(d.name.clone()) {
            continue;
        }
        let (kind, detail) = match (&d.params, d.kind) {
            (Some(p), _) => (
                CompletionItemKind::FUNCTION,
                format!("{}({})", d.name, names(p)),
            ),
            (None, DefKind::Constant) => (CompletionItemKind::CONSTANT, format!("{} :", d.name)),
            (None, DefKind::Assign) => (CompletionItemKind::VARIABLE, format!("{} =", d.name)),
        };
        let source = text.get(d.span.range()).map(str::to_string);
        items.push(item(d.name.clone(), kind, detail, source));
    }
    for l in calcomp::library() {
        if !seen.insert(l.name.to_string()) {
            continue;
        }
        let kind = match l.arity {
            Some(_) => CompletionItemKind::FUNCTION,
            None => CompletionItemKind::VARIABLE,
        };
        items.push(item(
            l.name.to_string(),
            kind,
            "library".into(),
            Some(l.doc),
        ));
    }
    Some(items)
}

fn names(params: &[radc_lang::cal::syntax::Ident]) -> String {
    params
        .iter()
        .map(|p| p.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_cal_document;

    #[test]
    fn parameters_then_definitions_then_the_library() {
        let text = "k : 2;\nf(x, y) = x + ";
        with_cal_document(text, |doc| {
            let items = completion(doc, Position::new(1, 14)).unwrap_or_default();
            let labels: Vec<&str> = items.iter().take(4).map(|i| i.label.as_str()).collect();
            // The unfinished statement is not a definition yet: no parameters.
            assert_eq!(labels, ["k", "acos", "asin", "atan"]);
            assert!(items.iter().any(|i| i.label == "Dx"));
            assert!(items.iter().any(|i| i.label == "noise3"));
        });
        with_cal_document("f(x, y) = x + k;\nk : 2;\n", |doc| {
            let items = completion(doc, Position::new(0, 14)).unwrap_or_default();
            let labels: Vec<&str> = items.iter().take(4).map(|i| i.label.as_str()).collect();
            assert_eq!(labels, ["x", "y", "k", "f"]);
            assert_eq!(items[3].detail.as_deref(), Some("f(x, y)"));
        });
    }
}
