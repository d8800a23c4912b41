//! `textDocument/definition`: where the modifier or alias under the cursor is
//! defined (the most recent definition above the use, as Radiance binds it).

use tower_lsp_server::ls_types::{GotoDefinitionResponse, Location, Position};

use crate::document::Document;

pub fn definition(doc: &Document<'_>, pos: Position) -> Option<GotoDefinitionResponse> {
    let (_, target) = doc.target_at(doc.offset(pos))?;
    Some(GotoDefinitionResponse::Scalar(Location {
        uri: doc.uri_of(target.file),
        range: doc.range_in(target.file, target.def.name_span),
    }))
}
