//! `textDocument/documentColor` and `colorPresentation`: the RGB triple of materials
//! and light sources whose first three reals are `red green blue`. Light values are
//! radiances, not reflectances: they are shown scaled to their largest component, and
//! a picked colour is written back at the original brightness.

use radc_lang::scene::syntax::{Item, Primitive};
use radc_lang::schema::{self, Category};
use tower_lsp_server::ls_types::{Color, ColorInformation, ColorPresentation, Range, TextEdit};

use crate::document::Document;

pub fn document_colors(doc: &Document<'_>) -> Vec<ColorInformation> {
    doc.parsed()
        .syntax
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Primitive(p) => rgb(p),
            _ => None,
        })
        .map(|(rgb, span)| {
            let scale = brightness(rgb).max(1.0);
            let c = rgb.map(|v| (v / scale).clamp(0.0, 1.0) as f32);
            ColorInformation {
                range: doc.range(span),
                color: Color {
                    red: c[0],
                    green: c[1],
                    blue: c[2],
                    alpha: 1.0,
                },
            }
        })
        .collect()
}

pub fn presentations(doc: &Document<'_>, color: Color, range: Range) -> Vec<ColorPresentation> {
    let (start, end) = (doc.offset(range.start), doc.offset(range.end));
    let old: Vec<f64> = doc
        .text()
        .get(start..end)
        .unwrap_or("")
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect();
    let scale = old.iter().copied().fold(1.0, f64::max);
    let value = |c: f32| trim(f64::from(c) * scale);
    let label = format!(
        "{} {} {}",
        value(color.red),
        value(color.green),
        value(color.blue)
    );
    vec![ColorPresentation {
        label: label.clone(),
        text_edit: Some(TextEdit {
            range,
            new_text: label,
        }),
        additional_text_edits: None,
    }]
}

/// The three colour reals and the span covering them.
fn rgb(p: &Primitive) -> Option<([f64; 3], radc_lang::Span)> {
    let ty = schema::lookup(&p.kind.text)?;
    if !matches!(ty.category, Category::Material | Category::Light) {
        return None;
    }
    let names: Vec<&str> = ty.reals.fixed.iter().take(3).map(|a| a.name).collect();
    if names != ["red", "green", "blue"] {
        return None;
    }
    let [r, g, b] = p.reals.items.get(..3)? else {
        return None;
    };
    Some(([r.value, g.value, b.value], r.span.to(b.span)))
}

fn brightness(rgb: [f64; 3]) -> f64 {
    rgb.iter().copied().fold(0.0, f64::max)
}

/// Three decimals, without trailing zeros: `0.5`, `0.125`, `50`.
fn trim(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.is_empty() || s == "-" || s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::with_document;

    #[test]
    fn lights_are_scaled_to_their_brightest_component() {
        let text = "void light lamp\n0\n0\n3 50 25 0\n";
        with_document(text, |doc| {
            let colors = document_colors(doc);
            assert_eq!(colors.len(), 1);
            assert_eq!((colors[0].color.red, colors[0].color.green), (1.0, 0.5));
            let picked = Color {
                red: 0.5,
                green: 1.0,
                blue: 0.0,
                alpha: 1.0,
            };
            let p = presentations(doc, picked, colors[0].range);
            assert_eq!(p[0].label, "25 50 0");
        });
    }

    #[test]
    fn trims_numbers() {
        assert_eq!(trim(0.5), "0.5");
        assert_eq!(trim(0.0), "0");
        assert_eq!(trim(0.1234), "0.123");
        assert_eq!(trim(-0.0001), "0");
    }
}
