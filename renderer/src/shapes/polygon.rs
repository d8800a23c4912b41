//! Polygons (`src/common/face.c`, `src/rt/o_face.c`): the plane from Newell's normal
//! and the mean vertex offset, rays within `FTINY` of parallel miss, and a crossing-number
//! inside test in the plane's dominant projection that counts points on an edge as
//! inside. Convex, concave and seamed polygons all work.

use crate::math::{Bounds, FTINY, Vec3, normalize};
use crate::ray::{Ray, ShapeHit};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Polygon {
    pub vertices: Vec<Vec3>,
    pub normal: Vec3,
    /// Plane offset: `normal . p` for points in the plane.
    pub offset: f64,
    pub area: f64,
    /// The axis the normal is most aligned with; the inside test drops it.
    axis: usize,
    /// The vertex mean.
    center: Vec3,
    /// Bounding box grown by `FTINY` (and rounding): hits outside it are refused.
    extent: Bounds,
}

/// `a` and `b` equal within `FTINY` relative (Radiance's `FRELEQ`).
fn rel_eq(a: f64, b: f64) -> bool {
    (a - b).abs() <= FTINY * 0.5 * (a.abs() + b.abs())
}

/// The two axes kept by the projection that drops `axis`.
#[inline(always)]
pub(crate) fn projection(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    }
}

/// One edge `a -> b` of the crossing-number test of point `(x, y)` (`inface`):
/// true when the point lies on the edge (inside, whatever the other edges say),
/// otherwise flips `odd` when the edge crosses the ray from the point along +x.
#[inline(always)]
pub(crate) fn crossing(a: (f64, f64), b: (f64, f64), x: f64, y: f64, odd: &mut bool) -> bool {
    let ((ax, ay), (bx, by)) = (a, b);
    // A horizontal edge through the point that spans it.
    if rel_eq(ay, y) && rel_eq(by, y) && ((ax > x) != (bx > x)) {
        return true;
    }
    if (ay > y) == (by > y) {
        return false;
    }
    match u8::from(ax > x) + u8::from(bx > x) {
        2 => *odd = !*odd,
        1 => {
            // Which side of the edge the point is on, from the two products of the
            // edge-to-point offsets; equal products mean it lies on the edge.
            let pa = (ay - y) * (bx - x);
            let pb = (ax - x) * (by - y);
            if rel_eq(pa, pb) {
                return true;
            }
            if (by > ay) != (pa > pb) {
                *odd = !*odd;
            }
        }
        _ => {
            if rel_eq(ax, x) && rel_eq(bx, x) {
                return true;
            }
        }
    }
    false
}

impl Polygon {
    /// `None` for fewer than 3 vertices or zero area (Radiance warns and the polygon is
    /// never hit).
    pub fn new(mut vertices: Vec<Vec3>) -> Option<Polygon> {
        if vertices.len() > 3
            && let (Some(first), Some(last)) = (vertices.first(), vertices.last())
            && first.distance_squared(*last) <= FTINY * FTINY
        {
            vertices.pop();
        }
        if vertices.len() < 3 {
            return None;
        }
        let v0 = vertices[0];
        let mut normal = Vec3::ZERO;
        let mut e1 = vertices[1] - v0;
        for v in &vertices[2..] {
            let e2 = *v - v0;
            normal += e1.cross(e2);
            e1 = e2;
        }
        let area = 0.5 * normalize(&mut normal);
        if area == 0.0 || !area.is_finite() {
            return None;
        }
        let offset = vertices.iter().map(|v| normal.dot(*v)).sum::<f64>() / vertices.len() as f64;
        let a = normal.abs();
        let mut axis = usize::from(a.y > a.x);
        if a.z > a[axis] {
            axis = 2;
        }
        let center = vertices.iter().copied().sum::<Vec3>() / vertices.len() as f64;
        let extent = vertices
            .iter()
            .fold(Bounds::EMPTY, |b, v| b.union(Bounds::point(*v)))
            .padded();
        Some(Polygon {
            vertices,
            normal,
            offset,
            area,
            axis,
            center,
            extent,
        })
    }

    pub fn intersect(&self, ray: &Ray) -> Option<ShapeHit> {
        self.intersect_within(ray, f64::INFINITY)
    }

    /// `intersect` for hits no farther than `tmax` (a farther hit is `None` before the
    /// inside test, which is the costly part).
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
        (self.extent.contains(p) && self.contains(p)).then_some(ShapeHit {
            t,
            normal: self.normal,
            rod,
            sub: 0,
        })
    }

    /// Whether a point of the plane lies inside (edges included), by counting the
    /// polygon's edges crossing the ray from `p` along the projection's +x axis, with
    /// Radiance's tolerances (`inface`).
    ///
    /// Those tolerances are relative to the coordinates' magnitude, so far from the
    /// origin they grow past the polygon's own size (a point 0.1 outside a polygon at
    /// x = 250000 counts as on its edge). Radiance's octree hides this by clipping hits
    /// to its cells; radc clips them to the polygon's bounding box (`extent`), which
    /// changes nothing near the origin.
    pub fn contains(&self, p: Vec3) -> bool {
        let (xi, yi) = projection(self.axis);
        let (x, y) = (p[xi], p[yi]);
        let Some(&last) = self.vertices.last() else {
            return false;
        };
        let mut odd = false;
        let mut a = last;
        for &b in &self.vertices {
            if crossing((a[xi], a[yi]), (b[xi], b[yi]), x, y, &mut odd) {
                return true;
            }
            a = b;
        }
        odd
    }

    /// The axis the inside test drops, for the triangle fast path.
    pub(crate) fn axis(&self) -> usize {
        self.axis
    }

    pub fn centroid(&self) -> Vec3 {
        self.center
    }

    pub fn bounds(&self) -> Bounds {
        self.extent
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polygon {
        Polygon::new(vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ])
        .unwrap()
    }

    #[test]
    fn normal_area_offset() {
        let p = square();
        assert_eq!(p.normal, Vec3::Z);
        assert_eq!(p.area, 4.0);
        assert_eq!(p.offset, 0.0);
    }

    #[test]
    fn hit_front_and_back() {
        let p = square();
        let h = p
            .intersect(&Ray::new(Vec3::new(0.5, 0.5, 2.0), -Vec3::Z))
            .unwrap();
        assert_eq!(h.t, 2.0);
        assert!(h.rod > 0.0);
        let h = p
            .intersect(&Ray::new(Vec3::new(0.5, 0.5, -2.0), Vec3::Z))
            .unwrap();
        assert!(h.rod < 0.0);
        assert!(
            p.intersect(&Ray::new(Vec3::new(1.5, 0.5, 2.0), -Vec3::Z))
                .is_none()
        );
        assert!(
            p.intersect(&Ray::new(Vec3::new(0.5, 0.5, 2.0), Vec3::X))
                .is_none()
        );
    }

    #[test]
    fn edges_and_corners_are_inside() {
        let p = square();
        for q in [
            (1.0, 0.0),
            (-1.0, 0.3),
            (0.2, 1.0),
            (-1.0, 1.0),
            (-1.0, -1.0),
            (1.0, -1.0),
        ] {
            assert!(p.contains(Vec3::new(q.0, q.1, 0.0)), "{q:?}");
        }
        // As in Radiance (checked with rtrace), the corner with the largest projected
        // coordinates is outside: no edge spans it and no crossing is counted.
        assert!(!p.contains(Vec3::new(1.0, 1.0, 0.0)));
    }

    #[test]
    fn concave_l_shape() {
        let p = Polygon::new(vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ])
        .unwrap();
        assert!(p.contains(Vec3::new(0.5, 1.5, 0.0)));
        assert!(p.contains(Vec3::new(1.5, 0.5, 0.0)));
        assert!(!p.contains(Vec3::new(1.5, 1.5, 0.0)));
    }

    #[test]
    fn zero_area_is_refused() {
        assert!(Polygon::new(vec![Vec3::ZERO, Vec3::X, 2.0 * Vec3::X]).is_none());
    }
}
