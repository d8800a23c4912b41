//! Lowering a parsed scene to the typed IR, and every check that needs meaning:
//! argument counts and values against the schema, modifier resolution, aliases,
//! geometry sanity, auxiliary files and unused modifiers.
//!
//! Checks follow what Radiance does (`readobj.c`, `modobject.c`, the `o_*.c` and
//! `m_*.c` argument checks): anything Radiance rejects, at oconv time or later at
//! render time, is an error here; anything it accepts with a warning, or accepts but
//! is almost certainly a mistake, is a warning.

use std::collections::{HashMap, HashSet};

use super::command::{CommandExpander, Expansion, MAX_DEPTH, NoCommands};
use super::functions::{self, FunctionFile};
use super::ir::{ModRef, Prim, PrimId, PrimKind, Rgb, Scene, Vec3};
use super::syntax::{Alias, Command, Item, Primitive, SceneFile, Word};
use crate::diagnostic::{self as codes, Diagnostic, suggest};
use crate::schema::{self, ArgList, Category, FileKind, PrimitiveType, StringKind};
use crate::source::{FileId, Span};
use crate::transform::Transform;

/// Answers whether an auxiliary file named in a scene exists. The CLI searches the
/// scene's folder and RAYPATH; `lang` itself never touches the file system.
pub trait FileLookup {
    fn exists(&self, name: &str, kind: FileKind, from: FileId) -> bool;

    /// The text of a file found the same way, for the checks that look inside
    /// auxiliary files (data files, function files). `None` skips those checks.
    fn read(&self, _name: &str, _kind: FileKind, _from: FileId) -> Option<String> {
        None
    }

    /// The first `max` bytes of a file found the same way (to recognise a picture
    /// without reading all of it). `None` skips the check.
    fn read_head(
        &self,
        _name: &str,
        _kind: FileKind,
        _from: FileId,
        _max: usize,
    ) -> Option<Vec<u8>> {
        None
    }

    /// A file to check in its own right (a function file), registered as a source so
    /// diagnostics can point into it. `None` skips those checks.
    fn load(&self, _name: &str, _kind: FileKind, _from: FileId) -> Option<(FileId, String)> {
        None
    }
}

/// For callers with no file system (or who don't want file checks).
pub struct AssumeFilesExist;

impl FileLookup for AssumeFilesExist {
    fn exists(&self, _: &str, _: FileKind, _: FileId) -> bool {
        true
    }
}

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
        (self.scene, self.diags)
    }
}

/// Surface names and where they were defined, only ever read to explain an error.
/// They are stored packed, and indexed on the first error that needs them.
#[derive(Default)]
struct SurfaceNames {
    packed: String,
    /// End of each name in `packed`, and its span.
    ends: Vec<(usize, Span)>,
    index: Option<HashMap<String, Span>>,
}

impl SurfaceNames {
    fn insert(&mut self, name: &str, span: Span) {
        match &mut self.index {
            Some(index) => {
                index.insert(name.to_string(), span);
            }
            None => {
                self.packed.push_str(name);
                self.ends.push((self.packed.len(), span));
            }
        }
    }

    /// The latest definition of `name` as a surface.
    fn get(&mut self, name: &str) -> Option<Span> {
        let index = self.index.get_or_insert_with(|| {
            let mut index = HashMap::with_capacity(self.ends.len());
            let mut start = 0;
            for &(end, span) in &self.ends {
                index.insert(
                    self.packed.get(start..end).unwrap_or_default().to_string(),
                    span,
                );
                start = end;
            }
            index
        });
        self.packed = String::new();
        self.ends = Vec::new();
        index.get(name).copied()
    }
}

#[derive(Clone, Copy)]
enum Deferred {
    /// Only an error if the modifier is reachable from a surface.
    IfUsed(PrimId),
    /// Only an error if this `source` is made of a light-emitting material.
    IfLightSource(PrimId),
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

    /// Expands a `!` line and lowers its output in place, as Radiance reads a
    /// command's output where the command stands. Diagnostics inside the output get a
    /// label pointing back at the command line.
    fn command(&mut self, c: &Command, warn_unused: bool, depth: u32) {
        if depth >= MAX_DEPTH {
            self.diags.push(
                Diagnostic::new(
                    codes::E0307,
                    c.span,
                    format!("commands nest more than {MAX_DEPTH} deep"),
                )
                .with_hint("a file probably includes itself through '!xform'"),
            );
            return;
        }
        match self.commands.expand(&c.text, c.span.file, depth + 1) {
            Expansion::Text { file, text } => self.output(c, file, &text, warn_unused, depth),
            Expansion::Partial {
                file,
                text,
                message,
                hint,
            } => {
                self.output(c, file, &text, warn_unused, depth);
                let mut d = Diagnostic::new(codes::W0306, c.span, message);
                if let Some(h) = hint {
                    d = d.with_hint(h);
                }
                self.diags.push(d);
            }
            Expansion::NotExpanded { reason } => self.diags.push(
                Diagnostic::new(
                    codes::W0303,
                    c.span,
                    "this '!' command was not run, so what it makes is not checked",
                )
                .with_hint(reason),
            ),
            Expansion::Cycle { message } => {
                self.diags
                    .push(Diagnostic::new(codes::E0307, c.span, message).with_hint(
                        "a scene cannot include itself; remove the '!' line that reads this file",
                    ))
            }
            Expansion::Failed { message, hint } => {
                // oconv only warns about a failing command ("bad status") and goes on.
                let mut d = Diagnostic::new(codes::W0306, c.span, message);
                if let Some(h) = hint {
                    d = d.with_hint(h);
                }
                self.diags.push(d);
            }
        }
    }

    /// Lowers a command's output where the command stands.
    fn output(&mut self, c: &Command, file: FileId, text: &str, warn_unused: bool, depth: u32) {
        let (syntax, mut diags) = super::parse(file, text);
        let first = self.diags.len();
        self.diags.append(&mut diags);
        self.items(&syntax.items, warn_unused, depth + 1);
        for d in &mut self.diags[first..] {
            if d.span.file == file {
                d.labels.push(crate::diagnostic::Label {
                    span: c.span,
                    message: "in the output of this command".into(),
                });
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
            kind,
            span: p.span,
        };
        self.define(prim, &p.name, warn_unused);
    }

    /// Records a new primitive and, for modifiers, binds its name.
    fn define(&mut self, prim: Prim, name: &Word, warn_unused: bool) {
        let category = prim.category();
        let id = self.push(prim, warn_unused);
        if category == Category::Surface {
            self.surfaces.insert(&name.text, name.span);
            return;
        }
        if name.text == "void" || name.text == "inherit" {
            self.diags.push(
                Diagnostic::new(
                    codes::E0204,
                    name.span,
                    format!("a modifier cannot be named '{}'", name.text),
                )
                .with_hint("'void' and 'inherit' are reserved words; choose another name"),
            );
            self.used.insert(id);
            return;
        }
        if let Some(&old) = self.modifiers.get(&name.text)
            && self.redefinition(old, id, name)
        {
            // Radiance keeps binding the name to the first of identical definitions
            // (`insertobject` in modobject.c); the copy is harmless, not unused.
            self.used.insert(id);
            return;
        }
        self.modifiers.insert(name.text.clone(), id);
    }

    /// Radiance silently keeps an identical redefinition; a different one rebinds the
    /// name for later uses only, which is worth a warning.
    /// Returns whether the new definition is identical to the old one.
    fn redefinition(&mut self, old: PrimId, new: PrimId, name: &Word) -> bool {
        let (Some(a), Some(b)) = (self.scene.get(old), self.scene.get(new)) else {
            return false;
        };
        if a.kind == b.kind && a.schema.name == b.schema.name && a.modifier == b.modifier {
            return true;
        }
        // Define, use, redefine is an idiom (gensurf -s writes a new `Phong` texture
        // before each polygon); only a definition replaced before any use is suspect.
        if self.used.contains(&old) {
            return false;
        }
        let old_span = a.span;
        self.diags.push(
            Diagnostic::new(
                codes::W0302,
                name.span,
                format!("modifier '{}' is defined again", name.text),
            )
            .with_label(old_span, "earlier definition")
            .with_hint("the earlier definition was never used; remove it or rename one of them"),
        );
        // Said here; not again as "never used".
        self.used.insert(old);
        false
    }

    fn resolve_modifier(&mut self, word: &Word, schema: &PrimitiveType) -> ModRef {
        match word.text.as_str() {
            "void" => ModRef::Void,
            "inherit" => {
                self.diags.push(
                    Diagnostic::new(
                        codes::E0206,
                        word.span,
                        format!("'inherit' cannot be the modifier of a {}", schema.name),
                    )
                    .with_hint("only an alias may use 'inherit' (`inherit alias new old`)"),
                );
                ModRef::Unresolved
            }
            name => self.lookup_modifier(name, word.span),
        }
    }

    /// Finds the most recent earlier modifier of this name, reporting if there is none.
    fn lookup_modifier(&mut self, name: &str, span: Span) -> ModRef {
        if let Some(&id) = self.modifiers.get(name) {
            self.used.insert(id);
            return ModRef::Prim(id);
        }
        if self.unknown.contains(name) {
            return ModRef::Unresolved;
        }
        if let Some(surface) = self.surfaces.get(name) {
            self.diags.push(
                Diagnostic::new(
                    codes::E0302,
                    span,
                    format!("'{name}' is a surface, not a modifier"),
                )
                .with_label(surface, "defined here as a surface")
                .with_hint("a modifier must be a material, pattern, texture, mixture or alias"),
            );
            return ModRef::Unresolved;
        }
        // One report per undefined name: a generator's output missing its material
        // would otherwise drown the file in identical errors.
        self.unknown.insert(name.to_string());
        let mut d = Diagnostic::new(
            codes::E0301,
            span,
            format!("modifier '{name}' is not defined before this point"),
        );
        let known = self.modifiers.keys().map(String::as_str);
        d = match suggest(name, known) {
            Some(s) => d.with_hint(format!("did you mean '{s}'?")),
            None => d.with_hint(
                "define the material above its first use, or use 'void' for no modifier",
            ),
        };
        self.diags.push(d);
        ModRef::Unresolved
    }

    fn alias(&mut self, a: &Alias, warn_unused: bool) {
        let Some(schema) = schema::lookup("alias") else {
            return;
        };
        let target = match self.modifiers.get(&a.target.text) {
            Some(&id) => {
                self.used.insert(id);
                Some(id)
            }
            None => {
                self.bad_alias_target(a);
                None
            }
        };
        let modifier = match a.modifier.text.as_str() {
            "inherit" => ModRef::Inherit,
            "void" => ModRef::Void,
            m => self.lookup_modifier(m, a.modifier.span),
        };
        let kind = match target {
            Some(target) => PrimKind::Alias { target },
            None => PrimKind::Other {
                strings: vec![a.target.text.clone()],
                reals: Vec::new(),
            },
        };
        let failed = target.is_none();
        let prim = Prim {
            name: a.name.text.clone(),
            name_span: a.name.span,
            modifier_span: a.modifier.span,
            schema,
            modifier,
            refs: Vec::new(),
            transform: Transform::IDENTITY,
            kind,
            span: a.span,
        };
        // A broken alias was reported already; don't also call it unused.
        self.define(prim, &a.name, warn_unused && !failed);
    }

    fn bad_alias_target(&mut self, a: &Alias) {
        let name = &a.target.text;
        if self.unknown.contains(name) {
            return;
        }
        if let Some(surface) = self.surfaces.get(name) {
            self.diags.push(
                Diagnostic::new(
                    codes::E0304,
                    a.target.span,
                    format!("'{name}' is a surface; only modifiers can be aliased"),
                )
                .with_label(surface, "defined here as a surface"),
            );
            return;
        }
        let mut d = Diagnostic::new(
            codes::E0303,
            a.target.span,
            format!(
                "alias '{}' refers to '{name}', which is not defined before it",
                a.name.text
            ),
        );
        if let Some(s) = suggest(name, self.modifiers.keys().map(String::as_str)) {
            d = d.with_hint(format!("did you mean '{s}'?"));
        }
        self.diags.push(d);
    }

    /// Argument counts against the schema. Returns whether both lists fit.
    fn check_counts(&mut self, p: &Primitive, schema: &PrimitiveType) -> bool {
        let mut ok = true;
        for (what, list, n, span) in [
            (
                "string",
                schema.strings,
                p.strings.len(),
                p.strings.count_span,
            ),
            ("real", schema.reals, p.reals.len(), p.reals.count_span),
        ] {
            let n = u32::try_from(n).unwrap_or(u32::MAX);
            if list.count.accepts(n) {
                continue;
            }
            if what == "string" && list.count == schema::Count::Exactly(0) {
                // No reader of a string-less type looks at its strings.
                self.diags.push(
                    Diagnostic::new(
                        codes::W0207,
                        span,
                        format!(
                            "{} takes no string arguments; Radiance ignores these {n}",
                            schema.name
                        ),
                    )
                    .with_hint("write 0 as the string count"),
                );
                continue;
            }
            ok = false;
            self.diags.push(
                Diagnostic::new(
                    codes::E0202,
                    span,
                    format!(
                        "{} takes {} {what} argument{}, found {n}",
                        schema.name,
                        list.count.describe(),
                        if list.count == schema::Count::Exactly(1) {
                            ""
                        } else {
                            "s"
                        },
                    ),
                )
                .with_label(
                    p.kind.span,
                    format!("{} {}", schema.category.as_str(), schema.name),
                )
                .with_hint(layout_hint(schema.name, what, &list)),
            );
        }
        ok
    }

    /// Hard limits (errors) and plausible ranges (warnings) of real arguments. Surface
    /// geometry is judged in `lower_kind`, where Radiance's own rules are known.
    fn check_values(&mut self, p: &Primitive, schema: &PrimitiveType) {
        // Radii, axes and vertices are judged by Radiance's own geometry rules in
        // `lower_kind` (a negative radius flips the surface rather than failing).
        let geometry = matches!(
            schema.name,
            "sphere" | "bubble" | "cone" | "cup" | "cylinder" | "tube" | "ring" | "polygon"
        );
        for (i, r) in p.reals.items.iter().enumerate() {
            let Some((arg, _)) = schema.reals.arg_at(i) else {
                continue;
            };
            if !r.value.is_finite() {
                self.diags.push(Diagnostic::new(
                    codes::E0203,
                    r.span,
                    format!(
                        "{} of {} '{}' overflows to infinity",
                        arg.name, schema.name, p.name.text
                    ),
                ));
            } else if !geometry && !arg.valid.contains(r.value) {
                self.diags.push(
                    Diagnostic::new(
                        codes::E0203,
                        r.span,
                        format!(
                            "{} of {} '{}' is {}, but must be {}",
                            arg.name,
                            schema.name,
                            p.name.text,
                            r.value,
                            arg.valid.describe()
                        ),
                    )
                    .with_hint(format!("{}: {}", arg.name, arg.meaning)),
                );
            } else if !geometry && !arg.plausible.contains(r.value) {
                self.diags.push(
                    Diagnostic::new(
                        codes::W0201,
                        r.span,
                        format!(
                            "{} of {} '{}' is {}, outside the usual range ({})",
                            arg.name,
                            schema.name,
                            p.name.text,
                            r.value,
                            arg.plausible.describe()
                        ),
                    )
                    .with_hint(format!("{}: {}", arg.name, arg.meaning)),
                );
            }
        }
    }

    fn check_files(&mut self, p: &Primitive, schema: &PrimitiveType) {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        for (i, w) in p.strings.items.iter().enumerate() {
            let Some((arg, _)) = schema.strings.arg_in(i, &words) else {
                continue;
            };
            if arg.kind == StringKind::Transform {
                break;
            }
            let StringKind::File(kind) = arg.kind else {
                continue;
            };
            if kind == FileKind::Cal && w.text == "." {
                continue;
            }
            if kind == FileKind::Data
                && let Some(text) = self.files.read(&w.text, kind, w.span.file)
                && let Err(e) = crate::datafile::DataFile::parse(&text)
            {
                self.diags.push(
                    Diagnostic::new(
                        codes::E0308,
                        w.span,
                        format!("data file '{}' cannot be read: {e}", w.text),
                    )
                    .with_hint("see the Radiance reference manual, section 2.2.2, for the data file layout"),
                );
                continue;
            }
            if kind == FileKind::Picture
                && let Some(head) = self.files.read_head(&w.text, kind, w.span.file, 2)
                && head != b"#?"
            {
                self.diags.push(
                    Diagnostic::new(
                        codes::E0309,
                        w.span,
                        format!(
                            "'{}' is not a Radiance picture (it does not start with '#?')",
                            w.text
                        ),
                    )
                    .with_hint("convert images with ra_tiff, ra_ppm or ra_bmp -r"),
                );
                continue;
            }
            if let Some(&first) = self.missing_files.get(&w.text) {
                // Reported once per file name (a generator's output can name the same
                // function file thousands of times); this primitive is one more user.
                // A surface that is not kept has no id; surfaces are always reached.
                let me = if self.current_kept {
                    PrimId(self.scene.prims.len() as u32)
                } else {
                    PrimId(u32::MAX)
                };
                self.more_users.entry(first).or_default().push(me);
                continue;
            }
            let key = (w.text.clone(), kind, w.span.file);
            let exists = match self.exists.get(&key) {
                Some(&e) => e,
                None => {
                    let e = self.files.exists(&w.text, kind, w.span.file);
                    self.exists.insert(key, e);
                    e
                }
            };
            if !exists {
                self.missing_files.insert(w.text.clone(), self.diags.len());
                self.diags.push(
                    Diagnostic::new(codes::E0305, w.span, format!("file '{}' not found", w.text))
                        .with_hint(
                            "radc looks in the scene's folder, then each folder of RAYPATH \
                         (Radiance's library is found there when RAYPATH is set)",
                        ),
                );
            }
        }
    }

    fn string_modifier_refs(&mut self, p: &Primitive, schema: &PrimitiveType) -> Vec<PrimId> {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        let mut refs = Vec::new();
        for (i, w) in p.strings.items.iter().enumerate() {
            let Some((arg, _)) = schema.strings.arg_in(i, &words) else {
                continue;
            };
            if arg.kind == StringKind::Transform {
                break;
            }
            if arg.kind != StringKind::Modifier || w.text == "void" || w.text == "inherit" {
                continue;
            }
            if matches!(schema.name, "antimatter" | "illum")
                && !self.modifiers.contains_key(&w.text)
            {
                // Radiance only warns about these (when a ray enters the antimatter, or
                // when an illum's alternate material is looked up).
                self.diags.push(Diagnostic::new(
                    codes::W0305,
                    w.span,
                    format!(
                        "{} '{}' names '{}', which is not defined before it",
                        schema.name, p.name.text, w.text
                    ),
                ));
                continue;
            }
            if let ModRef::Prim(id) = self.lookup_modifier(&w.text, w.span) {
                refs.push(id);
            }
        }
        refs
    }

    fn report_unused(&mut self) {
        let mut referenced = self.used.clone();
        for p in &self.scene.prims {
            if let ModRef::Prim(m) = p.modifier {
                referenced.insert(m);
            }
        }
        for (i, p) in self.scene.prims.iter().enumerate() {
            let id = PrimId(i as u32);
            if p.category() == Category::Surface
                || referenced.contains(&id)
                || !self.warn_unused.get(i).copied().unwrap_or(false)
            {
                continue;
            }
            self.diags.push(
                Diagnostic::new(
                    codes::W0301,
                    p.name_span,
                    format!("{} '{}' is never used", p.schema.name, p.name),
                )
                .with_hint("remove it, or keep it in a .mat library file where unused materials are expected"),
            );
        }
    }

    /// The xform-style transform at the end of the string arguments. Radiance rejects
    /// a bad one when it reads the primitive (oconv for instances and meshes, the
    /// renderer for patterns and textures).
    fn parse_transform(&mut self, p: &Primitive, schema: &PrimitiveType) -> Transform {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        let start = match schema.name {
            // Everything after the octree or mesh file is the transform.
            "instance" | "mesh" => 1,
            _ => match schema.strings.transform_start(&words) {
                Some(s) => s,
                None => return Transform::IDENTITY,
            },
        };
        let spanned: Vec<(&str, Span)> = p
            .strings
            .items
            .iter()
            .skip(start)
            .map(|w| (w.text.as_str(), w.span))
            .collect();
        if spanned.is_empty() {
            return Transform::IDENTITY;
        }
        match Transform::parse(&spanned) {
            Ok(t) => t,
            Err(d) => {
                self.diags
                    .push(d.with_label(p.kind.span, format!("transform of this {}", schema.name)));
                Transform::IDENTITY
            }
        }
    }

    /// The functions and variables a primitive names must exist in its function file
    /// (or rayinit.cal, or the renderer), and what they reach when evaluated must be
    /// defined too; the file itself must parse. Radiance finds these only when a ray
    /// first evaluates the primitive.
    fn check_functions(&mut self, p: &Primitive, schema: &PrimitiveType) {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        let kinds: Vec<Option<StringKind>> = (0..words.len())
            .map(|i| schema.strings.arg_in(i, &words).map(|(a, _)| a.kind))
            .collect();
        let uses_functions = kinds
            .iter()
            .any(|k| matches!(k, Some(StringKind::Function | StringKind::FunctionName)));
        if !uses_functions {
            return;
        }
        let cal = p
            .strings
            .items
            .iter()
            .zip(&kinds)
            .find(|(_, k)| **k == Some(StringKind::File(FileKind::Cal)))
            .map(|(w, _)| w);
        let key = cal.map_or(".", |w| w.text.as_str()).to_string();
        if !self.function_files.contains_key(&key) {
            let loaded = match cal {
                Some(w) if w.text != "." => self
                    .files
                    .load(&w.text, FileKind::Cal, w.span.file)
                    .map(|(file, text)| (FunctionFile::load(file, &w.text, &text), w.span)),
                _ => Some((FunctionFile::load(FileId(u32::MAX), ".", ""), p.kind.span)),
            };
            if let Some((ff, user)) = &loaded {
                for e in &ff.errors {
                    self.diags
                        .push(e.clone().with_label(*user, "loaded by this primitive"));
                }
            }
            self.function_files
                .insert(key.clone(), loaded.map(|(ff, _)| ff));
        }
        let Some(Some(ff)) = self.function_files.get(&key) else {
            return;
        };
        if !ff.errors.is_empty() {
            return;
        }
        let mut found = Vec::new();
        for (w, k) in p.strings.items.iter().zip(&kinds) {
            if !matches!(k, Some(StringKind::Function | StringKind::FunctionName))
                || !functions::is_plain_name(&w.text)
            {
                continue;
            }
            if !ff.defines(&w.text) {
                let known = ff.module.known_names();
                found.push(functions::undefined_in_file(&w.text, &key, w.span, &known));
                continue;
            }
            let reached = self
                .reached
                .entry((key.clone(), w.text.clone()))
                .or_insert_with(|| ff.undefined_reached_from(&w.text));
            for (name, span) in reached.iter().cloned() {
                found.push(
                    Diagnostic::new(
                        codes::E0601,
                        span,
                        format!(
                            "'{name}' is not defined, but evaluating '{}' reaches it",
                            w.text
                        ),
                    )
                    .with_label(w.span, "evaluated for this primitive")
                    .with_hint("define it in the function file (or one loaded before it)"),
                );
            }
        }
        self.diags.extend(found);
    }

    /// A data-driven type needs one coordinate function per dimension of its data
    /// file (spectral types one fewer: wavelength is the last dimension), written after
    /// the function file and before any transform. Radiance checks this when it first
    /// loads the data ("too few string arguments").
    fn check_data_coordinates(&mut self, p: &Primitive, schema: &PrimitiveType) {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        let mut cal_at = None;
        let mut dims = None;
        let mut data_word = None;
        for (i, w) in p.strings.items.iter().enumerate() {
            match schema.strings.arg_in(i, &words).map(|(a, _)| a.kind) {
                Some(StringKind::File(FileKind::Cal)) if cal_at.is_none() => cal_at = Some(i),
                Some(StringKind::File(FileKind::Data)) => {
                    let parsed = self
                        .files
                        .read(&w.text, FileKind::Data, w.span.file)
                        .and_then(|t| crate::datafile::DataFile::parse(&t).ok());
                    if let Some(d) = parsed {
                        dims = Some(dims.unwrap_or(0).max(d.dimensions()));
                        data_word = Some(w);
                    }
                }
                _ => {}
            }
        }
        let (Some(dims), Some(data_word)) = (dims, data_word) else {
            return;
        };
        if schema.name == "specfile" {
            if dims != 1 {
                self.diags.push(Diagnostic::new(
                    codes::E0308,
                    data_word.span,
                    format!(
                        "specfile needs a 1-dimensional data file (wavelength); '{}' has {dims}",
                        data_word.text
                    ),
                ));
            }
            return;
        }
        let Some(cal_at) = cal_at else { return };
        let end = schema
            .strings
            .transform_start(&words)
            .unwrap_or(words.len());
        let coords = end.saturating_sub(cal_at + 1);
        let needed = if schema.name.starts_with("spec") {
            dims.saturating_sub(1)
        } else {
            dims
        };
        if coords < needed {
            self.diags.push(
                Diagnostic::new(
                    codes::E0202,
                    p.strings.count_span,
                    format!(
                        "{} '{}' gives {coords} coordinate function{} for the {dims}-dimensional data file '{}'; it needs {needed}",
                        schema.name,
                        p.name.text,
                        if coords == 1 { "" } else { "s" },
                        data_word.text
                    ),
                )
                .with_label(data_word.span, format!("{dims}-dimensional data"))
                .with_hint("after the function file, name one coordinate variable or function per data dimension"),
            );
        }
    }

    /// Keeps deferred errors whose condition holds and turns the rest into W0304
    /// warnings, keeping the original code in the message.
    fn settle_deferred(&mut self) {
        let reachable = self.scene.reachable_from(&self.roots);
        for (condition, index) in std::mem::take(&mut self.deferred) {
            let (id, why) = match condition {
                Deferred::IfUsed(id) => {
                    let users = std::iter::once(id)
                        .chain(self.more_users.get(&index).into_iter().flatten().copied());
                    if users
                        .into_iter()
                        .any(|u| reachable.get(u.0 as usize).copied().unwrap_or(true))
                    {
                        continue;
                    }
                    (id, "nothing uses it, so Radiance never reads it")
                }
                Deferred::IfLightSource(id) => {
                    if self.emits_light(id) {
                        continue;
                    }
                    (
                        id,
                        "its material emits no light, so Radiance never reads it",
                    )
                }
            };
            let name = self
                .scene
                .get(id)
                .map(|p| p.name.clone())
                .unwrap_or_default();
            if let Some(d) = self.diags.get_mut(index) {
                d.message = format!("[{}] {} ('{name}': {why})", d.code.id, d.message);
                d.code = codes::W0304;
                d.severity = codes::W0304.severity;
            }
        }
    }

    /// Whether the first material in a primitive's modifier chain emits light.
    fn emits_light(&self, id: PrimId) -> bool {
        let Some(p) = self.scene.get(id) else {
            return false;
        };
        let mut next = p.modifier;
        for _ in 0..256 {
            let ModRef::Prim(m) = next else { return false };
            let Some((category, modifier)) = self.chain_link(m) else {
                return false;
            };
            match category {
                Category::Light => return true,
                Category::Material => return false,
                _ => next = modifier,
            }
        }
        false
    }

    /// What an element of a modifier chain really is: aliases are followed to their
    /// target's type, and take either their own modifier or (with `inherit`) the
    /// target's. Returns the category and the next link of the chain.
    fn chain_link(&self, id: PrimId) -> Option<(Category, ModRef)> {
        let mut cur = self.scene.get(id)?;
        let mut modifier = cur.modifier;
        for _ in 0..64 {
            match cur.kind {
                PrimKind::Alias { target } => {
                    cur = self.scene.get(target)?;
                    if modifier == ModRef::Inherit {
                        modifier = cur.modifier;
                    }
                }
                _ => return Some((cur.category(), modifier)),
            }
        }
        None
    }

    /// Radiance shades a hit with the first material in the surface's modifier chain
    /// and then applies the rest of the chain as patterns and textures; a second
    /// material there is fatal ("conflicting material", `raytexture` in raytrace.c)
    /// as soon as a ray hits it.
    fn report_conflicting_materials(&mut self) {
        let is_material = |c: Category| matches!(c, Category::Material | Category::Light);
        let mut found = Vec::new();
        for (i, p) in self.scene.prims.iter().enumerate() {
            if !is_material(p.category()) || matches!(p.kind, PrimKind::Alias { .. }) {
                continue;
            }
            let mut next = p.modifier;
            for _ in 0..256 {
                let ModRef::Prim(id) = next else { break };
                let Some((category, modifier)) = self.chain_link(id) else {
                    break;
                };
                if is_material(category) {
                    found.push((PrimId(i as u32), id));
                    break;
                }
                next = modifier;
            }
        }
        for (user, material) in found {
            let (Some(u), Some(m)) = (self.scene.get(user), self.scene.get(material)) else {
                continue;
            };
            self.diags.push(
                Diagnostic::new(
                    codes::E0302,
                    u.modifier_span,
                    format!(
                        "{} '{}' is modified by {} '{}': a material's modifiers may only be patterns, textures or mixtures of them",
                        u.schema.name, u.name, m.schema.name, m.name
                    ),
                )
                .with_label(m.name_span, "this material is further down the chain")
                .with_hint("Radiance stops with \"conflicting material\" when a ray hits this; give the material the modifier 'void' or a pattern"),
            );
        }
    }

    /// The typed form; counts are already known to fit the schema. For a primitive
    /// that is not `kept`, just its checks (the kind returned is then a placeholder).
    fn lower_kind(&mut self, p: &Primitive, schema: &PrimitiveType, kept: bool) -> PrimKind {
        // Counts were checked against the schema, but indexing stays total so a schema
        // slip can never become a panic on user input.
        let values = &p.reals.items;
        let r = Reals(values);
        let s: Vec<String> = p.strings.items.iter().map(|w| w.text.clone()).collect();
        let v3 = |i: usize| -> Vec3 { [r[i], r[i + 1], r[i + 2]] };
        let rgb = |i: usize| -> Rgb { [r[i], r[i + 1], r[i + 2]] };
        let first_string = || s.first().cloned();
        match schema.name {
            "source" => {
                if v3(0) == [0.0; 3] {
                    self.zero_direction(p, 0);
                }
                PrimKind::Source {
                    direction: v3(0),
                    angle: r[3],
                }
            }
            "sphere" | "bubble" => {
                self.check_radius(p, r[3], 3);
                let (center, radius) = (v3(0), r[3]);
                if (schema.name == "sphere") == (radius >= 0.0) {
                    PrimKind::Sphere {
                        center,
                        radius: radius.abs(),
                    }
                } else {
                    PrimKind::Bubble {
                        center,
                        radius: radius.abs(),
                    }
                }
            }
            "polygon" => {
                let mut vertices = std::mem::take(&mut self.vertices);
                vertices.clear();
                vertices.extend(
                    values
                        .chunks_exact(3)
                        .map(|c| [c[0].value, c[1].value, c[2].value]),
                );
                self.check_polygon(p, &vertices);
                if kept {
                    PrimKind::Polygon { vertices }
                } else {
                    self.vertices = vertices;
                    PrimKind::Polygon {
                        vertices: Vec::new(),
                    }
                }
            }
            "cone" | "cup" => {
                let (p0, p1, r0, r1) = (v3(0), v3(3), r[6], r[7]);
                self.check_axis(p, p0, p1);
                self.check_cone_radii(p, r0, r1);
                if (schema.name == "cone") == (r0 >= 0.0 && r1 >= 0.0) {
                    PrimKind::Cone {
                        p0,
                        p1,
                        r0: r0.abs(),
                        r1: r1.abs(),
                    }
                } else {
                    PrimKind::Cup {
                        p0,
                        p1,
                        r0: r0.abs(),
                        r1: r1.abs(),
                    }
                }
            }
            "cylinder" | "tube" => {
                let (p0, p1, radius) = (v3(0), v3(3), r[6]);
                self.check_axis(p, p0, p1);
                self.check_radius(p, radius, 6);
                if (schema.name == "cylinder") == (radius >= 0.0) {
                    PrimKind::Cylinder {
                        p0,
                        p1,
                        radius: radius.abs(),
                    }
                } else {
                    PrimKind::Tube {
                        p0,
                        p1,
                        radius: radius.abs(),
                    }
                }
            }
            "ring" => {
                let (center, normal, r0, r1) = (v3(0), v3(3), r[6], r[7]);
                if norm(normal) == 0.0 {
                    self.degenerate(
                        p,
                        real_span(p, 3).to(real_span(p, 5)),
                        "its normal is the zero vector",
                    );
                }
                self.check_ring_radii(p, r0, r1);
                PrimKind::Ring {
                    center,
                    normal,
                    r0: r0.min(r1),
                    r1: r0.max(r1),
                }
            }
            "instance" => PrimKind::Instance {
                octree: first_string().unwrap_or_default(),
                transform: s.iter().skip(1).cloned().collect(),
            },
            "mesh" => PrimKind::Mesh {
                file: first_string().unwrap_or_default(),
                transform: s.iter().skip(1).cloned().collect(),
            },
            "light" => PrimKind::Light { color: rgb(0) },
            "illum" => PrimKind::Illum {
                alternate: first_string(),
                color: rgb(0),
            },
            "glow" => PrimKind::Glow {
                color: rgb(0),
                max_radius: r[3],
            },
            "spotlight" => {
                if v3(4) == [0.0; 3] {
                    self.zero_direction(p, 4);
                }
                PrimKind::Spotlight {
                    color: rgb(0),
                    angle: r[3],
                    direction: v3(4),
                }
            }
            "mirror" => PrimKind::Mirror {
                alternate: first_string(),
                color: rgb(0),
            },
            "plastic" => PrimKind::Plastic {
                color: rgb(0),
                spec: r[3],
                rough: r[4],
            },
            "metal" => PrimKind::Metal {
                color: rgb(0),
                spec: r[3],
                rough: r[4],
            },
            "trans" => PrimKind::Trans {
                color: rgb(0),
                spec: r[3],
                rough: r[4],
                trans: r[5],
                tspec: r[6],
            },
            "glass" => PrimKind::Glass {
                transmission: rgb(0),
                // Radiance's default index of refraction for glass.
                index: values.get(3).map_or(1.52, |r| r.value),
            },
            "dielectric" => PrimKind::Dielectric {
                transmission: rgb(0),
                index: r[3],
                hartmann: r[4],
            },
            "interface" => PrimKind::Interface {
                t1: rgb(0),
                n1: r[3],
                t2: rgb(4),
                n2: r[7],
            },
            "antimatter" => PrimKind::Antimatter { modifiers: s },
            _ => other(p),
        }
    }

    /// Radiance stops with "zero direction" when it sets up such a source.
    fn zero_direction(&mut self, p: &Primitive, first: usize) {
        let span = real_span(p, first).to(real_span(p, first + 2));
        self.diags.push(
            Diagnostic::new(
                codes::E0203,
                span,
                format!(
                    "the direction of {} '{}' is the zero vector",
                    p.kind.text, p.name.text
                ),
            )
            .with_hint("give the direction the light travels toward, e.g. 0 0 -1"),
        );
    }

    fn degenerate(&mut self, p: &Primitive, span: Span, why: &str) {
        self.diags.push(
            Diagnostic::new(
                codes::W0206,
                span,
                format!("{} '{}' is degenerate: {why}", p.kind.text, p.name.text),
            )
            .with_hint("Radiance drops degenerate surfaces with a warning; fix or remove it"),
        );
    }

    fn check_radius(&mut self, p: &Primitive, radius: f64, index: usize) {
        let span = real_span(p, index);
        if radius == 0.0 {
            self.degenerate(p, span, "its radius is zero");
        } else if radius < 0.0 {
            let flipped = match p.kind.text.as_str() {
                "sphere" => "bubble",
                "bubble" => "sphere",
                "cylinder" => "tube",
                "tube" => "cylinder",
                _ => "its inside-out twin",
            };
            self.diags.push(
                Diagnostic::new(
                    codes::W0202,
                    span,
                    format!("negative radius: Radiance reads this {} as a {flipped}", p.kind.text),
                )
                .with_hint(format!("write a positive radius, or use the type '{flipped}' if the normals should point inward")),
            );
        }
    }

    fn check_axis(&mut self, p: &Primitive, p0: Vec3, p1: Vec3) {
        if p0 == p1 {
            let span = real_span(p, 0).to(real_span(p, 5));
            self.degenerate(p, span, "both end points are the same, so it has no axis");
        }
    }

    fn check_cone_radii(&mut self, p: &Primitive, r0: f64, r1: f64) {
        let span = real_span(p, 6).to(real_span(p, 7));
        if (r0 < 0.0) != (r1 < 0.0) && r0 != 0.0 && r1 != 0.0 {
            self.degenerate(p, span, "its radii have opposite signs");
        } else if r0 == 0.0 && r1 == 0.0 {
            self.degenerate(p, span, "both radii are zero");
        } else if r0 == r1 {
            self.diags.push(
                Diagnostic::new(
                    codes::W0205,
                    span,
                    format!("{} '{}' has equal radii", p.kind.text, p.name.text),
                )
                .with_hint(if p.kind.text == "cone" {
                    "use a cylinder: Radiance converts it anyway"
                } else {
                    "use a tube: Radiance converts it anyway"
                }),
            );
        } else if r0 < 0.0 && r1 < 0.0 {
            self.diags.push(Diagnostic::new(
                codes::W0202,
                span,
                format!(
                    "negative radii: Radiance reads this {} inside out",
                    p.kind.text
                ),
            ));
        }
    }

    fn check_ring_radii(&mut self, p: &Primitive, r0: f64, r1: f64) {
        let span = real_span(p, 6).to(real_span(p, 7));
        if r0 < 0.0 || r1 < 0.0 || r0 == r1 {
            self.degenerate(p, span, "its radii must be >= 0 and differ");
        }
    }

    /// Zero area and non-planarity, judged as Radiance's face setup does: the normal
    /// from Newell's method, and each vertex's distance from the plane.
    fn check_polygon(&mut self, p: &Primitive, vertices: &[Vec3]) {
        if vertices.len() < 3 {
            return;
        }
        let n = newell_normal(vertices);
        let area2 = norm(n);
        let span = p.reals.span_all();
        if area2 == 0.0 || !area2.is_finite() {
            self.diags.push(
                Diagnostic::new(
                    codes::W0204,
                    span,
                    format!(
                        "polygon '{}' has zero area (its vertices are collinear or coincide)",
                        p.name.text
                    ),
                )
                .with_hint("Radiance drops it with a warning"),
            );
            return;
        }
        let unit = [n[0] / area2, n[1] / area2, n[2] / area2];
        let d0 = dot(unit, vertices[0]);
        let size = vertices
            .iter()
            .flat_map(|v| v.iter())
            .fold(0.0f64, |m, c| m.max(c.abs()))
            .max(1.0);
        if let Some((i, _)) = vertices
            .iter()
            .enumerate()
            .find(|(_, v)| (dot(unit, **v) - d0).abs() > 1e-5 * size)
        {
            let s = real_span(p, i * 3).to(real_span(p, i * 3 + 2));
            self.diags.push(
                Diagnostic::new(
                    codes::W0203,
                    s,
                    format!(
                        "vertex {} of polygon '{}' is out of the polygon's plane",
                        i + 1,
                        p.name.text
                    ),
                )
                .with_hint("split the polygon into planar pieces (triangles are always planar)"),
            );
        }
    }
}

trait SpanAll {
    fn span_all(&self) -> Span;
}

impl SpanAll for super::syntax::ArgGroup<super::syntax::Real> {
    fn span_all(&self) -> Span {
        match (self.items.first(), self.items.last()) {
            (Some(a), Some(b)) => a.span.to(b.span),
            _ => self.count_span,
        }
    }
}

fn other(p: &Primitive) -> PrimKind {
    PrimKind::Other {
        strings: p.strings.items.iter().map(|w| w.text.clone()).collect(),
        reals: p.reals.items.iter().map(|r| r.value).collect(),
    }
}

fn layout_hint(type_name: &str, what: &str, list: &ArgList) -> String {
    let names: Vec<&str> = list.fixed.iter().map(|a| a.name).collect();
    let repeat: Vec<&str> = list.repeat.iter().map(|a| a.name).collect();
    let mut layout = names.join(" ");
    if !repeat.is_empty() {
        if !layout.is_empty() {
            layout.push(' ');
        }
        layout.push_str(&format!("[{}]...", repeat.join(" ")));
    }
    if layout.is_empty() {
        format!("{type_name} takes no {what} arguments: write 0")
    } else {
        format!("{type_name} {what} arguments: {layout}")
    }
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// Newell's method: twice the vector area of a (possibly non-planar) polygon.
fn newell_normal(v: &[Vec3]) -> Vec3 {
    let mut n = [0.0; 3];
    for (i, a) in v.iter().enumerate() {
        let b = v[(i + 1) % v.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Total indexing into a real list: missing values read as 0.
struct Reals<'a>(&'a [super::syntax::Real]);

impl std::ops::Index<usize> for Reals<'_> {
    type Output = f64;
    fn index(&self, i: usize) -> &f64 {
        self.0.get(i).map_or(&0.0, |r| &r.value)
    }
}

fn real_span(p: &Primitive, i: usize) -> Span {
    p.reals
        .items
        .get(i)
        .map(|r| r.span)
        .unwrap_or(p.reals.count_span)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::check_text;

    fn check(text: &str) -> (Scene, Vec<&'static str>) {
        let (scene, diags) = check_text(FileId(0), text, &AssumeFilesExist, true);
        (scene, diags.iter().map(|d| d.code.id).collect())
    }

    const PAINT: &str = "void plastic paint 0 0 5 .5 .5 .5 0 0\n";

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

    #[test]
    fn a_modifier_binds_to_the_most_recent_earlier_definition() {
        let text = format!(
            "{PAINT}paint sphere a 0 0 4 0 0 0 1\n\
             void metal paint 0 0 5 .5 .5 .5 .9 0\npaint sphere b 0 0 4 0 0 0 1\n"
        );
        let (scene, codes) = check(&text);
        // Define, use, redefine is an idiom: no warning.
        assert!(codes.is_empty(), "{codes:?}");
        let kind_of_modifier = |name: &str| {
            let p = scene.prims.iter().find(|p| p.name == name).unwrap();
            let ModRef::Prim(m) = p.modifier else {
                panic!()
            };
            scene.get(m).unwrap().schema.name
        };
        assert_eq!(kind_of_modifier("a"), "plastic");
        assert_eq!(kind_of_modifier("b"), "metal");
    }

    #[test]
    fn a_definition_replaced_before_any_use_is_warned_once() {
        let text =
            format!("{PAINT}void metal paint 0 0 5 .5 .5 .5 .9 0\npaint sphere b 0 0 4 0 0 0 1\n");
        assert_eq!(check(&text).1, vec!["W0302"]);
    }

    #[test]
    fn identical_redefinitions_are_silent() {
        let (_, codes) = check(&format!("{PAINT}{PAINT}paint sphere a 0 0 4 0 0 0 1\n"));
        assert!(codes.is_empty(), "{codes:?}");
    }

    #[test]
    fn aliases_resolve_and_inherit() {
        let text = format!(
            "{PAINT}inherit alias coat paint\nvoid alias coat2 coat\n\
             coat sphere a 0 0 4 0 0 0 1\ncoat2 sphere b 0 0 4 0 0 0 1\n"
        );
        let (scene, codes) = check(&text);
        assert!(codes.is_empty(), "{codes:?}");
        let coat = scene.prims.iter().find(|p| p.name == "coat").unwrap();
        assert!(matches!(coat.kind, PrimKind::Alias { .. }));
        assert_eq!(coat.modifier, ModRef::Inherit);
    }

    #[test]
    fn reference_errors() {
        assert_eq!(check("void alias a nothere\n").1, vec!["E0303"]);
        let surface = format!("{PAINT}paint sphere s 0 0 4 0 0 0 1\n");
        assert_eq!(
            check(&format!("{surface}void alias a s\n")).1,
            vec!["E0304"]
        );
        assert_eq!(
            check(&format!("{surface}s sphere t 0 0 4 0 0 0 1\n")).1,
            vec!["E0302"]
        );
        assert_eq!(
            check(&format!("{PAINT}inherit sphere t 0 0 4 0 0 0 1\n")).1,
            vec!["E0206", "W0301"]
        );
        assert_eq!(
            check("void plastic void 0 0 5 .5 .5 .5 0 0\n").1,
            vec!["E0204"]
        );
        // One report for an undefined name, however often it is used.
        assert_eq!(
            check("m sphere a 0 0 4 0 0 0 1\nm sphere b 0 0 4 0 0 0 1\n").1,
            vec!["E0301"]
        );
    }

    #[test]
    fn a_material_modified_by_a_material_conflicts() {
        let text =
            format!("{PAINT}paint plastic p2 0 0 5 .5 .5 .5 0 0\np2 sphere s 0 0 4 0 0 0 1\n");
        assert_eq!(check(&text).1, vec!["E0302"]);
    }

    #[test]
    fn counts_values_and_geometry() {
        assert_eq!(
            check("void plastic m 0 0 4 .5 .5 .5 0\nm sphere s 0 0 4 0 0 0 1\n").1,
            vec!["E0202"]
        );
        assert_eq!(
            check("void plastic m 0 0 5 1.5 .5 .5 0 0\nm sphere s 0 0 4 0 0 0 1\n").1,
            vec!["W0201"]
        );
        let (scene, codes) = check(&format!("{PAINT}paint sphere s 0 0 4 0 0 0 -1\n"));
        assert_eq!(codes, vec!["W0202"]);
        assert!(matches!(scene.prims[1].kind, PrimKind::Bubble { radius, .. } if radius == 1.0));
        assert_eq!(
            check(&format!("{PAINT}paint sphere s 0 0 4 0 0 0 0\n")).1,
            vec!["W0206"]
        );
        assert_eq!(
            check(&format!("{PAINT}paint cone c 0 0 8 0 0 0 0 0 0 1 .5\n")).1,
            vec!["W0206"]
        );
        assert_eq!(
            check(&format!("{PAINT}paint polygon p 0 0 9 0 0 0 1 1 1 2 2 2\n")).1,
            vec!["W0204"]
        );
        assert_eq!(
            check(&format!(
                "{PAINT}paint polygon p 0 0 12 0 0 0 1 0 0 1 1 0 0 1 1\n"
            ))
            .1,
            vec!["W0203"]
        );
    }

    #[test]
    fn unused_modifiers_are_warned_and_reachability_skips_them() {
        let text =
            format!("{PAINT}void plastic spare 0 0 5 .5 .5 .5 0 0\npaint sphere s 0 0 4 0 0 0 1\n");
        let (scene, codes) = check(&text);
        assert_eq!(codes, vec!["W0301"]);
        assert_eq!(scene.reachable(), vec![true, false, true]);
    }

    /// Expands `!gen NAME` into a sphere named NAME using the material `paint`, and
    /// `!loop` into itself.
    struct FakeGenerators;

    impl CommandExpander for FakeGenerators {
        fn expand(&self, command: &str, _: FileId, depth: u32) -> Expansion {
            let file = FileId(depth);
            match command.split_whitespace().collect::<Vec<_>>().as_slice() {
                ["gen", name] => Expansion::Text {
                    file,
                    text: format!("paint sphere {name} 0 0 4 0 0 0 1\n"),
                },
                ["genbad"] => Expansion::Text {
                    file,
                    text: "undefined sphere x 0 0 4 0 0 0 1\n".into(),
                },
                ["loop"] => Expansion::Text {
                    file,
                    text: "!loop\n".into(),
                },
                ["fail"] => Expansion::Failed {
                    message: "it failed".into(),
                    hint: None,
                },
                ["halfway", name] => Expansion::Partial {
                    file,
                    text: format!("paint sphere {name} 0 0 4 0 0 0 1\nundefined sphere y\n"),
                    message: "it failed halfway".into(),
                    hint: Some("the program's own message".into()),
                },
                _ => Expansion::NotExpanded {
                    reason: "not a generator".into(),
                },
            }
        }
    }

    fn check_with_commands(text: &str) -> (Scene, Vec<Diagnostic>) {
        let (syntax, mut diags) = crate::scene::parse(FileId(0), text);
        let input = LowerInput {
            file: FileId(0),
            syntax: &syntax,
            warn_unused: true,
        };
        let (scene, more) = lower_with(&[input], &AssumeFilesExist, &FakeGenerators);
        diags.extend(more);
        (scene, diags)
    }

    #[test]
    fn commands_expand_in_place_and_errors_point_back() {
        let (scene, diags) = check_with_commands(&format!("{PAINT}!gen ball\n!ls -l\n!genbad\n"));
        assert!(scene.prims.iter().any(|p| p.name == "ball"));
        let codes: Vec<_> = diags.iter().map(|d| d.code.id).collect();
        assert_eq!(codes, vec!["W0303", "E0301"]);
        assert_eq!(diags[1].labels[0].message, "in the output of this command");
        let (_, diags) = check_with_commands("!loop\n");
        assert_eq!(
            diags.iter().map(|d| d.code.id).collect::<Vec<_>>(),
            vec!["E0307"]
        );
    }

    #[test]
    fn output_before_a_failure_is_lowered_and_the_failure_warns_on_the_command() {
        let text = format!("{PAINT}\n!halfway half\n");
        let (scene, diags) = check_with_commands(&text);
        assert!(scene.prims.iter().any(|p| p.name == "half"));
        let failure = diags
            .iter()
            .find(|d| d.code.id == "W0306")
            .expect("a command-failed warning");
        assert_eq!(failure.span.file, FileId(0));
        let at = failure.span.start as usize..failure.span.end as usize;
        assert_eq!(&text[at], "!halfway half");
        assert_eq!(failure.hint.as_deref(), Some("the program's own message"));
        // The truncated primitive is reported in the output, pointing back at the line.
        let truncated = diags
            .iter()
            .find(|d| d.span.file != FileId(0))
            .expect("a diagnostic inside the output");
        assert_eq!(truncated.labels[0].span, failure.span);
    }
}
