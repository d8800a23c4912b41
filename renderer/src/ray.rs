//! Rays and what they hit.

use crate::math::{FHUGE, Vec3};

/// Index of an object (a surface) in [`crate::scene::Scene::objects`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ObjectId(pub u32);

/// A ray with a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub org: Vec3,
    pub dir: Vec3,
}

impl Ray {
    pub fn new(org: Vec3, dir: Vec3) -> Ray {
        Ray { org, dir }
    }

    pub fn at(&self, t: f64) -> Vec3 {
        self.org + self.dir * t
    }
}

/// A shape's answer to a ray: distance, surface normal and `rod`, the cosine between
/// the normal and the reversed ray (negative on the back side), as Radiance's `o_*`
/// routines set `rot`, `ron` and `rod`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeHit {
    pub t: f64,
    pub normal: Vec3,
    pub rod: f64,
}

/// The nearest surface along a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub object: ObjectId,
    pub t: f64,
    pub point: Vec3,
    pub normal: Vec3,
    pub rod: f64,
}

impl Hit {
    /// What Radiance reports for a ray that hits nothing: length `FHUGE`, the point at
    /// the origin.
    pub fn missed_length() -> f64 {
        FHUGE
    }
}
