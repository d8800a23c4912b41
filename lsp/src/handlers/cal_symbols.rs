//! `textDocument/documentSymbol` in a calcomp file: one entry per definition
//! statement, functions with their parameters.

use radc_lang::cal::syntax::DefKind;
use radc_lang::db;
use tower_lsp_server::ls_types::{DocumentSymbol, SymbolKind};

use crate::document::Document;

pub fn symbols(doc: &Document<'_>) -> Vec<DocumentSymbol> {
    db::cal_index(doc.db, doc.file)
        .defs
        .iter()
        .map(|d| {
            let (kind, detail) = match (&d.params, d.kind) {
                (Some(p), k) => {
                    let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
                    (
                        SymbolKind::FUNCTION,
                        format!("({}) {}", names.join(", "), k.symbol()),
                    )
                }
                (None, DefKind::Constant) => (SymbolKind::CONSTANT, ":".to_string()),
                (None, DefKind::Assign) => (SymbolKind::VARIABLE, "=".to_string()),
            };
            #[allow(deprecated)] // `deprecated` is a required field of the struct.
            DocumentSymbol {
                name: d.name.clone(),
                detail: Some(detail),
                kind,
                tags: None,
                deprecated: None,
                range: doc.range(d.span),
                selection_range: doc.range(d.name_span),
                children: None,
            }
        })
        .collect()
}
