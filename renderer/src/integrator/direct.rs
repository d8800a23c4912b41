//! Direct light: each source sample's coefficient, shadow ray and value
//! (`direct()` in source.c, every sample tested: rtrace `-dt 0`).
//!
//! `Tracer::direct` works in three passes over a point's source samples (`Shot`s): the
//! material's coefficients, the source surfaces' hits, then the shadow walks, adding in the
//! same order; the hits' dependent divisions and square roots then overlap instead of each
//! stalling between two walks. When every source is a lamp (a sphere that is its own
//! surface, no glow distance, spotlight cone, mirror image or beam; at most `MAX_LAMPS`)
//! and without jitter or `-dx+`, `direct_lamps` does the same passes with the lamps'
//! samples and packed spheres at hand and each shadow ray's slab values prepared in the
//! hits' pass. In a scene opaque to object shadows a shadow ray toward a real surface
//! source is no `RayState`: the emitter's value (`Emitter::aimed_shadow_radiance`), the
//! medium's absorption and whether the source is the nearest surface decide it
//! (`shadows.rs`). Virtual sources, `illum`s and backs seen with `-bv-` take the general
//! path (a spawned shadow ray, shaded).

use super::shadows::StartPlane;
use super::*;
use crate::bvh::Prepared;
use crate::lights::{Lamp, SourceSample, SourceTarget};
use crate::math::{Color, FTINY, Vec3, intensity};
use crate::ray::{Ray, ShapeHit};

thread_local! {
    /// [`Tracer::direct`]'s source samples, kept between calls.
    static SAMPLE_BUFFER: std::cell::Cell<Vec<SourceSample>> =
        const { std::cell::Cell::new(Vec::new()) };
    /// [`Tracer::direct`]'s shadow rays to test, kept between calls.
    static SHOT_BUFFER: std::cell::Cell<Vec<Shot>> = const { std::cell::Cell::new(Vec::new()) };
}

/// A shadow ray [`Tracer::direct`] will test: toward source `source` along `dir`,
/// bringing its radiance times `c`; `hit`, where it meets the source's surface, if
/// that is tested first.
#[derive(Clone, Copy)]
pub(super) struct Shot {
    pub(super) source: usize,
    pub(super) dir: Vec3,
    pub(super) c: Color,
    pub(super) hit: Option<Option<ShapeHit>>,
}

impl Tracer<'_> {
    /// Adds the direct contribution of every source to `r` (`direct()`), `coef` giving
    /// the material's coefficient for a source sample direction and solid angle.
    ///
    /// In three passes over the samples, each adding what it finds in the same order:
    /// the coefficients; where a shadow ray will be tested against its source surface
    /// first, that hit; then the shadow rays. A surface hit is a chain of divisions
    /// and a square root, each waiting for the one before; side by side, the chains of
    /// different samples overlap, where between shadow walks each would stall alone.
    pub fn direct(&self, r: &mut RayState, coef: &dyn Fn(Vec3, f64) -> Color) {
        if let Some(lamps) = &self.scene.lamps
            // `lamps` was derived for a scene opaque to object shadows; checked again
            // for callers (tests) that change the flag afterwards.
            && self.scene.opaque_to_object_shadows
            // As the general path's jitter test: NaN jitters nothing either.
            && (self.options.source_jitter <= 0.0 || self.options.source_jitter.is_nan())
            && !self.options.exact_sources
        {
            self.direct_lamps(r, coef, lamps);
            return;
        }
        // The thread's buffers, taken for this call so that no call allocates once
        // they have grown (a nested call, through a shadow ray, finds them empty and
        // uses fresh ones).
        let mut samples = SAMPLE_BUFFER.take();
        let mut shots = SHOT_BUFFER.take();
        shots.clear();
        for (si, s) in self.scene.sources.iter().enumerate() {
            samples.clear();
            let jitter = (self.options.source_jitter > 0.0).then(|| {
                (
                    self.options.source_jitter,
                    crate::random::derive(r.seed, SOURCE_JITTER + si as u64),
                )
            });
            s.jittered_samples(
                r.point,
                r.weight,
                self.options.source_size_ratio,
                jitter,
                self.options.exact_sources,
                &mut samples,
            );
            for sample in &samples {
                let c = coef(sample.dir, sample.omega);
                if intensity(c) <= 0.0 {
                    continue;
                }
                shots.push(Shot {
                    source: si,
                    dir: sample.dir,
                    c,
                    hit: None,
                });
            }
        }
        for shot in shots.iter_mut() {
            shot.hit = self.source_surface_hit(r, shot.source, shot.dir);
        }
        let start = self.start_plane(r);
        for shot in &shots {
            if let Some(v) = self.source_contribution(r, shot, &start) {
                r.color += v;
            }
        }
        samples.clear();
        SAMPLE_BUFFER.set(samples);
        shots.clear();
        SHOT_BUFFER.set(shots);
    }

    /// [`Tracer::direct`] when every source is a [`Lamp`] (`Scene::lamps`) and their
    /// samples are the centres: the same three passes and the same values, added in
    /// the same order, with the lamps' samples and surfaces at hand and the shots in
    /// arrays (a source gives at most one).
    pub(super) fn direct_lamps(
        &self,
        r: &mut RayState,
        coef: &dyn Fn(Vec3, f64) -> Color,
        lamps: &[Lamp],
    ) {
        let mut dirs = [Vec3::ZERO; MAX_LAMPS];
        let mut coefs = [Color::ZERO; MAX_LAMPS];
        let mut which = [0usize; MAX_LAMPS];
        let mut n = 0;
        for (si, lamp) in lamps.iter().enumerate() {
            let Some(sample) = lamp.sample(r.point) else {
                continue;
            };
            let c = coef(sample.dir, sample.omega);
            if intensity(c) <= 0.0 {
                continue;
            }
            let (Some(d), Some(k), Some(w)) = (dirs.get_mut(n), coefs.get_mut(n), which.get_mut(n))
            else {
                break;
            };
            (*d, *k, *w) = (sample.dir, c, si);
            n += 1;
        }
        let mut hits = [None; MAX_LAMPS];
        let mut prepared = [None; MAX_LAMPS];
        for k in 0..n {
            let ray = Ray::new(r.point, dirs[k]);
            hits[k] = lamps[which[k]].sphere.intersect_within(&ray, f64::INFINITY);
            prepared[k] = Some(Prepared::of(&ray));
        }
        let start = self.start_plane(r);
        for k in 0..n {
            let (si, dir, c) = (which[k], dirs[k], coefs[k]);
            let target = lamps[si].target;
            let walk = ShadowWalk {
                from: start.skip(dir),
                prepared: prepared[k].as_ref(),
            };
            let v = match self.object_source_shadow(r, target, dir, c, hits[k], &walk) {
                Some(v) => v,
                None => self.traced_source_contribution(r, si, dir, c),
            };
            if let Some(v) = v {
                r.color += v;
            }
        }
    }

    /// Where a shadow ray from `r` along `dir` meets source `si`'s surface, when
    /// [`Tracer::object_source_shadow`] will need it (`None` inside means a miss).
    pub(super) fn source_surface_hit(
        &self,
        r: &RayState,
        si: usize,
        dir: Vec3,
    ) -> Option<Option<ShapeHit>> {
        let source = self.scene.sources.get(si)?;
        if !self.scene.opaque_to_object_shadows || source.parent.is_some() {
            return None;
        }
        let SourceTarget::Object(target) = source.target else {
            return None;
        };
        let ray = Ray::new(r.point, dir);
        Some(match &self.scene.object(target)?.shape {
            Shape::Sphere(s) => s.intersect_within(&ray, f64::INFINITY),
            shape => shape.intersect(&ray),
        })
    }

    /// The radiance a shadow ray toward a source brings, times its coefficient, or
    /// `None` when blocked.
    pub(super) fn source_contribution(
        &self,
        r: &RayState,
        shot: &Shot,
        start: &StartPlane,
    ) -> Option<Color> {
        let &Shot {
            source: si,
            dir,
            c,
            hit,
        } = shot;
        let source = self.scene.sources.get(si)?;
        if let (SourceTarget::Object(target), Some(hit)) = (source.target, hit)
            && let Some(v) = self.object_source_shadow(
                r,
                target,
                dir,
                c,
                hit,
                &ShadowWalk {
                    from: start.skip(dir),
                    prepared: None,
                },
            )
        {
            return v;
        }
        if self.scene.opaque_to_shadows
            && source.parent.is_none()
            && let SourceTarget::Distant(d) = source.target
            && let Some(v) = self.distant_source_shadow(r, d, dir, c, start)
        {
            return v;
        }
        self.traced_source_contribution(r, si, dir, c)
    }

    /// [`Tracer::source_contribution`] by a shadow ray's full state.
    pub(super) fn traced_source_contribution(
        &self,
        r: &RayState,
        si: usize,
        dir: Vec3,
        c: Color,
    ) -> Option<Color> {
        // Worked on inside its `Option` (moving it out would copy the whole state).
        let mut spawned = self.spawn(r, RayKind::SHADOW, None);
        let sr = spawned.as_mut()?;
        sr.dir = dir;
        sr.source = Some(si);
        sr.coef = c;
        let source = self.scene.sources.get(si)?;
        // Whether `sr` has been shaded as the source (`source_value`, which then needs
        // no copy of it) and must be made afresh to shade a blocker.
        let mut shaded = false;
        let ray = Ray::new(sr.org, sr.dir);
        let value = if source.parent.is_some() {
            // A virtual source: the ray must meet its mirror; the path through the mirror
            // to the source it images is then always followed (Radiance follows it
            // unless a pretest found it clear, which gives the same value).
            let SourceTarget::Object(mirror) = source.target else {
                return None;
            };
            self.scene.object(mirror)?.shape.intersect(&ray)?;
            None
        } else {
            // The source's own value, from the source surface alone (`srcvalue`).
            shaded = true;
            Some(self.source_value(sr, si)? * c)
        };
        if self.scene.opaque_to_shadows && matches!(source.target, SourceTarget::Distant(_)) {
            // Whatever it hits shades it black (`Scene::opaque_to_shadows`), and the
            // distant source is no surface: the first hit found decides.
            return (!self.hits_anything(&ray, u32::MAX)).then_some(value?);
        }
        if self.scene.opaque_to_object_shadows
            && let (SourceTarget::Object(target), Some(v)) = (source.target, value)
        {
            // `source_value` met the source at `sr.length`.
            return self
                .source_is_nearest(&ray, target, sr.length, None, &ShadowWalk::PLAIN)
                .then_some(v);
        }
        match self.nearest(&ray, f64::INFINITY, f64::NEG_INFINITY, None) {
            None => value,
            Some(h) if value.is_some() && source.target == SourceTarget::Object(h.object) => value,
            Some(h) => {
                // Something is in the way (or a mirror to follow): shade it as a shadow
                // ray would see it.
                if shaded {
                    // The same ray as above: `spawn` depends on `r` and `kind` alone.
                    *sr = self.spawn(r, RayKind::SHADOW, None)?;
                    sr.dir = dir;
                    sr.source = Some(si);
                    sr.coef = c;
                }
                sr.hit = Target::Object(ObjectId(h.object));
                sr.length = h.t;
                sr.point = sr.org + sr.dir * h.t;
                sr.normal = h.normal;
                sr.rod = h.rod;
                self.shade_object(sr, h.object, h.sub);
                participate(sr);
                let mean = (sr.color.x + sr.color.y + sr.color.z) / 3.0;
                (mean > FTINY).then(|| sr.color * c)
            }
        }
    }

    /// The value of source `si` seen along shadow ray `probe`, shading `probe` as the
    /// source surface (what it held of a hit is overwritten).
    pub(super) fn source_value(&self, probe: &mut RayState, si: usize) -> Option<Color> {
        let s = self.scene.sources.get(si)?;
        let (org, dir) = (probe.org, probe.dir);
        match s.target {
            SourceTarget::Object(o) => {
                let obj = self.scene.object(o)?;
                let h = obj.shape.intersect(&Ray::new(org, dir))?;
                probe.hit = Target::Object(ObjectId(o));
                probe.length = h.t;
                probe.point = org + dir * h.t;
                probe.normal = h.normal;
                probe.rod = h.rod;
                self.shade(probe, obj.material);
            }
            SourceTarget::Distant(d) => {
                probe.hit = Target::Distant(d);
                self.shade(probe, self.scene.distant.get(d as usize)?.material);
            }
        }
        participate(probe);
        Some(probe.color)
    }
}
