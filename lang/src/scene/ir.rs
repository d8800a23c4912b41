//! The typed scene IR: each primitive lowered to what it means, modifiers resolved.
//!
//! Consumers (the renderer, the language server) read this, never the syntax tree.
//! Types the renderer models get a typed form; the rest (function, data and picture
//! types) keep their arguments, named by the schema, in [`PrimKind::Other`].

use crate::schema::{Category, PrimitiveType};
use crate::source::Span;

pub type Vec3 = [f64; 3];
pub type Rgb = [f64; 3];

/// Index of a primitive in [`Scene::prims`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PrimId(pub u32);

/// What a primitive's modifier word refers to. Radiance binds a modifier name to the
/// most recent earlier definition: a later redefinition does not relink earlier uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModRef {
    Void,
    Prim(PrimId),
    /// `inherit` on an alias: the alias takes its target's modifier.
    Inherit,
    /// The name did not resolve; a diagnostic was reported.
    Unresolved,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Prim {
    pub name: String,
    pub name_span: Span,
    /// The span of the modifier word.
    pub modifier_span: Span,
    pub schema: &'static PrimitiveType,
    pub modifier: ModRef,
    /// Other modifiers this one names in its string arguments (mixture foreground and
    /// background, illum/mirror alternates, antimatter lists), resolved where defined.
    pub refs: Vec<PrimId>,
    /// The transform written at the end of the string arguments (instances, meshes,
    /// patterns, textures, mixtures), parsed; identity when there is none.
    pub transform: crate::transform::Transform,
    /// For a material read from a mesh file: the `mesh` primitive whose frame its
    /// functions are evaluated in (Radiance's `rox`: the mesh's transform applies
    /// before the primitive's own). `None` for everything written in the scene.
    pub frame: Option<PrimId>,
    pub kind: PrimKind,
    pub span: Span,
}

impl Prim {
    pub fn category(&self) -> Category {
        self.schema.category
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum PrimKind {
    // --- surfaces -----------------------------------------------------------------
    Source {
        direction: Vec3,
        angle: f64,
    },
    Sphere {
        center: Vec3,
        radius: f64,
    },
    /// A sphere with inward normals (also what a negative-radius sphere is).
    Bubble {
        center: Vec3,
        radius: f64,
    },
    Polygon {
        vertices: Vec<Vec3>,
    },
    Cone {
        p0: Vec3,
        p1: Vec3,
        r0: f64,
        r1: f64,
    },
    Cup {
        p0: Vec3,
        p1: Vec3,
        r0: f64,
        r1: f64,
    },
    Cylinder {
        p0: Vec3,
        p1: Vec3,
        radius: f64,
    },
    Tube {
        p0: Vec3,
        p1: Vec3,
        radius: f64,
    },
    Ring {
        center: Vec3,
        normal: Vec3,
        r0: f64,
        r1: f64,
    },
    Instance {
        octree: String,
        transform: Vec<String>,
    },
    Mesh {
        file: String,
        transform: Vec<String>,
        /// With a `void` modifier, the materials its triangles name, by their index in
        /// the mesh file, read from the file and appended to the scene (each with
        /// [`Prim::frame`] this mesh); empty otherwise.
        materials: Vec<PrimId>,
    },
    // --- materials ----------------------------------------------------------------
    Light {
        color: Rgb,
    },
    Illum {
        alternate: Option<String>,
        color: Rgb,
    },
    Glow {
        color: Rgb,
        max_radius: f64,
    },
    Spotlight {
        color: Rgb,
        angle: f64,
        direction: Vec3,
    },
    Mirror {
        alternate: Option<String>,
        color: Rgb,
    },
    Plastic {
        color: Rgb,
        spec: f64,
        rough: f64,
    },
    Metal {
        color: Rgb,
        spec: f64,
        rough: f64,
    },
    Trans {
        color: Rgb,
        spec: f64,
        rough: f64,
        trans: f64,
        tspec: f64,
    },
    Glass {
        transmission: Rgb,
        index: f64,
    },
    Dielectric {
        transmission: Rgb,
        index: f64,
        hartmann: f64,
    },
    Interface {
        t1: Rgb,
        n1: f64,
        t2: Rgb,
        n2: f64,
    },
    Antimatter {
        modifiers: Vec<String>,
    },
    /// `alias`: a new name for `target` (already resolved).
    Alias {
        target: PrimId,
    },
    /// Every other type: the raw arguments, interpreted through the schema.
    Other {
        strings: Vec<String>,
        reals: Vec<f64>,
    },
}

/// A lowered scene: primitives in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    pub prims: Vec<Prim>,
    /// What surfaces that were checked but not kept (`lower::Keep::Modifiers`) refer
    /// to: with the kept surfaces, the roots of reachability. Empty when every surface
    /// was kept.
    pub roots: Vec<PrimId>,
    /// The function files the primitives name, as the renderer loads them (after
    /// rayinit.cal, in the file's context), by name as written (`.` for none); only
    /// files that loaded without errors.
    pub functions: FunctionModules,
    /// The data files and pictures reachable primitives name (brightdata, colordata,
    /// colorpict, ...), by name as written: the renderer never reads files, so what
    /// p_data.c's `getdata`/`getpict` would load travels here.
    pub data: AuxData,
}

/// Loaded data files (parsed) and pictures (their bytes, decoded by the renderer),
/// only those that loaded. Compared by name only, like [`FunctionModules`].
#[derive(Clone, Debug, Default)]
pub struct AuxData {
    pub files: std::collections::BTreeMap<String, std::sync::Arc<crate::datafile::DataFile>>,
    pub pictures: std::collections::BTreeMap<String, std::sync::Arc<Vec<u8>>>,
    /// Mesh files, read and checked, by name as written.
    pub meshes: std::collections::BTreeMap<String, std::sync::Arc<crate::compiled::MeshFile>>,
}

impl PartialEq for AuxData {
    fn eq(&self, other: &Self) -> bool {
        self.files.keys().eq(other.files.keys())
            && self.pictures.keys().eq(other.pictures.keys())
            && self.meshes.keys().eq(other.meshes.keys())
    }
}

/// Loaded function files by name. Compared by name only: a module is a function of
/// its file's text, which the scene's other fields already pin down.
#[derive(Clone, Debug, Default)]
pub struct FunctionModules(
    pub std::collections::BTreeMap<String, std::sync::Arc<crate::cal::Module>>,
);

impl PartialEq for FunctionModules {
    fn eq(&self, other: &Self) -> bool {
        self.0.keys().eq(other.0.keys())
    }
}

impl Scene {
    pub fn get(&self, id: PrimId) -> Option<&Prim> {
        self.prims.get(id.0 as usize)
    }

    /// The primitives a render needs: every surface and everything reachable from one
    /// through modifiers, aliases and modifier-naming string arguments. Unused
    /// modifiers cost nothing downstream.
    pub fn reachable(&self) -> Vec<bool> {
        self.reachable_from(&self.roots)
    }

    /// [`Scene::reachable`], with `roots` reached too: what surfaces that were
    /// checked but not kept (`lower::Keep::Modifiers`) refer to.
    pub fn reachable_from(&self, roots: &[PrimId]) -> Vec<bool> {
        let mut seen = vec![false; self.prims.len()];
        let mut stack: Vec<PrimId> = self
            .prims
            .iter()
            .enumerate()
            .filter(|(_, p)| p.category() == Category::Surface)
            .map(|(i, _)| PrimId(i as u32))
            .chain(roots.iter().copied())
            .collect();
        while let Some(id) = stack.pop() {
            let Some(slot) = seen.get_mut(id.0 as usize) else {
                continue;
            };
            if *slot {
                continue;
            }
            *slot = true;
            let Some(p) = self.get(id) else { continue };
            if let ModRef::Prim(m) = p.modifier {
                stack.push(m);
            }
            if let PrimKind::Alias { target } = p.kind {
                stack.push(target);
            }
            stack.extend(p.refs.iter().copied());
        }
        seen
    }
}
