//! The one place `lang` diagnostics become LSP diagnostics. Codes and messages are
//! kept word for word (the editor says what `radc check` says); the hint and the
//! secondary labels become related information.

use radc_lang::{Diagnostic, Severity};
use tower_lsp_server::ls_types::{
    self as lsp, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString,
};

use crate::document::Document;

pub fn to_lsp(doc: &Document<'_>, d: &Diagnostic) -> lsp::Diagnostic {
    let range = doc.range(d.span);
    let here = |message: String, range| DiagnosticRelatedInformation {
        location: Location {
            uri: doc.uri.clone(),
            range,
        },
        message,
    };
    let mut related: Vec<_> = d
        .labels
        .iter()
        .filter(|l| l.span.file == d.span.file)
        .map(|l| here(l.message.clone(), doc.range(l.span)))
        .collect();
    if let Some(hint) = &d.hint {
        related.push(here(format!("hint: {hint}"), range));
    }
    lsp::Diagnostic {
        range,
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
        }),
        code: Some(NumberOrString::String(d.code.id.to_string())),
        source: Some("radc".into()),
        message: d.message.clone(),
        related_information: (!related.is_empty()).then_some(related),
        ..lsp::Diagnostic::default()
    }
}

/// Every diagnostic of the document, as `radc check FILE` reports them (or, for a
/// document a `.rif` lists, `radc check` of all the rif's files, shown for this one).
pub fn for_document(doc: &Document<'_>) -> Vec<lsp::Diagnostic> {
    let all = match doc.scene {
        Some(set) => radc_lang::db::check_scene_set(doc.db, set),
        None => radc_lang::db::check_scene(doc.db, doc.file),
    };
    all.iter()
        .filter(|d| d.span.file == doc.file.id(doc.db))
        .map(|d| to_lsp(doc, d))
        .collect()
}
