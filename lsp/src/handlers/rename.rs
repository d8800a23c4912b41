//! `textDocument/rename` for modifiers and aliases defined in the document: every word
//! bound to that definition (Radiance's most-recent-earlier-definition rule, so a
//! redefinition's uses are left alone).

use std::collections::HashMap;

use tower_lsp_server::ls_types::{Position, TextEdit, WorkspaceEdit};

use crate::document::Document;

pub fn rename(doc: &Document<'_>, pos: Position, new_name: &str) -> Option<WorkspaceEdit> {
    // A name is one word: no blanks, no quotes (they would change the word count).
    let valid = !new_name.is_empty()
        && !new_name.contains(|c: char| c.is_whitespace() || c == '"' || c == '\'');
    if !valid || matches!(new_name, "void" | "inherit") {
        return None;
    }
    let scope = doc.scope();
    let def = scope.definition_at(doc.offset(pos))?;
    let edits = scope
        .uses_of(def)
        .into_iter()
        .map(|span| TextEdit {
            range: doc.range(span),
            new_text: new_name.to_string(),
        })
        .collect();
    Some(WorkspaceEdit {
        changes: Some(HashMap::from([(doc.uri.clone(), edits)])),
        ..WorkspaceEdit::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_document;

    const TEXT: &str = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\nred sphere a\n0\n0\n4 0 0 0 1\n\
                        void plastic red\n0\n0\n5 .1 .1 .5 0 0\nred sphere b\n0\n0\n4 0 0 3 1\n";

    #[test]
    fn renames_the_first_red_and_its_use_only() {
        with_document(TEXT, |doc| {
            let edit = rename(doc, Position::new(4, 1), "paint").and_then(|e| e.changes);
            let edits = edit.and_then(|mut c| c.remove(doc.uri)).unwrap_or_default();
            let lines: Vec<u32> = edits.iter().map(|e| e.range.start.line).collect();
            assert_eq!(lines, [0, 4]);
            assert!(rename(doc, Position::new(4, 1), "two words").is_none());
            assert!(rename(doc, Position::new(4, 1), "void").is_none());
        });
    }
}
