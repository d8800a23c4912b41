//! `textDocument/completion`: primitive types (with a snippet of their argument
//! layout) where a type keyword goes, and the modifiers in scope where a modifier
//! goes. Where a word goes is read from the line: a statement is
//! `modifier type name` at the start of a line, outside any primitive's arguments.

use radc_lang::scene::scope::Definition;
use radc_lang::schema::{self, ArgSide, PRIMITIVE_TYPES, PrimitiveType, StringKind};
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, InsertTextFormat,
    MarkupContent, MarkupKind, Position, Range, TextEdit,
};

use crate::document::{Document, Part};

#[derive(Debug, PartialEq)]
enum Slot {
    Modifier,
    Type,
}

pub fn completion(doc: &Document<'_>, pos: Position) -> Option<Vec<CompletionItem>> {
    let offset = doc.offset(pos);
    let text = doc.text();
    let word_start = text
        .get(..offset)?
        .rfind(char::is_whitespace)
        .map_or(0, |i| i + 1);
    let replace = Range {
        start: doc.position(word_start),
        end: pos,
    };
    let items = match slot(doc, word_start)? {
        Slot::Type => PRIMITIVE_TYPES
            .iter()
            .map(|t| type_item(t, replace))
            .collect(),
        Slot::Modifier => modifiers(doc, word_start, replace),
    };
    Some(items)
}

/// Which word of a statement the word starting at `word_start` would be, if the
/// line holds the start of a statement.
fn slot(doc: &Document<'_>, word_start: usize) -> Option<Slot> {
    if let Some((p, Part::Arg(ArgSide::Strings, i), _)) = doc.locate(word_start) {
        // Mixtures, antimatter, illum's alternate material: strings naming modifiers.
        let ty = schema::lookup(&p.kind.text)?;
        let kind = ty.strings.arg_at(i).map(|(a, _)| a.kind);
        return (kind == Some(StringKind::Modifier)).then_some(Slot::Modifier);
    }
    let text = doc.text();
    let line_start = text.get(..word_start)?.rfind('\n').map_or(0, |i| i + 1);
    let inside_earlier_item = doc.parsed().syntax.items.iter().any(|item| {
        let s = item.span();
        (s.start as usize) < line_start && line_start < s.end as usize
    });
    if inside_earlier_item {
        return None;
    }
    let before = text.get(line_start..word_start)?;
    if before.trim_start().starts_with(['#', '!']) {
        return None;
    }
    match before.split_whitespace().count() {
        0 => Some(Slot::Modifier),
        1 => Some(Slot::Type),
        _ => None,
    }
}

fn type_item(t: &PrimitiveType, replace: Range) -> CompletionItem {
    // The modifier is already written: the snippet starts at the type keyword.
    let snippet = schema::snippet(t);
    let snippet = snippet
        .strip_prefix("${1:mod} ")
        .unwrap_or(&snippet)
        .to_string();
    CompletionItem {
        label: t.name.to_string(),
        kind: Some(CompletionItemKind::KEYWORD),
        detail: Some(format!("{} — {}", t.category.as_str(), t.summary)),
        documentation: Some(Documentation::MarkupContent(MarkupContent {
            kind: MarkupKind::Markdown,
            value: schema::hover(t),
        })),
        insert_text_format: Some(InsertTextFormat::SNIPPET),
        text_edit: Some(CompletionTextEdit::Edit(TextEdit {
            range: replace,
            new_text: snippet,
        })),
        ..CompletionItem::default()
    }
}

fn modifiers(doc: &Document<'_>, word_start: usize, replace: Range) -> Vec<CompletionItem> {
    let local = doc.scope().visible_at(word_start);
    // Modifiers of the earlier files of a `.rif` scene, unless redefined here.
    let mut earlier: Vec<&Definition> = Vec::new();
    for file in doc.earlier_files() {
        let scope = radc_lang::db::modifier_scope(doc.db, file);
        for d in scope.visible_at(usize::MAX) {
            earlier.retain(|e| e.name != d.name);
            earlier.push(d);
        }
    }
    earlier.retain(|e| local.iter().all(|l| l.name != e.name));
    let named = earlier.into_iter().chain(local).map(|d| {
        let category = schema::lookup(&d.type_name).map_or("unknown type", |t| t.category.as_str());
        (d.name.clone(), format!("{} ({category})", d.type_name))
    });
    let void = ("void".to_string(), "no modifier".to_string());
    std::iter::once(void)
        .chain(named)
        .map(|(name, detail)| CompletionItem {
            label: name.clone(),
            kind: Some(CompletionItemKind::VARIABLE),
            detail: Some(detail),
            text_edit: Some(CompletionTextEdit::Edit(TextEdit {
                range: replace,
                new_text: name,
            })),
            ..CompletionItem::default()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_document;

    fn labels(text: &str, line: u32, character: u32) -> Option<Vec<String>> {
        with_document(text, |doc| {
            let items = completion(doc, Position::new(line, character))?;
            Some(items.into_iter().map(|i| i.label).collect())
        })
    }

    const MATERIALS: &str =
        "void plastic a\n0\n0\n5 1 1 1 0 0\n\nvoid plastic b\n0\n0\n5 1 1 1 0 0\n";

    #[test]
    fn modifiers_defined_above_the_cursor() {
        let text = format!("{MATERIALS}\n");
        assert_eq!(
            labels(&text, 9, 0),
            Some(vec!["void".into(), "a".into(), "b".into()])
        );
        // Between the two definitions only the first is visible.
        assert_eq!(
            labels(MATERIALS, 4, 0),
            Some(vec!["void".into(), "a".into()])
        );
    }

    #[test]
    fn types_after_a_modifier_and_nothing_inside_arguments() {
        let text = format!("{MATERIALS}\nb pl");
        let types = labels(&text, 10, 4).unwrap_or_default();
        assert_eq!(types.len(), PRIMITIVE_TYPES.len());
        assert_eq!(labels(&text, 3, 2), None, "inside a real argument list");
        assert_eq!(labels("# comment ", 0, 10), None);
    }

    #[test]
    fn modifiers_in_string_arguments_that_name_modifiers() {
        let text = format!("{MATERIALS}\nvoid mixfunc mix\n4 a b f .\n0\n0\n");
        // On `b`, the background modifier.
        assert_eq!(
            labels(&text, 11, 5),
            Some(vec!["void".into(), "a".into(), "b".into()])
        );
    }
}
