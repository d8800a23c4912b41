//! `textDocument/definition` in a calcomp file: a parameter's declaration, or the
//! definition in force of a variable or function (the file's last one). From a scene,
//! a name in a function argument goes to its definition in the primitive's function
//! files (see [`scene_definition`]).

use radc_lang::db;
use tower_lsp_server::ls_types::{GotoDefinitionResponse, Location, Position};

use crate::calcomp;
use crate::document::Document;

pub fn definition(doc: &Document<'_>, pos: Position) -> Option<GotoDefinitionResponse> {
    let index = db::cal_index(doc.db, doc.file);
    let at = index.at(doc.offset(pos))?;
    let span = index.declaration(&at.name)?;
    Some(GotoDefinitionResponse::Scalar(Location {
        uri: doc.uri.clone(),
        range: doc.range(span),
    }))
}

/// The definition of the calcomp name under `offset` in a scene document: in the
/// last of its primitive's function files that defines it, as the renderer loads
/// them in order.
pub fn scene_definition(doc: &Document<'_>, offset: usize) -> Option<Location> {
    let (_, name, files) = calcomp::scene_name_at(doc, offset)?;
    let file = calcomp::defining_file(doc, &files, &name)?;
    let def = file.index.definition(&name)?;
    Some(file.location(def.name_span))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_cal_document;

    #[test]
    fn goes_to_the_last_definition_and_to_parameters() {
        let text = "a = 1;\nf(x) = x + a;\na = 2;\n";
        with_cal_document(text, |doc| {
            let target = |line, character| match definition(doc, Position::new(line, character)) {
                Some(GotoDefinitionResponse::Scalar(l)) => {
                    Some((l.range.start.line, l.range.start.character))
                }
                _ => None,
            };
            assert_eq!(target(1, 11), Some((2, 0)));
            assert_eq!(target(1, 7), Some((1, 2)));
            assert_eq!(target(1, 9), None);
        });
    }
}
