//! Argument lists against the schema: the counts, the value ranges of real
//! arguments (hard limits are errors, plausible ranges warnings, as the `o_*.c`
//! and `m_*.c` readers judge them), and the xform-style transform that ends the
//! string arguments of patterns, textures, instances and meshes.

use super::Lowering;
use crate::diagnostic::{self as codes, Diagnostic};
use crate::scene::syntax::Primitive;
use crate::schema::{self, ArgList, PrimitiveType};
use crate::source::Span;
use crate::transform::Transform;

impl Lowering<'_> {
    /// Argument counts against the schema. Returns whether both lists fit.
    pub(super) fn check_counts(&mut self, p: &Primitive, schema: &PrimitiveType) -> bool {
        let mut ok = true;
        for (what, list, n, span) in [
            (
                "string",
                schema.strings,
                p.strings.len(),
                p.strings.count_span,
            ),
            ("real", schema.reals, p.reals.len(), p.reals.count_span),
        ] {
            let n = u32::try_from(n).unwrap_or(u32::MAX);
            if list.count.accepts(n) {
                continue;
            }
            if what == "string" && list.count == schema::Count::Exactly(0) {
                // No reader of a string-less type looks at its strings.
                self.diags.push(
                    Diagnostic::new(
                        codes::W0207,
                        span,
                        format!(
                            "{} takes no string arguments; Radiance ignores these {n}",
                            schema.name
                        ),
                    )
                    .with_hint("write 0 as the string count"),
                );
                continue;
            }
            ok = false;
            self.diags.push(
                Diagnostic::new(
                    codes::E0202,
                    span,
                    format!(
                        "{} takes {} {what} argument{}, found {n}",
                        schema.name,
                        list.count.describe(),
                        if list.count == schema::Count::Exactly(1) {
                            ""
                        } else {
                            "s"
                        },
                    ),
                )
                .with_label(
                    p.kind.span,
                    format!("{} {}", schema.category.as_str(), schema.name),
                )
                .with_hint(layout_hint(schema.name, what, &list)),
            );
        }
        ok
    }

    /// Hard limits (errors) and plausible ranges (warnings) of real arguments. Surface
    /// geometry is judged in `lower_kind`, where Radiance's own rules are known.
    pub(super) fn check_values(&mut self, p: &Primitive, schema: &PrimitiveType) {
        // Radii, axes and vertices are judged by Radiance's own geometry rules in
        // `lower_kind` (a negative radius flips the surface rather than failing).
        let geometry = matches!(
            schema.name,
            "sphere" | "bubble" | "cone" | "cup" | "cylinder" | "tube" | "ring" | "polygon"
        );
        for (i, r) in p.reals.items.iter().enumerate() {
            let Some((arg, _)) = schema.reals.arg_at(i) else {
                continue;
            };
            if !r.value.is_finite() {
                self.diags.push(Diagnostic::new(
                    codes::E0203,
                    r.span,
                    format!(
                        "{} of {} '{}' overflows to infinity",
                        arg.name, schema.name, p.name.text
                    ),
                ));
            } else if !geometry && !arg.valid.contains(r.value) {
                self.diags.push(
                    Diagnostic::new(
                        codes::E0203,
                        r.span,
                        format!(
                            "{} of {} '{}' is {}, but must be {}",
                            arg.name,
                            schema.name,
                            p.name.text,
                            r.value,
                            arg.valid.describe()
                        ),
                    )
                    .with_hint(format!("{}: {}", arg.name, arg.meaning)),
                );
            } else if !geometry && !arg.plausible.contains(r.value) {
                self.diags.push(
                    Diagnostic::new(
                        codes::W0201,
                        r.span,
                        format!(
                            "{} of {} '{}' is {}, outside the usual range ({})",
                            arg.name,
                            schema.name,
                            p.name.text,
                            r.value,
                            arg.plausible.describe()
                        ),
                    )
                    .with_hint(format!("{}: {}", arg.name, arg.meaning)),
                );
            }
        }
    }

    /// The xform-style transform at the end of the string arguments. Radiance rejects
    /// a bad one when it reads the primitive (oconv for instances and meshes, the
    /// renderer for patterns and textures).
    pub(super) fn parse_transform(&mut self, p: &Primitive, schema: &PrimitiveType) -> Transform {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        let start = match schema.name {
            // Everything after the octree or mesh file is the transform.
            "instance" | "mesh" => 1,
            _ => match schema.strings.transform_start(&words) {
                Some(s) => s,
                None => return Transform::IDENTITY,
            },
        };
        let spanned: Vec<(&str, Span)> = p
            .strings
            .items
            .iter()
            .skip(start)
            .map(|w| (w.text.as_str(), w.span))
            .collect();
        if spanned.is_empty() {
            return Transform::IDENTITY;
        }
        match Transform::parse(&spanned) {
            Ok(t) => t,
            Err(d) => {
                self.diags
                    .push(d.with_label(p.kind.span, format!("transform of this {}", schema.name)));
                Transform::IDENTITY
            }
        }
    }
}

fn layout_hint(type_name: &str, what: &str, list: &ArgList) -> String {
    let names: Vec<&str> = list.fixed.iter().map(|a| a.name).collect();
    let repeat: Vec<&str> = list.repeat.iter().map(|a| a.name).collect();
    let mut layout = names.join(" ");
    if !repeat.is_empty() {
        if !layout.is_empty() {
            layout.push(' ');
        }
        layout.push_str(&format!("[{}]...", repeat.join(" ")));
    }
    if layout.is_empty() {
        format!("{type_name} takes no {what} arguments: write 0")
    } else {
        format!("{type_name} {what} arguments: {layout}")
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::lower::tests::check;

    #[test]
    fn counts_and_values() {
        assert_eq!(
            check("void plastic m 0 0 4 .5 .5 .5 0\nm sphere s 0 0 4 0 0 0 1\n").1,
            vec!["E0202"]
        );
        assert_eq!(
            check("void plastic m 0 0 5 1.5 .5 .5 0 0\nm sphere s 0 0 4 0 0 0 1\n").1,
            vec!["W0201"]
        );
    }
}
