//! Spheres and bubbles (`src/rt/sphere.c`): the nearest root beyond `FTINY`, outward
//! normals (inward for a bubble).

use super::Quadratic;
use crate::math::{Bounds, FTINY, Vec3};
use crate::ray::{Ray, ShapeHit};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f64,
    /// Normals point inward (a `bubble`, or a sphere given a negative radius).
    pub inward: bool,
}

impl Sphere {
    pub fn intersect(&self, ray: &Ray) -> Option<ShapeHit> {
        self.intersect_within(ray, f64::INFINITY)
    }

    /// `intersect` for hits no farther than `tmax`.
    #[inline]
    pub fn intersect_within(&self, ray: &Ray, tmax: f64) -> Option<ShapeHit> {
        // Closest approach first: |oc|^2 - r^2 cancels badly far from the sphere, the
        // squared distance of the closest point to the centre does not.
        let oc = ray.org - self.center;
        let a = ray.dir.length_squared();
        if a <= FTINY {
            return None;
        }
        let tca = -oc.dot(ray.dir) / a;
        let perp = oc + ray.dir * tca;
        let disc = a * (self.radius * self.radius - perp.length_squared());
        let roots = if disc < -FTINY * FTINY || disc.is_nan() {
            Quadratic::None
        } else if disc <= FTINY * FTINY {
            Quadratic::One(tca)
        } else {
            let h = disc.sqrt() / a;
            Quadratic::Two(tca - h, tca + h)
        };
        let (_, t) = roots.roots().find(|&(_, t)| t > FTINY)?;
        if t > tmax {
            return None;
        }
        let p = ray.at(t);
        let scale = if self.inward {
            -self.radius
        } else {
            self.radius
        };
        let normal = (p - self.center) / scale;
        Some(ShapeHit {
            t,
            normal,
            rod: -ray.dir.dot(normal),
        })
    }

    pub fn bounds(&self) -> Bounds {
        let r = Vec3::splat(self.radius);
        Bounds {
            min: self.center - r,
            max: self.center + r,
        }
        .padded()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Sphere {
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
            inward: false,
        }
    }

    #[test]
    fn hits_front_from_outside() {
        let h = unit()
            .intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z))
            .unwrap();
        assert!((h.t - 4.0).abs() < 1e-12);
        assert!((h.normal - Vec3::Z).length() < 1e-12);
        assert!(h.rod > 0.0);
    }

    #[test]
    fn hits_back_from_inside() {
        let h = unit().intersect(&Ray::new(Vec3::ZERO, Vec3::X)).unwrap();
        assert!((h.t - 1.0).abs() < 1e-12);
        assert!(h.rod < 0.0);
    }

    #[test]
    fn far_away_sphere_is_hit_accurately() {
        let s = Sphere {
            center: Vec3::new(1e6, 1e6, 1e6),
            radius: 0.5,
            inward: false,
        };
        let o = Vec3::new(1e6, 1e6, 1e6 + 1e3);
        let h = s.intersect(&Ray::new(o, -Vec3::Z)).unwrap();
        assert!((h.t - 999.5).abs() < 1e-6);
    }

    #[test]
    fn misses() {
        assert!(
            unit()
                .intersect(&Ray::new(Vec3::new(0.0, 2.0, 5.0), -Vec3::Z))
                .is_none()
        );
        assert!(
            unit()
                .intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z))
                .is_none()
        );
    }
}
