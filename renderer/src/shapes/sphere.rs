//! Spheres and bubbles (`src/rt/sphere.c`): the nearest root beyond `FTINY`, outward
//! normals (inward for a bubble).

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
        PackedSphere::of(self).intersect_within(ray, tmax)
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

/// A sphere as the BVH's inner loop reads it, in 32 bytes (a leaf's four spheres in
/// two cache lines): the radius carries the normal's direction as its sign.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct PackedSphere {
    center: Vec3,
    /// The radius, negated for inward normals: the normal's divisor, and squared (the
    /// sign does not change the square's bits) the radius squared.
    scale: f64,
}

impl PackedSphere {
    pub fn of(s: &Sphere) -> PackedSphere {
        PackedSphere {
            center: s.center,
            scale: if s.inward { -s.radius } else { s.radius },
        }
    }

    /// [`Sphere::intersect_within`]: the roots of `a t^2 + b t + c` found from the
    /// closest approach, the nearer one if beyond `FTINY`, else the farther.
    #[inline(always)]
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
        let disc = a * (self.scale * self.scale - perp.length_squared());
        // A double root within FTINY^2 of a zero discriminant, as `quadratic`; the first
        // root beyond FTINY.
        let t = if disc < -FTINY * FTINY || disc.is_nan() {
            return None;
        } else if disc <= FTINY * FTINY {
            tca
        } else {
            let h = disc.sqrt() / a;
            let near = tca - h;
            if near > FTINY { near } else { tca + h }
        };
        if t > FTINY {
            if t > tmax {
                return None;
            }
        } else {
            return None;
        }
        let normal = (ray.at(t) - self.center) / self.scale;
        Some(ShapeHit {
            t,
            normal,
            rod: -ray.dir.dot(normal),
            sub: 0,
        })
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
    fn bubbles_face_inward() {
        let bubble = Sphere {
            inward: true,
            ..unit()
        };
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
        let (out, inn) = (
            unit().intersect(&ray).unwrap(),
            bubble.intersect(&ray).unwrap(),
        );
        assert_eq!(inn.t, out.t);
        assert_eq!(inn.normal, -out.normal);
        assert!(inn.rod < 0.0);
        let inside = bubble.intersect(&Ray::new(Vec3::ZERO, Vec3::X)).unwrap();
        assert!(inside.rod > 0.0);
    }

    /// The 32-byte record: its square of the negated radius is the radius's square.
    #[test]
    fn packed_is_32_bytes_and_negates_exactly() {
        assert_eq!(std::mem::size_of::<PackedSphere>(), 32);
        let r = 0.1 + 0.2;
        let s = PackedSphere::of(&Sphere {
            center: Vec3::ZERO,
            radius: r,
            inward: true,
        });
        assert_eq!((s.scale * s.scale).to_bits(), (r * r).to_bits());
    }

    /// The root selection as the enumerated roots of a [`Quadratic`] state it (the
    /// form this replaced), on rays through, grazing, from inside, behind and beyond
    /// `tmax`: the same hits bit for bit.
    #[test]
    fn roots_as_the_quadratic_orders_them() {
        use crate::random::uniform;
        use crate::shapes::Quadratic;
        let reference = |s: &Sphere, ray: &Ray, tmax: f64| -> Option<ShapeHit> {
            let oc = ray.org - s.center;
            let a = ray.dir.length_squared();
            if a <= FTINY {
                return None;
            }
            let tca = -oc.dot(ray.dir) / a;
            let perp = oc + ray.dir * tca;
            let disc = a * (s.radius * s.radius - perp.length_squared());
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
            let scale = if s.inward { -s.radius } else { s.radius };
            let normal = (ray.at(t) - s.center) / scale;
            Some(ShapeHit {
                t,
                normal,
                rod: -ray.dir.dot(normal),
                sub: 0,
            })
        };
        let (mut hits, mut checked) = (0, 0);
        for k in 0..4000u64 {
            let r = |j: u64| uniform(k, j) * 2.0 - 1.0;
            let s = Sphere {
                center: Vec3::new(r(0), r(1), r(2)) * 10.0,
                radius: uniform(k, 3) * 3.0,
                inward: k % 2 == 0,
            };
            // Aimed at the centre, at the rim (grazing), near it, and from inside.
            let side = Vec3::new(r(4), r(5), r(6)).normalize();
            let org = s.center + Vec3::new(r(7), r(8), r(9)).normalize() * (s.radius * 4.0);
            let rim = s.center + side * s.radius;
            for (org, target) in [
                (org, s.center),
                (org, rim),
                (org, s.center + side * (s.radius * (1.0 + 1e-9))),
                (s.center + side * (s.radius * 0.5), org),
                (rim, org),
            ] {
                let ray = Ray::new(org, (target - org).normalize());
                for tmax in [f64::INFINITY, s.radius * 4.0, 1e-7] {
                    let got = s.intersect_within(&ray, tmax);
                    assert_eq!(got, reference(&s, &ray, tmax), "sphere {k}, {ray:?}");
                    hits += usize::from(got.is_some());
                    checked += 1;
                }
            }
        }
        assert!(hits > checked / 3, "{hits} of {checked}");
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
