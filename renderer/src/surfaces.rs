//! The surfaces as BVH traversal sees them, indexed by leaf slot: for each slot the
//! object and where its geometry is, the geometry itself in compact per-kind lists in
//! slot order (neighbouring slots are neighbours in memory). Names, materials and
//! modifiers stay in [`crate::scene::Object`], which traversal never touches.
//! Triangles, four-vertex polygons and spheres are stored inline, other shapes are
//! intersected through their object.
//!
//! Derived from the objects and the BVH (never stored in a compiled scene file): built
//! by [`crate::scene::Scene::compile`] and when a compiled scene is loaded.

use crate::bvh::Bvh;
use crate::math::Vec3;
use crate::ray::{Ray, ShapeHit};
use crate::scene::Object;
use crate::shapes::{PackedSphere, Polygon, Quad, Shape, Triangle};

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surfaces {
    /// Per slot: the object, and its geometry's kind (top two bits) and index in that
    /// kind's list.
    slots: Vec<(u32, u32)>,
    /// Per object its slot (`u32::MAX`: none), so that a walk can skip one object's
    /// slot without asking the slot for its object.
    slot_of: Vec<u32>,
    triangles: Vec<Triangle>,
    quads: Vec<Quad>,
    spheres: Vec<PackedSphere>,
}

const KIND_SHIFT: u32 = 30;
const INDEX: u32 = (1 << KIND_SHIFT) - 1;
const TRIANGLE: u32 = 0;
const SPHERE: u32 = 1;
const OBJECT: u32 = 2;
const QUAD: u32 = 3;

impl Surfaces {
    /// The surface of every leaf slot of `bvh`, in slot order.
    pub fn pack(objects: &[Object], bvh: &Bvh) -> Surfaces {
        let mut s = Surfaces {
            slot_of: vec![u32::MAX; objects.len()],
            ..Surfaces::default()
        };
        for &object in bvh.order() {
            if let (Some(slot), Ok(at)) = (
                s.slot_of.get_mut(object as usize),
                u32::try_from(s.slots.len()),
            ) {
                *slot = at;
            }
            let shape = objects.get(object as usize).map(|o| &o.shape);
            let (kind, index) = match shape {
                Some(Shape::Polygon(p)) => s.pack_polygon(p),
                Some(Shape::Sphere(sp)) if s.spheres.len() < INDEX as usize => {
                    s.spheres.push(PackedSphere::of(sp));
                    (SPHERE, s.spheres.len() - 1)
                }
                _ => (OBJECT, 0),
            };
            s.slots.push((object, kind << KIND_SHIFT | index as u32));
        }
        s
    }

    /// A polygon's kind and index: packed when it has three or four vertices (and its
    /// list has room), otherwise intersected through its object.
    fn pack_polygon(&mut self, p: &Polygon) -> (u32, usize) {
        if let Some(t) = Triangle::of(p)
            && self.triangles.len() < INDEX as usize
        {
            self.triangles.push(t);
            return (TRIANGLE, self.triangles.len() - 1);
        }
        if let Some(q) = Quad::of(p)
            && self.quads.len() < INDEX as usize
        {
            self.quads.push(q);
            return (QUAD, self.quads.len() - 1);
        }
        (OBJECT, 0)
    }

    /// Bytes the intersection tests read from: the slots and the packed shapes.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.slots.as_slice())
            + std::mem::size_of_val(self.triangles.as_slice())
            + std::mem::size_of_val(self.quads.as_slice())
            + std::mem::size_of_val(self.spheres.as_slice())
    }

    /// The slot holding `object`, or `u32::MAX` (which no walk offers) when none does.
    #[inline(always)]
    pub fn slot_of(&self, object: u32) -> u32 {
        self.slot_of
            .get(object as usize)
            .copied()
            .unwrap_or(u32::MAX)
    }

    /// When `slot` holds a packed polygon: its normal and how far `org` lies off its
    /// plane, as its test computes them ([`crate::shapes::PackedPolygon::plane_gap`]).
    #[inline(always)]
    pub fn plane_gap(&self, slot: u32, org: Vec3) -> Option<(Vec3, f64)> {
        let &(_, at) = self.slots.get(slot as usize)?;
        let index = (at & INDEX) as usize;
        match at >> KIND_SHIFT {
            TRIANGLE => self
                .triangles
                .get(index)
                .map(|p| (p.normal(), p.plane_gap(org))),
            QUAD => self
                .quads
                .get(index)
                .map(|p| (p.normal(), p.plane_gap(org))),
            _ => None,
        }
    }

    /// The object in `slot`.
    #[inline(always)]
    pub fn object_at(&self, slot: u32) -> Option<u32> {
        self.slots.get(slot as usize).map(|s| s.0)
    }

    /// The object in `slot` and its hit (as [`Shape::intersect`] finds it), or `None`
    /// when there is none or it lies beyond `tmax`.
    #[inline(always)]
    pub fn intersect(
        &self,
        slot: u32,
        objects: &[Object],
        ray: &Ray,
        tmax: f64,
    ) -> Option<(u32, ShapeHit)> {
        let &(object, at) = self.slots.get(slot as usize)?;
        let index = (at & INDEX) as usize;
        let hit = match at >> KIND_SHIFT {
            TRIANGLE => self.triangles.get(index)?.intersect_within(ray, tmax),
            SPHERE => self.spheres.get(index)?.intersect_within(ray, tmax),
            QUAD => self.quads.get(index)?.intersect_within(ray, tmax),
            _ => objects
                .get(object as usize)?
                .shape
                .intersect_within(ray, tmax),
        };
        Some((object, hit?))
    }
}
