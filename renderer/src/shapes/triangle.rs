//! Three-vertex polygons packed for the BVH's inner loop: [`Polygon`]'s plane, inside
//! test and tolerances, with the edge loop unrolled, the vertices stored by projected
//! axis, and the bounding-box check computed only for points found inside. Every
//! operation is the polygon's, in the same order on the same numbers, so each hit or
//! miss is the polygon's bit for bit: shared edges and vertices behave exactly as there.

use super::polygon::{Polygon, crossing, projection};
use crate::math::{Bounds, FTINY, Vec3};
use crate::ray::{Ray, ShapeHit};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// The vertices' coordinates along the projection's x and y axes and along the axis
    /// it drops (`axis`).
    x: [f64; 3],
    y: [f64; 3],
    z: [f64; 3],
    normal: Vec3,
    offset: f64,
    axis: u8,
}

impl Triangle {
    /// The triangle of a three-vertex polygon, `None` for other polygons.
    pub fn of(p: &Polygon) -> Option<Triangle> {
        let [a, b, c] = p.vertices[..] else {
            return None;
        };
        let axis = p.axis();
        let (xi, yi) = projection(axis);
        Some(Triangle {
            x: [a[xi], b[xi], c[xi]],
            y: [a[yi], b[yi], c[yi]],
            z: [a[axis], b[axis], c[axis]],
            normal: p.normal,
            offset: p.offset,
            axis: axis as u8,
        })
    }

    /// [`Polygon::intersect_within`].
    #[inline]
    pub fn intersect_within(&self, ray: &Ray, tmax: f64) -> Option<ShapeHit> {
        let rod = -ray.dir.dot(self.normal);
        if rod.abs() <= FTINY {
            return None;
        }
        let t = (ray.org.dot(self.normal) - self.offset) / rod;
        if t <= FTINY || !t.is_finite() || t > tmax {
            return None;
        }
        let p = ray.at(t);
        let axis = usize::from(self.axis);
        let (xi, yi) = projection(axis);
        let q = Vec3::new(p[xi], p[yi], p[axis]);
        (self.contains(q.x, q.y) && self.extent().contains(q)).then_some(ShapeHit {
            t,
            normal: self.normal,
            rod,
        })
    }

    /// [`Polygon::contains`] for projected coordinates, its edges `c->a`, `a->b`, `b->c`
    /// in its order.
    #[inline]
    fn contains(&self, x: f64, y: f64) -> bool {
        let v = |i: usize| (self.x[i], self.y[i]);
        let mut odd = false;
        if crossing(v(2), v(0), x, y, &mut odd)
            || crossing(v(0), v(1), x, y, &mut odd)
            || crossing(v(1), v(2), x, y, &mut odd)
        {
            return true;
        }
        odd
    }

    /// The polygon's padded box, its axes in the projection's order (padding depends
    /// on the largest coordinate only, so the order does not change it).
    fn extent(&self) -> Bounds {
        (0..3)
            .map(|i| Vec3::new(self.x[i], self.y[i], self.z[i]))
            .fold(Bounds::EMPTY, |b, v| b.union(Bounds::point(v)))
            .padded()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::uniform;

    /// Against the polygon it packs, on rays aimed at vertices, edge points and random
    /// points of a fan of triangles sharing edges, in every orientation: the same hit
    /// or miss and the same numbers.
    #[test]
    fn decides_as_the_polygon() {
        let (mut checked, mut hits) = (0, 0);
        for k in 0..400u64 {
            let r = |j: u64| uniform(k, j) * 2.0 - 1.0;
            let v: Vec<Vec3> = (0..3)
                .map(|j| Vec3::new(r(3 * j), r(3 * j + 1), r(3 * j + 2)) * 10.0)
                .collect();
            let Some(p) = Polygon::new(v.clone()) else {
                continue;
            };
            let tri = Triangle::of(&p).expect("three vertices");
            let mut targets = v.clone();
            for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                for f in [0.0, 0.25, 0.5, 1.0 / 3.0, 1.0] {
                    targets.push(v[a] + (v[b] - v[a]) * f);
                }
            }
            targets.push((v[0] + v[1] + v[2]) / 3.0);
            targets.push(v[0] * 1.5 - v[1] * 0.5);
            for (n, target) in targets.into_iter().enumerate() {
                let org = Vec3::new(r(50 + n as u64), r(90 + n as u64), r(130 + n as u64)) * 30.0;
                let ray = Ray::new(org, (target - org).normalize());
                for tmax in [f64::INFINITY, 1.0, 40.0] {
                    assert_eq!(
                        tri.intersect_within(&ray, tmax),
                        p.intersect_within(&ray, tmax),
                        "triangle {k}, target {n}"
                    );
                }
                checked += 1;
                hits += usize::from(p.intersect(&ray).is_some());
            }
        }
        assert!(
            checked > 5000 && hits > checked / 2,
            "{hits} hits of {checked}"
        );
    }

    #[test]
    fn only_three_vertices() {
        let square =
            Polygon::new(vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]).unwrap();
        assert!(Triangle::of(&square).is_none());
    }
}
