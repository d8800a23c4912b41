//! `textDocument/references`: every word that names the definition under the cursor
//! (uses after a redefinition belong to the new definition, not this one). For a
//! modifier defined in an earlier file of a `.rif` scene: that definition and the
//! uses in this file (and, with [`super::rename`], in the later files of the scene).
//! A calcomp name in a function argument: see [`super::cal_references`].

use tower_lsp_server::ls_types::{Location, Position};

use crate::document::Document;

pub fn references(
    doc: &Document<'_>,
    pos: Position,
    include_declaration: bool,
) -> Option<Vec<Location>> {
    let offset = doc.offset(pos);
    let Some((_, target)) = doc.target_at(offset) else {
        return super::cal_references::scene_references(doc, offset, include_declaration);
    };
    // The definition's own name comes first.
    let skip = usize::from(!include_declaration);
    Some(
        super::rename::locations(doc, target)
            .into_iter()
            .skip(skip)
            .collect(),
    )
}
