//! `textDocument/rename` for calcomp names: a parameter within its function; a
//! variable or function everywhere [`super::cal_references`] finds it (its file and
//! the scenes that use it through their function arguments), in one workspace edit.

use std::collections::HashMap;

use radc_lang::db::{self, CalName};
use tower_lsp_server::ls_types::{Location, Position, TextEdit, Uri, WorkspaceEdit};

use super::cal_references::locations;
use crate::calcomp;
use crate::document::Document;

pub fn rename(doc: &Document<'_>, pos: Position, new_name: &str) -> Option<WorkspaceEdit> {
    if !calcomp::is_name(new_name) {
        return None;
    }
    let index = db::cal_index(doc.db, doc.file);
    let at = index.at(doc.offset(pos))?;
    if let CalName::Global(n) = &at.name
        && index.definition(n).is_none()
    {
        return None; // a library name: not this file's to rename
    }
    let file = calcomp::this_file(doc);
    Some(edit(locations(doc, &file, &at.name, true), new_name))
}

/// From a scene: renames the calcomp name under `offset` in a function argument,
/// in its function file and every scene using it.
pub fn scene_rename(doc: &Document<'_>, offset: usize, new_name: &str) -> Option<WorkspaceEdit> {
    if !calcomp::is_name(new_name) {
        return None;
    }
    let (_, name, files) = calcomp::scene_name_at(doc, offset)?;
    let file = calcomp::defining_file(doc, &files, &name)?;
    Some(edit(
        locations(doc, &file, &CalName::Global(name), true),
        new_name,
    ))
}

pub fn edit(locations: Vec<Location>, new_name: &str) -> WorkspaceEdit {
    let mut changes: HashMap<Uri, Vec<TextEdit>> = HashMap::new();
    for l in locations {
        let edits = changes.entry(l.uri).or_default();
        if !edits.iter().any(|e| e.range == l.range) {
            edits.push(TextEdit {
                range: l.range,
                new_text: new_name.to_string(),
            });
        }
    }
    WorkspaceEdit {
        changes: Some(changes),
        ..WorkspaceEdit::default()
    }
}
