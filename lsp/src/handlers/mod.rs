//! One file per request kind. Each handler takes a [`crate::document::Document`] and
//! the request's parameters and returns the response; none of them waits, locks or
//! does IO.

pub mod cal_completion;
pub mod cal_definition;
pub mod cal_hover;
pub mod cal_references;
pub mod cal_rename;
pub mod cal_symbols;
pub mod code_actions;
pub mod colors;
pub mod completion;
pub mod definition;
pub mod formatting;
pub mod highlights;
pub mod hover;
pub mod inlay_hints;
pub mod references;
pub mod rename;
pub mod semantic_tokens;
pub mod signature_help;
pub mod symbols;
pub mod workspace_symbols;

#[cfg(test)]
mod properties {
    use proptest::prelude::*;
    use tower_lsp_server::ls_types::{Color, Position, Range};

    use super::*;
    use crate::document::with_document;

    fn scene_text() -> impl Strategy<Value = String> {
        let word = prop_oneof![
            Just("void"),
            Just("plastic"),
            Just("light"),
            Just("polygon"),
            Just("mixfunc"),
            Just("alias"),
            Just("m"),
            Just("0"),
            Just("3"),
            Just("5"),
            Just("-1e2"),
            Just("#"),
            Just("!x"),
            Just("\""),
            Just("é😀"),
            Just("\n"),
            Just("\r\n"),
        ];
        prop::collection::vec(word, 0..50).prop_map(|w| w.join(" "))
    }

    proptest! {
        /// Every handler answers any text at any position without panicking.
        #[test]
        fn handlers_never_panic(text in scene_text(), line in 0u32..20, character in 0u32..40) {
            with_document(&text, |doc| {
                let pos = Position::new(line, character);
                let range = Range::new(Position::new(0, 0), pos);
                let _ = hover::hover(doc, pos);
                let _ = definition::definition(doc, pos);
                let _ = references::references(doc, pos, true);
                let _ = rename::rename(doc, pos, "n");
                let _ = highlights::highlights(doc, pos);
                let _ = signature_help::signature_help(doc, pos);
                let _ = completion::completion(doc, pos);
                let _ = inlay_hints::inlay_hints(doc, range);
                let _ = symbols::symbols(doc);
                let _ = formatting::formatting(doc);
                let _ = colors::document_colors(doc);
                let color = Color { red: 0.2, green: 0.4, blue: 0.6, alpha: 1.0 };
                let _ = colors::presentations(doc, color, range);
                let _ = crate::diagnostics::for_document(doc);
            });
        }
    }
}
