//! Surfaces: exact intersection with Radiance's acceptance rules (`t > FTINY`, rays
//! parallel to a plane within `FTINY` miss) and its normals and sides.

pub mod cone;
pub mod mesh;
pub mod packed;
pub mod polygon;
pub mod ring;
pub mod sphere;

pub use cone::Cone;
pub use mesh::{MeshGeometry, MeshShape, MeshSurface};
pub use packed::{PackedPolygon, Quad, Triangle};
pub use polygon::Polygon;
pub use ring::Ring;
pub use sphere::{PackedSphere, Sphere};

use crate::math::{Bounds, FTINY};
use crate::ray::{Ray, ShapeHit};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Shape {
    Sphere(Sphere),
    Polygon(Polygon),
    Ring(Ring),
    Cone(Cone),
    Mesh(MeshShape),
}

impl Shape {
    /// The nearest hit with `FTINY < t`, or `None`. Candidates farther than the current
    /// best are filtered by the caller (the BVH), which also breaks ties.
    pub fn intersect(&self, ray: &Ray) -> Option<ShapeHit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray),
            Shape::Polygon(p) => p.intersect(ray),
            Shape::Ring(r) => r.intersect(ray),
            Shape::Cone(c) => c.intersect(ray),
            Shape::Mesh(m) => m.intersect_within(ray, f64::INFINITY),
        }
    }

    /// `intersect` for hits no farther than `tmax`.
    pub fn intersect_within(&self, ray: &Ray, tmax: f64) -> Option<ShapeHit> {
        match self {
            Shape::Sphere(s) => s.intersect_within(ray, tmax),
            Shape::Polygon(p) => p.intersect_within(ray, tmax),
            Shape::Ring(r) => r.intersect(ray).filter(|h| h.t <= tmax),
            Shape::Cone(c) => c.intersect(ray).filter(|h| h.t <= tmax),
            Shape::Mesh(m) => m.intersect_within(ray, tmax),
        }
    }

    pub fn bounds(&self) -> Bounds {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Polygon(p) => p.bounds(),
            Shape::Ring(r) => r.bounds(),
            Shape::Cone(c) => c.bounds(),
            Shape::Mesh(m) => m.bounds(),
        }
    }

    /// Flat surfaces get a source-size term in the specular highlight (`SP_FLAT` in
    /// Radiance's normal.c) and relay mirrored lengths.
    pub fn is_flat(&self) -> bool {
        matches!(self, Shape::Polygon(_) | Shape::Ring(_))
    }
}

/// Roots of `a t^2 + b t + c` in ascending order with Radiance's degenerate cases
/// (`src/common/zeroes.c`): linear when `|a| <= FTINY`, a double root when the
/// discriminant is within `FTINY^2` of zero.
pub fn quadratic(a: f64, b: f64, c: f64) -> Quadratic {
    if a.abs() <= FTINY {
        if b.abs() > FTINY {
            return Quadratic::One(-c / b);
        }
        return Quadratic::None;
    }
    let hb = 0.5 * b;
    let disc = hb * hb - a * c;
    if disc < -FTINY * FTINY || disc.is_nan() {
        return Quadratic::None;
    }
    if disc <= FTINY * FTINY {
        return Quadratic::One(-hb / a);
    }
    // The stable form: no cancellation between -hb and the root.
    let q = -(hb + hb.signum() * disc.sqrt());
    let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Quadratic::Two(r0.min(r1), r0.max(r1))
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Quadratic {
    None,
    One(f64),
    Two(f64, f64),
}

impl Quadratic {
    /// The roots in ascending order, each with its index (Radiance's `i`, used to tell the
    /// entering root from the leaving one).
    pub fn roots(self) -> impl Iterator<Item = (usize, f64)> {
        let v: [Option<f64>; 2] = match self {
            Quadratic::None => [None, None],
            Quadratic::One(t) => [Some(t), None],
            Quadratic::Two(t0, t1) => [Some(t0), Some(t1)],
        };
        v.into_iter()
            .enumerate()
            .filter_map(|(i, t)| t.map(|t| (i, t)))
    }
}
