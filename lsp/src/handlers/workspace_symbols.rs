//! `workspace/symbol`: the named definitions of every open document and every scene
//! file read for a `.rif` (modifiers, surfaces, aliases; calcomp variables and
//! functions) whose name contains the query, case-insensitively (clients rank the
//! matches themselves). At most [`LIMIT`] answers, modifiers first.

use radc_lang::Span;
use radc_lang::db::{self, Database};
use radc_lang::schema::{self, Category};
use tower_lsp_server::ls_types::{Location, Position, Range, SymbolInformation, SymbolKind};

use crate::document::Kind;
use crate::session::Session;

pub const LIMIT: usize = 1000;

pub fn symbols(session: &Session, query: &str) -> Vec<SymbolInformation> {
    let db = session.db();
    let query = query.to_lowercase();
    let matches = |name: &str| query.is_empty() || name.to_lowercase().contains(&query);
    let mut modifiers = Vec::new();
    let mut others = Vec::new();
    for o in session.workspace() {
        let container = o
            .file
            .path(db)
            .rsplit(['/', '\\'])
            .next()
            .map(str::to_string);
        let location = |span: Span| Location {
            uri: o.uri.clone(),
            range: range(db, o.file, span),
        };
        #[allow(deprecated)] // `deprecated` is a required field of the struct.
        let info = |name: &str, kind, span| SymbolInformation {
            name: name.to_string(),
            kind,
            tags: None,
            deprecated: None,
            location: location(span),
            container_name: container.clone(),
        };
        match o.kind {
            Kind::Cal => {
                for d in db::cal_index(db, o.file)
                    .defs
                    .iter()
                    .filter(|d| matches(&d.name))
                {
                    let kind = if d.params.is_some() {
                        SymbolKind::FUNCTION
                    } else {
                        SymbolKind::VARIABLE
                    };
                    modifiers.push(info(&d.name, kind, d.name_span));
                }
            }
            Kind::Scene => {
                for d in db::modifier_scope(db, o.file).definitions.iter() {
                    if others.len() + modifiers.len() >= 4 * LIMIT || !matches(&d.name) {
                        continue;
                    }
                    let category = schema::lookup(&d.type_name).map(|t| t.category);
                    let kind = match category {
                        Some(Category::Surface) => SymbolKind::OBJECT,
                        Some(Category::Alias) => SymbolKind::VARIABLE,
                        Some(_) => SymbolKind::STRUCT,
                        None => SymbolKind::NULL,
                    };
                    if d.is_modifier {
                        modifiers.push(info(&d.name, kind, d.name_span));
                    } else {
                        others.push(info(&d.name, kind, d.name_span));
                    }
                }
            }
            Kind::Rif => {}
        }
    }
    modifiers.extend(others);
    modifiers.truncate(LIMIT);
    modifiers
}

fn range(db: &Database, file: radc_lang::db::SourceFile, span: Span) -> Range {
    let lines = db::line_index(db, file);
    let text = file.text(db);
    let at = |offset: u32| {
        let (line, character) = lines.line_utf16(text, offset as usize);
        Position { line, character }
    };
    Range {
        start: at(span.start),
        end: at(span.end),
    }
}
