//! The nearest surface along a ray, with Radiance's tie rules (`rayreject`), and the
//! distant source a ray that hits nothing meets.

use super::*;
use crate::bvh::Prepared;
use crate::lights::SourceTarget;
use crate::math::{FTINY, Vec3};
use crate::ray::{Ray, ShapeHit};

/// The best hit so far and what `rayreject` compares.
#[derive(Clone, Copy)]
pub(super) struct Candidate {
    pub(super) object: u32,
    pub(super) t: f64,
    pub(super) normal: Vec3,
    pub(super) rod: f64,
    /// [`ShapeHit::sub`].
    pub(super) sub: u32,
}

impl Tracer<'_> {
    /// The nearest surface along `ray`, with Radiance's tie rules for surfaces within
    /// `FTINY` of each other: a surface with a material beats one without, a front face
    /// beats a back face, then the later modifier wins.
    ///
    /// With `settle` above 0 the search may end at the first accepted hit nearer than
    /// it, which is then returned in place of the nearest: for callers to whom any
    /// surface that near is as good as the nearest one.
    ///
    /// `known`: an object whose hit along `ray` the caller has already found (as
    /// [`Shape::intersect`] finds it), used instead of testing the object again.
    pub(super) fn nearest(
        &self,
        ray: &Ray,
        limit: f64,
        settle: f64,
        known: Option<(u32, ShapeHit)>,
    ) -> Option<Candidate> {
        self.nearest_prepared(ray, &Prepared::of(ray), limit, settle, known)
    }

    /// [`Tracer::nearest`] with `ray`'s slab values prepared beforehand.
    pub(super) fn nearest_prepared(
        &self,
        ray: &Ray,
        prepared: &Prepared,
        limit: f64,
        settle: f64,
        known: Option<(u32, ShapeHit)>,
    ) -> Option<Candidate> {
        let mut best: Option<Candidate> = None;
        let scene = self.scene;
        scene
            .bvh
            .traverse_prepared(prepared, limit + FTINY, |slot| {
                // Farther hits are rejected whatever they are (`rejects`): the shape need
                // not finish testing them.
                let tmax = best.map_or(limit + FTINY, |b| b.t + FTINY);
                let found = match known {
                    // `intersect`'s answer: the same hit unless beyond `tmax`.
                    Some((o, h)) if scene.surfaces.object_at(slot) == Some(o) => {
                        (h.t <= tmax).then_some((o, h))
                    }
                    _ => scene.surfaces.intersect(slot, &scene.objects, ray, tmax),
                };
                if let Some((object, h)) = found
                    && h.t <= limit + FTINY
                {
                    let cand = Candidate {
                        object,
                        t: h.t,
                        normal: h.normal,
                        rod: h.rod,
                        sub: h.sub,
                    };
                    if !self.rejects(best.as_ref(), &cand) {
                        best = Some(cand);
                        // Shading the hit reads its `HitInfo`: in a large scene a miss,
                        // started here while traversal goes on.
                        scene.prefetch_hit_info(object);
                        if cand.t < settle {
                            return -1.0;
                        }
                    }
                }
                best.map_or(limit + FTINY, |b| b.t + FTINY)
            });
        best
    }

    /// Whether `ray` hits any surface (`nearest` would find one): stops at the first.
    /// Slot `from` ([`Tracer::start_slot`]) has no hit and is not tested.
    pub(super) fn hits_anything(&self, ray: &Ray, from: u32) -> bool {
        let scene = self.scene;
        scene.bvh.any(ray, f64::INFINITY, [from, u32::MAX], |slot| {
            scene
                .surfaces
                .intersect(slot, &scene.objects, ray, f64::INFINITY)
                .is_some()
        })
    }

    pub(super) fn rejects(&self, best: Option<&Candidate>, new: &Candidate) -> bool {
        let Some(old) = best else {
            return new.t <= FTINY;
        };
        if new.t <= FTINY || new.t > old.t + FTINY {
            return true;
        }
        if new.t < old.t - FTINY {
            return false;
        }
        let (Some(on), Some(oo)) = (
            self.scene.hit_info(new.object),
            self.scene.hit_info(old.object),
        ) else {
            return true;
        };
        let (mn, mo) = (
            on.material().and_then(|m| self.scene.material(m)),
            oo.material().and_then(|m| self.scene.material(m)),
        );
        match (mn, mo) {
            (None, Some(_)) => return true,
            (Some(_), None) => return false,
            (Some(n), Some(o)) => match (n.is_transparent(), o.is_transparent()) {
                (true, false) => return true,
                (false, true) => return false,
                _ => {}
            },
            (None, None) => {}
        }
        if new.rod <= 0.0 {
            if old.rod > 0.0 {
                return true;
            }
        } else if old.rod <= 0.0 {
            return false;
        }
        oo.modifier >= on.modifier
    }

    /// A ray that hit nothing may see a distant source (`sourcehit`): the first whose
    /// cone holds the ray, preferring real sources to glows and transparent illums.
    pub(super) fn distant_hit(&self, r: &RayState) -> Option<u32> {
        let aimed = r
            .source
            .and_then(|s| self.scene.sources.get(s))
            .map(|s| s.target);
        let mut glow = None;
        let mut trans_illum = None;
        for (i, d) in self.scene.distant.iter().enumerate() {
            let i = i as u32;
            if crate::lights::cap_solid_angle(d.direction.dot(r.dir)) > d.solid_angle {
                continue;
            }
            if aimed == Some(SourceTarget::Distant(i)) {
                return Some(i);
            }
            if aimed.is_some() {
                continue;
            }
            let e = match d.material.and_then(|m| self.scene.material(m)) {
                Some(Material::Emitter(e)) => Some(e),
                _ => None,
            };
            match e.map(|e| &e.kind) {
                Some(crate::materials::light::EmitterKind::Glow { .. }) => {
                    glow.get_or_insert(i);
                }
                Some(crate::materials::light::EmitterKind::Illum { alternate })
                    if !matches!(alternate, crate::materials::Alternate::Material(_)) =>
                {
                    trans_illum.get_or_insert(i);
                }
                Some(_) => return Some(i),
                None => {
                    // Not a light: Radiance never makes it a source, so never sees it.
                }
            }
        }
        if trans_illum.is_some() && r.kind.any(RayKind::AMBIENT | RayKind::SPECULAR) {
            return None;
        }
        glow
    }
}
