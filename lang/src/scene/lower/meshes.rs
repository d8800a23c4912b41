//! Mesh files named by `mesh` primitives: checked when named (oconv reads a mesh's
//! bounds, so a file that is not a mesh is an error there), read whole for a render,
//! and their materials appended to the scene for the meshes whose modifier is `void`
//! (o_mesh.c then shades each triangle with its own material, evaluated in the mesh's
//! frame).
//!
//! A mesh file's materials are a binary scene section; they are turned back into
//! scene text and lowered by a nested [`Lowering`] like any scene, so they get the
//! same checks and the same typed IR. Each `void` mesh gets its own copy: the copies
//! differ in their frame.

use std::sync::Arc;

use super::{Keep, Lowering};
use crate::compiled::MeshFile;
use crate::compiled::objects::objects_text;
use crate::diagnostic::{self as codes, Diagnostic, Severity};
use crate::scene::command::NoCommands;
use crate::scene::ir::{ModRef, PrimId, PrimKind};
use crate::scene::syntax::Word;
use crate::schema::FileKind;
use crate::source::Span;

/// Enough of a mesh file for its header, magic number and bounds (obj2mesh's header
/// holds its command line, rarely longer than this).
const MESH_HEAD_BYTES: usize = 8192;
/// The largest mesh file read (Radiance's patch numbering allows about 2^30 vertices
/// of 24 bytes; more than a 64-bit address space of files in practice).
const MAX_MESH_BYTES: usize = 1 << 36;

impl Lowering<'_> {
    /// Checks that the file a `mesh` names reads as a mesh file (E0310), and notes it
    /// to be read for a render.
    pub(super) fn check_mesh_file(&mut self, w: &Word) {
        self.mesh_files.entry(w.text.clone()).or_insert(w.span);
        let Some(head) =
            self.files
                .read_head(&w.text, FileKind::Mesh, w.span.file, MESH_HEAD_BYTES)
        else {
            return;
        };
        if let Err(e) = MeshFile::read_header(&head)
            && head.len() < MESH_HEAD_BYTES
        {
            self.diags.push(bad_mesh(w.span, &w.text, &e.to_string()));
        }
    }

    /// Reads the mesh files of reachable `mesh` primitives into the scene and appends
    /// the materials of those with a `void` modifier.
    pub(super) fn keep_meshes(&mut self) {
        if self.keep != Keep::Everything || self.mesh_files.is_empty() {
            return;
        }
        let reachable = self.scene.reachable();
        let meshes: Vec<(PrimId, String)> = self
            .scene
            .prims
            .iter()
            .enumerate()
            .filter(|(i, _)| reachable.get(*i) == Some(&true))
            .filter_map(|(i, p)| match &p.kind {
                PrimKind::Mesh { file, .. } => Some((PrimId(i as u32), file.clone())),
                _ => None,
            })
            .collect();
        for (id, name) in meshes {
            let Some(&span) = self.mesh_files.get(&name) else {
                continue;
            };
            let Some(mesh) = self.mesh_file(&name, span) else {
                continue;
            };
            let void = self
                .scene
                .get(id)
                .is_some_and(|p| p.modifier == ModRef::Void);
            if void && !mesh.materials.is_empty() {
                self.append_materials(id, &name, span, &mesh);
            }
        }
    }

    /// A mesh file read and decoded once per name; `None` (reported) when it cannot be.
    fn mesh_file(&mut self, name: &str, span: Span) -> Option<Arc<MeshFile>> {
        if let Some(m) = self.scene.data.meshes.get(name) {
            return Some(m.clone());
        }
        let bytes = self
            .files
            .read_head(name, FileKind::Mesh, span.file, MAX_MESH_BYTES)?;
        match MeshFile::read(&bytes) {
            Ok(m) => {
                let m = Arc::new(m);
                self.scene.data.meshes.insert(name.to_string(), m.clone());
                Some(m)
            }
            Err(e) => {
                self.diags.push(bad_mesh(span, name, &e.to_string()));
                None
            }
        }
    }

    /// Lowers the mesh file's materials and appends them, each framed by `mesh`.
    fn append_materials(&mut self, mesh: PrimId, name: &str, span: Span, file: &MeshFile) {
        let text = match objects_text(&file.materials) {
            Ok(t) => t,
            Err(e) => return self.diags.push(bad_mesh(span, name, &e.message)),
        };
        let mut nested = Lowering::new(self.files, &NoCommands, Keep::Everything);
        let mut diags =
            crate::scene::parse_each(span.file, &text, &mut |item| nested.item(item, false));
        let (scene, more) = nested.finish();
        diags.extend(more);
        // Every material may be used by a triangle: what Radiance reports when one is
        // used (W0304 in a scene where nothing uses it) is an error here.
        if let Some(d) = diags
            .iter()
            .find(|d| d.severity == Severity::Error || d.code == codes::W0304)
        {
            let what = format!("its materials: {}", d.message);
            return self.diags.push(bad_mesh(span, name, &what));
        }
        if scene.prims.len() != file.materials.len() {
            return self
                .diags
                .push(bad_mesh(span, name, "its materials could not be read"));
        }
        let base = self.scene.prims.len() as u32;
        let shift = |id: PrimId| PrimId(id.0 + base);
        let mut materials = Vec::with_capacity(scene.prims.len());
        for mut p in scene.prims {
            if let ModRef::Prim(m) = p.modifier {
                p.modifier = ModRef::Prim(shift(m));
            }
            for r in &mut p.refs {
                *r = shift(*r);
            }
            if let PrimKind::Alias { target } = &mut p.kind {
                *target = shift(*target);
            }
            p.frame = Some(mesh);
            // Errors point at the mesh's file name: the text they were found in is ours.
            p.span = span;
            p.name_span = span;
            p.modifier_span = span;
            materials.push(PrimId(self.scene.prims.len() as u32));
            self.push(p, false);
        }
        for (k, f) in scene.functions.0 {
            self.scene.functions.0.entry(k).or_insert(f);
        }
        for (k, f) in scene.data.files {
            self.scene.data.files.entry(k).or_insert(f);
        }
        for (k, f) in scene.data.pictures {
            self.scene.data.pictures.entry(k).or_insert(f);
        }
        if let Some(p) = self.scene.prims.get_mut(mesh.0 as usize) {
            p.refs.extend(materials.iter().copied());
            if let PrimKind::Mesh { materials: m, .. } = &mut p.kind {
                *m = materials;
            }
        }
    }
}

fn bad_mesh(span: Span, name: &str, why: &str) -> Diagnostic {
    Diagnostic::new(
        codes::E0310,
        span,
        format!("mesh file '{name}' cannot be read: {why}"),
    )
    .with_hint("mesh files are made by obj2mesh ('radc obj2mesh' or Radiance's)")
}
