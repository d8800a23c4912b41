//! Ray evaluation as Radiance's `raytrace()` does it: find the nearest surface (ties
//! broken as `rayreject` breaks them), shade it with its material, fall back on distant
//! sources for rays that hit nothing, and add direct light by shadow rays to each
//! source sample (`direct()` in source.c, testing every sample: rtrace `-dt 0`). Indirect
//! light is the constant ambient value (`-ab 0 -av r g b`).

use crate::lights::{SourceSample, SourceTarget};
use crate::materials::plastic::Normal;
use crate::materials::{Material, MaterialId};
use crate::math::{Color, FHUGE, FTINY, Vec3, brightness, intensity};
use crate::ray::{ObjectId, Ray};
use crate::scene::Scene;

/// Ray types (Radiance's `PRIMARY`, `RSHADOW`, ... flags); a ray's `kind` is its own
/// type or'ed with its ancestors'.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayKind(pub u32);

impl RayKind {
    pub const PRIMARY: RayKind = RayKind(0o1);
    pub const SHADOW: RayKind = RayKind(0o2 | 0o200);
    pub const REFLECTED: RayKind = RayKind(0o4);
    pub const TRANS: RayKind = RayKind(0o20);
    pub const AMBIENT: RayKind = RayKind(0o40 | 0o400);
    pub const SPECULAR: RayKind = RayKind(0o100 | 0o1000);

    pub fn any(self, other: RayKind) -> bool {
        self.0 & other.0 != 0
    }

    /// Kinds that start a new reflection level.
    fn reflects(self) -> bool {
        self.0 & (0o2 | 0o4 | 0o40 | 0o100) != 0
    }
}

impl std::ops::BitOr for RayKind {
    type Output = RayKind;
    fn bitor(self, o: RayKind) -> RayKind {
        RayKind(self.0 | o.0)
    }
}

/// rtrace/rpict options that change values.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// `-av`: the ambient radiance.
    pub ambient: Color,
    /// `-ds`: source partition size ratio (0 disables partitioning).
    pub source_size_ratio: f64,
    /// `-lr`: reflection limit (negative: a hard limit of its magnitude).
    pub max_depth: i32,
    /// `-lw`: rays of lower weight are not traced.
    pub min_weight: f64,
    /// `-st`: rough highlights at or below this specularity are not sampled.
    pub specular_threshold: f64,
    /// `-bv`: back faces are visible (otherwise rays pass through them).
    pub backface_visible: bool,
    /// `-i`: primary rays report the irradiance at the opaque surfaces they hit.
    pub irradiance_at_hits: bool,
}

impl Default for Options {
    /// rtrace's defaults.
    fn default() -> Options {
        Options {
            ambient: Color::ZERO,
            source_size_ratio: 0.2,
            max_depth: -10,
            min_weight: 1e-4,
            specular_threshold: 0.15,
            backface_visible: true,
            irradiance_at_hits: false,
        }
    }
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    None,
    Object(ObjectId),
    Distant(u32),
}

/// A ray being evaluated: Radiance's `RAY` without the parts radc does not model.
#[derive(Clone, Debug)]
pub struct RayState {
    pub org: Vec3,
    pub dir: Vec3,
    pub kind: RayKind,
    pub weight: f64,
    pub level: u32,
    /// Coefficient applied by the parent.
    pub coef: Color,
    /// Source this (shadow) ray is aimed at.
    pub source: Option<usize>,
    pub hit: Target,
    /// Distance to the hit (`FHUGE` when nothing was hit).
    pub length: f64,
    pub point: Vec3,
    /// Surface normal, flipped to face the ray by two-sided materials.
    pub normal: Vec3,
    pub rod: f64,
    pub flips: u32,
    pub color: Color,
    /// The part of `color` from a mirror reflection, and the distance it appears at.
    pub mirror_color: Color,
    pub mirror_length: f64,
    /// The distance of everything else (through transparent surfaces).
    pub other_length: f64,
}

impl RayState {
    pub fn primary(org: Vec3, dir: Vec3) -> RayState {
        RayState {
            org,
            dir,
            kind: RayKind::PRIMARY,
            weight: 1.0,
            level: 0,
            coef: Color::ONE,
            source: None,
            hit: Target::None,
            length: FHUGE,
            point: org,
            normal: -dir,
            rod: 1.0,
            flips: 0,
            color: Color::ZERO,
            mirror_color: Color::ZERO,
            mirror_length: FHUGE,
            other_length: FHUGE,
        }
    }

    /// Radiance's `flipsurface`: look at the back as if it were the front.
    pub fn flip(&mut self) {
        self.rod = -self.rod;
        self.normal = -self.normal;
        self.flips += 1;
    }

    /// `raydistance`: where the ray's value appears to come from.
    pub fn effective_length(&self) -> f64 {
        if brightness(self.mirror_color) > 0.5 * brightness(self.color) {
            self.mirror_length
        } else {
            self.other_length
        }
    }

    /// For a shadow ray: whether what it hit is not the source it was aimed at (`None`
    /// when it is not aimed at a source).
    pub fn aimed_at_other_source(&self, scene: &Scene) -> Option<bool> {
        let s = scene.sources.get(self.source?)?;
        let on_target = match (s.target, self.hit) {
            (SourceTarget::Object(a), Target::Object(b)) => a == b.0,
            (SourceTarget::Distant(a), Target::Distant(b)) => a == b,
            _ => false,
        };
        Some(!on_target)
    }

    pub fn hit_is_flat(&self, scene: &Scene) -> bool {
        match self.hit {
            Target::Object(o) => scene.object(o.0).is_some_and(|o| o.shape.is_flat()),
            _ => false,
        }
    }

    /// The unperturbed normal as it was before any flips (`-oN`).
    pub fn surface_normal(&self) -> Vec3 {
        if self.flips % 2 == 1 {
            -self.normal
        } else {
            self.normal
        }
    }
}

/// Radiance's `Lamb`: white plastic of reflectance pi, which reflects the irradiance.
const LAMBERTIAN: Normal = Normal {
    color: Color::splat(std::f64::consts::PI),
    spec: 0.0,
    rough: 0.0,
    metal: false,
};

/// Evaluates rays in a compiled scene.
pub struct Tracer<'a> {
    scene: &'a Scene,
    options: Options,
}

/// The best hit so far and what `rayreject` compares.
#[derive(Clone, Copy)]
struct Candidate {
    object: u32,
    t: f64,
    normal: Vec3,
    rod: f64,
}

impl<'a> Tracer<'a> {
    pub fn new(scene: &'a Scene, options: Options) -> Tracer<'a> {
        Tracer { scene, options }
    }

    pub fn scene(&self) -> &'a Scene {
        self.scene
    }

    pub fn options(&self) -> &Options {
        &self.options
    }

    /// A primary ray's full evaluation.
    pub fn radiance(&self, org: Vec3, dir: Vec3) -> RayState {
        let mut r = RayState::primary(org, dir);
        self.trace(&mut r);
        r
    }

    /// Irradiance at `org` for a surface facing `dir` (rtrace `-I`): a white Lambertian
    /// surface of reflectance `pi` pretended to be hit just in front of the point.
    pub fn irradiance(&self, org: Vec3, dir: Vec3) -> RayState {
        let mut r = RayState::primary(org + dir * 1.1e-4, -dir);
        r.length = 1e-5;
        r.other_length = 1e-5;
        r.point = r.org + r.dir * r.length;
        r.normal = dir;
        r.rod = 1.0;
        LAMBERTIAN.shade(self, &mut r);
        r
    }

    /// Radiance's `raytrace`.
    pub fn trace(&self, r: &mut RayState) {
        if let Some(c) = self.nearest(&Ray::new(r.org, r.dir)) {
            r.hit = Target::Object(ObjectId(c.object));
            r.length = c.t;
            r.point = r.org + r.dir * c.t;
            r.normal = c.normal;
            r.rod = c.rod;
            let material = self.scene.object(c.object).and_then(|o| o.material);
            self.shade(r, material);
        } else if let Some(d) = self.distant_hit(r) {
            r.hit = Target::Distant(d);
            let material = self.scene.distant.get(d as usize).and_then(|o| o.material);
            self.shade(r, material);
        }
    }

    /// Shades a hit with `material` (`rayshade`); no material lets the ray through.
    pub fn shade(&self, r: &mut RayState, material: Option<MaterialId>) {
        r.other_length = r.length;
        let material = material.and_then(|m| self.scene.material(m));
        // `-i`: a primary (or passed-through) ray sees every reflecting surface as the
        // white Lambertian of `-I` (raytrace.c's `raytirrad`); lights stay lights.
        let primary = r.kind.0 & !(RayKind::PRIMARY.0 | RayKind::TRANS.0) == 0;
        if self.options.irradiance_at_hits
            && primary
            && matches!(material, Some(Material::Normal(_) | Material::Mirror(_)))
        {
            return LAMBERTIAN.shade(self, r);
        }
        match material {
            Some(Material::Normal(n)) => n.shade(self, r),
            Some(Material::Mirror(m)) => m.shade(self, r),
            Some(Material::Emitter(e)) => e.shade(self, r),
            None => self.transmit(r),
        }
    }

    /// Whether the source a shadow ray aims at is a glow or illum (`illumblock`).
    pub fn aimed_source_is_weak(&self, r: &RayState) -> bool {
        let Some(s) = r.source.and_then(|s| self.scene.sources.get(s)) else {
            return false;
        };
        let material = match s.target {
            SourceTarget::Object(o) => self.scene.object(o).and_then(|o| o.material),
            SourceTarget::Distant(d) => self.scene.distant.get(d as usize).and_then(|d| d.material),
        };
        matches!(material.and_then(|m| self.scene.material(m)), Some(Material::Emitter(e)) if e.is_weak())
    }

    /// Continues a ray unchanged past its hit (`raytrans`).
    pub fn transmit(&self, r: &mut RayState) {
        let Some(mut child) = self.spawn(r, RayKind::TRANS, None) else {
            return;
        };
        child.dir = r.dir;
        self.trace(&mut child);
        r.mirror_color = child.mirror_color;
        r.color = child.color;
        r.mirror_length = r.length + child.mirror_length;
        r.other_length = r.length + child.other_length;
    }

    /// A child ray from `r`'s hit point (`rayorigin`), or `None` when it would be too
    /// weak or too deep. Radiance plays Russian roulette with rays below `-lw` when `-lr`
    /// is not positive; radc drops them, which keeps results repeatable.
    pub fn spawn(&self, r: &RayState, kind: RayKind, coef: Option<Color>) -> Option<RayState> {
        if r.length >= FHUGE * 0.99 {
            return None;
        }
        let rw = coef.map_or(1.0, |c| intensity(c).min(1.0));
        let mut child = RayState::primary(r.point, r.dir);
        child.kind = r.kind | kind;
        child.coef = coef.unwrap_or(Color::ONE);
        child.weight = r.weight * rw;
        child.level = r.level + u32::from(kind.reflects());
        child.source = if kind.reflects() { None } else { r.source };
        if child.weight <= 0.0 || child.weight.is_nan() {
            return None;
        }
        if child.kind.any(RayKind::SHADOW) {
            return Some(child);
        }
        let o = &self.options;
        let limit = o.max_depth.unsigned_abs();
        let ok = if o.max_depth <= 0 && coef.is_some() {
            !(o.max_depth < 0 && child.level > limit) && child.weight >= o.min_weight
        } else {
            child.weight >= o.min_weight && child.level <= limit
        };
        ok.then_some(child)
    }

    /// The nearest surface along `ray`, with Radiance's tie rules for surfaces within
    /// `FTINY` of each other: a surface with a material beats one without, a front face
    /// beats a back face, then the later modifier wins.
    fn nearest(&self, ray: &Ray) -> Option<Candidate> {
        let mut best: Option<Candidate> = None;
        self.scene.bvh.traverse(ray, f64::INFINITY, |i| {
            if let Some(o) = self.scene.object(i)
                && let Some(h) = o.shape.intersect(ray, best.map_or(f64::INFINITY, |b| b.t))
            {
                let cand = Candidate {
                    object: i,
                    t: h.t,
                    normal: h.normal,
                    rod: h.rod,
                };
                if !self.rejects(best.as_ref(), &cand) {
                    best = Some(cand);
                }
            }
            best.map_or(f64::INFINITY, |b| b.t + FTINY)
        });
        best
    }

    fn rejects(&self, best: Option<&Candidate>, new: &Candidate) -> bool {
        let Some(old) = best else {
            return new.t <= FTINY;
        };
        if new.t <= FTINY || new.t > old.t + FTINY {
            return true;
        }
        if new.t < old.t - FTINY {
            return false;
        }
        let (Some(on), Some(oo)) = (self.scene.object(new.object), self.scene.object(old.object))
        else {
            return true;
        };
        match (on.material.is_some(), oo.material.is_some()) {
            (false, true) => return true,
            (true, false) => return false,
            _ => {}
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
    fn distant_hit(&self, r: &RayState) -> Option<u32> {
        let aimed = r
            .source
            .and_then(|s| self.scene.sources.get(s))
            .map(|s| s.target);
        let mut glow = None;
        let mut trans_illum = None;
        for (i, d) in self.scene.distant.iter().enumerate() {
            let i = i as u32;
            if 2.0 * std::f64::consts::PI * (1.0 - d.direction.dot(r.dir)) > d.solid_angle {
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

    /// Adds the direct contribution of every source to `r` (`direct()`), `coef` giving
    /// the material's coefficient for a source sample direction and solid angle.
    pub fn direct(&self, r: &mut RayState, coef: &dyn Fn(Vec3, f64) -> Color) {
        let mut samples: Vec<SourceSample> = Vec::new();
        for (si, s) in self.scene.sources.iter().enumerate() {
            samples.clear();
            s.samples(
                r.point,
                r.weight,
                self.options.source_size_ratio,
                &mut samples,
            );
            for sample in &samples {
                let c = coef(sample.dir, sample.omega);
                if intensity(c) <= 0.0 {
                    continue;
                }
                if let Some(v) = self.source_contribution(r, si, sample.dir, c) {
                    r.color += v;
                }
            }
        }
    }

    /// The radiance a shadow ray toward source `si` brings, times `c`, or `None` when
    /// blocked.
    fn source_contribution(&self, r: &RayState, si: usize, dir: Vec3, c: Color) -> Option<Color> {
        let mut sr = self.spawn(r, RayKind::SHADOW, None)?;
        sr.dir = dir;
        sr.source = Some(si);
        sr.coef = c;
        // The source's own value, from the source surface alone (`srcvalue`).
        let value = self.source_value(&sr, si)? * c;
        match self.nearest(&Ray::new(sr.org, sr.dir)) {
            None => Some(value),
            Some(h) if self.scene.sources[si].target == SourceTarget::Object(h.object) => {
                Some(value)
            }
            Some(h) => {
                // Something else is in the way: shade it as a shadow ray would see it.
                sr.hit = Target::Object(ObjectId(h.object));
                sr.length = h.t;
                sr.point = sr.org + sr.dir * h.t;
                sr.normal = h.normal;
                sr.rod = h.rod;
                let material = self.scene.object(h.object).and_then(|o| o.material);
                self.shade(&mut sr, material);
                let mean = (sr.color.x + sr.color.y + sr.color.z) / 3.0;
                (mean > FTINY).then(|| sr.color * c)
            }
        }
    }

    fn source_value(&self, sr: &RayState, si: usize) -> Option<Color> {
        let s = self.scene.sources.get(si)?;
        let mut probe = sr.clone();
        match s.target {
            SourceTarget::Object(o) => {
                let obj = self.scene.object(o)?;
                let h = obj
                    .shape
                    .intersect(&Ray::new(sr.org, sr.dir), f64::INFINITY)?;
                probe.hit = Target::Object(ObjectId(o));
                probe.length = h.t;
                probe.point = sr.org + sr.dir * h.t;
                probe.normal = h.normal;
                probe.rod = h.rod;
                self.shade(&mut probe, obj.material);
            }
            SourceTarget::Distant(d) => {
                probe.hit = Target::Distant(d);
                self.shade(&mut probe, self.scene.distant.get(d as usize)?.material);
            }
        }
        Some(probe.color)
    }
}
