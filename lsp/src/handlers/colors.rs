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
    if s.is_empty() || s == "-" {
        "0".into()
    } else {
        s.to_string()
    }
}
