//! Rays and what they hit.

use crate::math::Vec3;

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
    /// Which part of the shape: a mesh's triangle (its slot in the mesh's tree); 0 for
    /// the other shapes.
    pub sub: u32,
}
