//! `textDocument/inlayHint`: the name of each positional real argument (`spec=`,
//! `rough=`, `x2=`) before it, from the schema. Off when the client's settings say
//! `inlayHints.enabled: false`.

use radc_lang::scene::syntax::Item;
use radc_lang::schema;
use tower_lsp_server::ls_types::{InlayHint, InlayHintKind, InlayHintLabel, Range};

use crate::document::Document;

pub fn inlay_hints(doc: &Document<'_>, range: Range) -> Vec<InlayHint> {
    let (start, end) = (doc.offset(range.start), doc.offset(range.end));
    let mut hints = Vec::new();
    for item in &doc.parsed().syntax.items {
        let Item::Primitive(p) = item else {
            continue;
        };
        let Some(ty) = schema::lookup(&p.kind.text) else {
            continue;
        };
        for (i, real) in p.reals.items.iter().enumerate() {
            let at = real.span.start as usize;
            if at < start || at > end {
                continue;
            }
            let Some(label) = ty.reals.label(i) else {
                break;
            };
            hints.push(InlayHint {
                position: doc.position(at),
                label: InlayHintLabel::String(format!("{label}=")),
                kind: Some(InlayHintKind::PARAMETER),
                text_edits: None,
                tooltip: None,
                padding_left: None,
                padding_right: None,
                data: None,
            });
        }
    }
    hints
}
