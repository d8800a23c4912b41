//! `textDocument/codeAction`: quick fixes for the diagnostics whose hint names the fix
//! ("did you mean 'plastic'?" on a misspelled type, modifier, transform option or
//! calcomp name): replace the misspelled word, as the hint says. Diagnostics are
//! recomputed (the same queries as the published ones), so a fix never rests on what
//! a client echoes back.

use std::collections::HashMap;

use radc_lang::Diagnostic;
use tower_lsp_server::ls_types::{
    self as lsp, CodeAction, CodeActionKind, CodeActionOrCommand, TextEdit, WorkspaceEdit,
};

use crate::document::{Document, Kind};

pub fn code_actions(doc: &Document<'_>, asked: &[lsp::Diagnostic]) -> Vec<CodeActionOrCommand> {
    let here = doc.file.id(doc.db);
    let all: &[Diagnostic] = match (doc.kind, doc.scene) {
        (Kind::Cal, _) => radc_lang::db::check_cal(doc.db, doc.file),
        (_, Some(set)) => radc_lang::db::check_scene_set(doc.db, set),
        (_, None) => radc_lang::db::check_scene(doc.db, doc.file),
    };
    let mut out = Vec::new();
    for d in all.iter().filter(|d| d.span.file == here) {
        let Some(suggestion) = d.hint.as_deref().and_then(suggested) else {
            continue;
        };
        let range = doc.range(d.span);
        let code = lsp::NumberOrString::String(d.code.id.to_string());
        let Some(matching) = asked
            .iter()
            .find(|a| a.range == range && a.code.as_ref() == Some(&code))
        else {
            continue;
        };
        let Some((start, end)) = misspelled(doc.text(), d) else {
            continue;
        };
        let edit = TextEdit {
            range: lsp::Range {
                start: doc.position(start),
                end: doc.position(end),
            },
            new_text: suggestion.to_string(),
        };
        out.push(CodeActionOrCommand::CodeAction(CodeAction {
            title: format!("Change to '{suggestion}'"),
            kind: Some(CodeActionKind::QUICKFIX),
            diagnostics: Some(vec![matching.clone()]),
            edit: Some(WorkspaceEdit {
                changes: Some(HashMap::from([(doc.uri.clone(), vec![edit])])),
                ..WorkspaceEdit::default()
            }),
            is_preferred: Some(true),
            ..CodeAction::default()
        }));
    }
    out
}

/// The name a "did you mean 'x'?" hint offers.
fn suggested(hint: &str) -> Option<&str> {
    hint.strip_prefix("did you mean '")?.strip_suffix("'?")
}

/// The byte range of the misspelled word: the first name quoted in the message that
/// appears, as a whole word, in the diagnostic's span.
fn misspelled(text: &str, d: &Diagnostic) -> Option<(usize, usize)> {
    let start = d.span.start as usize;
    let source = text.get(d.span.range())?;
    let quoted = d.message.split('\'').skip(1).step_by(2);
    let is_word = |c: char| c.is_alphanumeric() || matches!(c, '_' | '.' | '`' | '-');
    for name in quoted.filter(|n| !n.is_empty()) {
        for (i, _) in source.match_indices(name) {
            let before = source[..i].chars().next_back();
            let after = source[i + name.len()..].chars().next();
            if !before.is_some_and(is_word) && !after.is_some_and(is_word) {
                return Some((start + i, start + i + name.len()));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::{with_cal_document, with_document};

    fn fixes(doc: &Document<'_>) -> Vec<(String, String)> {
        let published = crate::diagnostics::for_document(doc);
        code_actions(doc, &published)
            .into_iter()
            .filter_map(|a| match a {
                CodeActionOrCommand::CodeAction(a) => {
                    let edits = a.edit?.changes?.into_values().next()?;
                    let e = edits.first()?;
                    let (s, t) = (doc.offset(e.range.start), doc.offset(e.range.end));
                    Some((doc.text()[s..t].to_string(), e.new_text.clone()))
                }
                _ => None,
            })
            .collect()
    }

    #[test]
    fn misspelled_types_modifiers_and_calcomp_names() {
        let scene = "void plastc red\n0\n0\n5 .5 .1 .1 0 0\nvoid plastic blue\n0\n0\n5 .1 .1 .5 0 0\n\
                     blu sphere ball\n0\n0\n4 0 0 0 1\n";
        with_document(scene, |doc| {
            assert_eq!(
                fixes(doc),
                [
                    ("plastc".into(), "plastic".into()),
                    ("blu".into(), "blue".into())
                ]
            );
        });
        with_cal_document("a = sinn(1) + bb;\nbc = 2;\n", |doc| {
            assert_eq!(
                fixes(doc),
                [("sinn".into(), "sin".into()), ("bb".into(), "bc".into())]
            );
        });
    }
}
