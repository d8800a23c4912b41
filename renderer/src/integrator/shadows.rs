//! Shadow rays decided without a full ray state where the scene allows it: the
//! packed polygon a point leaves, blockers before a source, distant sources.

use super::*;
use crate::bvh::Prepared;
use crate::math::{Color, FHUGE, FTINY, Vec3};
use crate::ray::{Ray, ShapeHit};

/// The packed polygon a point's shadow rays start from: its slot, normal, and the
/// point's gap to its plane, as its test computes them. A walk may skip the slot for
/// a ray its plane test surely rejects ([`StartPlane::skip`]): it cannot hit the
/// surface it leaves, and testing it is most of the calls a shadow walk makes.
#[derive(Clone, Copy)]
pub(super) struct StartPlane {
    pub(super) slot: u32,
    pub(super) normal: Vec3,
    pub(super) gap: f64,
}

impl StartPlane {
    /// No polygon: `skip` always gives `u32::MAX` (a zero `rod`).
    pub(super) const NONE: StartPlane = StartPlane {
        slot: u32::MAX,
        normal: Vec3::ZERO,
        gap: f64::NAN,
    };

    /// The slot to skip for a shadow ray along `dir`, or `u32::MAX`: the slot when the
    /// polygon's test would stop at the plane. Its `rod`, bit for bit, then `t = gap /
    /// rod` need not be divided out: a gap of the other sign than `rod` (or none) puts
    /// `t` at or behind the origin, and one well under `FTINY * |rod|` keeps it below
    /// `FTINY` (either way the test rejects `t <= FTINY`); anything else is tested.
    #[inline(always)]
    pub(super) fn skip(&self, dir: Vec3) -> u32 {
        let rod = -dir.dot(self.normal);
        let gap = self.gap;
        if rod.abs() <= FTINY || gap * rod <= 0.0 || gap.abs() < 0.5 * FTINY * rod.abs() {
            self.slot
        } else {
            u32::MAX
        }
    }
}

/// What a shadow ray's walk may know before it starts: the slot it leaves
/// ([`StartPlane::skip`]) and its slab values, when its caller prepared them with
/// others ([`Prepared`]).
pub(super) struct ShadowWalk<'p> {
    pub(super) from: u32,
    pub(super) prepared: Option<&'p Prepared>,
}

impl ShadowWalk<'_> {
    /// Nothing known beforehand.
    pub(super) const PLAIN: ShadowWalk<'static> = ShadowWalk {
        from: u32::MAX,
        prepared: None,
    };
}

/// How many FTINY-wide ties (plus as many relative 1e-6 margins) a blocker must lie
/// before a surface source for a shadow ray to settle on it without the nearest hit.
pub(super) const SETTLE: f64 = 16.0;

impl Tracer<'_> {
    /// [`Tracer::source_contribution`] toward the distant source `d` (no virtual one)
    /// in a scene opaque to shadows, without a shadow ray's state: the value
    /// `source_value` finds from the emitter alone (a fresh shadow ray faces it, and
    /// travels `FHUGE` through the medium), kept when the ray hits nothing. `None`
    /// where that needs the general path (an `illum`).
    pub(super) fn distant_source_shadow(
        &self,
        r: &RayState,
        d: u32,
        dir: Vec3,
        c: Color,
        start: &StartPlane,
    ) -> Option<Option<Color>> {
        if !may_spawn(r, child_weight(r, 1.0)) {
            return Some(None);
        }
        let Some(distant) = self.scene.distant.get(d as usize) else {
            return Some(None);
        };
        if distant
            .material
            .is_some_and(|m| self.scene.patterns_of(m).is_some())
        {
            return None; // a patterned light is shaded along the ray
        }
        let Some(Material::Emitter(e)) = distant.material.and_then(|m| self.scene.material(m))
        else {
            return None;
        };
        let seen = e.aimed_shadow_radiance(1.0, dir, self.options.backface_visible)?;
        let v = absorbed(seen, r.extinction, FHUGE) * c;
        let ray = Ray::new(r.point, dir);
        Some((!self.hits_anything(&ray, start.skip(dir))).then_some(v))
    }

    /// [`Tracer::source_contribution`] toward the surface source `target` (no virtual
    /// one) in a scene opaque to object shadows, met by the shadow ray at `hit`
    /// ([`Tracer::source_surface_hit`]), without a shadow ray's state: the value
    /// `source_value` finds from the emitter alone, kept when the source is the
    /// nearest surface. `None` where the emitter's value needs a ray (an `illum`, a
    /// back seen with `-bv-`): then the general path decides.
    pub(super) fn object_source_shadow(
        &self,
        r: &RayState,
        target: u32,
        dir: Vec3,
        c: Color,
        hit: Option<ShapeHit>,
        walk: &ShadowWalk,
    ) -> Option<Option<Color>> {
        // The shadow ray `spawn` would make: unweighted, so only its limits matter.
        if !may_spawn(r, child_weight(r, 1.0)) {
            return Some(None);
        }
        let Some(obj) = self.scene.object(target) else {
            return Some(None);
        };
        if obj
            .material
            .is_some_and(|m| self.scene.patterns_of(m).is_some())
        {
            return None; // a patterned light is shaded along the ray
        }
        let Some(Material::Emitter(e)) = obj.material.and_then(|m| self.scene.material(m)) else {
            return None;
        };
        let Some(h) = hit else {
            return Some(None);
        };
        let seen = e.aimed_shadow_radiance(h.rod, dir, self.options.backface_visible)?;
        let v = absorbed(seen, r.extinction, h.t) * c;
        let ray = Ray::new(r.point, dir);
        Some(
            self.source_is_nearest(&ray, target, h.t, Some(h), walk)
                .then_some(v),
        )
    }

    /// The surface `r`'s shadow rays start from, when its test is a packed polygon's.
    pub(super) fn start_plane(&self, r: &RayState) -> StartPlane {
        let surfaces = &self.scene.surfaces;
        if let Target::Object(ObjectId(o)) = r.hit {
            let slot = surfaces.slot_of(o);
            if let Some((normal, gap)) = surfaces.plane_gap(slot, r.point) {
                return StartPlane { slot, normal, gap };
            }
        }
        StartPlane::NONE
    }

    /// In a scene opaque to object shadows (`Scene::opaque_to_object_shadows`): whether
    /// the source `target`, met at `t` along shadow ray `ray` (with `hit`, if the caller
    /// has it), is the nearest surface; whatever else the ray hits shades it black, so
    /// that alone decides. The search goes no farther than the source and ends at a
    /// surface clearly before it: one more than `SETTLE` nearer beats it (within FTINY
    /// surfaces tie, so only a chain of that many surfaces each within FTINY of the
    /// next could pass the decision on to the source).
    pub(super) fn source_is_nearest(
        &self,
        ray: &Ray,
        target: u32,
        t: f64,
        hit: Option<ShapeHit>,
        walk: &ShadowWalk,
    ) -> bool {
        let settle = t - SETTLE * (FTINY + 1e-6 * t);
        // With the source's hit known, the other surfaces mostly decide alone.
        if hit.is_some()
            && let Some(blocked) = self.blocked_before(ray, target, t, settle, walk)
        {
            return !blocked;
        }
        !matches!(
            self.nearest(ray, t, settle, hit.map(|h| (target, h))),
            Some(b) if b.object != target
        )
    }

    /// [`Tracer::source_is_nearest`]'s answer where it follows from the other surfaces
    /// alone, whatever order `nearest` meets them in: `Some(false)` when no surface but
    /// the source has a hit in `(FTINY, t + FTINY]` (then `nearest` can only find the
    /// source or nothing), `Some(true)` when one has a hit before `settle - FTINY`
    /// (`nearest` always reaches it, or stops earlier at a surface as near: every
    /// surface it holds by then lies at or beyond `settle`, more than `FTINY` behind
    /// it, so it is taken, and being before `settle` it ends the search). Hits in
    /// between, where the tie rules and the order decide, give `None`: the caller asks
    /// `nearest`.
    ///
    /// This walk keeps no nearest candidate, so it skips the source and needs no
    /// ordering of children: a fifth fewer instructions a shadow ray in the room of
    /// `bench/trace_rays.py` (851 to 672), most of whose shadow rays are unblocked.
    ///
    /// Slot `from` ([`Tracer::start_slot`]) has no hit and is not tested.
    pub(super) fn blocked_before(
        &self,
        ray: &Ray,
        target: u32,
        t: f64,
        settle: f64,
        walk: &ShadowWalk,
    ) -> Option<bool> {
        let scene = self.scene;
        let tmax = t + FTINY;
        let blocking = settle - FTINY;
        let mut unsure = false;
        let skip = [scene.surfaces.slot_of(target), walk.from];
        let prepared = Prepared::given_or_of(walk.prepared, ray);
        let blocked = scene.bvh.any_prepared(&prepared, tmax, skip, |slot| {
            if scene.surfaces.object_at(slot) == Some(target) {
                return false;
            }
            match scene.surfaces.intersect(slot, &scene.objects, ray, tmax) {
                Some((_, h)) if h.t > FTINY && h.t <= tmax => {
                    if h.t < blocking {
                        return true;
                    }
                    unsure = true;
                    false
                }
                _ => false,
            }
        });
        if blocked {
            Some(true)
        } else if unsure {
            None
        } else {
            Some(false)
        }
    }
}
