//! Lowering a parsed scene to the typed IR, and every check that needs meaning:
//! argument counts and values against the schema, modifier resolution, aliases,
//! geometry sanity, auxiliary files and unused modifiers.
//!
//! Checks follow what Radiance does (`readobj.c`, `modobject.c`, the `o_*.c` and
//! `m_*.c` argument checks): anything Radiance rejects, at oconv time or later at
//! render time, is an error here; anything it accepts with a warning, or accepts but
//! is almost certainly a mistake, is a warning.
//!
//! This module holds the stream ([`Lowering`]) and the pipeline each primitive
//! goes through; what the pipeline consults lives in a module per concept:
//! modifier names, argument lists, auxiliary files, typed kinds, geometry,
//! modifier chains, deferred errors and `!` commands.

mod arguments;
mod chain;
mod commands;
mod deferred;
mod files;
mod geometry;
mod kind;
mod meshes;
mod resolve;

pub use files::{AssumeFilesExist, FileLookup};

use std::collections::{HashMap, HashSet};

use super::command::{CommandExpander, NoCommands};
use super::functions::FunctionFile;
use super::ir::{ModRef, Prim, PrimId, PrimKind, Scene, Vec3};
use super::syntax::{Item, Primitive, SceneFile};
use crate::diagnostic::Diagnostic;
use crate::schema::{self, Category, FileKind, PrimitiveType};
use crate::source::{FileId, Span};
use crate::transform::Transform;
use deferred::Deferred;
use kind::other;
use resolve::SurfaceNames;

/// One parsed input file, with whether unused modifiers defined in it are worth a
/// warning (not for material libraries, which exist to be picked from).
pub struct LowerInput<'a> {
    pub file: FileId,
    pub syntax: &'a SceneFile,
    pub warn_unused: bool,
}

/// Lowers files read in order into one scene, as oconv reads its arguments. `!`
/// commands are reported as not expanded.
pub fn lower(inputs: &[LowerInput<'_>], files: &dyn FileLookup) -> (Scene, Vec<Diagnostic>) {
    lower_with(inputs, files, &NoCommands)
}

/// [`lower`], expanding `!` commands through `commands`.
pub fn lower_with(
    inputs: &[LowerInput<'_>],
    files: &dyn FileLookup,
    commands: &dyn CommandExpander,
) -> (Scene, Vec<Diagnostic>) {
    let mut cx = Lowering::new(files, commands, Keep::Everything);
    for input in inputs {
        cx.items(&input.syntax.items, input.warn_unused, 0);
    }
    cx.finish()
}

/// Which lowered primitives the scene keeps. A check needs only the modifiers (later
/// primitives refer to them) and the `source`s (whose errors depend on their
/// material); other surfaces are checked as they stream past, so checking a scene of
/// a million polygons does not hold a million polygons. The diagnostics are the same
/// whatever is kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Keep {
    Everything,
    Modifiers,
}

/// Lowering as a stream: items go in one at a time, in file order (files in the order
/// oconv would read them), and the scene and its diagnostics come out at the end.
pub struct Lowering<'a> {
    scene: Scene,
    keep: Keep,
    diags: Vec<Diagnostic>,
    /// Modifier name -> most recent definition.
    modifiers: HashMap<String, PrimId>,
    /// Surface names, to explain "that's a surface, not a modifier".
    surfaces: SurfaceNames,
    /// What the surfaces that were not kept refer to (their modifiers and
    /// modifier-naming strings): with the kept surfaces, the roots of reachability.
    roots: Vec<PrimId>,
    /// Per kept primitive: whether it is in `roots` already.
    rooted: Vec<bool>,
    /// Whether the primitive being lowered will be kept.
    current_kept: bool,
    /// The schema of the last type looked up: scenes repeat one type for long runs.
    last_schema: Option<&'static PrimitiveType>,
    /// A polygon's vertices, reused while surfaces are checked but not kept.
    vertices: Vec<Vec3>,
    /// `FileLookup::exists` answers by (name, kind, file naming it): generators name
    /// one function file thousands of times, and the disk does not change meanwhile.
    exists: HashMap<(String, FileKind, FileId), bool>,
    /// Undefined names each entry point of a function file reaches, by (file key,
    /// entry): the same few functions are evaluated for thousands of primitives.
    reached: HashMap<(String, String), Vec<(String, Span)>>,
    /// Names defined by primitives of unknown type: uses are not reported again.
    unknown: HashSet<String>,
    used: HashSet<PrimId>,
    warn_unused: Vec<bool>,
    files: &'a dyn FileLookup,
    commands: &'a dyn CommandExpander,
    /// Errors Radiance only raises when the primitive is actually used (materials are
    /// checked when a ray first hits them, sources when they are set up), by the index
    /// of the diagnostic. Judged once the whole scene is known.
    deferred: Vec<(Deferred, usize)>,
    /// Missing auxiliary files already reported, with the index of their diagnostic.
    missing_files: HashMap<String, usize>,
    /// Further primitives sharing a deferred diagnostic (by its index) reported once.
    more_users: HashMap<usize, Vec<PrimId>>,
    /// Function files loaded so far, by name as written (`None`: could not be loaded).
    function_files: HashMap<String, Option<FunctionFile>>,
    /// Data files parsed so far, by name as written (`None`: missing or unreadable).
    data_files: HashMap<String, Option<std::sync::Arc<crate::datafile::DataFile>>>,
    /// Pictures named, with the file naming each: read in `finish`, and only for a
    /// render (`Keep::Everything`) and reachable primitives, as they can be large.
    picture_files: HashMap<String, FileId>,
    /// Mesh files named, with the first word naming each: read in `finish` for a
    /// render and reachable meshes.
    mesh_files: HashMap<String, Span>,
}

impl<'a> Lowering<'a> {
    pub fn new(files: &'a dyn FileLookup, commands: &'a dyn CommandExpander, keep: Keep) -> Self {
        Lowering {
            scene: Scene::default(),
            keep,
            diags: Vec::new(),
            modifiers: HashMap::new(),
            surfaces: SurfaceNames::default(),
            roots: Vec::new(),
            rooted: Vec::new(),
            current_kept: true,
            last_schema: None,
            vertices: Vec::new(),
            exists: HashMap::new(),
            reached: HashMap::new(),
            unknown: HashSet::new(),
            used: HashSet::new(),
            warn_unused: Vec::new(),
            files,
            commands,
            deferred: Vec::new(),
            function_files: HashMap::new(),
            data_files: HashMap::new(),
            picture_files: HashMap::new(),
            mesh_files: HashMap::new(),
            missing_files: HashMap::new(),
            more_users: HashMap::new(),
        }
    }

    /// Lowers the next item of a file read from disk; `warn_unused` says whether its
    /// file is a scene rather than a material library.
    pub fn item(&mut self, item: &Item, warn_unused: bool) {
        self.items(std::slice::from_ref(item), warn_unused, 0);
    }

    /// The scene (what `Keep` asked for) and every lowering diagnostic, in order.
    pub fn finish(mut self) -> (Scene, Vec<Diagnostic>) {
        self.report_conflicting_materials();
        self.settle_deferred();
        self.report_unused();
        self.scene.roots = std::mem::take(&mut self.roots);
        for (name, file) in std::mem::take(&mut self.function_files) {
            if let Some(f) = file.filter(|f| f.errors.is_empty()) {
                self.scene
                    .functions
                    .0
                    .insert(name, std::sync::Arc::new(f.module));
            }
        }
        self.keep_meshes();
        self.keep_aux_data();
        (self.scene, self.diags)
    }
}

impl Lowering<'_> {
    fn items(&mut self, items: &[Item], warn_unused: bool, depth: u32) {
        for item in items {
            match item {
                Item::Primitive(p) => self.primitive(p, warn_unused),
                Item::Alias(a) => self.alias(a, warn_unused),
                Item::Command(c) => self.command(c, warn_unused, depth),
                Item::Comment(_) | Item::Error(_) => {}
            }
        }
    }

    fn push(&mut self, prim: Prim, warn_unused: bool) -> PrimId {
        let id = PrimId(self.scene.prims.len() as u32);
        self.scene.prims.push(prim);
        self.warn_unused.push(warn_unused);
        id
    }

    fn schema(&mut self, type_name: &str) -> Option<&'static PrimitiveType> {
        if let Some(s) = self.last_schema
            && s.name == type_name
        {
            return Some(s);
        }
        let s = schema::lookup(type_name)?;
        self.last_schema = Some(s);
        Some(s)
    }

    /// Marks what a surface that is not kept refers to as reachable.
    fn add_root(&mut self, id: PrimId) {
        let i = id.0 as usize;
        if i >= self.rooted.len() {
            self.rooted.resize(i + 1, false);
        }
        if !self.rooted[i] {
            self.rooted[i] = true;
            self.roots.push(id);
        }
    }

    fn primitive(&mut self, p: &Primitive, warn_unused: bool) {
        let Some(schema) = self.schema(&p.kind.text) else {
            // The parser reported the unknown type.
            self.unknown.insert(p.name.text.clone());
            return;
        };
        if schema.category == Category::Alias {
            return;
        }
        // A `source` is kept: whether its errors count depends on its material,
        // judged at the end. Instances and meshes are kept so that what the renderer
        // would refuse of them is known (they are few, and hold only file names).
        let kept = self.keep == Keep::Everything
            || schema.category != Category::Surface
            || matches!(schema.name, "source" | "instance" | "mesh");
        self.current_kept = kept;
        let modifier = self.resolve_modifier(&p.modifier, schema);
        let id = PrimId(self.scene.prims.len() as u32);
        let first = self.diags.len();
        let counts_ok = self.check_counts(p, schema);
        if counts_ok {
            self.check_values(p, schema);
            self.check_files(p, schema);
            self.check_data_coordinates(p, schema);
            self.check_functions(p, schema);
        }
        let refs = if counts_ok {
            self.string_modifier_refs(p, schema)
        } else {
            Vec::new()
        };
        let kind = if counts_ok {
            self.lower_kind(p, schema, kept)
        } else if kept {
            other(p)
        } else {
            PrimKind::Other {
                strings: Vec::new(),
                reals: Vec::new(),
            }
        };
        let condition = if schema.category.is_modifier() {
            Some(Deferred::IfUsed(id))
        } else if schema.name == "source" {
            Some(Deferred::IfLightSource(id))
        } else {
            None
        };
        if let Some(condition) = condition {
            for i in first..self.diags.len() {
                if self.diags[i].is_error() {
                    self.deferred.push((condition, i));
                }
            }
        }
        let transform = if counts_ok {
            self.parse_transform(p, schema)
        } else {
            Transform::IDENTITY
        };
        if !kept {
            // Checked; nothing will look it up again but reachability (through what
            // it refers to) and an error message naming it.
            if let ModRef::Prim(m) = modifier {
                self.add_root(m);
            }
            for r in refs {
                self.add_root(r);
            }
            self.surfaces.insert(&p.name.text, p.name.span);
            return;
        }
        let prim = Prim {
            name: p.name.text.clone(),
            name_span: p.name.span,
            modifier_span: p.modifier.span,
            schema,
            modifier,
            refs,
            transform,
            frame: None,
            kind,
            span: p.span,
        };
        self.define(prim, &p.name, warn_unused);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::check_text;

    pub(super) fn check(text: &str) -> (Scene, Vec<&'static str>) {
        let (scene, diags) = check_text(FileId(0), text, &AssumeFilesExist, true);
        (scene, diags.iter().map(|d| d.code.id).collect())
    }

    pub(super) const PAINT: &str = "void plastic paint 0 0 5 .5 .5 .5 0 0\n";

    /// Files whose names start with `missing` do not exist.
    struct SomeMissing;

    impl FileLookup for SomeMissing {
        fn exists(&self, name: &str, _: FileKind, _: FileId) -> bool {
            !name.starts_with("missing")
        }
    }

    fn check_keeping(text: &str, keep: Keep) -> (Scene, Vec<Diagnostic>) {
        let mut lowering = Lowering::new(&SomeMissing, &NoCommands, keep);
        let mut diags =
            crate::scene::parse_each(FileId(0), text, &mut |item| lowering.item(item, true));
        let (scene, more) = lowering.finish();
        diags.extend(more);
        (scene, diags)
    }

    #[test]
    fn keeping_only_modifiers_changes_no_diagnostic() {
        let text = "void colorpict p1 7 red green blue missing.hdr picture.cal pic_u pic_v 0 0\n\
            void colorpict p2 7 red green blue missing.hdr picture.cal pic_u pic_v 0 0\n\
            p2 plastic m2 0 0 5 .5 .5 .5 0 0\n\
            m2 sphere s 0 0 4 0 0 0 1\n\
            void colorpict p3 7 red green blue missing2.hdr picture.cal pic_u pic_v 0 0\n\
            p3 plastic m3 0 0 5 .5 .5 .5 0 0\n\
            void light l 0 0 3 1 1 1\n\
            l source sun 0 0 4 0 0 0 .5\n\
            m2 source notsun 0 0 4 0 0 0 .5\n\
            void alias x s\n\
            s plastic y 0 0 5 .5 .5 .5 0 0\n\
            m2 polygon flat 0 0 9 0 0 0 1 0 0 2 0 0\n\
            m2 instance i 1 missing.oct 0 0\n\
            undefined ring r 0 0 8 0 0 0 0 0 1 1 2\n";
        let (all, diags_all) = check_keeping(text, Keep::Everything);
        let (mods, diags_mods) = check_keeping(text, Keep::Modifiers);
        assert_eq!(diags_all, diags_mods);
        let codes: Vec<_> = diags_all.iter().map(|d| d.code.id).collect();
        for code in [
            "E0305", "W0304", "E0203", "W0301", "E0304", "E0302", "E0301",
        ] {
            assert!(codes.contains(&code), "{code} missing from {codes:?}");
        }
        // p1's missing file stays an error (p2, sharing the report, is reached through
        // a surface that was not kept); p3's becomes a warning.
        let e0305: Vec<_> = diags_all.iter().filter(|d| d.code.id == "E0305").collect();
        assert!(
            e0305.iter().any(|d| d.message.contains("missing.hdr")),
            "{e0305:?}"
        );
        assert!(
            diags_all
                .iter()
                .any(|d| d.code.id == "W0304" && d.message.contains("missing2.hdr")),
            "{diags_all:?}"
        );
        assert!(all.prims.iter().any(|p| p.name == "s"));
        assert!(!mods.prims.iter().any(|p| p.name == "s" || p.name == "flat"));
        assert!(
            mods.prims.iter().any(|p| p.name == "sun"),
            "sources are kept"
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]

        /// Streaming with only the modifiers kept gives exactly the full lowering's
        /// diagnostics, on random mixes of statements.
        #[test]
        fn keep_modes_agree(lines in proptest::collection::vec(proptest::sample::select(&[
            "void plastic m 0 0 5 .5 .5 .5 0 0",
            "void plastic m 0 0 5 .6 .5 .5 0 0",
            "void plastic bad 0 0 5 -1 .5 .5 0 0",
            "void colorpict p 7 red green blue missing.hdr picture.cal pic_u pic_v 0 0",
            "void colorpict q 7 red green blue here.hdr picture.cal pic_u pic_v 0 0",
            "p plastic m 0 0 5 .5 .5 .5 0 0",
            "q plastic m 0 0 5 .5 .5 .5 0 0",
            "bad alias a m",
            "void alias a p",
            "a sphere s 0 0 4 0 0 0 1",
            "m sphere s 0 0 4 0 0 0 1",
            "bad sphere t 0 0 4 0 0 0 1",
            "p polygon g 0 0 9 0 0 0 1 0 0 0 1 0",
            "m polygon g 0 0 9 0 0 0 1 0 0 2 0 0",
            "void light l 0 0 3 1 1 1",
            "l source sun 0 0 4 0 0 0 .5",
            "m source sun 0 0 4 0 0 0 .5",
            "s plastic x 0 0 5 .5 .5 .5 0 0",
            "void alias x s",
            "m instance i 1 missing.oct 0 0",
            "l mixfunc mx 4 m p mix . 0 0",
            "mx sphere s 0 0 4 0 0 0 1",
        ][..]), 0..14)) {
            let text = lines.join("\n");
            // Among equally close names, which one a "did you mean" offers depends on
            // a hash map's order, so those hints are left out of the comparison.
            let without_guesses = |mut diags: Vec<Diagnostic>| {
                for d in &mut diags {
                    if d.hint.as_deref().is_some_and(|h| h.starts_with("did you mean")) {
                        d.hint = None;
                    }
                }
                diags
            };
            let (_, all) = check_keeping(&text, Keep::Everything);
            let (_, mods) = check_keeping(&text, Keep::Modifiers);
            proptest::prop_assert_eq!(without_guesses(all), without_guesses(mods));
        }
    }
}
