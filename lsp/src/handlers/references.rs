//! `textDocument/references`: every word that names the definition under the cursor
//! (uses after a redefinition belong to the new definition, not this one). For a
//! modifier defined in an earlier file of a `.rif` scene: that definition and the
//! uses in this file.

use tower_lsp_server::ls_types::{Location, Position};

use crate::document::Document;

pub fn references(
    doc: &Document<'_>,
    pos: Position,
    include_declaration: bool,
) -> Option<Vec<Location>> {
    let scope = doc.scope();
    let (_, target) = doc.target_at(doc.offset(pos))?;
    let here = |span| Location {
        uri: doc.uri.clone(),
        range: doc.range(span),
    };
    if target.file == doc.file {
        let spans = scope.uses_of(target.def);
        let skip = usize::from(!include_declaration);
        return Some(spans.into_iter().skip(skip).map(here).collect());
    }
    // Its uses here are the references this file does not resolve itself.
    let declaration = include_declaration.then(|| Location {
        uri: doc.uri_of(target.file),
        range: doc.range_in(target.file, target.def.name_span),
    });
    let uses = scope
        .references
        .iter()
        .filter(|r| r.target.is_none() && r.name == target.def.name)
        .map(|r| here(r.span));
    Some(declaration.into_iter().chain(uses).collect())
}
