//! `textDocument/formatting`: the formatter in `lang` (also `radc fmt`), as one edit
//! replacing the whole text. A file with syntax errors is left alone.

use tower_lsp_server::ls_types::TextEdit;

use crate::document::Document;

pub fn formatting(doc: &Document<'_>) -> Option<Vec<TextEdit>> {
    let formatted = radc_lang::db::format_scene(doc.db, doc.file).as_ref()?;
    if formatted == doc.text() {
        return Some(Vec::new());
    }
    Some(vec![TextEdit {
        range: doc.full_range(),
        new_text: formatted.clone(),
    }])
}
