//! Where a source is: the shape each surface type gives its source, and the geometry
//! tests (parallelogram, convex) that decide how it is partitioned.

use super::*;
use crate::math::{FTINY, Vec3, normalize, perpendicular};

impl SourceShape {
    pub fn sphere(center: Vec3, radius: f64) -> SourceShape {
        SourceShape::Sphere { center, radius }
    }

    /// A polygon source as `fsetsrc` sets it up: centred on the vertex mean, with exact
    /// half-extents for parallelograms and triangles, otherwise a square of equal area.
    pub fn polygon(vertices: &[Vec3], normal: Vec3, area: f64) -> SourceShape {
        let n = vertices.len() as f64;
        let center = vertices.iter().copied().sum::<Vec3>() / n;
        let (u, v) = match vertices {
            [a, b, _, d] => (0.5 * (*b - *a), 0.5 * (*d - *a)),
            [_, _, _] => {
                // Aim U along the edge nearest the centre, scaled to that distance.
                let edges = [(2usize, 0usize), (0, 1), (1, 2)];
                let (mut near0, mut dmin) = (2usize, dist2_line(center, vertices[2], vertices[0]));
                for &(i, j) in &edges[1..] {
                    let d = dist2_line(center, vertices[i], vertices[j]);
                    if d < dmin {
                        near0 = i;
                        dmin = d;
                    }
                }
                let i = (near0 + 1) % 3;
                let mut u = vertices[i] - vertices[near0];
                normalize(&mut u);
                let u = u * dmin.sqrt();
                (u, normal.cross(u))
            }
            _ => square_extents(normal, area),
        };
        SourceShape::Flat {
            center,
            normal,
            area,
            u,
            v,
            circular: false,
            parallelogram: is_parallelogram(vertices),
            convex_outline: if !is_parallelogram(vertices) && is_convex(vertices, normal) {
                vertices.to_vec()
            } else {
                Vec::new()
            },
            radius: vertices
                .iter()
                .map(|p| p.distance(center))
                .fold(0.0, f64::max),
        }
    }

    pub fn cylinder(p0: Vec3, p1: Vec3, radius: f64) -> SourceShape {
        SourceShape::Cylinder {
            center: 0.5 * (p0 + p1),
            half_axis: 0.5 * (p1 - p0),
            radius,
        }
    }

    pub fn disk(center: Vec3, normal: Vec3, radius: f64) -> SourceShape {
        let area = std::f64::consts::PI * radius * radius;
        let (u, v) = square_extents(normal, area);
        SourceShape::Flat {
            center,
            normal,
            area,
            u,
            v,
            circular: true,
            parallelogram: false,
            convex_outline: Vec::new(),
            radius,
        }
    }

    /// A distant source of full angle `angle_deg` degrees toward `direction`. Its solid
    /// angle is `cap_solid_angle`'s, the form rtrace computes it in.
    pub fn distant(mut direction: Vec3, angle_deg: f64) -> Option<SourceShape> {
        if normalize(&mut direction) == 0.0 {
            return None;
        }
        let theta = (std::f64::consts::PI / 180.0 / 2.0) * angle_deg;
        if theta <= FTINY {
            return None;
        }
        Some(SourceShape::Distant {
            direction,
            solid_angle: cap_solid_angle(theta.cos()),
        })
    }

    /// The centre and bounding radius (for `glow` proximity).
    pub(crate) fn center_radius(&self) -> (Vec3, f64) {
        match self {
            SourceShape::Sphere { center, radius } => (*center, *radius),
            SourceShape::Flat { center, radius, .. } => (*center, *radius),
            SourceShape::Distant {
                direction,
                solid_angle,
            } => (*direction, (solid_angle / std::f64::consts::PI).sqrt()),
            SourceShape::Cylinder {
                center, half_axis, ..
            } => (*center, half_axis.length()),
        }
    }
}

/// Whether four vertices form a parallelogram (opposite corners share a midpoint, to
/// rounding).
pub(super) fn is_parallelogram(vertices: &[Vec3]) -> bool {
    let [a, b, c, d] = vertices else {
        return false;
    };
    let size = (*c - *a).length().max((*d - *b).length());
    ((*a + *c) - (*b + *d)).length() <= 1e-9 * size
}

/// Whether a planar polygon is convex: every corner turns the same way about
/// `normal` (none turning the other way, to rounding).
pub(super) fn is_convex(vertices: &[Vec3], normal: Vec3) -> bool {
    let n = vertices.len();
    if n < 3 {
        return false;
    }
    let (mut pos, mut neg) = (false, false);
    let size = vertices
        .iter()
        .map(|v| v.distance(vertices[0]))
        .fold(0.0, f64::max);
    for i in 0..n {
        let (a, b, c) = (vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]);
        let turn = (b - a).cross(c - b).dot(normal);
        if turn > 1e-12 * size * size {
            pos = true;
        } else if turn < -1e-12 * size * size {
            neg = true;
        }
    }
    pos != neg
}

/// Half-extents of a square of `area` in the plane of `normal` (`setflatss`, without
/// randomized orientation).
pub(super) fn square_extents(normal: Vec3, area: f64) -> (Vec3, Vec3) {
    let u = perpendicular(normal).unwrap_or(Vec3::X) * (0.5 * area.sqrt());
    (u, normal.cross(u))
}

/// Squared distance from `p` to the line through `a` and `b`.
pub(super) fn dist2_line(p: Vec3, a: Vec3, b: Vec3) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let w = p - a;
    if len2 == 0.0 {
        return w.length_squared();
    }
    let along = w.dot(d);
    w.length_squared() - along * along / len2
}
