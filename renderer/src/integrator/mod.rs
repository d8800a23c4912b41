//! Ray evaluation as Radiance's `raytrace()` does it: find the nearest surface (ties
//! broken as `rayreject` breaks them), shade it with its material, fall back on distant
//! sources for rays that hit nothing, and add direct light by shadow rays to each
//! source sample (`direct()` in source.c, testing every sample: rtrace `-dt 0`). Indirect
//! light is sampled by [`crate::ambient`] for `-ab` bounces, then the constant `-av`.

use crate::bvh::Prepared;
use crate::lights::SourceTarget;
use crate::materials::plastic::Plastic;
use crate::materials::{Material, MaterialId, ShadingContext};
use crate::math::{Color, FHUGE, FTINY, Vec3, intensity};
use crate::ray::{ObjectId, Ray};
use crate::scene::MAX_LAMPS;
use crate::scene::Scene;
use crate::shapes::Shape;

mod direct;
mod nearest;
mod options;
mod ray_state;
mod shadows;

pub use options::{Options, RayKind};
pub use ray_state::{RayState, Target};
use shadows::ShadowWalk;

/// Salt of a ray's Russian roulette draw.
const ROULETTE: u64 = 0x5255_4c45;
/// Salts of the jitter of each source's samples (plus the source index).
const SOURCE_JITTER: u64 = 0x4a49_5454_0000;

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
const LAMBERTIAN: Plastic = Plastic {
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
            self.shade_object(r, c.object, c.sub);
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
    fn shade_object(&self, r: &mut RayState, object: u32, sub: u32) {
        let Some(o) = self.scene.hit_info(object) else {
            return;
        };
        if r.clipset.contains(&o.modifier) {
            r.other_length = r.length;
            return self.transmit(r);
        }
        let material = if o.mesh {
            self.mesh_surface(r, object, sub)
        } else {
            o.material()
        };
        self.shade(r, material);
    }

    /// A mesh hit's smoothed normal and (u,v) into `r`, and its material: the
    /// triangle's own when the mesh's modifier is `void` and the triangle has one,
    /// otherwise the mesh's (o_mesh.c).
    fn mesh_surface(&self, r: &mut RayState, object: u32, sub: u32) -> Option<MaterialId> {
        let o = self.scene.object(object)?;
        let crate::shapes::Shape::Mesh(mesh) = &o.shape else {
            return o.material;
        };
        let s = mesh.surface(&Ray::new(r.org, r.dir), sub, r.normal);
        r.pert = s.pert;
        r.uv = s.uv;
        match usize::try_from(s.material) {
            Ok(m) if m < o.triangle_materials.len() => {
                r.triangle = u16::try_from(m).ok();
                o.triangle_materials[m].material
            }
            _ => o.material,
        }
    }

    /// Shades a hit with `material` (`rayshade`); no material lets the ray through.
    pub fn shade(&self, r: &mut RayState, material: Option<MaterialId>) {
        if let Some(id) = material
            && let Some(patterns) = self.scene.patterns_of(id)
        {
            return self.shade_patterned(r, id, patterns);
        }
        if let Some(id) = material
            && r.pert != Vec3::ZERO
        {
            return self.shade_patterned(r, id, &[]);
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
            && matches!(material, Material::Plastic(n) if n.transmission.is_none())
        {
            return;
        }
        let view = r.view();
        let mut pcol = Color::ONE;
        // The surface's own perturbation comes first; textures add to it.
        let mut pert = r.pert;
        if let Some(functions) = self.scene.functions.as_deref() {
            for &i in patterns {
                if let Some(p) = functions.patterns.get(i as usize) {
                    p.apply(functions, i, &view, &mut pcol, &mut pert);
                }
            }
        } else if pert == Vec3::ZERO {
            return self.shade_with(r, Some(material));
        }
        // What the material shades with, and what `-on` reports (`r->pert`).
        r.pert = pert;
        let mut shaded = material.clone();
        match &mut shaded {
            Material::Plastic(n) => {
                n.color *= pcol;
                n.texture = pert;
            }
            Material::Emitter(e) => e.color *= pcol,
            Material::Function(f) => {
                f.color *= pcol;
                f.texture = pert;
            }
            Material::Brtd(b, _) => {
                b.pattern_color = pcol;
                b.texture = pert;
            }
            Material::Anisotropic(a) => {
                a.color *= pcol;
                a.texture = pert;
            }
            Material::Mirror(m) => {
                m.color *= pcol;
                m.texture = pert;
            }
            Material::Glass(g) => {
                g.pattern_color = pcol;
                g.texture = pert;
            }
            Material::Dielectric(d) => {
                d.pattern_color = pcol;
                d.texture = pert;
            }
            Material::Ashikhmin(a) => {
                a.color *= pcol;
                a.texture = pert;
            }
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
                Some(
                    Material::Plastic(_)
                    | Material::Mirror(_)
                    | Material::Anisotropic(_)
                    | Material::Function(_)
                    | Material::Brtd(..)
                    | Material::Ashikhmin(_),
                ) => {
                    return LAMBERTIAN.shade(self, r);
                }
                _ => {}
            }
        }
        match material {
            Some(Material::Plastic(n)) => n.shade(self, r),
            Some(Material::Mirror(m)) => m.shade(self, r),
            Some(Material::Glass(g)) => g.shade(self, r),
            Some(Material::Dielectric(d)) => d.shade(self, r),
            Some(Material::Antimatter(a)) => a.shade(self, r),
            Some(Material::Anisotropic(a)) => a.shade(self, r),
            Some(Material::Mist(m)) => m.shade(self, r),
            Some(Material::Emitter(e)) => e.shade(self, r),
            Some(Material::Mixture(m)) => m.shade(self, r),
            Some(Material::Function(f)) => f.shade(self, r),
            Some(Material::Brtd(b, _)) => b.shade(self, r),
            Some(Material::Ashikhmin(a)) => a.shade(self, r),
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
            pert: Vec3::ZERO,
            uv: [0.0, 0.0],
            triangle: None,
        })
    }
}

/// The tracer is the context materials shade in when rendering.
impl ShadingContext for Tracer<'_> {
    fn options(&self) -> &Options {
        &self.options
    }

    fn hit_is_flat(&self, r: &RayState) -> bool {
        r.hit_is_flat(self.scene)
    }

    fn aimed_at_other_source(&self, r: &RayState) -> Option<bool> {
        r.aimed_at_other_source(self.scene)
    }

    fn aimed_source_is_weak(&self, r: &RayState) -> bool {
        Tracer::aimed_source_is_weak(self, r)
    }

    fn imaged_source(&self, source: usize) -> Option<usize> {
        self.scene.sources.get(source).and_then(|s| s.parent)
    }

    fn spawn(&self, r: &RayState, kind: RayKind, coef: Option<Color>) -> Option<RayState> {
        Tracer::spawn(self, r, kind, coef)
    }

    fn trace(&self, r: &mut RayState) {
        Tracer::trace(self, r)
    }

    fn shade(&self, r: &mut RayState, material: Option<MaterialId>) {
        Tracer::shade(self, r, material)
    }

    fn transmit(&self, r: &mut RayState) {
        Tracer::transmit(self, r)
    }

    fn brdf(
        &self,
        pattern: u32,
        view: &crate::procedural::RayView,
        shade: &crate::procedural::ShadeState,
        dir: Vec3,
        omega: f64,
    ) -> Option<f64> {
        let functions = self.scene.functions.as_deref()?;
        let p = functions.patterns.get(pattern as usize)?;
        p.brdf(functions, pattern, view, shade, dir, omega)
    }

    fn brtd(
        &self,
        pattern: u32,
        view: &crate::procedural::RayView,
        shade: &crate::procedural::ShadeState,
        part: crate::materials::brtd::BrtdPart,
    ) -> Option<Color> {
        use crate::materials::brtd::BrtdPart;
        let functions = self.scene.functions.as_deref()?;
        let p = functions.patterns.get(pattern as usize)?;
        match part {
            BrtdPart::Mirror => p.brtd_coefficient(functions, pattern, view, shade, 0),
            BrtdPart::Straight => p.brtd_coefficient(functions, pattern, view, shade, 1),
            BrtdPart::Directional(dir, omega) => {
                p.brtd_directional(functions, pattern, view, shade, dir, omega)
            }
        }
    }

    fn orientation(&self, pattern: u32, view: &crate::procedural::RayView) -> Option<Vec3> {
        let functions = self.scene.functions.as_deref()?;
        let p = functions.patterns.get(pattern as usize)?;
        p.vector(functions, pattern, view)
            .map(|v| Vec3::new(v[0], v[1], v[2]))
    }

    fn mixture_coefficient(&self, pattern: u32, r: &RayState) -> Option<f64> {
        let functions = self.scene.functions.as_deref()?;
        let p = functions.patterns.get(pattern as usize)?;
        p.coefficient(functions, pattern, &r.view())
    }

    fn ambient(&self, r: &RayState, coef: Color, normal: Vec3) -> Color {
        Tracer::ambient(self, r, coef, normal)
    }

    fn direct(&self, r: &mut RayState, coef: &dyn Fn(Vec3, f64) -> Color) {
        Tracer::direct(self, r, coef)
    }
}

#[cfg(test)]
mod tests {
    use super::shadows::SETTLE;
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
