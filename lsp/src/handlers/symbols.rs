//! `textDocument/documentSymbol`: the outline, one entry per named primitive or alias.

use radc_lang::schema::{self, Category};
use tower_lsp_server::ls_types::{DocumentSymbol, SymbolKind};

use crate::document::Document;

pub fn symbols(doc: &Document<'_>) -> Vec<DocumentSymbol> {
    doc.scope()
        .definitions
        .iter()
        .map(|d| {
            #[allow(deprecated)] // `deprecated` is a required field of the struct.
            DocumentSymbol {
                name: d.name.clone(),
                detail: Some(d.type_name.to_string()),
                kind: kind(&d.type_name),
                tags: None,
                deprecated: None,
                range: doc.range(d.span),
                selection_range: doc.range(d.name_span),
                children: None,
            }
        })
        .collect()
}

fn kind(type_name: &str) -> SymbolKind {
    match schema::lookup(type_name).map(|t| t.category) {
        Some(Category::Surface) => SymbolKind::OBJECT,
        Some(Category::Material) => SymbolKind::STRUCT,
        Some(Category::Light) => SymbolKind::EVENT,
        Some(Category::Texture | Category::Pattern | Category::Mixture) => SymbolKind::FUNCTION,
        Some(Category::Alias) => SymbolKind::VARIABLE,
        None => SymbolKind::NULL,
    }
}
