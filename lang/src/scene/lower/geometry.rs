//! Geometry sanity, judged by Radiance's own rules: a negative radius turns a
//! surface inside out (a warning), degenerate surfaces are dropped with a warning,
//! polygons are measured as the face setup measures them (Newell's normal and
//! each vertex's distance from the plane), and a zero light direction is fatal.

use super::Lowering;
use crate::diagnostic::{self as codes, Diagnostic};
use crate::scene::ir::Vec3;
use crate::scene::syntax::Primitive;
use crate::source::Span;

impl Lowering<'_> {
    /// Radiance stops with "zero direction" when it sets up such a source.
    pub(super) fn zero_direction(&mut self, p: &Primitive, first: usize) {
        let span = real_span(p, first).to(real_span(p, first + 2));
        self.diags.push(
            Diagnostic::new(
                codes::E0203,
                span,
                format!(
                    "the direction of {} '{}' is the zero vector",
                    p.kind.text, p.name.text
                ),
            )
            .with_hint("give the direction the light travels toward, e.g. 0 0 -1"),
        );
    }

    pub(super) fn degenerate(&mut self, p: &Primitive, span: Span, why: &str) {
        self.diags.push(
            Diagnostic::new(
                codes::W0206,
                span,
                format!("{} '{}' is degenerate: {why}", p.kind.text, p.name.text),
            )
            .with_hint("Radiance drops degenerate surfaces with a warning; fix or remove it"),
        );
    }

    pub(super) fn check_radius(&mut self, p: &Primitive, radius: f64, index: usize) {
        let span = real_span(p, index);
        if radius == 0.0 {
            self.degenerate(p, span, "its radius is zero");
        } else if radius < 0.0 {
            let flipped = match p.kind.text.as_str() {
                "sphere" => "bubble",
                "bubble" => "sphere",
                "cylinder" => "tube",
                "tube" => "cylinder",
                _ => "its inside-out twin",
            };
            self.diags.push(
                Diagnostic::new(
                    codes::W0202,
                    span,
                    format!("negative radius: Radiance reads this {} as a {flipped}", p.kind.text),
                )
                .with_hint(format!("write a positive radius, or use the type '{flipped}' if the normals should point inward")),
            );
        }
    }

    pub(super) fn check_axis(&mut self, p: &Primitive, p0: Vec3, p1: Vec3) {
        if p0 == p1 {
            let span = real_span(p, 0).to(real_span(p, 5));
            self.degenerate(p, span, "both end points are the same, so it has no axis");
        }
    }

    pub(super) fn check_cone_radii(&mut self, p: &Primitive, r0: f64, r1: f64) {
        let span = real_span(p, 6).to(real_span(p, 7));
        if (r0 < 0.0) != (r1 < 0.0) && r0 != 0.0 && r1 != 0.0 {
            self.degenerate(p, span, "its radii have opposite signs");
        } else if r0 == 0.0 && r1 == 0.0 {
            self.degenerate(p, span, "both radii are zero");
        } else if r0 == r1 {
            self.diags.push(
                Diagnostic::new(
                    codes::W0205,
                    span,
                    format!("{} '{}' has equal radii", p.kind.text, p.name.text),
                )
                .with_hint(if p.kind.text == "cone" {
                    "use a cylinder: Radiance converts it anyway"
                } else {
                    "use a tube: Radiance converts it anyway"
                }),
            );
        } else if r0 < 0.0 && r1 < 0.0 {
            self.diags.push(Diagnostic::new(
                codes::W0202,
                span,
                format!(
                    "negative radii: Radiance reads this {} inside out",
                    p.kind.text
                ),
            ));
        }
    }

    pub(super) fn check_ring_radii(&mut self, p: &Primitive, r0: f64, r1: f64) {
        let span = real_span(p, 6).to(real_span(p, 7));
        if r0 < 0.0 || r1 < 0.0 || r0 == r1 {
            self.degenerate(p, span, "its radii must be >= 0 and differ");
        }
    }

    /// Zero area and non-planarity, judged as Radiance's face setup does: the normal
    /// from Newell's method, and each vertex's distance from the plane.
    pub(super) fn check_polygon(&mut self, p: &Primitive, vertices: &[Vec3]) {
        if vertices.len() < 3 {
            return;
        }
        let n = newell_normal(vertices);
        let area2 = norm(n);
        let span = p.reals.span_all();
        if area2 == 0.0 || !area2.is_finite() {
            self.diags.push(
                Diagnostic::new(
                    codes::W0204,
                    span,
                    format!(
                        "polygon '{}' has zero area (its vertices are collinear or coincide)",
                        p.name.text
                    ),
                )
                .with_hint("Radiance drops it with a warning"),
            );
            return;
        }
        let unit = [n[0] / area2, n[1] / area2, n[2] / area2];
        let d0 = dot(unit, vertices[0]);
        let size = vertices
            .iter()
            .flat_map(|v| v.iter())
            .fold(0.0f64, |m, c| m.max(c.abs()))
            .max(1.0);
        if let Some((i, _)) = vertices
            .iter()
            .enumerate()
            .find(|(_, v)| (dot(unit, **v) - d0).abs() > 1e-5 * size)
        {
            let s = real_span(p, i * 3).to(real_span(p, i * 3 + 2));
            self.diags.push(
                Diagnostic::new(
                    codes::W0203,
                    s,
                    format!(
                        "vertex {} of polygon '{}' is out of the polygon's plane",
                        i + 1,
                        p.name.text
                    ),
                )
                .with_hint("split the polygon into planar pieces (triangles are always planar)"),
            );
        }
    }
}

trait SpanAll {
    fn span_all(&self) -> Span;
}

impl SpanAll for crate::scene::syntax::ArgGroup<crate::scene::syntax::Real> {
    fn span_all(&self) -> Span {
        match (self.items.first(), self.items.last()) {
            (Some(a), Some(b)) => a.span.to(b.span),
            _ => self.count_span,
        }
    }
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// Newell's method: twice the vector area of a (possibly non-planar) polygon.
fn newell_normal(v: &[Vec3]) -> Vec3 {
    let mut n = [0.0; 3];
    for (i, a) in v.iter().enumerate() {
        let b = v[(i + 1) % v.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

pub(super) fn real_span(p: &Primitive, i: usize) -> Span {
    p.reals
        .items
        .get(i)
        .map(|r| r.span)
        .unwrap_or(p.reals.count_span)
}

#[cfg(test)]
mod tests {
    use crate::scene::ir::PrimKind;
    use crate::scene::lower::tests::{PAINT, check};

    #[test]
    fn geometry() {
        let (scene, codes) = check(&format!("{PAINT}paint sphere s 0 0 4 0 0 0 -1\n"));
        assert_eq!(codes, vec!["W0202"]);
        assert!(matches!(scene.prims[1].kind, PrimKind::Bubble { radius, .. } if radius == 1.0));
        assert_eq!(
            check(&format!("{PAINT}paint sphere s 0 0 4 0 0 0 0\n")).1,
            vec!["W0206"]
        );
        assert_eq!(
            check(&format!("{PAINT}paint cone c 0 0 8 0 0 0 0 0 0 1 .5\n")).1,
            vec!["W0206"]
        );
        assert_eq!(
            check(&format!("{PAINT}paint polygon p 0 0 9 0 0 0 1 1 1 2 2 2\n")).1,
            vec!["W0204"]
        );
        assert_eq!(
            check(&format!(
                "{PAINT}paint polygon p 0 0 12 0 0 0 1 0 0 1 1 0 0 1 1\n"
            ))
            .1,
            vec!["W0203"]
        );
    }
}
