//! `textDocument/definition`: where the modifier or alias under the cursor is
//! defined (the most recent definition above the use, as Radiance binds it, or in an
//! earlier file of a `.rif` scene); on a string that names a file (function file, data,
//! picture, font, octree, mesh), that file, found as the checks find it; on a calcomp
//! name in a function argument, its definition in the primitive's function files.

use radc_lang::db::Db;
use radc_lang::schema::{self, ArgSide, StringKind};
use tower_lsp_server::ls_types::{GotoDefinitionResponse, Location, Position, Range, Uri};

use crate::document::{Document, Part};

pub fn definition(doc: &Document<'_>, pos: Position) -> Option<GotoDefinitionResponse> {
    let offset = doc.offset(pos);
    let location = match doc.target_at(offset) {
        Some((_, target)) => Location {
            uri: doc.uri_of(target.file),
            range: doc.range_in(target.file, target.def.name_span),
        },
        None => match super::cal_definition::scene_definition(doc, offset) {
            Some(location) => location,
            None => file_argument(doc, offset)?,
        },
    };
    Some(GotoDefinitionResponse::Scalar(location))
}

fn file_argument(doc: &Document<'_>, offset: usize) -> Option<Location> {
    let (p, Part::Arg(ArgSide::Strings, i), _) = doc.locate(offset)? else {
        return None;
    };
    let ty = schema::lookup(&p.kind.text)?;
    let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
    let (arg, _) = ty.strings.arg_in(i, &words)?;
    let StringKind::File(kind) = arg.kind else {
        return None;
    };
    let name = words.get(i)?;
    let scene_path = std::path::Path::new(doc.file.path(doc.db));
    let found = doc.db.aux_files().locate(name, kind, scene_path)?;
    let found = found.canonicalize().unwrap_or(found);
    Some(Location {
        uri: Uri::from_file_path(found)?,
        range: Range::default(),
    })
}
