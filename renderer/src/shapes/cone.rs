//! Cones, cups, cylinders and tubes (`src/rt/o_cone.c`), intersected in world space:
//! with `h` the height along the axis and `q` the radial offset, the surface is
//! `|q|^2 = (r0 + (r1 - r0) h / len)^2` for `0 <= h <= len`. Normals point outward (inward
//! for cups and tubes); the quadratic keeps Radiance's linear and double-root cases.

use super::quadratic;
use crate::math::{Bounds, FTINY, Vec3, normalize};
use crate::ray::{Ray, ShapeHit};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Cone {
    pub p0: Vec3,
    pub r0: f64,
    pub r1: f64,
    /// Unit axis from `p0` to the other end.
    pub axis: Vec3,
    pub length: f64,
    /// Cup or tube: normals point inward.
    pub inward: bool,
    p1: Vec3,
}

impl Cone {
    /// `None` for a zero-length axis or two zero radii.
    pub fn new(p0: Vec3, p1: Vec3, r0: f64, r1: f64, inward: bool) -> Option<Cone> {
        let mut axis = p1 - p0;
        let length = normalize(&mut axis);
        let (r0, r1) = (r0.abs(), r1.abs());
        if length == 0.0 || (r0 <= FTINY && r1 <= FTINY) {
            return None;
        }
        Some(Cone {
            p0,
            r0,
            r1,
            axis,
            length,
            inward,
            p1,
        })
    }

    /// Equal radii: a cylinder (or tube).
    pub fn is_cylinder(&self) -> bool {
        (self.r0 - self.r1).abs() <= FTINY
    }

    pub fn p1(&self) -> Vec3 {
        self.p1
    }

    pub fn intersect(&self, ray: &Ray) -> Option<ShapeHit> {
        let k = (self.r1 - self.r0) / self.length;
        let w = ray.org - self.p0;
        let (hw, hd) = (w.dot(self.axis), ray.dir.dot(self.axis));
        let qw = w - self.axis * hw;
        let qd = ray.dir - self.axis * hd;
        let (rw, rd) = (self.r0 + k * hw, k * hd);
        let a = qd.length_squared() - rd * rd;
        let b = 2.0 * (qw.dot(qd) - rw * rd);
        let c = qw.length_squared() - rw * rw;
        for (_, t) in quadratic(a, b, c).roots() {
            if t <= FTINY || !t.is_finite() {
                continue;
            }
            let h = hw + t * hd;
            if !(0.0..=self.length).contains(&h) {
                continue;
            }
            let q = qw + qd * t;
            let radius = self.r0 + k * h;
            if radius <= 0.0 {
                continue;
            }
            let slant = ((self.r1 - self.r0).powi(2) + self.length * self.length).sqrt();
            let mut normal = (q / radius * self.length - self.axis * (self.r1 - self.r0)) / slant;
            let len2 = normal.length_squared();
            if !(1.0 - FTINY..=1.0 + FTINY).contains(&len2) {
                normal /= 0.5 + 0.5 * len2;
            }
            if self.inward {
                normal = -normal;
            }
            return Some(ShapeHit {
                t,
                normal,
                rod: -ray.dir.dot(normal),
                sub: 0,
            });
        }
        None
    }

    pub fn bounds(&self) -> Bounds {
        let r = Vec3::splat(self.r0.max(self.r1));
        Bounds {
            min: self.p0.min(self.p1) - r,
            max: self.p0.max(self.p1) + r,
        }
        .padded()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_side_hit() {
        let c = Cone::new(Vec3::ZERO, Vec3::Z * 2.0, 1.0, 1.0, false).unwrap();
        let h = c
            .intersect(&Ray::new(Vec3::new(5.0, 0.0, 1.0), -Vec3::X))
            .unwrap();
        assert!((h.t - 4.0).abs() < 1e-12);
        assert!((h.normal - Vec3::X).length() < 1e-12);
        // Past the end cap: miss.
        assert!(
            c.intersect(&Ray::new(Vec3::new(5.0, 0.0, 3.0), -Vec3::X))
                .is_none()
        );
    }

    #[test]
    fn cone_normal_tilts_toward_narrow_end() {
        let c = Cone::new(Vec3::ZERO, Vec3::Z, 1.0, 0.0, false).unwrap();
        let h = c
            .intersect(&Ray::new(Vec3::new(5.0, 0.0, 0.5), -Vec3::X))
            .unwrap();
        assert!((h.t - 4.5).abs() < 1e-12);
        let s = 0.5f64.sqrt();
        assert!(
            (h.normal - Vec3::new(s, 0.0, s)).length() < 1e-9,
            "{:?}",
            h.normal
        );
    }

    #[test]
    fn tube_from_inside_faces_the_ray() {
        let c = Cone::new(Vec3::ZERO, Vec3::Z * 2.0, 1.0, 1.0, true).unwrap();
        let h = c
            .intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::X))
            .unwrap();
        assert!(h.rod > 0.0);
    }
}
