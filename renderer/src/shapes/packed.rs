//! Polygons of three and four vertices packed for the BVH's inner loop ([`Triangle`],
//! [`Quad`]): [`Polygon`]'s plane, inside test and tolerances, with the edge loop
//! unrolled, the vertices stored by projected axis, and the bounding-box check computed
//! only for points found inside. Every operation is the polygon's, in the same order on
//! the same numbers, so each hit or miss is the polygon's bit for bit, whatever the
//! shape (convex, concave, a bow-tie): shared edges and vertices behave exactly as
//! there.
//!
//! One shortcut, for quads whose projection is a rectangle with sides along the
//! projection's axes (genbox's boxes, most rooms): a point strictly inside it is inside
//! by the crossing test too, whatever the tolerances, so the edge loop is skipped. In
//! such a rectangle each edge keeps one coordinate: a horizontal edge (its `y` the
//! same at both ends, its ends on both sides of the point in `x`) finds the point on
//! it or counts nothing, as its ends are on the same side in `y`; both vertical edges
//! span the point's `y`, the one right of it counts a crossing and the one left of it
//! finds the point on it or counts nothing. So the test answers "inside": on an edge,
//! or one crossing.

use super::polygon::{Polygon, crossing, projection};
use crate::math::{Bounds, FTINY, Vec3};
use crate::ray::{Ray, ShapeHit};

/// A polygon of `N` vertices. The plane comes first: most tests end there.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct PackedPolygon<const N: usize> {
    normal: Vec3,
    offset: f64,
    /// The vertices' coordinates along the projection's x and y axes and along the axis
    /// it drops (`axis`).
    x: [f64; N],
    y: [f64; N],
    /// The lowest and highest vertex coordinate along `axis`: all the extent needs
    /// of them (8 bytes less per triangle than the three, in memory-bound scenes).
    z: [f64; 2],
    axis: u8,
    /// The projection is a rectangle along its axes, vertices 0 and 2 at opposite
    /// corners (see the module's documentation).
    rectangle: bool,
}

pub type Triangle = PackedPolygon<3>;
pub type Quad = PackedPolygon<4>;

impl<const N: usize> PackedPolygon<N> {
    /// The packing of a polygon of `N` vertices, `None` for other polygons.
    pub fn of(p: &Polygon) -> Option<PackedPolygon<N>> {
        let v: &[Vec3; N] = p.vertices.as_slice().try_into().ok()?;
        let (xi, yi) = projection(p.axis());
        // The polygon's axis, or for a corrupt one (a loaded file's) the axis its own
        // projection drops.
        let axis = 3 - xi - yi;
        let (x, y) = (v.map(|v| v[xi]), v.map(|v| v[yi]));
        Some(PackedPolygon {
            normal: p.normal,
            offset: p.offset,
            x,
            y,
            z: z_range(v.map(|v| v[axis])),
            axis: axis as u8,
            rectangle: is_rectangle(&x, &y),
        })
    }

    /// [`Polygon::intersect_within`].
    #[inline]
    pub fn intersect_within(&self, ray: &Ray, tmax: f64) -> Option<ShapeHit> {
        let (t, rod) = self.plane_hit(ray)?;
        if t > tmax {
            return None;
        }
        let p = ray.at(t);
        let axis = usize::from(self.axis);
        let (xi, yi) = projection(axis);
        let q = Vec3::new(p[xi], p[yi], p[axis]);
        let inside = (N == 4 && self.rectangle && self.strictly_inside_rectangle(q.x, q.y))
            || self.contains(q.x, q.y);
        (inside && self.extent().contains(q)).then_some(ShapeHit {
            t,
            normal: self.normal,
            rod,
            sub: 0,
        })
    }

    /// Where `ray` meets the polygon's plane ahead (beyond FTINY), and `rod`; `None`
    /// where [`PackedPolygon::intersect_within`] stops at the plane, whatever its limit.
    #[inline(always)]
    pub fn plane_hit(&self, ray: &Ray) -> Option<(f64, f64)> {
        let rod = -ray.dir.dot(self.normal);
        if rod.abs() <= FTINY {
            return None;
        }
        let t = self.plane_gap(ray.org) / rod;
        // `t <= FTINY || !t.is_finite()` in two comparisons: beyond FTINY, t is no NaN.
        let ahead = t > FTINY && t < f64::INFINITY;
        ahead.then_some((t, rod))
    }

    /// How far `org` lies off the plane (times the normal's length), as
    /// [`PackedPolygon::plane_hit`] computes it; with the normal, all a caller needs to
    /// know for which rays from `org` that test stops at the plane.
    #[inline(always)]
    pub fn plane_gap(&self, org: Vec3) -> f64 {
        org.dot(self.normal) - self.offset
    }

    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// [`Polygon::contains`] for projected coordinates, its edges `N-1 -> 0`, `0 -> 1`,
    /// ... in its order.
    #[inline]
    fn contains(&self, x: f64, y: f64) -> bool {
        let v = |i: usize| (self.x[i], self.y[i]);
        let mut odd = false;
        let mut a = N - 1;
        for b in 0..N {
            if crossing(v(a), v(b), x, y, &mut odd) {
                return true;
            }
            a = b;
        }
        odd
    }

    /// Strictly inside the rectangle between vertices 0 and 2.
    #[inline]
    fn strictly_inside_rectangle(&self, x: f64, y: f64) -> bool {
        let (x0, x1) = (self.x[0].min(self.x[2]), self.x[0].max(self.x[2]));
        let (y0, y1) = (self.y[0].min(self.y[2]), self.y[0].max(self.y[2]));
        x0 < x && x < x1 && y0 < y && y < y1
    }

    /// The polygon's padded box, its axes in the projection's order (padding depends
    /// on the largest coordinate only, so the order does not change it).
    fn extent(&self) -> Bounds {
        let b = (0..N)
            .map(|i| Vec3::new(self.x[i], self.y[i], self.z[0]))
            .fold(Bounds::EMPTY, |b, v| b.union(Bounds::point(v)));
        Bounds {
            min: Vec3::new(b.min.x, b.min.y, self.z[0]),
            max: Vec3::new(b.max.x, b.max.y, self.z[1]),
        }
        .padded()
    }
}

/// The lowest and highest of `z`, as the vertices' bounding box finds them (the same
/// fold, so the same answer also for a NaN).
fn z_range<const N: usize>(z: [f64; N]) -> [f64; 2] {
    let b = z.iter().fold(Bounds::EMPTY, |b, &z| {
        b.union(Bounds::point(Vec3::splat(z)))
    });
    [b.min.x, b.max.x]
}

/// Four finite vertices making a rectangle along the axes: every edge changes exactly
/// one coordinate, and vertices 0 and 2, and 1 and 3, differ in both (opposite corners,
/// so the four corners are distinct and visited in order around it).
fn is_rectangle<const N: usize>(x: &[f64; N], y: &[f64; N]) -> bool {
    if N != 4 || !x.iter().chain(y).all(|c| c.is_finite()) {
        return false;
    }
    let edges_along_axes = (0..4).all(|b| {
        let a = (b + 3) % 4;
        (x[a] == x[b]) != (y[a] == y[b])
    });
    edges_along_axes && x[0] != x[2] && y[0] != y[2] && x[1] != x[3] && y[1] != y[3]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sizes the memory-bound scenes depend on (a triangle was 112 bytes with all
    /// three coordinates along its axis).
    #[test]
    fn packed_sizes() {
        assert_eq!(std::mem::size_of::<Triangle>(), 104);
        assert_eq!(std::mem::size_of::<Quad>(), 120);
    }
    use crate::random::uniform;

    /// The packed polygon and the polygon it packs give the same hit or miss and the
    /// same numbers for each ray, with three limits. Returns how many rays hit.
    fn compare<const N: usize>(p: &Polygon, rays: &[Ray], what: &str) -> usize {
        let packed = PackedPolygon::<N>::of(p).expect("N vertices");
        let mut hits = 0;
        for (n, ray) in rays.iter().enumerate() {
            for tmax in [f64::INFINITY, 1.0, 40.0] {
                assert_eq!(
                    packed.intersect_within(ray, tmax),
                    p.intersect_within(ray, tmax),
                    "{what}, ray {n}: {ray:?}"
                );
            }
            hits += usize::from(p.intersect(ray).is_some());
        }
        hits
    }

    /// Rays from random origins (from `seed`) aimed at `targets`.
    fn aimed_at(targets: &[Vec3], seed: u64) -> Vec<Ray> {
        let r = |j: u64| uniform(seed, j) * 2.0 - 1.0;
        (0..targets.len() as u64)
            .zip(targets)
            .map(|(n, &target)| {
                let org = Vec3::new(r(1000 + n), r(2000 + n), r(3000 + n)) * 30.0;
                Ray::new(org, (target - org).normalize())
            })
            .collect()
    }

    /// Vertices, points along every edge (ends, quarters, thirds, midpoints), the
    /// centroid, points just beyond a vertex and between non-adjacent vertices.
    fn targets(v: &[Vec3]) -> Vec<Vec3> {
        let mut t = v.to_vec();
        let n = v.len();
        for a in 0..n {
            for b in 0..n {
                if a == b {
                    continue;
                }
                for f in [0.0, 0.25, 0.5, 1.0 / 3.0, 1.0, 1.0 + 1e-7, -1e-7] {
                    t.push(v[a] + (v[b] - v[a]) * f);
                }
            }
        }
        t.push(v.iter().copied().sum::<Vec3>() / n as f64);
        t.push(v[0] * 1.5 - v[1] * 0.5);
        t
    }

    /// Against the polygon it packs, on rays aimed at vertices, edge points and random
    /// points of random triangles, in every orientation.
    #[test]
    fn triangles_decide_as_the_polygon() {
        let (mut checked, mut hits) = (0, 0);
        for k in 0..400u64 {
            let r = |j: u64| uniform(k, j) * 2.0 - 1.0;
            let v: Vec<Vec3> = (0..3)
                .map(|j| Vec3::new(r(3 * j), r(3 * j + 1), r(3 * j + 2)) * 10.0)
                .collect();
            let Some(p) = Polygon::new(v.clone()) else {
                continue;
            };
            let rays = aimed_at(&targets(&v), k);
            checked += rays.len();
            hits += compare::<3>(&p, &rays, &format!("triangle {k}"));
        }
        assert!(
            checked > 15000 && hits > checked / 3,
            "{hits} hits of {checked}"
        );
    }

    /// Random quads: planar (a random triangle's plane), convex, concave, bow-ties, and
    /// non-planar ones (a polygon's plane is Newell's, its inside test projects).
    #[test]
    fn quads_decide_as_the_polygon() {
        let (mut checked, mut hits) = (0, 0);
        for k in 0..600u64 {
            let r = |j: u64| uniform(k + 7919, j) * 2.0 - 1.0;
            let (o, u, w) = (
                Vec3::new(r(0), r(1), r(2)) * 10.0,
                Vec3::new(r(3), r(4), r(5)),
                Vec3::new(r(6), r(7), r(8)),
            );
            let planar = k % 3 != 0;
            let v: Vec<Vec3> = (0..4u64)
                .map(|j| {
                    let (a, b) = (r(10 + 2 * j) * 8.0, r(11 + 2 * j) * 8.0);
                    let off = if planar {
                        Vec3::ZERO
                    } else {
                        u.cross(w) * r(20 + j)
                    };
                    o + u * a + w * b + off
                })
                .collect();
            let Some(p) = Polygon::new(v.clone()) else {
                continue;
            };
            let rays = aimed_at(&targets(&v), k);
            checked += rays.len();
            hits += compare::<4>(&p, &rays, &format!("quad {k}"));
        }
        assert!(
            checked > 40000 && hits > checked / 4,
            "{hits} hits of {checked}"
        );
    }

    /// Axis-aligned rectangles (as genbox writes them) and a bow-tie, an arrowhead and
    /// a seam, aimed at from inside, along the planes' axes and grazing them.
    #[test]
    fn rectangles_and_odd_quads_decide_as_the_polygon() {
        let quads: [[(f64, f64); 4]; 5] = [
            [(0.0, 0.0), (12.0, 0.0), (12.0, 16.0), (0.0, 16.0)],
            [(12.0, 16.0), (12.0, 0.0), (0.0, 0.0), (0.0, 16.0)],
            [(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0)],
            [(0.0, 0.0), (2.0, 1.0), (0.0, 2.0), (0.5, 1.0)],
            [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, 1.0)],
        ];
        let (mut checked, mut hits) = (0, 0);
        for (k, q) in quads.iter().enumerate() {
            for axis in 0..3 {
                let v: Vec<Vec3> = q
                    .iter()
                    .map(|&(a, b)| {
                        let mut v = Vec3::splat(3.0);
                        v[(axis + 1) % 3] = a;
                        v[(axis + 2) % 3] = b;
                        v
                    })
                    .collect();
                let Some(p) = Polygon::new(v.clone()) else {
                    continue;
                };
                let t = targets(&v);
                let mut rays = aimed_at(&t, (k * 3 + axis) as u64);
                // Grazing: from 20 units away along the plane, lifted off it by a little
                // (parallel within FTINY: a miss) to a lot, aimed at every target.
                for &target in &t {
                    for lift in [0.0, 1e-9, 1e-5, 1e-2, 1.0] {
                        let mut org = target;
                        org[(axis + 1) % 3] -= 20.0;
                        org[axis] += lift;
                        rays.push(Ray::new(org, (target - org).normalize()));
                    }
                }
                checked += rays.len();
                hits += compare::<4>(&p, &rays, &format!("rectangle {k} across axis {axis}"));
            }
        }
        assert!(
            checked > 1000 && hits > checked / 4,
            "{hits} hits of {checked}"
        );
    }

    /// The rectangle shortcut on axis-aligned rectangles near and far from the origin
    /// (where the crossing test's tolerances exceed the rectangle), in both orientations
    /// and every plane: rays at random points in and around them and at points within
    /// the tolerances of their edges, from inside and outside.
    #[test]
    fn rectangles_near_and_far_decide_as_the_polygon() {
        let (mut checked, mut hits) = (0, 0);
        for k in 0..240u64 {
            let r = |j: u64| uniform(k + 104729, j);
            let far = [0.0, 3.0, 1e3, 2.5e5, -1e6][(k % 5) as usize];
            let (w, h) = (0.01 + r(0) * 10.0, 0.01 + r(1) * 10.0);
            let (x0, y0) = (far + (r(2) - 0.5) * 20.0, -far + (r(3) - 0.5) * 20.0);
            let corners = if k % 2 == 0 {
                [(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)]
            } else {
                [(x0, y0 + h), (x0 + w, y0 + h), (x0 + w, y0), (x0, y0)]
            };
            let axis = (k / 2 % 3) as usize;
            let depth = (r(4) - 0.5) * 10.0;
            let at = |a: f64, b: f64, c: f64| {
                let mut v = Vec3::ZERO;
                v[(axis + 1) % 3] = a;
                v[(axis + 2) % 3] = b;
                v[axis] = c;
                v
            };
            let v: Vec<Vec3> = corners.iter().map(|&(a, b)| at(a, b, depth)).collect();
            let p = Polygon::new(v.clone()).expect("a rectangle");
            assert!(Quad::of(&p).expect("four vertices").rectangle);
            let tol = 1e-6 * (x0.abs() + y0.abs() + w + h);
            let mut targets = targets(&v);
            for j in 0..60u64 {
                let (a, b) = (r(10 + 2 * j) * 1.4 - 0.2, r(11 + 2 * j) * 1.4 - 0.2);
                targets.push(at(x0 + a * w, y0 + b * h, depth));
                // Within the tolerances of an edge, on either side.
                let d = (r(200 + j) - 0.5) * 4.0 * tol;
                targets.push(at(x0 + d, y0 + b * h, depth));
                targets.push(at(x0 + a * w, y0 + h + d, depth));
            }
            let mut rays = aimed_at(&targets, k);
            for &target in &targets[..20] {
                let org = target + at(r(500) - 0.5, r(501) - 0.5, 0.0) * 0.5;
                rays.push(Ray::new(org, (target - org).normalize()));
            }
            checked += rays.len();
            hits += compare::<4>(&p, &rays, &format!("rectangle {k} at {far}"));
        }
        assert!(
            checked > 40000 && hits > checked / 4,
            "{hits} hits of {checked}"
        );
    }

    #[test]
    fn rectangles_are_recognised() {
        let quad = |c: [(f64, f64); 4]| is_rectangle(&c.map(|c| c.0), &c.map(|c| c.1));
        assert!(quad([(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]));
        assert!(quad([(0.0, 0.0), (0.0, 1.0), (2.0, 1.0), (2.0, 0.0)]));
        // A bow-tie on the same corners, a rotated square, a trapezoid, and a
        // quad doubling back on one edge.
        assert!(!quad([(0.0, 0.0), (2.0, 1.0), (2.0, 0.0), (0.0, 1.0)]));
        assert!(!quad([(1.0, 0.0), (2.0, 1.0), (1.0, 2.0), (0.0, 1.0)]));
        assert!(!quad([(0.0, 0.0), (3.0, 0.0), (2.0, 1.0), (0.0, 1.0)]));
        assert!(!quad([(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (2.0, 0.0)]));
        assert!(!quad([(0.0, 0.0), (f64::NAN, 0.0), (2.0, 1.0), (0.0, 1.0)]));
        assert!(!is_rectangle(&[0.0, 1.0, 1.0], &[0.0, 0.0, 1.0]));
        // What packing finds for a genbox face.
        let face = [(0.0, 0.0), (12.0, 0.0), (12.0, 16.0), (0.0, 16.0)];
        let p = Polygon::new(face.map(|(a, b)| Vec3::new(a, 3.0, b)).to_vec()).unwrap();
        assert!(Quad::of(&p).unwrap().rectangle);
    }

    #[test]
    fn only_their_vertex_count() {
        let square =
            Polygon::new(vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]).unwrap();
        assert!(Triangle::of(&square).is_none());
        assert!(Quad::of(&square).is_some());
        let tri = Polygon::new(vec![Vec3::ZERO, Vec3::X, Vec3::Y]).unwrap();
        assert!(Quad::of(&tri).is_none());
    }
}
