//! `textDocument/references` for calcomp names: a parameter's uses in its function;
//! a variable's or function's definitions and uses in its file, plus the scenes open
//! in the editor (or read for a `.rif`) whose primitives load the file and name it in
//! a function argument. From a scene, the same set for a name in a function argument.

use std::path::Path;

use radc_lang::db::{self, CalName};
use tower_lsp_server::ls_types::{Location, Position};

use crate::calcomp::{self, CalFile};
use crate::document::Document;

pub fn references(
    doc: &Document<'_>,
    pos: Position,
    include_declaration: bool,
) -> Option<Vec<Location>> {
    let index = db::cal_index(doc.db, doc.file);
    let at = index.at(doc.offset(pos))?;
    let file = calcomp::this_file(doc);
    Some(locations(doc, &file, &at.name, include_declaration))
}

/// From a scene: the uses of the calcomp name under `offset` in a function argument.
pub fn scene_references(
    doc: &Document<'_>,
    offset: usize,
    include_declaration: bool,
) -> Option<Vec<Location>> {
    let (_, name, files) = calcomp::scene_name_at(doc, offset)?;
    let file = calcomp::defining_file(doc, &files, &name)?;
    Some(locations(
        doc,
        &file,
        &CalName::Global(name),
        include_declaration,
    ))
}

/// Every word naming `name` of `file`: in the file, then in the scenes that load it.
pub fn locations(
    doc: &Document<'_>,
    file: &CalFile,
    name: &CalName,
    include_declaration: bool,
) -> Vec<Location> {
    let declaration = file.index.declaration(name);
    let here = file
        .index
        .spans_of(name)
        .into_iter()
        .filter(|s| include_declaration || Some(*s) != declaration)
        .map(|s| file.location(s));
    let mut out: Vec<Location> = here.collect();
    if let CalName::Global(n) = name {
        out.extend(calcomp::scene_uses(doc, Path::new(&file.path), n));
    }
    out
}
