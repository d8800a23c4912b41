//! `textDocument/signatureHelp`: inside a primitive's string or real arguments, the
//! layout of that list (`red green blue spec rough`) with the argument at the cursor
//! highlighted and explained, from the schema.

use radc_lang::scene::syntax::{Item, Primitive};
use radc_lang::schema::{self, ArgSide};
use tower_lsp_server::ls_types::{
    Documentation, ParameterInformation, ParameterLabel, Position, SignatureHelp,
    SignatureInformation,
};

use crate::document::Document;

pub fn signature_help(doc: &Document<'_>, pos: Position) -> Option<SignatureHelp> {
    let offset = doc.offset(pos);
    let p = doc
        .parsed()
        .syntax
        .items
        .iter()
        .find_map(|item| match item {
            Item::Primitive(p)
                if p.span.start as usize <= offset && offset <= p.span.end as usize =>
            {
                Some(p)
            }
            _ => None,
        })?;
    let (side, index) = argument_at(p, offset)?;
    let ty = schema::lookup(&p.kind.text)?;
    let list = ty.args(side);
    let given = match side {
        ArgSide::Strings => p.strings.len(),
        ArgSide::Reals => p.reals.len(),
    };
    let shown = given.max(list.count.min() as usize).max(index + 1);
    let mut label = format!("{} {}:", ty.name, side_name(side));
    let mut parameters = Vec::new();
    for i in 0..shown {
        let Some(name) = list.label(i) else {
            break;
        };
        label.push(' ');
        let start = label.encode_utf16().count() as u32;
        label.push_str(&name);
        let end = label.encode_utf16().count() as u32;
        parameters.push(ParameterInformation {
            label: ParameterLabel::LabelOffsets([start, end]),
            documentation: schema::arg_hint(ty, side, i).map(Documentation::String),
        });
    }
    if parameters.is_empty() {
        return None;
    }
    let active = (index as u32).min(parameters.len() as u32 - 1);
    Some(SignatureHelp {
        signatures: vec![SignatureInformation {
            label,
            documentation: Some(Documentation::String(format!(
                "{} {} argument(s): {}",
                ty.name,
                side_name(side),
                list.count.describe()
            ))),
            parameters: Some(parameters),
            active_parameter: Some(active),
        }],
        active_signature: Some(0),
        active_parameter: Some(active),
    })
}

fn side_name(side: ArgSide) -> &'static str {
    match side {
        ArgSide::Strings => "strings",
        ArgSide::Reals => "reals",
    }
}

/// Which list the cursor is in, and which argument of it (0-based) it is on or about
/// to type: past the list's count word and, for strings, before the integer count.
fn argument_at(p: &Primitive, offset: usize) -> Option<(ArgSide, usize)> {
    let after = |s: radc_lang::Span| offset > s.end as usize;
    let index = |starts: &mut dyn Iterator<Item = radc_lang::Span>| {
        starts.filter(|s| (s.end as usize) < offset).count()
    };
    if after(p.reals.count_span) {
        let i = index(&mut p.reals.items.iter().map(|r| r.span));
        return Some((ArgSide::Reals, i));
    }
    if after(p.strings.count_span) && offset < p.ints.count_span.start as usize {
        let i = index(&mut p.strings.items.iter().map(|w| w.span));
        return Some((ArgSide::Strings, i));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_document;

    #[test]
    fn highlights_the_real_under_the_cursor() {
        let text = "void plastic red\n0\n0\n5 .5 .1 .1 .05 .1\n";
        with_document(text, |doc| {
            let help = signature_help(doc, Position::new(3, 12));
            let sig = help.map(|h| h.signatures[0].clone());
            assert_eq!(
                sig.as_ref().map(|s| s.label.as_str()),
                Some("plastic reals: red green blue spec rough")
            );
            assert_eq!(sig.and_then(|s| s.active_parameter), Some(3));
            // On the count word, or in the head: no help.
            assert!(signature_help(doc, Position::new(3, 0)).is_none());
            assert!(signature_help(doc, Position::new(0, 2)).is_none());
        });
    }

    #[test]
    fn string_lists_too() {
        let text = "void mixfunc m\n4 a b f .\n0\n0\n";
        with_document(text, |doc| {
            let help = signature_help(doc, Position::new(1, 4));
            let label = help
                .map(|h| h.signatures[0].label.clone())
                .unwrap_or_default();
            assert!(
                label.starts_with("mixfunc strings: foreground background"),
                "{label}"
            );
        });
    }
}
