//! The compiled scene: the reachable surfaces of an `ir::Scene` with their shapes and
//! resolved materials, the BVH over them, and the light sources.

use radc_lang::scene::ir::{self, ModRef, PrimId, PrimKind};
use radc_lang::schema::Category;

use crate::bvh::Bvh;
use crate::lights::{Source, SourceShape, SourceTarget};
use crate::materials::light::{Emitter, EmitterKind};
use crate::materials::mirror::Mirror;
use crate::materials::{Alternate, Material, MaterialId, metal, plastic};
use crate::math::{Vec3, vec3};
use crate::shapes::{Cone, Polygon, Ring, Shape, Sphere};

/// A surface.
#[derive(Clone, Debug)]
pub struct Object {
    pub name: String,
    pub shape: Shape,
    pub material: Option<MaterialId>,
    /// Index of the modifier primitive (-1 for `void`): Radiance breaks ties between
    /// coincident surfaces in favour of the later modifier.
    pub modifier: i64,
    pub modifier_name: String,
    pub material_name: String,
}

/// A distant `source`: seen by rays that hit nothing, within its cone.
#[derive(Clone, Debug)]
pub struct DistantObject {
    pub name: String,
    pub direction: Vec3,
    pub solid_angle: f64,
    pub material: Option<MaterialId>,
    pub modifier_name: String,
    pub material_name: String,
}

#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub distant: Vec<DistantObject>,
    pub materials: Vec<Material>,
    pub sources: Vec<Source>,
    pub bvh: Bvh,
}

/// Something in the scene radc cannot render yet (or that Radiance refuses at render
/// time), by primitive name and type.
#[derive(Clone, Debug, PartialEq)]
pub struct Unsupported {
    pub prim: PrimId,
    pub name: String,
    pub type_name: &'static str,
    pub why: &'static str,
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} '{}': {}", self.type_name, self.name, self.why)
    }
}

struct Compiler<'a> {
    ir: &'a ir::Scene,
    scene: Scene,
    /// Material index per primitive, once compiled.
    material_of_prim: Vec<Option<Option<MaterialId>>>,
    problems: Vec<Unsupported>,
}

impl Scene {
    /// Compiles the surfaces of `ir` that a render needs. Everything radc does not model
    /// yet is listed, never silently dropped.
    pub fn compile(ir: &ir::Scene) -> Result<Scene, Vec<Unsupported>> {
        let mut c = Compiler {
            ir,
            scene: Scene::default(),
            material_of_prim: vec![None; ir.prims.len()],
            problems: Vec::new(),
        };
        let reachable = ir.reachable();
        for (i, p) in ir.prims.iter().enumerate() {
            if reachable.get(i) == Some(&true) && p.category() == Category::Surface {
                c.surface(PrimId(i as u32), p);
            }
        }
        if !c.problems.is_empty() {
            return Err(c.problems);
        }
        let mut scene = c.scene;
        scene.sources = find_sources(&scene);
        let bounds: Vec<_> = scene.objects.iter().map(|o| o.shape.bounds()).collect();
        scene.bvh = Bvh::build(&bounds);
        Ok(scene)
    }

    pub fn material(&self, id: MaterialId) -> Option<&Material> {
        self.materials.get(id.0 as usize)
    }

    pub fn object(&self, i: u32) -> Option<&Object> {
        self.objects.get(i as usize)
    }
}

impl Compiler<'_> {
    fn unsupported(&mut self, id: PrimId, why: &'static str) {
        if let Some(p) = self.ir.get(id) {
            self.problems.push(Unsupported {
                prim: id,
                name: p.name.clone(),
                type_name: p.schema.name,
                why,
            });
        }
    }

    fn surface(&mut self, id: PrimId, p: &ir::Prim) {
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
            PrimKind::Instance { .. } | PrimKind::Mesh { .. } => {
                return self.unsupported(id, "instances and meshes are not rendered yet");
            }
            _ => return,
        };
        // Degenerate geometry (zero area, zero axis) is never hit, as in Radiance.
        let Some(shape) = shape else { return };
        let (material, material_name) = self.material_of(p.modifier);
        self.scene.objects.push(Object {
            name: p.name.clone(),
            shape,
            material,
            modifier: match p.modifier {
                ModRef::Prim(m) => i64::from(m.0),
                _ => -1,
            },
            modifier_name: self.modifier_name(p.modifier),
            material_name,
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
            Category::Pattern | Category::Texture | Category::Mixture => {
                self.unsupported(id, "patterns, textures and mixtures are not rendered yet");
                (None, String::new())
            }
            Category::Surface => (None, "void".into()),
        }
    }

    fn compile_material(&mut self, id: PrimId) -> Option<MaterialId> {
        if let Some(Some(done)) = self.material_of_prim.get(id.0 as usize) {
            return *done;
        }
        // Mark as in progress (an alternate naming itself ends here).
        if let Some(slot) = self.material_of_prim.get_mut(id.0 as usize) {
            *slot = Some(None);
        }
        let kind = self.alias_target(id)?;
        let p = self.ir.get(kind)?;
        let rgb = |c: &[f64; 3]| vec3(*c);
        let material = match &p.kind {
            PrimKind::Plastic { color, spec, rough } => Material::Normal(plastic::Normal {
                color: rgb(color),
                spec: *spec,
                rough: *rough,
                metal: false,
            }),
            PrimKind::Metal { color, spec, rough } => {
                Material::Normal(metal::metal(rgb(color), *spec, *rough))
            }
            PrimKind::Mirror { alternate, color } => {
                let alternate = self.alternate(kind, alternate.as_deref());
                Material::Mirror(Mirror {
                    color: rgb(color),
                    alternate,
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
            PrimKind::Illum { alternate, color } => {
                let alternate = self.alternate(kind, alternate.as_deref());
                Material::Emitter(Emitter {
                    color: rgb(color),
                    kind: EmitterKind::Illum { alternate },
                })
            }
            _ => {
                self.unsupported(kind, "this material type is not rendered yet");
                return None;
            }
        };
        let mid = MaterialId(self.scene.materials.len() as u32);
        self.scene.materials.push(material);
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
/// except glows with no radius of influence.
fn find_sources(scene: &Scene) -> Vec<Source> {
    let emitter = |m: Option<MaterialId>| match m.and_then(|m| scene.material(m)) {
        Some(Material::Emitter(e)) if e.is_source() => Some(e.clone()),
        _ => None,
    };
    let proximity = |e: &Emitter| match e.kind {
        EmitterKind::Glow { max_radius } => Some(max_radius),
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
            // Radiance refuses these as sources ("illegal material"); cylinders it
            // samples along their length, which radc does not yet.
            _ => continue,
        };
        out.push(Source {
            shape,
            proximity: proximity(&e),
            target: SourceTarget::Object(i as u32),
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
        out.push(Source {
            shape: SourceShape::Distant {
                direction: d.direction,
                solid_angle: d.solid_angle,
            },
            proximity: None,
            target: SourceTarget::Distant(i as u32),
        });
    }
    out
}
