//! Ray evaluation as Radiance's `raytrace()` does it: find the nearest surface (ties
//! broken as `rayreject` breaks them), shade it with its material, fall back on distant
//! sources for rays that hit nothing, and add direct light by shadow rays to each
//! source sample (`direct()` in source.c, testing every sample: rtrace `-dt 0`). Indirect
//! light is sampled by [`crate::ambient`] for `-ab` bounces, then the constant `-av`.

use crate::bvh::Prepared;
use crate::lights::{Lamp, SourceSample, SourceTarget};
use crate::materials::plastic::Normal;
use crate::materials::{Material, MaterialId};
use crate::math::{Color, FHUGE, FTINY, Vec3, brightness, intensity};
use crate::ray::{ObjectId, Ray, ShapeHit};
use crate::scene::MAX_LAMPS;
use crate::scene::Scene;
use crate::shapes::Shape;

/// Ray types (Radiance's `PRIMARY`, `RSHADOW`, ... flags); a ray's `kind` is its own
/// type or'ed with its ancestors'.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayKind(pub u32);

impl RayKind {
    pub const PRIMARY: RayKind = RayKind(0o1);
    pub const SHADOW: RayKind = RayKind(0o2 | 0o200);
    pub const REFLECTED: RayKind = RayKind(0o4);
    pub const REFRACTED: RayKind = RayKind(0o10);
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
    /// `-dr`: relays of light through mirrors (virtual sources; apply with
    /// `Scene::add_virtual_sources`).
    pub relays: u32,
    /// `-me`: extinction coefficient of the medium filling the scene (absorbing only).
    pub medium: Color,
    /// `-dv`: light sources are seen by rays (otherwise only by shadow rays).
    pub direct_visible: bool,
    /// `-ab`: ambient bounces: diffuse reflections estimated by Monte Carlo hemisphere
    /// sampling before the constant `-av` takes over.
    pub ambient_bounces: u32,
    /// `-ad`: hemisphere samples at full ray weight (0: no sampling).
    pub ambient_divisions: u32,
    /// `-as`: extra samples, at full ray weight, for the strata that differ most from
    /// their neighbours.
    pub ambient_supersamples: u32,
    /// `-dj`: source jitter, 0 (sample points at partition centres) to 1 (anywhere in
    /// the partition).
    pub source_jitter: f64,
    /// `-dx+` (radc's own): sample convex polygon, disk, sphere and distant sources
    /// with each partition's exact solid angle, so that a fully visible source lights a
    /// Lambertian surface exactly (`lights::Source::exact_samples`). Off, samples are
    /// Radiance's partition centres and agree with rtrace.
    pub exact_sources: bool,
    /// Rays below `-lw` play Russian roulette when `-lr` is not positive (Radiance's
    /// `rayorigin`). Off, they are dropped, which keeps `-ab 0 -dj 0` deterministic.
    pub russian_roulette: bool,
}

impl Options {
    /// Whether any option asks for random sampling (then Russian roulette is played as
    /// Radiance plays it).
    pub fn samples_randomly(&self) -> bool {
        (self.ambient_bounces > 0 && self.ambient_divisions > 0) || self.source_jitter > 0.0
    }
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
            relays: 2,
            medium: Color::ZERO,
            direct_visible: true,
            ambient_bounces: 0,
            ambient_divisions: 1024,
            ambient_supersamples: 512,
            source_jitter: 0.0,
            exact_sources: false,
            russian_roulette: false,
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
struct Shot {
    source: usize,
    dir: Vec3,
    c: Color,
    hit: Option<Option<ShapeHit>>,
}

/// The packed polygon a point's shadow rays start from: its slot, normal, and the
/// point's gap to its plane, as its test computes them. A walk may skip the slot for
/// a ray its plane test surely rejects ([`StartPlane::skip`]): it cannot hit the
/// surface it leaves, and testing it is most of the calls a shadow walk makes.
#[derive(Clone, Copy)]
struct StartPlane {
    slot: u32,
    normal: Vec3,
    gap: f64,
}

impl StartPlane {
    /// No polygon: `skip` always gives `u32::MAX` (a zero `rod`).
    const NONE: StartPlane = StartPlane {
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
    fn skip(&self, dir: Vec3) -> u32 {
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
struct ShadowWalk<'p> {
    from: u32,
    prepared: Option<&'p Prepared>,
}

impl ShadowWalk<'_> {
    /// Nothing known beforehand.
    const PLAIN: ShadowWalk<'static> = ShadowWalk {
        from: u32::MAX,
        prepared: None,
    };
}

/// A ray being evaluated: Radiance's `RAY` without the parts radc does not model.
#[derive(Clone, Debug)]
pub struct RayState {
    pub org: Vec3,
    pub dir: Vec3,
    pub kind: RayKind,
    pub weight: f64,
    pub level: u32,
    /// Rays in the chain down from the primary, of every kind (transmitted rays keep
    /// `level`).
    pub depth: u32,
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
    /// Extinction coefficient of the medium the ray travels in (inside a dielectric).
    pub extinction: Color,
    /// Distance travelled from the eye to this ray's origin.
    pub path_length: f64,
    /// Farthest distance the ray may hit at (0: unlimited; rtrace's `-ld`, the aft
    /// clipping plane). Rays passed through a surface keep what is left of it.
    pub max_distance: f64,
    /// Modifiers whose surfaces this ray passes through (inside `antimatter`), and the
    /// set its transmitted continuations get (`clipset`, `newcset`).
    pub clipset: Vec<i64>,
    pub new_clipset: Option<Vec<i64>>,
    /// For each transmitted link up the ray tree: the modifier of the surface passed
    /// and whether it was entered from the front (antimatter's penetration count).
    pub passages: Vec<(i64, bool)>,
    /// Seed of this ray's random choices ([`crate::random`]).
    pub seed: u64,
    /// Ambient rays among this ray's ancestors (and itself): Radiance's ambient
    /// recursion depth, compared with `-ab`.
    pub ambient_depth: u32,
}

impl RayState {
    pub fn primary(org: Vec3, dir: Vec3) -> RayState {
        RayState {
            org,
            dir,
            kind: RayKind::PRIMARY,
            weight: 1.0,
            level: 0,
            depth: 0,
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
            extinction: Color::ZERO,
            path_length: 0.0,
            max_distance: 0.0,
            clipset: Vec::new(),
            new_clipset: None,
            passages: Vec::new(),
            seed: 0,
            ambient_depth: 0,
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
            Target::Object(o) => scene.hit_info(o.0).is_some_and(|o| o.flat),
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

/// Salt of a ray's Russian roulette draw.
const ROULETTE: u64 = 0x5255_4c45;
/// Salts of the jitter of each source's samples (plus the source index).
const SOURCE_JITTER: u64 = 0x4a49_5454_0000;

/// How many FTINY-wide ties (plus as many relative 1e-6 margins) a blocker must lie
/// before a surface source for a shadow ray to settle on it without the nearest hit.
const SETTLE: f64 = 16.0;

/// Longest chain of rays radc follows. Radiance limits reflections (`-lr`) but not rays
/// passing through surfaces; a scene of thousands of stacked `void` surfaces would
/// otherwise exhaust the stack.
pub const MAX_CHAIN: u32 = 10_000;

/// Absorption along a ray inside a medium (`rayparticipate` without scattering).
fn participate(r: &mut RayState) {
    r.color = absorbed(r.color, r.extinction, r.length);
}

/// `color` after `length` through a medium of extinction coefficient `extinction`.
fn absorbed(color: Color, extinction: Color, length: f64) -> Color {
    if extinction.max_element() <= 1.0 / FHUGE {
        return color;
    }
    let att = |k: f64| {
        let e = length * k;
        if e <= FTINY {
            1.0
        } else if e > 92.0 {
            0.0
        } else {
            (-e).exp()
        }
    };
    color * Color::new(att(extinction.x), att(extinction.y), att(extinction.z))
}

/// The weight of a child of `r` whose coefficient has intensity `rw` (at most 1): the
/// parent's path through an absorbing medium weakens what follows it.
fn child_weight(r: &RayState, rw: f64) -> f64 {
    let weight = r.weight * rw;
    let re = r.extinction.min_element() * r.length;
    if re > 0.1 {
        if re > 92.0 { 0.0 } else { weight * (-re).exp() }
    } else {
        weight
    }
}

/// Whether `r` may have a child of weight `weight` at all (the limits of `rayorigin`
/// that hold for every kind, shadow rays included).
fn may_spawn(r: &RayState, weight: f64) -> bool {
    if r.length >= FHUGE * 0.99 || r.depth >= MAX_CHAIN {
        return false;
    }
    weight > 0.0
}

/// Radiance's `Lamb`: white plastic of reflectance pi, which reflects the irradiance.
const LAMBERTIAN: Normal = Normal {
    color: Color::splat(std::f64::consts::PI),
    spec: 0.0,
    rough: 0.0,
    metal: false,
    transmission: None,
    texture: Vec3::ZERO,
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
        self.radiance_within(org, dir, 0.0)
    }

    /// A primary ray that may hit nothing beyond `max_distance` (0: no limit).
    pub fn radiance_within(&self, org: Vec3, dir: Vec3, max_distance: f64) -> RayState {
        self.radiance_seeded(org, dir, max_distance, 0)
    }

    /// [`Tracer::radiance_within`] for primary ray number `index` (its random choices
    /// derive from the index alone).
    pub fn radiance_seeded(&self, org: Vec3, dir: Vec3, max_distance: f64, index: u64) -> RayState {
        self.radiance_prepared(
            org,
            dir,
            max_distance,
            index,
            &Prepared::of(&Ray::new(org, dir)),
        )
    }

    /// [`Tracer::radiance_seeded`] with the ray's slab values prepared beforehand
    /// (`Prepared::of(&Ray::new(org, dir))`): a caller tracing many rays prepares the
    /// next while this one is traced, and its divisions overlap this ray's work.
    pub fn radiance_prepared(
        &self,
        org: Vec3,
        dir: Vec3,
        max_distance: f64,
        index: u64,
        prepared: &Prepared,
    ) -> RayState {
        let mut r = RayState::primary(org, dir);
        r.max_distance = max_distance;
        r.extinction = self.options.medium;
        r.seed = crate::random::primary_seed(index);
        self.trace_prepared(&mut r, Some(prepared));
        r
    }

    /// Irradiance at `org` for a surface facing `dir` (rtrace `-I`): a white Lambertian
    /// surface of reflectance `pi` pretended to be hit just in front of the point.
    pub fn irradiance(&self, org: Vec3, dir: Vec3) -> RayState {
        self.irradiance_seeded(org, dir, 0)
    }

    /// [`Tracer::irradiance`] for input ray number `index`.
    pub fn irradiance_seeded(&self, org: Vec3, dir: Vec3, index: u64) -> RayState {
        let mut r = RayState::primary(org + dir * 1.1e-4, -dir);
        r.seed = crate::random::primary_seed(index);
        r.extinction = self.options.medium;
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
        self.trace_prepared(r, None);
    }

    /// [`Tracer::trace`], with `r`'s slab values when they were prepared beforehand.
    #[inline(always)]
    fn trace_prepared(&self, r: &mut RayState, prepared: Option<&Prepared>) {
        let limit = if r.max_distance > FTINY {
            r.max_distance
        } else {
            f64::INFINITY
        };
        let ray = Ray::new(r.org, r.dir);
        let prepared = Prepared::given_or_of(prepared, &ray);
        if let Some(c) = self.nearest_prepared(&ray, &prepared, limit, f64::NEG_INFINITY, None) {
            r.hit = Target::Object(ObjectId(c.object));
            r.length = c.t;
            r.point = r.org + r.dir * c.t;
            r.normal = c.normal;
            r.rod = c.rod;
            self.shade_object(r, c.object);
        } else if limit.is_finite() {
            // Stopped by the aft plane: nothing seen, not even distant sources.
        } else if let Some(d) = self.distant_hit(r) {
            r.hit = Target::Distant(d);
            let material = self.scene.distant.get(d as usize).and_then(|o| o.material);
            self.shade(r, material);
        }
        participate(r);
    }

    /// Shades a surface hit (`raycont`): surfaces whose modifier the ray's antimatter set
    /// holds are passed through.
    fn shade_object(&self, r: &mut RayState, object: u32) {
        let Some(o) = self.scene.hit_info(object) else {
            return;
        };
        if r.clipset.contains(&o.modifier) {
            r.other_length = r.length;
            return self.transmit(r);
        }
        self.shade(r, o.material());
    }

    /// Shades a hit with `material` (`rayshade`); no material lets the ray through.
    pub fn shade(&self, r: &mut RayState, material: Option<MaterialId>) {
        if let Some(id) = material
            && let Some(patterns) = self.scene.patterns_of(id)
        {
            return self.shade_patterned(r, id, patterns);
        }
        self.shade_with(r, material.and_then(|m| self.scene.material(m)));
    }

    /// `raytexture` before the material: the patterns give the colour (`pcol`) the
    /// material's or light's own colour is multiplied by (normal.c, source.c
    /// `m_light`), the textures the perturbation of its normal (`pert`), then it is
    /// shaded with them.
    fn shade_patterned(&self, r: &mut RayState, id: MaterialId, patterns: &[u32]) {
        let Some(material) = self.scene.material(id) else {
            return;
        };
        // normal.c's easy shadow test comes before its patterns.
        if r.kind.any(RayKind::SHADOW)
            && matches!(material, Material::Normal(n) if n.transmission.is_none())
        {
            return;
        }
        let Some(functions) = self.scene.functions.as_deref() else {
            return self.shade_with(r, Some(material));
        };
        let view = crate::procedural::RayView {
            dir: r.dir,
            normal: r.normal,
            point: r.point,
            total_distance: r.path_length + r.length,
            length: r.length,
            rod: r.rod,
            uv: [0.0, 0.0],
        };
        let mut pcol = Color::ONE;
        let mut pert = Vec3::ZERO;
        for &i in patterns {
            if let Some(p) = functions.patterns.get(i as usize) {
                p.apply(functions, i, &view, &mut pcol, &mut pert);
            }
        }
        let mut shaded = material.clone();
        match &mut shaded {
            Material::Normal(n) => {
                n.color *= pcol;
                n.texture = pert;
            }
            Material::Emitter(e) => e.color *= pcol,
            _ => {}
        }
        self.shade_with(r, Some(&shaded));
    }

    /// [`Tracer::shade`] with the material itself.
    fn shade_with(&self, r: &mut RayState, material: Option<&Material>) {
        r.other_length = r.length;
        // `-i`: a primary (or passed-through) ray sees every reflecting surface as the
        // white Lambertian of `-I` (raytrace.c's `raytirrad`); lights stay lights.
        let primary = r.kind.0 & !(RayKind::PRIMARY.0 | RayKind::TRANS.0) == 0;
        if self.options.irradiance_at_hits && primary {
            match material {
                Some(m) if m.is_transparent() => return self.transmit(r),
                Some(Material::Normal(_) | Material::Mirror(_) | Material::Anisotropic(_)) => {
                    return LAMBERTIAN.shade(self, r);
                }
                _ => {}
            }
        }
        match material {
            Some(Material::Normal(n)) => n.shade(self, r),
            Some(Material::Mirror(m)) => m.shade(self, r),
            Some(Material::Glass(g)) => g.shade(self, r),
            Some(Material::Dielectric(d)) => d.shade(self, r),
            Some(Material::Antimatter(a)) => a.shade(self, r),
            Some(Material::Anisotropic(a)) => a.shade(self, r),
            Some(Material::Mist(m)) => m.shade(self, r),
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
    /// is not positive; radc does too when it samples at random (`-ab`, `-dj`), and
    /// otherwise drops them, which keeps results repeatable.
    pub fn spawn(&self, r: &RayState, kind: RayKind, coef: Option<Color>) -> Option<RayState> {
        self.spawn_salted(r, kind, coef, u64::from(kind.0))
    }

    /// [`Tracer::spawn`] for one of several siblings of one kind: `salt` tells them
    /// apart in the child's seed.
    pub fn spawn_salted(
        &self,
        r: &RayState,
        kind: RayKind,
        coef: Option<Color>,
        salt: u64,
    ) -> Option<RayState> {
        let rw = coef.map_or(1.0, |c| intensity(c).min(1.0));
        let mut weight = child_weight(r, rw);
        if !may_spawn(r, weight) {
            return None;
        }
        let reflects = kind.reflects();
        let child_kind = r.kind | kind;
        let mut child_coef = coef.unwrap_or(Color::ONE);
        let level = r.level + u32::from(reflects);
        let depth = r.depth + 1;
        let seed = crate::random::derive(r.seed, salt);
        if !child_kind.any(RayKind::SHADOW) {
            let o = &self.options;
            let limit = o.max_depth.unsigned_abs();
            let ok = if o.max_depth <= 0 && coef.is_some() {
                if o.max_depth < 0 && level > limit {
                    return None;
                }
                if weight < o.min_weight && o.russian_roulette && o.min_weight > 0.0 {
                    // Survivors are promoted to the limit weight, their coefficient
                    // scaled to keep the estimate unbiased.
                    let keep = weight / o.min_weight;
                    if crate::random::uniform(seed, ROULETTE) >= keep {
                        return None;
                    }
                    child_coef /= keep;
                    weight = o.min_weight;
                }
                weight >= o.min_weight
            } else {
                weight >= o.min_weight && level <= limit
            };
            if !ok {
                return None;
            }
        }
        let mut passages = r.passages.clone();
        if !reflects
            && let Target::Object(o) = r.hit
            && let Some(obj) = self.scene.hit_info(o.0)
        {
            passages.push((obj.modifier, r.rod > 0.0));
        }
        // Built once all is decided, in place (no ray state copied on the way out).
        Some(RayState {
            org: r.point,
            dir: r.dir,
            kind: child_kind,
            weight,
            level,
            depth,
            coef: child_coef,
            source: if reflects { None } else { r.source },
            hit: Target::None,
            length: FHUGE,
            point: r.point,
            normal: -r.dir,
            rod: 1.0,
            flips: 0,
            color: Color::ZERO,
            mirror_color: Color::ZERO,
            mirror_length: FHUGE,
            other_length: FHUGE,
            extinction: r.extinction,
            path_length: r.path_length + r.length,
            max_distance: if reflects || r.max_distance <= FTINY {
                0.0
            } else {
                r.max_distance - r.length
            },
            clipset: if reflects {
                r.clipset.clone()
            } else {
                r.new_clipset.clone().unwrap_or_else(|| r.clipset.clone())
            },
            new_clipset: None,
            passages,
            seed,
            ambient_depth: r.ambient_depth + u32::from(kind == RayKind::AMBIENT),
        })
    }

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
    fn nearest(
        &self,
        ray: &Ray,
        limit: f64,
        settle: f64,
        known: Option<(u32, ShapeHit)>,
    ) -> Option<Candidate> {
        self.nearest_prepared(ray, &Prepared::of(ray), limit, settle, known)
    }

    /// [`Tracer::nearest`] with `ray`'s slab values prepared beforehand.
    fn nearest_prepared(
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
    fn hits_anything(&self, ray: &Ray, from: u32) -> bool {
        let scene = self.scene;
        scene.bvh.any(ray, f64::INFINITY, [from, u32::MAX], |slot| {
            scene
                .surfaces
                .intersect(slot, &scene.objects, ray, f64::INFINITY)
                .is_some()
        })
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
    fn distant_hit(&self, r: &RayState) -> Option<u32> {
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
    fn direct_lamps(&self, r: &mut RayState, coef: &dyn Fn(Vec3, f64) -> Color, lamps: &[Lamp]) {
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
    fn source_surface_hit(&self, r: &RayState, si: usize, dir: Vec3) -> Option<Option<ShapeHit>> {
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
    fn source_contribution(&self, r: &RayState, shot: &Shot, start: &StartPlane) -> Option<Color> {
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

    /// [`Tracer::source_contribution`] toward the distant source `d` (no virtual one)
    /// in a scene opaque to shadows, without a shadow ray's state: the value
    /// `source_value` finds from the emitter alone (a fresh shadow ray faces it, and
    /// travels `FHUGE` through the medium), kept when the ray hits nothing. `None`
    /// where that needs the general path (an `illum`).
    fn distant_source_shadow(
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
    fn object_source_shadow(
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
    fn start_plane(&self, r: &RayState) -> StartPlane {
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
    fn source_is_nearest(
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
    fn blocked_before(
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

    /// [`Tracer::source_contribution`] by a shadow ray's full state.
    fn traced_source_contribution(
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
                self.shade_object(sr, h.object);
                participate(sr);
                let mean = (sr.color.x + sr.color.y + sr.color.z) / 3.0;
                (mean > FTINY).then(|| sr.color * c)
            }
        }
    }

    /// The value of source `si` seen along shadow ray `probe`, shading `probe` as the
    /// source surface (what it held of a hit is overwritten).
    fn source_value(&self, probe: &mut RayState, si: usize) -> Option<Color> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::tests::IrBuilder;
    use radc_lang::scene::ir::PrimKind;

    fn hit_name(scene: &Scene, org: Vec3, dir: Vec3) -> String {
        let t = Tracer::new(scene, Options::default());
        match t.radiance(org, dir).hit {
            Target::Object(o) => scene
                .object(o.0)
                .map(|o| o.name.clone())
                .unwrap_or_default(),
            _ => String::new(),
        }
    }

    /// Radiance's `rayreject`: among coincident surfaces the later modifier wins, a
    /// front face beats a back face, and a surface with a material beats one without.
    #[test]
    fn coincident_surfaces_break_ties_as_radiance() {
        let mut b = IrBuilder::default();
        let first = b.plastic("first", 0.2);
        let second = b.plastic("second", 0.8);
        b.square("early", first, 0.0, true);
        b.square("late", second, 0.0, true);
        let scene = Scene::compile(&b.scene).expect("compiles");
        assert_eq!(hit_name(&scene, Vec3::new(0.2, 0.1, 1.0), -Vec3::Z), "late");

        let mut b = IrBuilder::default();
        let first = b.plastic("first", 0.2);
        let second = b.plastic("second", 0.8);
        b.square("front", first, 0.0, true);
        b.square("back", second, 0.0, false);
        let scene = Scene::compile(&b.scene).expect("compiles");
        assert_eq!(
            hit_name(&scene, Vec3::new(0.2, 0.1, 1.0), -Vec3::Z),
            "front"
        );
    }

    /// Calls `each` with the points of an `n` by `n` grid over the square (-1, -1, 0) to
    /// (1, 1, 0).
    fn floor_grid(n: usize, mut each: impl FnMut(Vec3)) {
        let half = n as f64 / 2.0;
        for i in 0..n {
            for j in 0..n {
                each(Vec3::new(i as f64 / half - 1.0, j as f64 / half - 1.0, 0.0));
            }
        }
    }

    /// The radiance of rays from `org` toward every point of [`floor_grid`]`(n)`.
    fn grid_radiance(t: &Tracer<'_>, n: usize, org: Vec3) -> Vec<Color> {
        let mut colors = Vec::new();
        floor_grid(n, |aim| {
            colors.push(t.radiance(org, (aim - org).normalize()).color);
        });
        colors
    }

    /// Renders with a fast path on (`set(scene, true)`) and off, and asserts the
    /// colours are the same bit for bit, with more than `min_lit` of them lit.
    fn assert_same_both_ways(
        scene: &mut Scene,
        set: fn(&mut Scene, bool),
        options: &Options,
        min_lit: usize,
        render: impl Fn(&Tracer<'_>) -> Vec<Color>,
    ) {
        let mut pixels = Vec::new();
        for on in [true, false] {
            set(scene, on);
            pixels.push(render(&Tracer::new(scene, options.clone())));
        }
        let lit = pixels[1].iter().filter(|c| c.max_element() > 0.0).count();
        assert!(
            lit > min_lit,
            "the floor is lit ({lit} of {})",
            pixels[1].len()
        );
        for (k, (a, b)) in pixels[0].iter().zip(&pixels[1]).enumerate() {
            assert_eq!(
                a.to_array().map(f64::to_bits),
                b.to_array().map(f64::to_bits),
                "ray {k} with {options:?}"
            );
        }
    }

    /// A floor under three lamps: one with a coincident twin, one with a ball within
    /// `FTINY` below it, one alone; with the builder, a grey plastic and the lamps'
    /// light for more.
    fn lamps_with_near_blockers() -> (IrBuilder, u32, u32) {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        let lamp = b.add("light", "lamp", None, PrimKind::Light { color: [10.0; 3] });
        b.square("floor", grey, 0.0, true);
        b.sphere("lamp_a", lamp, [0.0, 0.0, 1.5], 0.1);
        b.sphere("twin_of_a", grey, [0.0, 0.0, 1.5], 0.1);
        b.sphere("lamp_b", lamp, [0.6, 0.0, 1.5], 0.1);
        b.sphere("touching_b", grey, [0.6, 0.0, 1.4 - 0.05 - 3e-7], 0.05);
        b.sphere("lamp_c", lamp, [-0.6, 0.3, 1.2], 0.1);
        (b, grey, lamp)
    }

    /// Shadow rays toward surface sources in a scene opaque to them end at the first
    /// clear blocker and never look beyond the source (`opaque_to_object_shadows`); the
    /// pixels are those of the full nearest-surface search, bit for bit, also with
    /// blockers coincident with a lamp, within `FTINY` of it, just before and just
    /// behind it, and lamps blocking each other.
    #[test]
    fn shadow_rays_settle_as_the_full_search_decides() {
        let (mut b, grey, lamp) = lamps_with_near_blockers();
        b.sphere("lamp_d", lamp, [-0.6, 0.3, 1.6], 0.1);
        b.sphere("behind_d", grey, [-0.6, 0.3, 1.7 + 0.02], 0.02);
        b.sphere("ball", grey, [0.3, -0.4, 0.5], 0.2);
        b.square("shelf", grey, 1.4 - 5e-7, false);
        let mut scene = Scene::compile(&b.scene).expect("compiles");
        assert!(scene.opaque_to_object_shadows);
        let set = |s: &mut Scene, on: bool| s.opaque_to_object_shadows = on;
        assert_same_both_ways(&mut scene, set, &Options::default(), 100, |t| {
            grid_radiance(t, 40, Vec3::new(0.05, -0.02, 1.3))
        });
    }

    /// [`Tracer::blocked_before`], where it answers, answers as the full search
    /// (`nearest`) does, and it leaves to that search exactly the shadow rays that meet
    /// another surface within the tie window around the source: the lamp with a
    /// coincident twin and the one with a ball within `FTINY` below it.
    #[test]
    fn clear_and_blocked_shadow_rays_are_decided_as_the_full_search_decides() {
        let (mut b, grey, _) = lamps_with_near_blockers();
        b.sphere("ball", grey, [0.3, -0.4, 0.5], 0.2);
        let scene = Scene::compile(&b.scene).expect("compiles");
        let t = Tracer::new(&scene, Options::default());
        let lamps: Vec<(u32, Vec3)> = scene
            .objects
            .iter()
            .enumerate()
            .filter(|(_, o)| o.name.starts_with("lamp"))
            .filter_map(|(i, o)| match &o.shape {
                Shape::Sphere(s) => Some((i as u32, s.center)),
                _ => None,
            })
            .collect();
        assert_eq!(lamps.len(), 3);
        let mut outcomes = [0usize; 3];
        floor_grid(40, |p| {
            for &(target, center) in &lamps {
                let org = p + Vec3::new(0.0, 0.0, 0.001);
                let ray = Ray::new(org, (center - org).normalize());
                let Some(h) = scene.objects[target as usize].shape.intersect(&ray) else {
                    continue;
                };
                let settle = h.t - SETTLE * (FTINY + 1e-6 * h.t);
                let full = matches!(
                    t.nearest(&ray, h.t, settle, Some((target, h))),
                    Some(b) if b.object != target
                );
                match t.blocked_before(&ray, target, h.t, settle, &ShadowWalk::PLAIN) {
                    Some(blocked) => {
                        assert_eq!(blocked, full, "{org} toward lamp {target}");
                        outcomes[usize::from(blocked)] += 1;
                    }
                    None => outcomes[2] += 1,
                }
            }
        });
        let [clear, blocked, unsure] = outcomes;
        assert!(clear > 100 && blocked > 100 && unsure > 100, "{outcomes:?}");
    }

    /// The settings the lamp tests render with: the defaults, `-bv-`, an absorbing
    /// medium (`-me`) and `-dv-`.
    fn lamp_variants() -> [Options; 4] {
        [
            Options::default(),
            Options {
                backface_visible: false,
                ..Options::default()
            },
            Options {
                medium: Color::new(0.1, 0.2, 0.4),
                ..Options::default()
            },
            Options {
                direct_visible: false,
                ..Options::default()
            },
        ]
    }

    /// Rays from above toward [`floor_grid`]`(30)`, and `-I` points just above each
    /// aim, some of them inside a lamp around (-0.5, -0.5, 0.15), which they see from
    /// the back.
    fn floor_and_irradiance(t: &Tracer<'_>) -> Vec<Color> {
        let mut colors = Vec::new();
        floor_grid(30, |aim| {
            let org = Vec3::new(0.05, -0.02, 1.3);
            colors.push(t.radiance_within(org, (aim - org).normalize(), 0.0).color);
            colors.push(t.irradiance(aim + Vec3::new(0.0, 0.0, 0.01), Vec3::Z).color);
        });
        colors
    }

    /// The shadow rays of a scene opaque to them bring, without a ray state, what the
    /// general path's shadow rays bring, bit for bit: toward a spotlight (inside and
    /// outside its cone), a glow, a lamp seen from inside (its back, also with `-bv-`,
    /// which passes the ray on), through an absorbing medium (`-me`) and with `-dv-`.
    #[test]
    fn light_shadow_rays_match_the_general_path() {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        let lamp = b.add("light", "lamp", None, PrimKind::Light { color: [10.0; 3] });
        let glow = b.add(
            "glow",
            "glow",
            None,
            PrimKind::Glow {
                color: [4.0, 5.0, 6.0],
                max_radius: 1.2,
            },
        );
        let spot = b.add(
            "spotlight",
            "spot",
            None,
            PrimKind::Spotlight {
                color: [20.0, 10.0, 5.0],
                angle: 40.0,
                direction: [0.3, 0.0, -1.0],
            },
        );
        b.square("floor", grey, 0.0, true);
        b.sphere("lamp", lamp, [0.0, 0.0, 1.5], 0.1);
        b.sphere("around", lamp, [-0.5, -0.5, 0.15], 0.3);
        b.sphere("glow", glow, [0.5, 0.5, 0.8], 0.1);
        b.sphere("spot", spot, [0.4, -0.4, 1.2], 0.05);
        b.sphere("ball", grey, [0.3, -0.1, 0.4], 0.15);
        let mut scene = Scene::compile(&b.scene).expect("compiles");
        assert!(scene.opaque_to_object_shadows);
        let set = |s: &mut Scene, on: bool| s.opaque_to_object_shadows = on;
        for options in lamp_variants() {
            assert_same_both_ways(&mut scene, set, &options, 200, floor_and_irradiance);
        }
    }

    /// Direct lighting's lamp path (`Scene::lamps`) adds what its general passes add,
    /// bit for bit: on a floor and balls, from lamps with blockers within `FTINY`, a
    /// coincident twin, and one lamp around part of the floor (its back seen, also with
    /// `-bv-`, which takes the traced path), through `-me` and with `-dv-`.
    #[test]
    fn lamp_path_matches_the_general_passes() {
        let (mut b, grey, lamp) = lamps_with_near_blockers();
        b.sphere("around", lamp, [-0.5, -0.5, 0.15], 0.3);
        b.sphere("ball", grey, [0.3, -0.4, 0.5], 0.2);
        let mut scene = Scene::compile(&b.scene).expect("compiles");
        assert_eq!(scene.lamps.as_ref().map(Vec::len), Some(4));
        let set = |s: &mut Scene, on: bool| {
            if on {
                s.pack_surfaces();
            } else {
                s.lamps = None;
            }
        };
        for options in lamp_variants() {
            assert_same_both_ways(&mut scene, set, &options, 200, floor_and_irradiance);
        }
    }

    /// A shadow ray's walk skips the polygon it starts on only where that polygon's own
    /// test finds no hit: from points where rays from above met the floor (and points a
    /// hair off it), toward directions all around, grazing ones included; it skips
    /// most of them.
    #[test]
    fn start_planes_are_skipped_only_where_their_test_misses() {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        b.square("floor", grey, 0.0, true);
        let scene = Scene::compile(&b.scene).expect("compiles");
        let t = Tracer::new(&scene, Options::default());
        let (mut skipped, mut tested) = (0, 0);
        floor_grid(20, |aim| {
            let org = Vec3::new(0.31, -0.17, 2.3);
            let mut r = t.radiance(org, (aim * 0.9 - org).normalize());
            let Target::Object(ObjectId(o)) = r.hit else {
                panic!("the ray toward {aim} hits the floor");
            };
            let slot = scene.surfaces.slot_of(o);
            // Also from just off the plane, where rays toward it must be tested.
            let lift = [0.0, 0.0, 1e-8, 1e-5, -1e-5][(aim.x * 10.0).rem_euclid(5.0) as usize];
            r.point.z += lift;
            let start = t.start_plane(&r);
            for k in 0..200 {
                let a = k as f64 * 0.7;
                // Elevations from straight up to just below the plane, some within a
                // hair of it.
                let z = [1.0, 0.3, 1e-3, 1e-9, 1e-15, 0.0, -1e-12, -0.2][k % 8];
                let dir = Vec3::new(a.cos(), a.sin(), z).normalize();
                let ray = Ray::new(r.point, dir);
                if start.skip(dir) == slot {
                    assert!(
                        scene
                            .surfaces
                            .intersect(slot, &scene.objects, &ray, f64::INFINITY)
                            .is_none(),
                        "skipped a hit from {} along {dir}",
                        r.point
                    );
                    skipped += 1;
                } else {
                    tested += 1;
                }
            }
        });
        assert!(
            skipped > 10 * tested && tested > 0,
            "{skipped} skipped, {tested} tested"
        );
    }

    /// Shadow rays toward a distant source in a scene opaque to shadows bring, without
    /// a ray state, what the general path's bring, bit for bit (also through `-me`).
    #[test]
    fn distant_shadow_rays_match_the_general_path() {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        let sun = b.add(
            "light",
            "sunlight",
            None,
            PrimKind::Light {
                color: [6e6, 6e6, 5.5e6],
            },
        );
        b.add(
            "source",
            "sun",
            Some(sun),
            PrimKind::Source {
                direction: [0.4, 0.3, 0.85],
                angle: 0.5,
            },
        );
        b.square("floor", grey, 0.0, true);
        for (k, c) in [[0.3, -0.4, 0.2], [-0.2, 0.3, 0.1]].into_iter().enumerate() {
            b.add(
                "sphere",
                &format!("ball{k}"),
                Some(grey),
                PrimKind::Sphere {
                    center: c,
                    radius: 0.15,
                },
            );
        }
        let mut scene = Scene::compile(&b.scene).expect("compiles");
        assert!(scene.opaque_to_shadows);
        let variants = [
            Options::default(),
            Options {
                medium: Color::new(1e-9, 2e-9, 4e-9),
                ..Options::default()
            },
            Options {
                backface_visible: false,
                direct_visible: false,
                ..Options::default()
            },
        ];
        let set = |s: &mut Scene, on: bool| s.opaque_to_shadows = on;
        for options in variants {
            assert_same_both_ways(&mut scene, set, &options, 100, |t| {
                grid_radiance(t, 30, Vec3::new(0.05, -0.02, 0.5))
            });
        }
    }

    /// Hits closer than `FTINY` are ignored: a ray leaving a surface does not hit it
    /// again.
    #[test]
    fn hits_within_ftiny_are_ignored() {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        b.square("floor", grey, 0.0, true);
        let scene = Scene::compile(&b.scene).expect("compiles");
        assert_eq!(
            hit_name(&scene, Vec3::new(0.0, 0.0, 0.5 * FTINY), -Vec3::Z),
            ""
        );
        assert_eq!(
            hit_name(&scene, Vec3::new(0.0, 0.0, 2.0 * FTINY), -Vec3::Z),
            "floor"
        );
    }
}
