//! `textDocument/documentHighlight`: the definition under the cursor (as written) and
//! the words bound to it (as read), by the same rule as references.

use tower_lsp_server::ls_types::{DocumentHighlight, DocumentHighlightKind, Position};

use crate::document::Document;

pub fn highlights(doc: &Document<'_>, pos: Position) -> Option<Vec<DocumentHighlight>> {
    let scope = doc.scope();
    let def = scope.definition_at(doc.offset(pos))?;
    let spans = scope.uses_of(def);
    let kinds = std::iter::once(DocumentHighlightKind::WRITE)
        .chain(std::iter::repeat(DocumentHighlightKind::READ));
    let highlights = spans
        .into_iter()
        .zip(kinds)
        .map(|(span, kind)| DocumentHighlight {
            range: doc.range(span),
            kind: Some(kind),
        });
    Some(highlights.collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_document;

    const TEXT: &str = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\nred sphere a\n0\n0\n4 0 0 0 1\n\
                        void plastic red\n0\n0\n5 .1 .1 .5 0 0\nred sphere b\n0\n0\n4 0 0 3 1\n";

    #[test]
    fn highlights_definition_and_uses() {
        with_document(TEXT, |doc| {
            let h = highlights(doc, Position::new(12, 0)).unwrap_or_default();
            let lines: Vec<u32> = h.iter().map(|h| h.range.start.line).collect();
            assert_eq!(lines, [8, 12]);
            assert_eq!(h[0].kind, Some(DocumentHighlightKind::WRITE));
        });
    }
}
