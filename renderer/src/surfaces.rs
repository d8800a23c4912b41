//! The surfaces as BVH traversal sees them: one record per leaf slot, in slot order,
//! holding the geometry the intersection test reads and the object it belongs to.
//! Names, materials and modifiers stay in [`crate::scene::Object`], which traversal
//! never touches; neighbouring slots are neighbours in memory. Triangles and spheres
//! are stored inline, other shapes are intersected through their object.
//!
//! Derived from the objects and the BVH (never stored in a compiled scene file): built
//! by [`crate::scene::Scene::compile`] and when a compiled scene is loaded.

use crate::bvh::Bvh;
use crate::ray::{Ray, ShapeHit};
use crate::scene::Object;
use crate::shapes::{Shape, Sphere, Triangle};

#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    pub object: u32,
    geometry: Geometry,
}

#[derive(Clone, Debug, PartialEq)]
enum Geometry {
    Triangle(Triangle),
    Sphere(Sphere),
    /// The object's own shape.
    Object,
}

/// The surface of every leaf slot of `bvh`, in slot order.
pub fn pack(objects: &[Object], bvh: &Bvh) -> Vec<Surface> {
    bvh.order()
        .iter()
        .map(|&object| {
            let geometry = match objects.get(object as usize).map(|o| &o.shape) {
                Some(Shape::Polygon(p)) => {
                    Triangle::of(p).map_or(Geometry::Object, Geometry::Triangle)
                }
                Some(Shape::Sphere(s)) => Geometry::Sphere(s.clone()),
                _ => Geometry::Object,
            };
            Surface { object, geometry }
        })
        .collect()
}

impl Surface {
    /// The shape's hit (as [`Shape::intersect`] finds it), or `None` when there is none
    /// or it lies beyond `tmax`.
    #[inline]
    pub fn intersect(&self, objects: &[Object], ray: &Ray, tmax: f64) -> Option<ShapeHit> {
        match &self.geometry {
            Geometry::Triangle(t) => t.intersect_within(ray, tmax),
            Geometry::Sphere(s) => s.intersect_within(ray, tmax),
            Geometry::Object => objects
                .get(self.object as usize)?
                .shape
                .intersect_within(ray, tmax),
        }
    }
}
