//! The one place `lang` diagnostics become LSP diagnostics. Codes and messages are
//! kept word for word (the editor says what `radc check` says); the hint and the
//! secondary labels become related information. A diagnostic inside text the editor
//! does not show (a generator's output, a function file) is shown where this document
//! brought that text in: at its label here ("in the output of this command").

use radc_lang::{Diagnostic, Severity};
use tower_lsp_server::ls_types::{
    self as lsp, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString,
};

use crate::document::Document;

/// `None` for diagnostics of the other files of a `.rif` scene (they are shown in
/// those files).
pub fn to_lsp(doc: &Document<'_>, d: &Diagnostic) -> Option<lsp::Diagnostic> {
    let here = doc.file.id(doc.db);
    let span = if d.span.file == here {
        d.span
    } else if doc.is_scene_file(d.span.file) {
        return None;
    } else {
        d.labels.iter().find(|l| l.span.file == here)?.span
    };
    let range = doc.range(span);
    let info = |message: String, range| DiagnosticRelatedInformation {
        location: Location {
            uri: doc.uri.clone(),
            range,
        },
        message,
    };
    let mut related: Vec<_> = d
        .labels
        .iter()
        .filter(|l| l.span.file == here)
        .map(|l| info(l.message.clone(), doc.range(l.span)))
        .collect();
    if let Some(hint) = &d.hint {
        related.push(info(format!("hint: {hint}"), range));
    }
    Some(lsp::Diagnostic {
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
    })
}

/// Every diagnostic of the document, as `radc check FILE` reports them (or, for a
/// document a `.rif` lists, `radc check` of all the rif's files, shown for this one).
/// A calcomp document gets what `radc check FILE.cal` reports.
pub fn for_document(doc: &Document<'_>) -> Vec<lsp::Diagnostic> {
    if doc.kind == crate::document::Kind::Cal {
        let all = radc_lang::db::check_cal(doc.db, doc.file);
        return all.iter().filter_map(|d| to_lsp(doc, d)).collect();
    }
    let all = match doc.scene {
        Some(set) => radc_lang::db::check_scene_set(doc.db, set),
        None => radc_lang::db::check_scene(doc.db, doc.file),
    };
    all.iter().filter_map(|d| to_lsp(doc, d)).collect()
}
