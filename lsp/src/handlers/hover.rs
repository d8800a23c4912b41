//! `textDocument/hover`: a modifier's definition, a type's documentation and argument
//! layout, or what one argument means, all from the schema.

use radc_lang::scene::syntax::Primitive;
use radc_lang::schema::{self, ArgList, ArgSide, PrimitiveType};
use tower_lsp_server::ls_types::{Hover, HoverContents, MarkupContent, MarkupKind, Position};

use crate::document::{Document, Part, Target};

/// Definitions longer than this are cut in hover text.
const MAX_DEFINITION_LINES: usize = 12;

pub fn hover(doc: &Document<'_>, pos: Position) -> Option<Hover> {
    let offset = doc.offset(pos);
    let (text, span) = match doc.target_at(offset) {
        Some((span, target)) => (definition(doc, target), span),
        None => {
            let (p, part, span) = doc.locate(offset)?;
            (part_text(p, part)?, span)
        }
    };
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: text,
        }),
        range: Some(doc.range(span)),
    })
}

fn definition(doc: &Document<'_>, target: Target<'_>) -> String {
    let def = target.def;
    let ty = schema::lookup(&def.type_name);
    let what = ty.map_or("unknown type", |t| t.category.as_str());
    let text = target.file.text(doc.db);
    let source = text.get(def.span.range()).unwrap_or("");
    let mut lines: Vec<&str> = source.lines().take(MAX_DEFINITION_LINES).collect();
    if source.lines().count() > MAX_DEFINITION_LINES {
        lines.push("...");
    }
    let line = doc.position_in(target.file, def.span.start as usize).line + 1;
    let place = if target.file == doc.file {
        format!("line {line}")
    } else {
        let path = target.file.path(doc.db);
        let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
        format!("line {line} of {name}")
    };
    format!(
        "**{}** — {} ({what}), defined on {place}\n\n```radiance\n{}\n```",
        def.name,
        def.type_name,
        lines.join("\n")
    )
}

fn part_text(p: &Primitive, part: Part) -> Option<String> {
    let ty = schema::lookup(&p.kind.text);
    match part {
        Part::Type => Some(schema::hover(ty?)),
        Part::Modifier if p.modifier.text == "void" => {
            Some("`void`: no modifier (the primitive has no material or pattern)".into())
        }
        Part::Modifier | Part::Name => None,
        Part::Count(side) => Some(count_text(p, ty, side)),
        Part::Arg(side, i) => arg_text(p, ty?, side, i),
    }
}

fn count_text(p: &Primitive, ty: Option<&PrimitiveType>, side: Option<ArgSide>) -> String {
    let Some(side) = side else {
        return "the number of integer arguments: always 0 for scene primitives".into();
    };
    let (what, written) = match side {
        ArgSide::Strings => ("string", p.strings.len()),
        ArgSide::Reals => ("real", p.reals.len()),
    };
    let mut text = format!("the number of {what} arguments ({written} given)");
    if let Some(t) = ty {
        text.push_str(&format!(
            "; **{}** takes {}",
            t.name,
            t.args(side).count.describe()
        ));
    }
    text
}

fn arg_text(p: &Primitive, ty: &PrimitiveType, side: ArgSide, i: usize) -> Option<String> {
    let hint = match side {
        ArgSide::Strings => {
            let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
            match ty.strings.arg_in(i, &words) {
                Some((a, _)) if a == ArgList::TRANSFORM => {
                    format!("transform — {}", ArgList::TRANSFORM.meaning)
                }
                _ => schema::arg_hint(ty, side, i)?,
            }
        }
        ArgSide::Reals => schema::arg_hint(ty, side, i)?,
    };
    let what = match side {
        ArgSide::Strings => "string",
        ArgSide::Reals => "real",
    };
    Some(format!(
        "{hint}\n\n{what} argument {} of **{}**",
        i + 1,
        ty.name
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_document;

    fn hover_text(text: &str, line: u32, character: u32) -> Option<String> {
        with_document(text, |doc| {
            let h = hover(doc, Position::new(line, character))?;
            match h.contents {
                HoverContents::Markup(m) => Some(m.value),
                _ => None,
            }
        })
    }

    #[test]
    fn counts_arguments_and_void() {
        let text = "void plastic red\n0\n0\n4 .5 .1 .1 0\n";
        assert_eq!(
            hover_text(text, 3, 0).as_deref(),
            Some("the number of real arguments (4 given); **plastic** takes 5")
        );
        assert!(hover_text(text, 0, 1).is_some_and(|t| t.starts_with("`void`")));
        assert!(hover_text(text, 3, 3).is_some_and(|t| t.starts_with("red — ")));
    }

    #[test]
    fn unknown_types_and_blank_space_have_no_hover() {
        let text = "void plastik red\n0\n0\n0\n\n";
        assert_eq!(hover_text(text, 0, 7), None);
        assert_eq!(hover_text(text, 4, 0), None);
    }
}
