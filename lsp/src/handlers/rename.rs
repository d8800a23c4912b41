//! `textDocument/rename` for modifiers and aliases: every word bound to that
//! definition (Radiance's most-recent-earlier-definition rule, so a redefinition's
//! uses are left alone), in its file and, for a file of a `.rif` scene, in the later
//! files of the scene that use it (a material of `basic.mat` renamed in the scenes
//! that use it). A calcomp name in a function argument is renamed in its function
//! file and every scene using it ([`super::cal_rename`]).

use tower_lsp_server::ls_types::{Location, Position, WorkspaceEdit};

use crate::document::{Document, Target};

pub fn rename(doc: &Document<'_>, pos: Position, new_name: &str) -> Option<WorkspaceEdit> {
    let offset = doc.offset(pos);
    let Some((_, target)) = doc.target_at(offset) else {
        return super::cal_rename::scene_rename(doc, offset, new_name);
    };
    // A name is one word: no blanks, no quotes (they would change the word count).
    let valid = !new_name.is_empty()
        && !new_name.contains(|c: char| c.is_whitespace() || c == '"' || c == '\'');
    if !valid || matches!(new_name, "void" | "inherit") {
        return None;
    }
    Some(super::cal_rename::edit(locations(doc, target), new_name))
}

/// Every word naming the definition `target`: its name and uses in its own file,
/// then the uses in the later files of the scene that it is the definition of (no
/// file in between redefines it, and the later file uses it before defining its own).
pub fn locations(doc: &Document<'_>, target: Target<'_>) -> Vec<Location> {
    let scope = radc_lang::db::modifier_scope(doc.db, target.file);
    let located = |file, span| Location {
        uri: doc.uri_of(file),
        range: doc.range_in(file, span),
    };
    let mut out: Vec<Location> = scope
        .uses_of(target.def)
        .into_iter()
        .map(|s| located(target.file, s))
        .collect();
    let files = match doc.scene {
        Some(set) => set.files(doc.db).clone(),
        None => return out,
    };
    let name = &target.def.name;
    if scope.last_modifier(name) != Some(target.def) {
        return out; // redefined later in its own file: later files see the other one
    }
    let later = files.iter().skip_while(|f| **f != target.file).skip(1);
    for &file in later {
        let scope = radc_lang::db::modifier_scope(doc.db, file);
        out.extend(
            scope
                .references
                .iter()
                .filter(|r| r.target.is_none() && r.name == *name)
                .map(|r| located(file, r.span)),
        );
        if scope.last_modifier(name).is_some() {
            break;
        }
    }
    out
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
            let mut lines: Vec<u32> = edits.iter().map(|e| e.range.start.line).collect();
            lines.sort();
            assert_eq!(lines, [0, 4]);
            assert!(rename(doc, Position::new(4, 1), "two words").is_none());
            assert!(rename(doc, Position::new(4, 1), "void").is_none());
        });
    }
}
