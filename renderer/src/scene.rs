//! The compiled scene: the reachable surfaces of an `ir::Scene` with their shapes and
//! resolved materials, the BVH over them, and the light sources.
//!
//! Anything in a reachable modifier chain the renderer does not model is listed as
//! `Unsupported` with the chain, never dropped; `Scene::refusals` is what `radc check` and
//! the language server report as W0307. `Scene::validate` checks the indices tracing
//! relies on. Derived at compile and at load, never stored: `Scene::opaque_to_shadows`
//! (every surface is plastic or metal without transmission, so a shadow ray toward a
//! distant source is decided by its first hit), `Scene::opaque_to_object_shadows` (every
//! surface is such or a light, glow or spotlight: a shadow ray toward a surface source
//! only asks whether the source is the nearest surface), `HitInfo` (per object the
//! material, modifier and flatness shading reads, 16 bytes apart from the `Object`), the
//! lamps and the packed surfaces.

use radc_lang::scene::ir::{self, ModRef, PrimId, PrimKind};
use radc_lang::schema::Category;

use crate::bvh::Bvh;
use crate::lights::{Lamp, Source, SourceShape, SourceTarget};
use crate::materials::anisotropic::Anisotropic;
use crate::materials::antimatter::Antimatter;
use crate::materials::ashikhmin::Ashikhmin;
use crate::materials::brtd::Brtd;
use crate::materials::dielectric::Dielectric;
use crate::materials::function::FunctionMaterial;
use crate::materials::glass::Glass;
use crate::materials::light::{Emitter, EmitterKind, Spot};
use crate::materials::mirror::Mirror;
use crate::materials::mist::Mist;
use crate::materials::mixture::Mixture;
use crate::materials::{Alternate, Material, MaterialId, metal, plastic, trans};
use crate::math::{FTINY, Vec3, vec3};
use crate::procedural::{
    DataLookup, DataSource, Engine, Functions, MixSource, Pattern, PatternKind, PictureLookup,
    ProgramId,
};
use crate::shapes::{Cone, MeshGeometry, MeshShape, Polygon, Ring, Shape, Sphere};
use crate::surfaces::Surfaces;

/// A surface.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Object {
    /// The primitive this object was compiled from.
    #[serde(with = "crate::scene_file::prim_id")]
    pub prim: PrimId,
    pub name: String,
    pub shape: Shape,
    pub material: Option<MaterialId>,
    /// Index of the modifier primitive (-1 for `void`): Radiance breaks ties between
    /// coincident surfaces in favour of the later modifier.
    pub modifier: i64,
    pub modifier_name: String,
    pub material_name: String,
    /// For a mesh with a `void` modifier: per material of its file, that material
    /// compiled (in the mesh's frame); empty for everything else.
    #[serde(default)]
    pub triangle_materials: Vec<TriangleMaterial>,
}

/// A mesh file's material as its triangles are shaded with it.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct TriangleMaterial {
    pub material: Option<MaterialId>,
    /// The modifier's name (rtrace `-om`) and its material's (`-oM`).
    pub modifier_name: String,
    pub material_name: String,
}

/// What tracing and shading read of a hit object, 16 bytes each apart from the
/// [`Object`]s (240 bytes, mostly names): in a large scene a hit then touches one line
/// of a compact list instead of a record far from any cache.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HitInfo {
    pub modifier: i64,
    /// The material's index, `u32::MAX` for none.
    material: u32,
    pub flat: bool,
    /// A mesh: shading asks its triangle for the material, normal and (u,v).
    pub mesh: bool,
}

impl HitInfo {
    fn of(o: &Object) -> HitInfo {
        HitInfo {
            modifier: o.modifier,
            material: o.material.map_or(u32::MAX, |m| m.0),
            flat: o.shape.is_flat(),
            mesh: matches!(o.shape, Shape::Mesh(_)),
        }
    }

    pub fn material(&self) -> Option<MaterialId> {
        (self.material != u32::MAX).then_some(MaterialId(self.material))
    }
}

/// A distant `source`: seen by rays that hit nothing, within its cone.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct DistantObject {
    pub name: String,
    pub direction: Vec3,
    pub solid_angle: f64,
    pub material: Option<MaterialId>,
    pub modifier_name: String,
    pub material_name: String,
}

#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub distant: Vec<DistantObject>,
    pub materials: Vec<Material>,
    pub sources: Vec<Source>,
    pub bvh: Bvh,
    /// The BVH's leaf slots' geometry, derived from `objects` and `bvh`
    /// ([`Scene::pack_surfaces`]).
    #[serde(skip)]
    pub surfaces: Surfaces,
    /// Per object what a hit needs of it, derived with `surfaces`.
    #[serde(skip)]
    hits: Vec<HitInfo>,
    /// Every surface has a plastic or metal material with no transmission, which shades
    /// shadow rays black whatever else holds (and without antimatter no ray passes a
    /// surface): a shadow ray toward a distant source is blocked by anything it hits,
    /// so only whether it hits anything matters. Derived with `surfaces`.
    #[serde(skip)]
    pub opaque_to_shadows: bool,
    /// Every surface shades shadow rays black as above, or emits without being an
    /// `illum` (a light, glow or spotlight blocks shadow rays aimed at other sources):
    /// a shadow ray toward a surface source brings its value exactly when that source
    /// is the nearest surface, and nothing otherwise. Derived with `surfaces`.
    #[serde(skip)]
    pub opaque_to_object_shadows: bool,
    /// Every source as a [`Lamp`], when each is one, there are at most [`MAX_LAMPS`]
    /// and the scene is opaque to object shadows: direct lighting then takes
    /// [`crate::integrator::Tracer::direct`]'s lamp path. Derived with `surfaces`.
    #[serde(skip)]
    pub lamps: Option<Vec<Lamp>>,
    /// The patterns materials and lights are shaded with, compiled (`None`: none).
    /// Not stored in compiled scene files, which refuse such scenes.
    #[serde(skip)]
    pub functions: Option<std::sync::Arc<Functions>>,
    /// Per material, the patterns (indices into `functions`) applied before shading,
    /// nearest modifier first; empty for most.
    #[serde(skip)]
    pub material_patterns: Vec<Vec<u32>>,
}

/// The most sources the lamp path of direct lighting takes (its buffers are arrays).
pub const MAX_LAMPS: usize = 8;

/// Something in the scene radc cannot render yet (or that Radiance refuses at render
/// time), by primitive name and type, with the modifier chain that reaches it.
#[derive(Clone, Debug, PartialEq)]
pub struct Unsupported {
    pub prim: PrimId,
    pub name: String,
    pub type_name: &'static str,
    pub why: String,
    /// What uses the refused primitive (what it modifies, the alias or material naming
    /// it), nearest first, each as `type 'name'`, down to the surface (when the surface was kept): a pattern deep in a chain is
    /// only found by its users.
    pub chain: Vec<String>,
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} '{}': {}", self.type_name, self.name, self.why)?;
        for (i, user) in self.chain.iter().enumerate() {
            let joint = if i == 0 { " (" } else { ", " };
            write!(f, "{joint}used by {user}")?;
        }
        if !self.chain.is_empty() {
            write!(f, ")")?;
        }
        Ok(())
    }
}

/// The renderer's judgement for `radc check` and the language server
/// ([`radc_lang::scene::RenderSupport`]): exactly what [`Scene::compile`] refuses.
pub struct RendererSupport;

impl radc_lang::scene::RenderSupport for RendererSupport {
    fn refusals(&self, scene: &ir::Scene) -> Vec<(PrimId, String)> {
        Scene::refusals(scene)
            .into_iter()
            .map(|u| (u.prim, u.to_string()))
            .collect()
    }
}

struct Compiler<'a> {
    ir: &'a ir::Scene,
    scene: Scene,
    /// Material index per primitive, once compiled.
    material_of_prim: Vec<Option<Option<MaterialId>>>,
    problems: Vec<Unsupported>,
    /// The primitives being compiled, from the surface down to the innermost
    /// modifier: the chain a refusal shows.
    path: Vec<PrimId>,
    functions: Functions,
    /// Pattern index per primitive, once compiled.
    pattern_of_prim: std::collections::HashMap<PrimId, u32>,
    material_patterns: Vec<Vec<u32>>,
    /// The material each surface-level pattern chain ends in, compiled with the chain.
    surface_chains: std::collections::HashMap<PrimId, (Option<MaterialId>, String)>,
    /// Mixtures of patterns compiled: pattern index, and whether a side has a texture.
    mixtures: std::collections::HashMap<PrimId, (u32, bool)>,
    /// Mesh files' geometry, built once per file.
    meshes: std::collections::HashMap<String, std::sync::Arc<MeshGeometry>>,
}

/// A mesh's placement (Radiance's `FULLXF`, both scales made positive as
/// `getmeshinst` makes them).
struct Frame {
    forward: radc_lang::transform::Transform,
    backward: radc_lang::transform::Transform,
}

impl Frame {
    fn of(words: &[String]) -> Option<Frame> {
        let words: Vec<(&str, radc_lang::Span)> = words
            .iter()
            .map(|w| (w.as_str(), radc_lang::Span::default()))
            .collect();
        let mut forward = radc_lang::transform::Transform::parse(&words).ok()?;
        let mut backward = radc_lang::transform::Transform::parse_inverse(&words).ok()?;
        forward.scale = forward.scale.abs();
        backward.scale = backward.scale.abs();
        Some(Frame { forward, backward })
    }
}

/// Why radc refuses a modifier of this category where it sits: the renderer does not
/// run function files yet, and a material shaded without its pattern, texture or
/// mixture would be silently wrong.
fn not_modelled(category: Category) -> &'static str {
    match category {
        Category::Pattern => "patterns are not rendered yet",
        Category::Texture => "textures are not rendered yet",
        Category::Mixture => "mixtures are not rendered yet",
        Category::Surface => "a surface cannot be a modifier",
        Category::Material | Category::Light | Category::Alias => {
            "this material type is not rendered yet"
        }
    }
}

impl<'a> Compiler<'a> {
    fn new(ir: &'a ir::Scene) -> Self {
        Compiler {
            ir,
            scene: Scene::default(),
            material_of_prim: vec![None; ir.prims.len()],
            problems: Vec::new(),
            path: Vec::new(),
            functions: Functions::new(),
            pattern_of_prim: std::collections::HashMap::new(),
            material_patterns: Vec::new(),
            surface_chains: std::collections::HashMap::new(),
            mixtures: std::collections::HashMap::new(),
            meshes: std::collections::HashMap::new(),
        }
    }

    /// Compiles every reachable surface, then what surfaces that were checked but not
    /// kept refer to (`ir::Scene::roots`), so a scene lowered for checking is judged as
    /// the full scene would be.
    fn compile_reachable(&mut self) {
        let ir = self.ir;
        let reachable = ir.reachable();
        for (i, p) in ir.prims.iter().enumerate() {
            if reachable.get(i) == Some(&true) && p.category() == Category::Surface {
                self.surface(PrimId(i as u32), p);
            }
        }
        for &root in &ir.roots {
            self.path.clear();
            self.material_of(ModRef::Prim(root));
        }
    }
}

impl Scene {
    /// Compiles the surfaces of `ir` that a render needs. Everything radc does not model
    /// yet is listed, never silently dropped.
    pub fn compile(ir: &ir::Scene) -> Result<Scene, Vec<Unsupported>> {
        Scene::compile_with(ir, Engine::Jit)
    }

    /// [`Scene::compile`], with the scene's functions run by `engine`.
    pub fn compile_with(ir: &ir::Scene, engine: Engine) -> Result<Scene, Vec<Unsupported>> {
        let mut c = Compiler::new(ir);
        c.compile_reachable();
        if !c.problems.is_empty() {
            return Err(c.problems);
        }
        let (sources, illegal) = find_sources(&c.scene);
        for i in illegal {
            if let Some(prim) = c.scene.objects.get(i).map(|o| o.prim) {
                c.unsupported(prim, "Radiance cannot use this shape as a light source");
            }
        }
        if !c.problems.is_empty() {
            return Err(c.problems);
        }
        let mut scene = c.scene;
        scene.sources = sources;
        if !c.functions.is_empty() {
            c.functions.compile(engine);
            scene.functions = Some(std::sync::Arc::new(c.functions));
        }
        c.material_patterns
            .resize(scene.materials.len(), Vec::new());
        scene.material_patterns = c.material_patterns;
        let objects = &scene.objects;
        scene.bvh = Bvh::build_with(objects.len(), |i| objects[i].shape.bounds());
        scene.pack_surfaces();
        Ok(scene)
    }

    /// What [`Scene::compile`] would refuse in `ir`, without building anything else:
    /// `radc check` warns of exactly these, so check and render never disagree.
    pub fn refusals(ir: &ir::Scene) -> Vec<Unsupported> {
        let mut c = Compiler::new(ir);
        c.compile_reachable();
        c.problems
    }

    /// Lays out the surfaces in BVH order for traversal (after the BVH was built or
    /// loaded).
    pub fn pack_surfaces(&mut self) {
        self.surfaces = Surfaces::pack(&self.objects, &self.bvh);
        self.hits = self.objects.iter().map(HitInfo::of).collect();
        let opaque = |m: Option<&Material>| matches!(m, Some(Material::Plastic(n)) if n.transmission.is_none());
        let material = |o: &Object| o.material.and_then(|m| self.material(m));
        let opaque_to_shadows = self.objects.iter().all(|o| opaque(material(o)));
        let opaque_to_object_shadows = self.objects.iter().all(|o| {
            let m = material(o);
            opaque(m)
                || matches!(m, Some(Material::Emitter(e)) if !matches!(e.kind, EmitterKind::Illum { .. }))
        });
        self.opaque_to_shadows = opaque_to_shadows;
        self.opaque_to_object_shadows = opaque_to_object_shadows;
        // A patterned light's value depends on the ray: no lamp path.
        let patterned_light = self.sources.iter().any(|s| {
            let material = match s.target {
                SourceTarget::Object(o) => self.object(o).and_then(|o| o.material),
                SourceTarget::Distant(d) => self.distant.get(d as usize).and_then(|d| d.material),
            };
            material.is_some_and(|m| self.patterns_of(m).is_some())
        });
        self.lamps =
            (opaque_to_object_shadows && !patterned_light && self.sources.len() <= MAX_LAMPS)
                .then(|| {
                    self.sources
                        .iter()
                        .map(|s| Lamp::of(s, &self.objects))
                        .collect::<Option<Vec<Lamp>>>()
                })
                .flatten();
    }

    /// Whether a surface is a mesh (compiled scene files do not hold their geometry).
    pub fn has_meshes(&self) -> bool {
        self.objects
            .iter()
            .any(|o| matches!(o.shape, Shape::Mesh(_)))
    }

    /// Checks the indices that tracing relies on: what a compiled scene file
    /// (`scene_file`) holds was written by this code, but a damaged or foreign payload
    /// with a matching checksum must give an error, not a panic.
    pub fn validate(&self) -> Result<(), String> {
        self.bvh.validate(self.objects.len())?;
        if let Some(p) = self.objects.iter().find_map(|o| match &o.shape {
            Shape::Polygon(p) if p.vertices.len() < 3 => Some(&o.name),
            _ => None,
        }) {
            return Err(format!("polygon '{p}' has fewer than 3 vertices"));
        }
        for s in &self.sources {
            let ok = match s.target {
                SourceTarget::Object(i) => (i as usize) < self.objects.len(),
                SourceTarget::Distant(i) => (i as usize) < self.distant.len(),
            };
            if !ok || s.parent.is_some_and(|p| p >= self.sources.len()) {
                return Err("a light source refers to a surface out of range".into());
            }
        }
        // Alternates are compiled before the materials that name them, so a chain
        // always ends; a loop (only a damaged file has one) would recurse forever.
        for start in &self.materials {
            let mut next = start.alternate();
            for _ in 0..=self.materials.len() {
                next = match next {
                    Some(m) => self.material(m).and_then(Material::alternate),
                    None => break,
                };
            }
            if next.is_some() {
                return Err("materials name each other as alternates in a loop".into());
            }
        }
        Ok(())
    }

    /// The patterns material `id` is shaded with, if any.
    #[inline]
    pub fn patterns_of(&self, id: MaterialId) -> Option<&[u32]> {
        self.material_patterns
            .get(id.0 as usize)
            .filter(|p| !p.is_empty())
            .map(Vec::as_slice)
    }

    pub fn material(&self, id: MaterialId) -> Option<&Material> {
        self.materials.get(id.0 as usize)
    }

    /// Bytes that finding a ray's nearest hit reads from: BVH nodes, slots, packed
    /// shapes and hit records. Above the size of a core's cache, the order rays are
    /// traced in decides how many of those reads go to memory.
    pub fn traversal_bytes(&self) -> usize {
        self.bvh.bytes() + self.surfaces.bytes() + std::mem::size_of_val(self.hits.as_slice())
    }

    pub fn object(&self, i: u32) -> Option<&Object> {
        self.objects.get(i as usize)
    }

    /// Starts fetching object `i`'s [`HitInfo`] (a hint).
    #[inline(always)]
    pub fn prefetch_hit_info(&self, i: u32) {
        if let Some(h) = self.hits.get(i as usize) {
            crate::math::prefetch(h);
        }
    }

    /// What a hit on object `i` needs of it ([`Scene::pack_surfaces`] must have run).
    #[inline]
    pub fn hit_info(&self, i: u32) -> Option<HitInfo> {
        self.hits.get(i as usize).copied()
    }
}

impl Compiler<'_> {
    fn unsupported(&mut self, id: PrimId, why: &'static str) {
        self.refuse_with(id, why.to_string());
    }

    fn refuse_with(&mut self, id: PrimId, why: String) {
        let Some(p) = self.ir.get(id) else { return };
        let chain = self
            .path
            .iter()
            .rev()
            .filter(|&&user| user != id)
            .filter_map(|&user| self.ir.get(user))
            .map(|u| format!("{} '{}'", u.schema.name, u.name))
            .collect();
        self.problems.push(Unsupported {
            prim: id,
            name: p.name.clone(),
            type_name: p.schema.name,
            why,
            chain,
        });
    }

    fn surface(&mut self, id: PrimId, p: &ir::Prim) {
        self.path.clear();
        self.path.push(id);
        self.surface_shape(id, p);
        self.path.clear();
    }

    fn surface_shape(&mut self, id: PrimId, p: &ir::Prim) {
        let shape = match &p.kind {
            PrimKind::Sphere { center, radius } | PrimKind::Bubble { center, radius } => {
                Some(Shape::Sphere(Sphere {
                    center: vec3(*center),
                    radius: radius.abs(),
                    inward: matches!(p.kind, PrimKind::Bubble { .. }),
                }))
            }
            PrimKind::Polygon { vertices } => {
                Polygon::new(vertices.iter().map(|v| vec3(*v)).collect()).map(Shape::Polygon)
            }
            PrimKind::Ring {
                center,
                normal,
                r0,
                r1,
            } => Ring::new(vec3(*center), vec3(*normal), *r0, *r1).map(Shape::Ring),
            PrimKind::Cone { p0, p1, r0, r1 } | PrimKind::Cup { p0, p1, r0, r1 } => Cone::new(
                vec3(*p0),
                vec3(*p1),
                *r0,
                *r1,
                matches!(p.kind, PrimKind::Cup { .. }),
            )
            .map(Shape::Cone),
            PrimKind::Cylinder { p0, p1, radius } | PrimKind::Tube { p0, p1, radius } => Cone::new(
                vec3(*p0),
                vec3(*p1),
                *radius,
                *radius,
                matches!(p.kind, PrimKind::Tube { .. }),
            )
            .map(Shape::Cone),
            PrimKind::Source { direction, angle } => {
                self.distant_source(id, p, vec3(*direction), *angle);
                return;
            }
            PrimKind::Mesh {
                file,
                transform,
                materials,
            } => return self.mesh(id, p, file, transform, materials),
            PrimKind::Instance { .. } => {
                return self.unsupported(id, "instances are not rendered yet");
            }
            _ => return,
        };
        // Degenerate geometry (zero area, zero axis) is never hit, as in Radiance.
        let Some(shape) = shape else { return };
        let (material, material_name) = self.material_of(p.modifier);
        self.scene.objects.push(Object {
            prim: id,
            name: p.name.clone(),
            shape,
            material,
            modifier: match p.modifier {
                ModRef::Prim(m) => i64::from(m.0),
                _ => -1,
            },
            modifier_name: self.modifier_name(p.modifier),
            material_name,
            triangle_materials: Vec::new(),
        });
    }

    /// A `mesh`: its file's geometry (one tree per file, shared), its placement, and
    /// its materials: the modifier's, or with `void` the file's own per triangle.
    fn mesh(
        &mut self,
        id: PrimId,
        p: &ir::Prim,
        file: &str,
        words: &[String],
        materials: &[PrimId],
    ) {
        let Some(data) = self.ir.data.meshes.get(file) else {
            return self.refuse_with(id, format!("its mesh file '{file}' could not be loaded"));
        };
        let geometry = self
            .meshes
            .entry(file.to_string())
            .or_insert_with(|| std::sync::Arc::new(MeshGeometry::new(data.clone())))
            .clone();
        let Some(frame) = Frame::of(words) else {
            return self.unsupported(id, "bad transform");
        };
        let shape = Shape::Mesh(MeshShape::new(geometry, frame.forward, frame.backward));
        let (material, material_name) = self.material_of(p.modifier);
        let triangle_materials = materials
            .iter()
            .map(|&m| {
                let (material, material_name) = self.material_of(ModRef::Prim(m));
                TriangleMaterial {
                    material,
                    modifier_name: self.modifier_name(ModRef::Prim(m)),
                    material_name,
                }
            })
            .collect();
        self.scene.objects.push(Object {
            prim: id,
            name: p.name.clone(),
            shape,
            material,
            modifier: match p.modifier {
                ModRef::Prim(m) => i64::from(m.0),
                _ => -1,
            },
            modifier_name: self.modifier_name(p.modifier),
            material_name,
            triangle_materials,
        });
    }

    fn distant_source(&mut self, id: PrimId, p: &ir::Prim, direction: Vec3, angle: f64) {
        let Some(SourceShape::Distant {
            direction,
            solid_angle,
        }) = SourceShape::distant(direction, angle)
        else {
            return self.unsupported(id, "a source needs a non-zero direction and angle");
        };
        let (material, material_name) = self.material_of(p.modifier);
        self.scene.distant.push(DistantObject {
            name: p.name.clone(),
            direction,
            solid_angle,
            material,
            modifier_name: self.modifier_name(p.modifier),
            material_name,
        });
    }

    fn modifier_name(&self, m: ModRef) -> String {
        match m {
            ModRef::Prim(id) => self.ir.get(id).map(|p| p.name.clone()).unwrap_or_default(),
            _ => "void".into(),
        }
    }

    /// Radiance's `findmaterial`: the material a surface's modifier names.
    fn material_of(&mut self, m: ModRef) -> (Option<MaterialId>, String) {
        let ModRef::Prim(id) = m else {
            return (None, "void".into());
        };
        let Some(p) = self.ir.get(id) else {
            return (None, "void".into());
        };
        match p.category() {
            Category::Material | Category::Light | Category::Alias => {
                let name = p.name.clone();
                (self.compile_material(id), name)
            }
            Category::Pattern | Category::Texture => self.patterned_material(id),
            Category::Mixture if is_rendered_mixture(p.schema.name) && self.mixes_materials(id) => {
                let name = p.name.clone();
                (self.mixture_material(id), name)
            }
            Category::Mixture if is_rendered_mixture(p.schema.name) => self.patterned_material(id),
            category @ Category::Mixture => {
                self.unsupported(id, not_modelled(category));
                (None, String::new())
            }
            Category::Surface => (None, "void".into()),
        }
    }

    /// A surface modified by patterns or textures before its material (`rayshade`
    /// applies each modifier until a material shades): the material compiled again
    /// with those applied first. Its name (for `-om`) is the material's, as rtrace
    /// reports the modifier that shades.
    fn patterned_material(&mut self, first: PrimId) -> (Option<MaterialId>, String) {
        if let Some(done) = self.surface_chains.get(&first) {
            return done.clone();
        }
        let done = self.patterned_material_once(first);
        self.surface_chains.insert(first, done.clone());
        done
    }

    fn patterned_material_once(&mut self, first: PrimId) -> (Option<MaterialId>, String) {
        let mut prefix = Vec::new();
        let mut next = Some(first);
        let depth = self.path.len();
        let mut target = None;
        while let Some(m) = next {
            let Some(p) = self.ir.get(m) else { break };
            if prefix.len() > self.ir.prims.len() {
                break;
            }
            match p.category() {
                Category::Pattern | Category::Texture if is_rendered_pattern(p.schema.name) => {
                    let Some(i) = self.pattern(m) else {
                        self.path.truncate(depth);
                        return (None, String::new());
                    };
                    prefix.push((i, is_texture(p.schema.name), m));
                    self.path.push(m);
                    next = match p.modifier {
                        ModRef::Prim(n) => Some(n),
                        _ => None,
                    };
                }
                Category::Mixture if is_rendered_mixture(p.schema.name) => {
                    if self.mixes_materials(m) {
                        self.unsupported(
                            m,
                            "patterns before a mixture of materials are not rendered yet",
                        );
                        self.path.truncate(depth);
                        return (None, String::new());
                    }
                    let Some((i, texture)) = self.mixture_pattern(m) else {
                        self.path.truncate(depth);
                        return (None, String::new());
                    };
                    prefix.push((i, texture, m));
                    self.path.push(m);
                    next = match p.modifier {
                        ModRef::Prim(n) => Some(n),
                        _ => None,
                    };
                }
                Category::Material | Category::Light | Category::Alias => {
                    target = Some(m);
                    break;
                }
                category => {
                    self.unsupported(m, not_modelled(category));
                    self.path.truncate(depth);
                    return (None, String::new());
                }
            }
        }
        let Some(target) = target else {
            // Nothing shades: the ray passes, the patterns change nothing.
            self.path.truncate(depth);
            return (None, "void".into());
        };
        let name = self
            .ir
            .get(target)
            .map(|p| p.name.clone())
            .unwrap_or_default();
        let base = self.compile_material(target);
        self.path.truncate(depth);
        let Some(base) = base else {
            return (None, name);
        };
        let Some(material) = self.scene.material(base).cloned() else {
            return (None, name);
        };
        let kind = self.alias_target(target).unwrap_or(target);
        if let Some(&(_, texture, m)) = prefix
            .iter()
            .find(|(_, texture, _)| !self.takes_modifier(kind, *texture))
        {
            self.unsupported(m, refused_on(texture));
            return (None, name);
        }
        let mut patterns: Vec<u32> = prefix.iter().map(|(i, _, _)| *i).collect();
        if let Some(own) = self.material_patterns.get(base.0 as usize) {
            patterns.extend(own);
        }
        let mid = MaterialId(self.scene.materials.len() as u32);
        self.scene.materials.push(material);
        self.material_patterns
            .resize(self.scene.materials.len(), Vec::new());
        self.material_patterns[mid.0 as usize] = patterns;
        (Some(mid), name)
    }

    fn compile_material(&mut self, id: PrimId) -> Option<MaterialId> {
        if let Some(Some(done)) = self.material_of_prim.get(id.0 as usize) {
            return *done;
        }
        // Mark as in progress (an alternate naming itself ends here).
        if let Some(slot) = self.material_of_prim.get_mut(id.0 as usize) {
            *slot = Some(None);
        }
        let depth = self.path.len();
        self.path.push(id);
        let compiled = self.compile_material_kind(id);
        self.path.truncate(depth);
        compiled
    }

    /// The patterns applied to material `id` before it is shaded (an alias's own
    /// modifier, or the target's through `inherit`), as Radiance's `raytexture` walks
    /// them: nearest first, each one's own modifier next. `None` (after refusing it)
    /// where a modifier is not modelled, or `kind` does not take patterns yet.
    fn material_modifiers(&mut self, id: PrimId, kind: PrimId) -> Option<Vec<u32>> {
        let mut patterns = Vec::new();
        let mut next = self.effective_modifier(id);
        let depth = self.path.len();
        let mut result = Some(());
        while let Some(m) = next {
            if patterns.len() > self.ir.prims.len() {
                break;
            }
            let Some(p) = self.ir.get(m) else { break };
            let compiled = if is_rendered_mixture(p.schema.name) {
                if self.mixes_materials(m) {
                    self.unsupported(m, "a mixture of materials cannot modify a material");
                    result = None;
                    break;
                }
                self.mixture_pattern(m)
            } else if is_rendered_pattern(p.schema.name) {
                let texture = is_texture(p.schema.name);
                if self.takes_modifier(kind, texture) {
                    self.pattern(m).map(|i| (i, texture))
                } else {
                    self.unsupported(m, refused_on(texture));
                    None
                }
            } else {
                self.unsupported(m, not_modelled(p.category()));
                None
            };
            match compiled {
                Some((_, texture)) if !self.takes_modifier(kind, texture) => {
                    self.unsupported(m, refused_on(texture));
                    result = None;
                    break;
                }
                Some((i, _)) => patterns.push(i),
                None => {
                    result = None;
                    break;
                }
            }
            self.path.push(m);
            next = match p.modifier {
                ModRef::Prim(n) => Some(n),
                _ => None,
            };
        }
        self.path.truncate(depth);
        result.map(|()| patterns)
    }

    /// Whether material `kind` is shaded with patterns (or, `texture`, textures) yet:
    /// textures perturb the normal of the normal materials (and bend trans's and
    /// glass's transmitted rays), mirrors, anisotropic and function materials; lights
    /// take patterns only.
    fn takes_modifier(&self, kind: PrimId, texture: bool) -> bool {
        self.ir.get(kind).is_some_and(|k| match k.kind {
            PrimKind::Plastic { .. }
            | PrimKind::Metal { .. }
            | PrimKind::Mirror { .. }
            | PrimKind::Glass { .. }
            | PrimKind::Dielectric { .. }
            | PrimKind::Interface { .. } => true,
            PrimKind::Other { .. }
                if is_function_material(k.schema.name)
                    || matches!(
                        k.schema.name,
                        "BRTDfunc" | "plastic2" | "metal2" | "trans2" | "ashik2"
                    ) =>
            {
                true
            }
            PrimKind::Trans { .. } => true,
            PrimKind::Light { .. } | PrimKind::Glow { .. } | PrimKind::Spotlight { .. } => !texture,
            _ => false,
        })
    }

    /// Compiles pattern primitive `id` (brightfunc, colorfunc, texfunc, texdata,
    /// brightdata, colordata, colorpict) into the scene's functions, once.
    fn pattern(&mut self, id: PrimId) -> Option<u32> {
        if let Some(&i) = self.pattern_of_prim.get(&id) {
            return Some(i);
        }
        let p = self.ir.get(id)?;
        let PrimKind::Other { strings, reals } = &p.kind else {
            self.unsupported(id, "its arguments could not be read");
            return None;
        };
        let Some(layout) = PatternLayout::of(p.schema.name, strings, &self.ir.data) else {
            self.unsupported(id, "too few string arguments");
            return None;
        };
        let layout = match layout {
            Ok(layout) => layout,
            Err(why) => {
                self.refuse_with(id, why);
                return None;
            }
        };
        let file = &strings[layout.file];
        let program = self.function_program(id, file, false)?;
        let mut indices = self.expressions(id, program, &strings[layout.exprs.clone()])?;
        let kind = match self.pattern_kind(program, strings, layout.source) {
            Ok(kind) => kind,
            Err(why) => {
                self.refuse_with(id, why);
                return None;
            }
        };
        if matches!(kind, PatternKind::BrightData(_)) {
            indices.reverse();
        }
        // The transform starts at the first option after the file and the
        // expressions (func.c `getfunc`).
        let words: Vec<(&str, radc_lang::Span)> = strings[layout.exprs.end.max(layout.file + 1)..]
            .iter()
            .skip_while(|w| !radc_lang::schema::is_transform_option(w))
            .map(|w| (w.as_str(), radc_lang::Span::default()))
            .collect();
        let Ok(mut inverse) = radc_lang::transform::Transform::parse_inverse(&words) else {
            self.unsupported(id, "bad transform");
            return None;
        };
        inverse.scale = inverse.scale.abs();
        let mut forward = (p.transform != radc_lang::transform::Transform::IDENTITY)
            .then_some(p.transform)
            .map(|mut f| {
                f.scale = f.scale.abs();
                f
            });
        let inverse = self.in_frame(id, inverse);
        if let Some(frame) = self.frame_of(id) {
            // A texture's displacement turns with its own transform, then the mesh's
            // (t_func.c, t_data.c).
            forward = Some(forward.map_or(frame.forward, |f| f.then(&frame.forward)));
        }
        let index = self.functions.patterns.len() as u32;
        self.functions.patterns.push(Pattern {
            who: format!("{} '{}'", p.schema.name, p.name),
            kind,
            program,
            exprs: indices,
            args: reals.clone(),
            inverse,
            forward,
        });
        self.pattern_of_prim.insert(id, index);
        Some(index)
    }

    /// What a pattern evaluates, with its data or picture and the function calls
    /// p_data.c applies to the values found (in `program`).
    fn pattern_kind(
        &mut self,
        program: ProgramId,
        strings: &[String],
        source: PatternSource,
    ) -> Result<PatternKind, String> {
        let mut calls = |names: &[String], triple: bool| -> Result<Vec<usize>, String> {
            names
                .iter()
                .enumerate()
                .map(|(i, n)| {
                    self.functions
                        .add_data_function(program, n, i as u32, triple)
                })
                .collect()
        };
        Ok(match source {
            PatternSource::Bright => PatternKind::Bright,
            PatternSource::Color => PatternKind::Color,
            PatternSource::Texture => PatternKind::Texture,
            PatternSource::BrightData(data) => PatternKind::BrightData(DataLookup {
                source: DataSource::Bright(data),
                functions: calls(&strings[..1], false)?,
            }),
            PatternSource::ColorData(data) => PatternKind::ColorData(DataLookup {
                source: DataSource::Color(data),
                functions: calls(&strings[..3], true)?,
            }),
            // t_data.c looks values up and applies its functions as p_cdata does.
            PatternSource::TextureData(data) => PatternKind::TextureData(DataLookup {
                source: DataSource::Color(data),
                functions: calls(&strings[..3], true)?,
            }),
            PatternSource::ColorPict(picture) => PatternKind::ColorPict(PictureLookup {
                picture,
                functions: calls(&strings[..3], true)?,
            }),
            // The sides are filled in by `mixture_pattern` or `mixture_material`.
            PatternSource::MixFunction => PatternKind::Mixture {
                source: MixSource::Function,
                fore: Vec::new(),
                back: Vec::new(),
            },
            // mx_data.c: `funvalue(func, 1, &value)`; mx_pdata: `funvalue(func, 3, col)`.
            PatternSource::MixData(data) => PatternKind::Mixture {
                source: MixSource::Data(DataLookup {
                    source: DataSource::Mix(data),
                    functions: calls(&strings[2..3], false)?,
                }),
                fore: Vec::new(),
                back: Vec::new(),
            },
            PatternSource::MixPicture(picture) => PatternKind::Mixture {
                source: MixSource::Picture(PictureLookup {
                    picture,
                    functions: calls(&strings[2..3], true)?,
                }),
                fore: Vec::new(),
                back: Vec::new(),
            },
        })
    }

    /// A function or data material: its colour and parts from the reals, its function
    /// (and, for the data forms, the data file and coordinate functions) compiled as a
    /// pattern the material evaluates per light sample.
    fn function_material(
        &mut self,
        id: PrimId,
        name: &str,
        strings: &[String],
        reals: &[f64],
    ) -> Option<FunctionMaterial> {
        use crate::materials::function::FunctionKind;
        let kind = match name {
            "plasfunc" | "plasdata" => FunctionKind::Plastic,
            "metfunc" | "metdata" => FunctionKind::Metal,
            _ => FunctionKind::Trans,
        };
        let data_form = name.ends_with("data");
        let (want_strings, want_reals) = (
            if data_form { 4 } else { 2 },
            if kind == FunctionKind::Trans { 6 } else { 4 },
        );
        if strings.len() < want_strings || reals.len() < want_reals {
            self.unsupported(id, "bad # arguments");
            return None;
        }
        let data = if data_form {
            match self.ir.data.files.get(strings[1].as_str()) {
                Some(d) => Some(d.clone()),
                None => {
                    self.refuse_with(
                        id,
                        format!("its data file '{}' could not be loaded", strings[1]),
                    );
                    return None;
                }
            }
        } else {
            None
        };
        let file_at = if data_form { 2 } else { 1 };
        let program = self.function_program(id, &strings[file_at], true)?;
        use crate::procedural::brdf::{LIGHT_CHANNEL, VALUE_CHANNEL};
        let light: Vec<u32> = (0..4).map(|i| LIGHT_CHANNEL + i).collect();
        let dims = data.as_ref().map_or(0, |d| d.dimensions());
        let coords_end = file_at + 1 + dims;
        if strings.len() < coords_end {
            self.unsupported(id, "bad # arguments");
            return None;
        }
        let mut coords = Vec::new();
        for f in &strings[file_at + 1..coords_end] {
            match self.functions.add_call(program, f, &light) {
                Ok(k) => coords.push(k),
                Err(why) => {
                    self.refuse_with(id, why);
                    return None;
                }
            }
        }
        let mut value_args = Vec::new();
        if data_form {
            value_args.push(VALUE_CHANNEL);
        }
        value_args.extend(&light);
        let value = match self.functions.add_call(program, &strings[0], &value_args) {
            Ok(k) => k,
            Err(why) => {
                self.refuse_with(id, why);
                return None;
            }
        };
        let inverse = self.function_frame(id, &strings[coords_end..])?;
        let brdf = PatternKind::Brdf(crate::procedural::BrdfLookup { data, value });
        let pattern = self.material_pattern(id, brdf, program, coords, reals, inverse);
        let real = |i: usize| reals.get(i).copied().unwrap_or(0.0);
        Some(FunctionMaterial {
            kind,
            color: Vec3::new(real(0), real(1), real(2)),
            spec: real(3),
            transmission: real(4),
            transmitted_specular: real(5),
            pattern,
            texture: Vec3::ZERO,
        })
    }

    /// The program of a pattern's or material's function file, refusing it when the file
    /// could not be loaded; with m_brdf.c's shading variables bound when `shading`.
    fn function_program(&mut self, id: PrimId, file: &str, shading: bool) -> Option<ProgramId> {
        let Some(module) = self.ir.functions.0.get(file) else {
            self.unsupported(id, "its function file could not be loaded");
            return None;
        };
        let program = self.functions.program(file, module);
        if shading {
            self.functions.bind_shading_variables(program);
        }
        Some(program)
    }

    /// Each of `texts` parsed as an expression in `program`; `None` after refusing
    /// primitive `id` for the first that cannot be.
    fn expressions(
        &mut self,
        id: PrimId,
        program: ProgramId,
        texts: &[String],
    ) -> Option<Vec<usize>> {
        let mut out = Vec::with_capacity(texts.len());
        for e in texts {
            match self.functions.add_expression(program, e) {
                Ok(k) => out.push(k),
                Err(why) => {
                    self.refuse_with(id, why);
                    return None;
                }
            }
        }
        Some(out)
    }

    /// The frame a material's functions see (func.c `getfunc`'s `bxp`): the inverse
    /// of the transform in `words`, its scale made positive; `None` after refusing.
    fn function_frame(
        &mut self,
        id: PrimId,
        words: &[String],
    ) -> Option<radc_lang::transform::Transform> {
        let words: Vec<(&str, radc_lang::Span)> = words
            .iter()
            .map(|w| (w.as_str(), radc_lang::Span::default()))
            .collect();
        let Ok(mut inverse) = radc_lang::transform::Transform::parse_inverse(&words) else {
            self.unsupported(id, "bad transform");
            return None;
        };
        inverse.scale = inverse.scale.abs();
        Some(self.in_frame(id, inverse))
    }

    /// The placement of the mesh whose frame `id`'s functions are evaluated in, when
    /// `id` is a material read from a mesh file.
    fn frame_of(&self, id: PrimId) -> Option<Frame> {
        let mesh = self.ir.get(id)?.frame?;
        match &self.ir.get(mesh)?.kind {
            PrimKind::Mesh { transform, .. } => Frame::of(transform),
            _ => None,
        }
    }

    /// func.c's `setfunc` with `rox`: coordinates go into the mesh's frame first
    /// (`multmat4(funcxf, rox->b, bxp)`), then into the primitive's own.
    fn in_frame(
        &self,
        id: PrimId,
        inverse: radc_lang::transform::Transform,
    ) -> radc_lang::transform::Transform {
        match self.frame_of(id) {
            Some(frame) => frame.backward.then(&inverse),
            None => inverse,
        }
    }

    /// Adds the pattern a function material evaluates; its index.
    fn material_pattern(
        &mut self,
        id: PrimId,
        kind: PatternKind,
        program: ProgramId,
        exprs: Vec<usize>,
        reals: &[f64],
        inverse: radc_lang::transform::Transform,
    ) -> u32 {
        let who = self
            .ir
            .get(id)
            .map_or_else(String::new, |p| format!("{} '{}'", p.schema.name, p.name));
        self.functions.patterns.push(Pattern {
            who,
            kind,
            program,
            exprs,
            args: reals.to_vec(),
            inverse,
            forward: None,
        });
        self.functions.patterns.len() as u32 - 1
    }

    /// An anisotropic material's orientation expressions (its first three strings, in
    /// the function file that follows) as a pattern the material evaluates per hit.
    fn orientation_pattern(
        &mut self,
        id: PrimId,
        strings: &[String],
        reals: &[f64],
        transform: radc_lang::transform::Transform,
    ) -> Option<u32> {
        if strings.len() < 4 {
            self.unsupported(id, "bad # arguments");
            return None;
        }
        let program = self.function_program(id, &strings[3], false)?;
        let exprs = self.expressions(id, program, &strings[..3])?;
        let inverse = self.function_frame(id, &strings[4..])?;
        let pattern =
            self.material_pattern(id, PatternKind::Orientation, program, exprs, reals, inverse);
        if let Some(p) = self.functions.patterns.get_mut(pattern as usize) {
            p.forward =
                (transform != radc_lang::transform::Transform::IDENTITY).then_some(transform);
        }
        Some(pattern)
    }

    /// A BRTDfunc: its reals, and its expressions and directional functions compiled as
    /// a pattern the material evaluates.
    fn brtd_material(&mut self, id: PrimId, strings: &[String], reals: &[f64]) -> Option<Brtd> {
        use crate::procedural::Directional;
        use crate::procedural::brdf::LIGHT_CHANNEL;
        if strings.len() < 10 || reals.len() < 9 {
            self.unsupported(id, "bad # arguments");
            return None;
        }
        let program = self.function_program(id, &strings[9], true)?;
        let exprs = self.expressions(id, program, &strings[..6])?;
        let light: Vec<u32> = (0..4).map(|i| LIGHT_CHANNEL + i).collect();
        let mut directional = [Directional::Zero; 3];
        for i in 0..3 {
            let name = &strings[6 + i];
            directional[i] = if name == "0" {
                Directional::Zero
            } else if let Some(j) = (0..i).find(|&j| strings[6 + j] == *name) {
                Directional::SameAs(j)
            } else {
                match self.functions.add_call(program, name, &light) {
                    Ok(k) => Directional::Call(k),
                    Err(why) => {
                        self.refuse_with(id, why);
                        return None;
                    }
                }
            };
        }
        let inverse = self.function_frame(id, &strings[10..])?;
        let kind = PatternKind::Brtd(crate::procedural::BrtdLookup { directional });
        let pattern = self.material_pattern(id, kind, program, exprs, reals, inverse);
        let rgb = |i: usize| Vec3::new(reals[i], reals[i + 1], reals[i + 2]);
        Some(Brtd {
            front_diffuse: rgb(0),
            back_diffuse: rgb(3),
            transmitted_diffuse: rgb(6),
            directional: strings[6] != "0",
            pattern,
            pattern_color: Vec3::ONE,
            texture: Vec3::ZERO,
        })
    }

    /// A mixture's two sides as named in its first two strings (`None` for `void`);
    /// `Err` after refusing a name that resolves to nothing.
    fn mixture_sides(&mut self, id: PrimId) -> Result<[Option<PrimId>; 2], ()> {
        let Some(PrimKind::Other { strings, .. }) = self.ir.get(id).map(|p| &p.kind) else {
            self.unsupported(id, "its arguments could not be read");
            return Err(());
        };
        if strings.len() < 4 {
            self.unsupported(id, "bad # arguments");
            return Err(());
        }
        let mut sides = [None, None];
        for (k, side) in sides.iter_mut().enumerate() {
            let name = &strings[k];
            if name == "void" {
                continue;
            }
            match self.named_ref(id, name) {
                Some(m) => *side = Some(m),
                None => {
                    self.refuse_with(id, format!("undefined modifier \"{name}\""));
                    return Err(());
                }
            }
        }
        Ok(sides)
    }

    /// Whether `rayshade` from modifier `first` ends in a material: whether a mixture
    /// with that side mixes materials (raymixture's `foremat`).
    fn shades_a_material(&self, first: PrimId) -> bool {
        let mut next = Some(first);
        for _ in 0..self.ir.prims.len() + 1 {
            let Some(p) = next.and_then(|m| self.ir.get(m)) else {
                return false;
            };
            match p.category() {
                Category::Material | Category::Light | Category::Alias => return true,
                Category::Mixture if next.is_some_and(|m| self.mixes_materials(m)) => {
                    return true;
                }
                _ => {}
            }
            next = match p.modifier {
                ModRef::Prim(n) => Some(n),
                _ => None,
            };
        }
        false
    }

    /// Whether mixture `id` blends materials (either side shades one) rather than
    /// patterns and textures.
    fn mixes_materials(&self, id: PrimId) -> bool {
        let Some(PrimKind::Other { strings, .. }) = self.ir.get(id).map(|p| &p.kind) else {
            return false;
        };
        strings.iter().take(2).any(|name| {
            name != "void"
                && self
                    .named_ref(id, name)
                    .is_some_and(|m| m != id && self.shades_a_material(m))
        })
    }

    /// The pattern chain `rayshade` applies from `first` down its modifiers (a side of
    /// a mixture of patterns), and whether it holds a texture; `None` after refusing.
    fn pattern_chain(&mut self, first: Option<PrimId>) -> Option<(Vec<u32>, bool)> {
        let mut chain = Vec::new();
        let mut texture = false;
        let mut next = first;
        let depth = self.path.len();
        while let Some(m) = next {
            let Some(p) = self.ir.get(m) else { break };
            if chain.len() > self.ir.prims.len() {
                break;
            }
            let compiled = if is_rendered_mixture(p.schema.name) {
                self.mixture_pattern(m)
            } else if is_rendered_pattern(p.schema.name) {
                self.pattern(m).map(|i| (i, is_texture(p.schema.name)))
            } else {
                self.unsupported(m, not_modelled(p.category()));
                None
            };
            let Some((i, t)) = compiled else {
                self.path.truncate(depth);
                return None;
            };
            chain.push(i);
            texture |= t;
            self.path.push(m);
            next = match p.modifier {
                ModRef::Prim(n) => Some(n),
                _ => None,
            };
        }
        self.path.truncate(depth);
        Some((chain, texture))
    }

    /// A mixture of patterns and textures, compiled once: its coefficient and the two
    /// sides' chains. Returns its pattern index and whether either side holds a texture.
    fn mixture_pattern(&mut self, id: PrimId) -> Option<(u32, bool)> {
        if let Some(&done) = self.mixtures.get(&id) {
            return Some(done);
        }
        let sides = self.mixture_sides(id).ok()?;
        let index = self.pattern(id)?;
        let depth = self.path.len();
        self.path.push(id);
        let fore = self.pattern_chain(sides[0]);
        let back = self.pattern_chain(sides[1]);
        self.path.truncate(depth);
        let ((fore, tf), (back, tb)) = (fore?, back?);
        if let Some(Pattern {
            kind: PatternKind::Mixture {
                fore: f, back: b, ..
            },
            ..
        }) = self.functions.patterns.get_mut(index as usize)
        {
            *f = fore;
            *b = back;
        }
        let done = (index, tf || tb);
        self.mixtures.insert(id, done);
        Some(done)
    }

    /// A mixture of materials (the surface's modifier): each side compiled as a
    /// surface's modifier would be.
    fn mixture_material(&mut self, id: PrimId) -> Option<MaterialId> {
        if let Some(Some(done)) = self.material_of_prim.get(id.0 as usize) {
            return *done;
        }
        if self.ir.get(id).is_some_and(|p| p.modifier != ModRef::Void) {
            self.unsupported(
                id,
                "inappropriate modifier: a mixture of materials takes void",
            );
            return None;
        }
        let sides = self.mixture_sides(id).ok()?;
        let pattern = self.pattern(id)?;
        let depth = self.path.len();
        self.path.push(id);
        let [fore, back] = sides.map(|side| side.and_then(|m| self.material_of(ModRef::Prim(m)).0));
        self.path.truncate(depth);
        let mid = MaterialId(self.scene.materials.len() as u32);
        self.scene.materials.push(Material::Mixture(Mixture {
            pattern,
            fore,
            back,
        }));
        self.material_patterns
            .resize(self.scene.materials.len(), Vec::new());
        if let Some(slot) = self.material_of_prim.get_mut(id.0 as usize) {
            *slot = Some(Some(mid));
        }
        Some(mid)
    }

    /// The modifier a material is shaded with: an alias's own (`mod alias new old`
    /// gives `old`'s arguments a new modifier), or, through `inherit`, its target's.
    fn effective_modifier(&self, mut id: PrimId) -> Option<PrimId> {
        for _ in 0..self.ir.prims.len() + 1 {
            let p = self.ir.get(id)?;
            match (p.modifier, &p.kind) {
                (ModRef::Inherit, PrimKind::Alias { target }) => id = *target,
                (ModRef::Prim(m), _) => return Some(m),
                _ => return None,
            }
        }
        None
    }

    fn compile_material_kind(&mut self, id: PrimId) -> Option<MaterialId> {
        let kind = self.alias_target(id)?;
        let patterns = self.material_modifiers(id, kind)?;
        let p = self.ir.get(kind)?;
        let rgb = |c: &[f64; 3]| vec3(*c);
        let material = match &p.kind {
            PrimKind::Plastic { color, spec, rough } => Material::Plastic(plastic::Plastic {
                color: rgb(color),
                spec: *spec,
                rough: *rough,
                metal: false,
                transmission: None,
                texture: Vec3::ZERO,
            }),
            PrimKind::Trans {
                color,
                spec,
                rough,
                trans: tr,
                tspec,
            } => Material::Plastic(trans::trans(rgb(color), *spec, *rough, *tr, *tspec)),
            PrimKind::Metal { color, spec, rough } => {
                Material::Plastic(metal::metal(rgb(color), *spec, *rough))
            }
            PrimKind::Mirror { alternate, color } => {
                let alternate = self.alternate(kind, alternate.as_deref());
                Material::Mirror(Mirror {
                    color: rgb(color),
                    alternate,
                    texture: Vec3::ZERO,
                })
            }
            PrimKind::Glass {
                transmission,
                index,
            } => Material::Glass(Glass {
                transmission: rgb(transmission),
                index: *index,
                pattern_color: Vec3::ONE,
                texture: Vec3::ZERO,
            }),
            PrimKind::Dielectric {
                transmission,
                index,
                hartmann,
            } => {
                if *hartmann != 0.0 {
                    self.unsupported(
                        kind,
                        "dispersion (a non-zero Hartmann constant) is not rendered yet",
                    );
                    return None;
                }
                Material::Dielectric(Dielectric {
                    inside: rgb(transmission),
                    index: *index,
                    outside: None,
                    pattern_color: Vec3::ONE,
                    texture: Vec3::ZERO,
                })
            }
            PrimKind::Interface { t1, n1, t2, n2 } => Material::Dielectric(Dielectric {
                inside: rgb(t1),
                index: *n1 / *n2,
                outside: Some(rgb(t2)),
                pattern_color: Vec3::ONE,
                texture: Vec3::ZERO,
            }),
            PrimKind::Antimatter { modifiers } => {
                let mut ids = Vec::new();
                for name in modifiers.iter().filter(|n| n.as_str() != "void") {
                    if let Some(m) = self.named_ref(kind, name) {
                        ids.push(i64::from(m.0));
                    }
                }
                let face = match modifiers.first().map(String::as_str) {
                    None | Some("void") => None,
                    Some(name) => Some(
                        self.named_ref(kind, name)
                            .and_then(|m| self.compile_material(m)),
                    ),
                };
                Material::Antimatter(Antimatter {
                    modifiers: ids,
                    face,
                })
            }
            PrimKind::Light { color } => Material::Emitter(Emitter {
                color: rgb(color),
                kind: EmitterKind::Light,
            }),
            PrimKind::Glow { color, max_radius } => Material::Emitter(Emitter {
                color: rgb(color),
                kind: EmitterKind::Glow {
                    max_radius: *max_radius,
                },
            }),
            PrimKind::Spotlight {
                color,
                angle,
                direction,
            } => match Spot::new(*angle, vec3(*direction)) {
                Some(spot) => Material::Emitter(Emitter {
                    color: rgb(color),
                    kind: EmitterKind::Spot(spot),
                }),
                None => {
                    self.unsupported(kind, "a spotlight needs a positive angle and a direction");
                    return None;
                }
            },
            PrimKind::Illum { alternate, color } => {
                let alternate = self.alternate(kind, alternate.as_deref());
                Material::Emitter(Emitter {
                    color: rgb(color),
                    kind: EmitterKind::Illum { alternate },
                })
            }
            PrimKind::Other { reals, .. } if p.schema.name == "mist" => {
                if reals.len() > 3 && reals[3..6.min(reals.len())].iter().any(|a| *a > FTINY) {
                    self.unsupported(
                        kind,
                        "scattering mist (an albedo) is not rendered yet; absorbing mist is",
                    );
                    return None;
                }
                let e = |i: usize| reals.get(i).copied().unwrap_or(0.0);
                let extinction = if reals.len() > 2 {
                    Vec3::new(e(0), e(1), e(2))
                } else {
                    Vec3::ZERO
                };
                Material::Mist(Mist { extinction })
            }
            PrimKind::Other { strings, reals } if p.schema.name == "ashik2" => {
                let number = |i: usize| {
                    strings
                        .get(i)
                        .and_then(|w| w.parse::<f64>().ok())
                        .filter(|x| x.is_finite())
                };
                if reals.len() != 8 {
                    self.unsupported(kind, "bad number of real arguments");
                    return None;
                }
                let numeric = match (number(0), number(1), number(2)) {
                    (Some(ux), Some(uy), Some(uz)) if strings.len() <= 4 => {
                        Some(Vec3::new(ux, uy, uz))
                    }
                    _ => None,
                };
                let orientation_pattern = match numeric {
                    Some(_) => None,
                    None => Some(self.orientation_pattern(kind, strings, reals, p.transform)?),
                };
                Material::Ashikhmin(Ashikhmin {
                    color: Vec3::new(reals[0], reals[1], reals[2]),
                    specular: Vec3::new(reals[3], reals[4], reals[5]),
                    u_power: reals[6],
                    v_power: reals[7],
                    orientation: numeric.unwrap_or(Vec3::ZERO),
                    orientation_pattern,
                    texture: Vec3::ZERO,
                })
            }
            PrimKind::Other { strings, reals } if p.schema.name == "BRTDfunc" => {
                let transparent = strings.iter().skip(3).take(3).any(|w| w != "0");
                Material::Brtd(self.brtd_material(kind, strings, reals)?, transparent)
            }
            PrimKind::Other { strings, reals } if is_function_material(p.schema.name) => {
                let name = p.schema.name;
                Material::Function(self.function_material(kind, name, strings, reals)?)
            }
            PrimKind::Other { strings, reals }
                if matches!(p.schema.name, "plastic2" | "metal2" | "trans2") =>
            {
                let number = |i: usize| {
                    strings
                        .get(i)
                        .and_then(|w| w.parse::<f64>().ok())
                        .filter(|x| x.is_finite())
                };
                let numeric = match (number(0), number(1), number(2)) {
                    (Some(ux), Some(uy), Some(uz)) if strings.len() <= 4 => {
                        Some(Vec3::new(ux, uy, uz))
                    }
                    _ => None,
                };
                let orientation_pattern = match numeric {
                    Some(_) => None,
                    None => Some(self.orientation_pattern(kind, strings, reals, p.transform)?),
                };
                let real = |i: usize| reals.get(i).copied().unwrap_or(0.0);
                if real(4) <= FTINY || real(5) <= FTINY {
                    self.unsupported(kind, "roughness too small (Radiance refuses it)");
                    return None;
                }
                Material::Anisotropic(Anisotropic {
                    color: Vec3::new(real(0), real(1), real(2)),
                    spec: real(3),
                    u_rough: real(4),
                    v_rough: real(5),
                    orientation: numeric.unwrap_or(Vec3::ZERO),
                    orientation_pattern,
                    metal: p.schema.name == "metal2",
                    transmission: (p.schema.name == "trans2").then(|| (real(6), real(7))),
                    texture: Vec3::ZERO,
                })
            }
            _ => {
                self.unsupported(kind, not_modelled(p.category()));
                return None;
            }
        };
        let mid = MaterialId(self.scene.materials.len() as u32);
        self.scene.materials.push(material);
        if !patterns.is_empty() {
            self.material_patterns
                .resize(self.scene.materials.len(), Vec::new());
            self.material_patterns[mid.0 as usize] = patterns;
        }
        if let Some(slot) = self.material_of_prim.get_mut(id.0 as usize) {
            *slot = Some(Some(mid));
        }
        Some(mid)
    }

    /// The primitive an alias chain ends at.
    fn alias_target(&self, mut id: PrimId) -> Option<PrimId> {
        for _ in 0..self.ir.prims.len() + 1 {
            match self.ir.get(id)?.kind {
                PrimKind::Alias { target } => id = target,
                _ => return Some(id),
            }
        }
        None
    }

    /// The modifier `name` in `owner`'s string arguments, as the front end resolved it.
    fn named_ref(&self, owner: PrimId, name: &str) -> Option<PrimId> {
        self.ir
            .get(owner)?
            .refs
            .iter()
            .copied()
            .find(|r| self.ir.get(*r).is_some_and(|q| q.name == name))
    }

    fn alternate(&mut self, owner: PrimId, name: Option<&str>) -> Alternate {
        match name {
            None => Alternate::None,
            Some("void") => Alternate::Void,
            Some(n) => {
                let target = self.ir.get(owner).and_then(|p| {
                    p.refs
                        .iter()
                        .copied()
                        .find(|r| self.ir.get(*r).is_some_and(|q| q.name == n))
                });
                match target.and_then(|t| self.compile_material(t)) {
                    Some(m) => Alternate::Material(m),
                    None => Alternate::Void,
                }
            }
        }
    }
}

/// Radiance's `marksources`: every surface whose material emits becomes a source,
/// except glows with no radius of influence. Also returns the objects Radiance refuses
/// as sources (cones, cups, tubes, rings with a hole: "illegal material").
fn find_sources(scene: &Scene) -> (Vec<Source>, Vec<usize>) {
    let mut illegal = Vec::new();
    let emitter = |m: Option<MaterialId>| match m.and_then(|m| scene.material(m)) {
        Some(Material::Emitter(e)) if e.is_source() => Some(e.clone()),
        _ => None,
    };
    let proximity = |e: &Emitter| match e.kind {
        EmitterKind::Glow { max_radius } => Some(max_radius),
        _ => None,
    };
    let spot = |e: &Emitter| match e.kind {
        EmitterKind::Spot(s) => Some(s),
        _ => None,
    };
    let mut out = Vec::new();
    for (i, o) in scene.objects.iter().enumerate() {
        let Some(e) = emitter(o.material) else {
            continue;
        };
        let shape = match &o.shape {
            Shape::Sphere(s) => SourceShape::sphere(s.center, s.radius),
            Shape::Polygon(p) => SourceShape::polygon(&p.vertices, p.normal, p.area),
            Shape::Ring(r) if r.r0 <= 0.0 => SourceShape::disk(r.center, r.normal, r.r1),
            Shape::Cone(c) if c.is_cylinder() && !c.inward => {
                SourceShape::cylinder(c.p0, c.p1(), c.r0)
            }
            _ => {
                illegal.push(i);
                continue;
            }
        };
        // A flat spotlight aimed behind itself is skipped (with a warning in Radiance).
        if let (Some(s), SourceShape::Flat { normal, .. }) = (spot(&e), &shape)
            && !s.faces(*normal)
        {
            continue;
        }
        out.push(Source {
            axes: crate::virtuals::radiance_axes(&shape),
            shape,
            proximity: proximity(&e),
            spot: spot(&e),
            target: SourceTarget::Object(i as u32),
            parent: None,
            beam: None,
        });
    }
    for (i, d) in scene.distant.iter().enumerate() {
        let Some(e) = emitter(d.material) else {
            continue;
        };
        // A distant glow is only seen, never sampled.
        if matches!(e.kind, EmitterKind::Glow { .. }) {
            continue;
        }
        let shape = SourceShape::Distant {
            direction: d.direction,
            solid_angle: d.solid_angle,
        };
        out.push(Source {
            axes: crate::virtuals::radiance_axes(&shape),
            shape,
            proximity: None,
            spot: None,
            target: SourceTarget::Distant(i as u32),
            parent: None,
            beam: None,
        });
    }
    (out, illegal)
}

/// The patterns and textures the renderer runs (`pattern` compiles them); any other
/// modifier in a chain is refused by name.
/// Why a pattern or texture is refused on a material that does not take it.
fn refused_on(texture: bool) -> &'static str {
    if texture {
        "textures on this material type are not rendered yet"
    } else {
        "patterns on this material type are not rendered yet"
    }
}

/// The function and data materials (m_brdf.c `m_brdf2`).
fn is_function_material(name: &str) -> bool {
    matches!(
        name,
        "plasfunc" | "metfunc" | "transfunc" | "plasdata" | "metdata" | "transdata"
    )
}

/// Whether a pattern type displaces the normal (a texture).
fn is_texture(name: &str) -> bool {
    matches!(name, "texfunc" | "texdata")
}

fn is_rendered_mixture(name: &str) -> bool {
    matches!(name, "mixfunc" | "mixdata" | "mixpict")
}

fn is_rendered_pattern(name: &str) -> bool {
    matches!(
        name,
        "brightfunc"
            | "colorfunc"
            | "texfunc"
            | "texdata"
            | "brightdata"
            | "colordata"
            | "colorpict"
    )
}

/// Where a pattern's strings sit (p_func.c, p_data.c: which are expressions, which
/// the function file) and the data or picture it reads.
struct PatternLayout {
    file: usize,
    exprs: std::ops::Range<usize>,
    source: PatternSource,
}

enum PatternSource {
    Bright,
    Color,
    Texture,
    BrightData(std::sync::Arc<radc_lang::datafile::DataFile>),
    ColorData([std::sync::Arc<radc_lang::datafile::DataFile>; 3]),
    /// `texdata`: the x, y and z displacement files.
    TextureData([std::sync::Arc<radc_lang::datafile::DataFile>; 3]),
    ColorPict(std::sync::Arc<radc_picture::ColorPicture>),
    MixFunction,
    MixData(std::sync::Arc<radc_lang::datafile::DataFile>),
    MixPicture(std::sync::Arc<radc_picture::ColorPicture>),
}

impl PatternLayout {
    /// `None` when the strings are too few (getfunc's "too few string arguments",
    /// p_data.c's "bad # arguments"); an error when a file is unusable.
    fn of(
        kind: &str,
        strings: &[String],
        data: &radc_lang::scene::ir::AuxData,
    ) -> Option<Result<PatternLayout, String>> {
        let file = |name: &String| {
            data.files
                .get(name.as_str())
                .cloned()
                .ok_or_else(|| format!("its data file '{name}' could not be loaded"))
        };
        // (function file index, first expression, the source, its dimensions)
        let (at, first, source, dims) = match kind {
            "brightfunc" => (1, 0, Ok(PatternSource::Bright), 1),
            "colorfunc" => (3, 0, Ok(PatternSource::Color), 3),
            "texfunc" => (3, 0, Ok(PatternSource::Texture), 3),
            "brightdata" => {
                let d = file(strings.get(1)?);
                let dims = d.as_ref().map_or(0, |d| d.dimensions());
                (2, 3, d.map(PatternSource::BrightData), dims)
            }
            "colordata" | "texdata" => {
                let d = (
                    file(strings.get(3)?),
                    file(strings.get(4)?),
                    file(strings.get(5)?),
                );
                let d = match d {
                    (Ok(r), Ok(g), Ok(b))
                        if r.dimensions() == g.dimensions() && r.dimensions() == b.dimensions() =>
                    {
                        Ok([r, g, b])
                    }
                    (Ok(_), Ok(_), Ok(_)) => Err("dimension error: its data files differ in \
                        dimensions"
                        .to_string()),
                    (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => Err(e),
                };
                let dims = d.as_ref().map_or(0, |d| d[0].dimensions());
                let source = if kind == "texdata" {
                    d.map(PatternSource::TextureData)
                } else {
                    d.map(PatternSource::ColorData)
                };
                (6, 7, source, dims)
            }
            "colorpict" | "mixpict" => {
                let name = strings.get(3)?;
                let picture = data
                    .pictures
                    .get(name.as_str())
                    .ok_or_else(|| format!("its picture '{name}' could not be loaded"))
                    .and_then(|bytes| {
                        radc_picture::Picture::read(bytes)
                            .and_then(|p| radc_picture::ColorPicture::new(&p))
                            .map_err(|e| format!("bad picture file '{name}': {e}"))
                    })
                    .map(std::sync::Arc::new);
                let source = if kind == "mixpict" {
                    picture.map(PatternSource::MixPicture)
                } else {
                    picture.map(PatternSource::ColorPict)
                };
                (4, 5, source, 2)
            }
            // mixfunc: foreground, background, the coefficient's expression, the file.
            "mixfunc" => (3, 2, Ok(PatternSource::MixFunction), 1),
            "mixdata" => {
                let d = file(strings.get(3)?);
                let dims = d.as_ref().map_or(0, |d| d.dimensions());
                (4, 5, d.map(PatternSource::MixData), dims)
            }
            _ => return Some(Err(format!("{kind} patterns are not rendered yet"))),
        };
        let source = match source {
            Ok(s) => s,
            Err(e) => return Some(Err(e)),
        };
        strings.get(at)?;
        let exprs = first..first + dims;
        strings.get(exprs.clone())?;
        Some(Ok(PatternLayout {
            file: at,
            exprs,
            source,
        }))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use radc_lang::scene::ir::Prim;
    use radc_lang::source::{FileId, Span};

    /// Builds IR scenes by hand: the renderer's tests never go through text.
    #[derive(Default)]
    pub(crate) struct IrBuilder {
        pub scene: ir::Scene,
    }

    impl IrBuilder {
        pub fn add(
            &mut self,
            type_name: &str,
            name: &str,
            modifier: Option<u32>,
            kind: PrimKind,
        ) -> u32 {
            let span = Span::new(FileId(0), 0..0);
            self.scene.prims.push(Prim {
                name: name.into(),
                name_span: span,
                modifier_span: span,
                schema: radc_lang::schema::lookup(type_name).expect("a known type"),
                modifier: modifier.map_or(ModRef::Void, |m| ModRef::Prim(PrimId(m))),
                refs: Vec::new(),
                transform: radc_lang::transform::Transform::IDENTITY,
                frame: None,
                kind,
                span,
            });
            self.scene.prims.len() as u32 - 1
        }

        pub fn plastic(&mut self, name: &str, grey: f64) -> u32 {
            self.add(
                "plastic",
                name,
                None,
                PrimKind::Plastic {
                    color: [grey; 3],
                    spec: 0.0,
                    rough: 0.0,
                },
            )
        }

        pub fn square(&mut self, name: &str, modifier: u32, z: f64, up: bool) -> u32 {
            let mut vertices = vec![
                [-1.0, -1.0, z],
                [1.0, -1.0, z],
                [1.0, 1.0, z],
                [-1.0, 1.0, z],
            ];
            if !up {
                vertices.reverse();
            }
            self.add(
                "polygon",
                name,
                Some(modifier),
                PrimKind::Polygon { vertices },
            )
        }

        pub fn sphere(&mut self, name: &str, modifier: u32, center: [f64; 3], radius: f64) -> u32 {
            self.add(
                "sphere",
                name,
                Some(modifier),
                PrimKind::Sphere { center, radius },
            )
        }
    }

    #[test]
    fn compiles_reachable_surfaces_and_their_sources() {
        let mut b = IrBuilder::default();
        let lamp = b.add("light", "lamp", None, PrimKind::Light { color: [10.0; 3] });
        b.add(
            "sphere",
            "bulb",
            Some(lamp),
            PrimKind::Sphere {
                center: [0.0, 0.0, 3.0],
                radius: 0.5,
            },
        );
        let grey = b.plastic("grey", 0.5);
        b.plastic("unused", 0.2);
        b.square("floor", grey, 0.0, true);
        let scene = Scene::compile(&b.scene).expect("compiles");
        assert_eq!(scene.objects.len(), 2);
        assert_eq!(
            scene.materials.len(),
            2,
            "the unused material is not compiled"
        );
        assert_eq!(scene.sources.len(), 1);
    }

    /// Shadow rays may stop at their first hit only when every surface shades them
    /// black: plastic alone, not with a glass pane or a lamp among the surfaces.
    #[test]
    fn opaque_to_shadows_only_without_transparent_or_emitting_surfaces() {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        b.square("floor", grey, 0.0, true);
        assert!(
            Scene::compile(&b.scene)
                .expect("compiles")
                .opaque_to_shadows
        );
        let pane = b.add(
            "glass",
            "pane",
            None,
            PrimKind::Glass {
                transmission: [0.9; 3],
                index: 1.52,
            },
        );
        b.square("window", pane, 1.0, true);
        assert!(
            !Scene::compile(&b.scene)
                .expect("compiles")
                .opaque_to_shadows
        );
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        let lamp = b.add("light", "lamp", None, PrimKind::Light { color: [10.0; 3] });
        b.square("floor", grey, 0.0, true);
        b.square("panel", lamp, 2.0, false);
        let scene = Scene::compile(&b.scene).expect("compiles");
        assert!(!scene.opaque_to_shadows);
        // A lamp blocks shadow rays aimed at other sources: still opaque to those.
        assert!(scene.opaque_to_object_shadows);
        let illum = b.add(
            "illum",
            "window_light",
            None,
            PrimKind::Illum {
                color: [1.0; 3],
                alternate: None,
            },
        );
        b.square("window", illum, 1.0, false);
        assert!(
            !Scene::compile(&b.scene)
                .expect("compiles")
                .opaque_to_object_shadows
        );
    }

    #[test]
    fn unsupported_types_are_listed_not_dropped() {
        let mut b = IrBuilder::default();
        let m = b.add(
            "mist",
            "fog",
            None,
            PrimKind::Other {
                strings: Vec::new(),
                reals: vec![0.1, 0.1, 0.1, 0.5, 0.5, 0.5],
            },
        );
        b.square("cloud", m, 0.0, true);
        let problems = Scene::compile(&b.scene).expect_err("scattering mist is not rendered yet");
        assert_eq!(problems.len(), 1);
        assert_eq!(problems[0].name, "fog");
        assert_eq!(problems[0].type_name, "mist");
    }
}
