//! Auxiliary files a primitive names: whether they exist (asked of the caller
//! through [`FileLookup`], since `lang` never touches the file system), whether
//! data files and pictures are what they claim to be, whether the functions named
//! from a function file are defined there, and which of these files a render keeps.
//! A missing file is reported once per name, however many primitives name it.

use std::collections::HashSet;

use super::{Keep, Lowering};
use crate::diagnostic::{self as codes, Diagnostic};
use crate::scene::functions::{self, FunctionFile};
use crate::scene::ir::{PrimId, PrimKind};
use crate::scene::syntax::Primitive;
use crate::schema::{FileKind, PrimitiveType, StringKind};
use crate::source::FileId;

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

impl Lowering<'_> {
    /// Moves the data files and pictures that reachable primitives name into the
    /// scene (p_data.c loads a file when a ray first meets its pattern: unreachable
    /// ones cost nothing).
    pub(super) fn keep_aux_data(&mut self) {
        if self.data_files.is_empty() && self.picture_files.is_empty() {
            return;
        }
        let reachable = self.scene.reachable();
        let mut named: HashSet<&str> = HashSet::new();
        for (p, _) in self.scene.prims.iter().zip(&reachable).filter(|(_, r)| **r) {
            if let PrimKind::Other { strings, .. } = &p.kind {
                named.extend(strings.iter().map(String::as_str));
            }
        }
        for (name, file) in &self.data_files {
            if let Some(file) = file.as_ref().filter(|_| named.contains(name.as_str())) {
                self.scene.data.files.insert(name.clone(), file.clone());
            }
        }
        if self.keep != Keep::Everything {
            return;
        }
        for (name, &from) in &self.picture_files {
            if named.contains(name.as_str())
                && let Some(bytes) =
                    self.files
                        .read_head(name, FileKind::Picture, from, MAX_PICTURE_BYTES)
            {
                self.scene
                    .data
                    .pictures
                    .insert(name.clone(), std::sync::Arc::new(bytes));
            }
        }
    }

    /// A data file by name, parsed once.
    fn data_file(
        &mut self,
        name: &str,
        from: FileId,
    ) -> Option<std::sync::Arc<crate::datafile::DataFile>> {
        if let Some(known) = self.data_files.get(name) {
            return known.clone();
        }
        let parsed = self
            .files
            .read(name, FileKind::Data, from)
            .and_then(|t| crate::datafile::DataFile::parse(&t).ok())
            .map(std::sync::Arc::new);
        self.data_files.insert(name.to_string(), parsed.clone());
        parsed
    }

    pub(super) fn check_files(&mut self, p: &Primitive, schema: &PrimitiveType) {
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
                && !matches!(self.data_files.get(&w.text), Some(Some(_)))
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
            if kind == FileKind::Mesh {
                self.check_mesh_file(w);
            }
            if kind == FileKind::Picture {
                self.picture_files
                    .entry(w.text.clone())
                    .or_insert(w.span.file);
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

    /// The functions and variables a primitive names must exist in its function file
    /// (or rayinit.cal, or the renderer), and what they reach when evaluated must be
    /// defined too; the file itself must parse. Radiance finds these only when a ray
    /// first evaluates the primitive.
    pub(super) fn check_functions(&mut self, p: &Primitive, schema: &PrimitiveType) {
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
    pub(super) fn check_data_coordinates(&mut self, p: &Primitive, schema: &PrimitiveType) {
        let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
        let mut cal_at = None;
        let mut dims = None;
        let mut data_word = None;
        for (i, w) in p.strings.items.iter().enumerate() {
            match schema.strings.arg_in(i, &words).map(|(a, _)| a.kind) {
                Some(StringKind::File(FileKind::Cal)) if cal_at.is_none() => cal_at = Some(i),
                Some(StringKind::File(FileKind::Data)) => {
                    if let Some(d) = self.data_file(&w.text, w.span.file) {
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
}

/// The largest picture read for a render (a 4096x4096 flat RGBE picture is 64 MiB).
const MAX_PICTURE_BYTES: usize = 256 << 20;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::check_text;
    use crate::scene::ir::Scene;

    /// Files by name; any other name is missing.
    struct Files(&'static [(&'static str, &'static str)]);

    impl FileLookup for Files {
        fn exists(&self, name: &str, _: FileKind, _: FileId) -> bool {
            self.0.iter().any(|(n, _)| *n == name)
        }

        fn read(&self, name: &str, _: FileKind, _: FileId) -> Option<String> {
            let (_, text) = self.0.iter().find(|(n, _)| *n == name)?;
            Some(text.to_string())
        }

        fn read_head(
            &self,
            name: &str,
            kind: FileKind,
            from: FileId,
            max: usize,
        ) -> Option<Vec<u8>> {
            let text = self.read(name, kind, from)?;
            Some(text.as_bytes().iter().take(max).copied().collect())
        }
    }

    const FILES: Files = Files(&[
        ("picture.cal", ""),
        ("sky.hdr", "#?RADIANCE\n"),
        ("photo.jpg", "\u{ff}\u{d8}"),
        ("flat.dat", "2\n0 1 2\n0 1 2\n1 2 3 4\n"),
        ("broken.dat", "x\n"),
    ]);

    fn check(text: &str) -> (Scene, Vec<&'static str>) {
        let (scene, diags) = check_text(FileId(0), text, &FILES, true);
        (scene, diags.iter().map(|d| d.code.id).collect())
    }

    fn picture(name: &str, file: &str) -> String {
        format!(
            "void colorpict {name} 7 red green blue {file} picture.cal pic_u pic_v 0 0\n\
             {name} plastic {name}m 0 0 5 .5 .5 .5 0 0\n{name}m sphere {name}s 0 0 4 0 0 0 1\n"
        )
    }

    #[test]
    fn a_missing_file_is_reported_once_per_name() {
        let text = picture("a", "missing.hdr") + &picture("b", "missing.hdr");
        assert_eq!(check(&text).1, vec!["E0305"]);
        assert!(check(&picture("a", "sky.hdr")).1.is_empty());
    }

    #[test]
    fn files_must_be_what_they_claim_to_be() {
        assert_eq!(check(&picture("a", "photo.jpg")).1, vec!["E0309"]);
        let data = |file: &str, coords: &str| {
            let count = 3 + coords.split_whitespace().count();
            format!(
                "void brightdata d {count} noop {file} . {coords} 0 0\n\
                 d plastic m 0 0 5 .5 .5 .5 0 0\nm sphere s 0 0 4 0 0 0 1\n"
            )
        };
        assert_eq!(check(&data("broken.dat", "Px Py")).1, vec!["E0308"]);
        assert!(check(&data("flat.dat", "Px Py")).1.is_empty());
        assert_eq!(check(&data("flat.dat", "Px")).1, vec!["E0202"]);
    }
}
