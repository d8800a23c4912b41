//! `textDocument/references`: every word that names the definition under the cursor
//! (uses after a redefinition belong to the new definition, not this one).

use tower_lsp_server::ls_types::{Location, Position};

use crate::document::Document;

pub fn references(
    doc: &Document<'_>,
    pos: Position,
    include_declaration: bool,
) -> Option<Vec<Location>> {
    let scope = doc.scope();
    let def = scope.definition_at(doc.offset(pos))?;
    let spans = scope.uses_of(def);
    let skip = usize::from(!include_declaration);
    let locations = spans.into_iter().skip(skip).map(|s| Location {
        uri: doc.uri.clone(),
        range: doc.range(s),
    });
    Some(locations.collect())
}
