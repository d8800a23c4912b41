//! Rings (disks with an optional hole, `src/rt/o_cone.c`): the plane through the centre
//! with the given normal, hit where `r0^2 <= d^2 <= r1^2`.

use crate::math::{Bounds, FTINY, Vec3, normalize};
use crate::ray::{Ray, ShapeHit};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ring {
    pub center: Vec3,
    pub normal: Vec3,
    pub r0: f64,
    pub r1: f64,
}

impl Ring {
    /// `None` for a zero normal or equal radii (Radiance: "unknown orientation",
    /// "illegal radii").
    pub fn new(center: Vec3, mut normal: Vec3, r0: f64, r1: f64) -> Option<Ring> {
        let (r0, r1) = (r0.abs().min(r1.abs()), r0.abs().max(r1.abs()));
        if normalize(&mut normal) == 0.0 || r1 - r0 <= FTINY {
            return None;
        }
        Some(Ring {
            center,
            normal,
            r0,
            r1,
        })
    }

    pub fn intersect(&self, ray: &Ray) -> Option<ShapeHit> {
        let rdot = ray.dir.dot(self.normal);
        if rdot.abs() <= FTINY {
            return None;
        }
        let t = (self.center - ray.org).dot(self.normal) / rdot;
        if t <= FTINY || !t.is_finite() {
            return None;
        }
        let d2 = (ray.at(t) - self.center).length_squared();
        if d2 > self.r1 * self.r1 || d2 < self.r0 * self.r0 {
            return None;
        }
        Some(ShapeHit {
            t,
            normal: self.normal,
            rod: -rdot,
            sub: 0,
        })
    }

    pub fn bounds(&self) -> Bounds {
        // Extent of a disk of radius r1 with normal n along axis i: r1 * sqrt(1 - n_i^2).
        let n = self.normal;
        let e = Vec3::new(
            (1.0 - n.x * n.x).max(0.0).sqrt(),
            (1.0 - n.y * n.y).max(0.0).sqrt(),
            (1.0 - n.z * n.z).max(0.0).sqrt(),
        ) * self.r1;
        Bounds {
            min: self.center - e,
            max: self.center + e,
        }
        .padded()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hole_is_missed() {
        let r = Ring::new(Vec3::ZERO, Vec3::Z, 0.5, 1.0).unwrap();
        assert!(
            r.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z))
                .is_none()
        );
        let h = r
            .intersect(&Ray::new(Vec3::new(0.75, 0.0, 1.0), -Vec3::Z))
            .unwrap();
        assert_eq!(h.t, 1.0);
        assert!(h.rod > 0.0);
    }
}
