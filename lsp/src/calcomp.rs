//! Where scenes and calcomp files meet: the calcomp names a scene primitive gives in
//! its function arguments (`brightfunc`'s `refl`, `texfunc`'s expressions), the
//! function files it loads, and the files' indexes, whether open in the editor (the
//! database's) or only on disk (read and indexed here, for one request).

use std::path::{Path, PathBuf};

use radc_lang::db::{self, CalIndex, Db};
use radc_lang::scene::syntax::{Item, Primitive};
use radc_lang::schema::{self, FileKind, StringKind};
use radc_lang::{FileId, LineIndex, Span};
use tower_lsp_server::ls_types::{Location, Position, Range, Uri};

use crate::document::{Document, Kind};
use crate::rif;

/// A calcomp file as one request sees it.
pub struct CalFile {
    pub uri: Uri,
    pub path: PathBuf,
    pub text: String,
    pub index: CalIndex,
    lines: LineIndex,
}

impl CalFile {
    pub fn range(&self, span: Span) -> Range {
        let at = |offset: u32| {
            let (line, character) = self.lines.line_utf16(&self.text, offset as usize);
            Position { line, character }
        };
        Range {
            start: at(span.start),
            end: at(span.end),
        }
    }

    pub fn location(&self, span: Span) -> Location {
        Location {
            uri: self.uri.clone(),
            range: self.range(span),
        }
    }
}

/// The calcomp file at canonical `path`: the open document's text if it is open,
/// else the disk's.
pub fn load(doc: &Document<'_>, path: &Path) -> Option<CalFile> {
    let open = doc
        .workspace
        .iter()
        .find(|o| o.kind == Kind::Cal && Path::new(o.file.path(doc.db)) == path);
    if let Some(o) = open {
        return Some(CalFile {
            uri: o.uri.clone(),
            path: path.to_path_buf(),
            text: o.file.text(doc.db).clone(),
            index: db::cal_index(doc.db, o.file).clone(),
            lines: db::line_index(doc.db, o.file).clone(),
        });
    }
    let bytes = std::fs::read(path).ok()?;
    let (text, _) = radc_lang::source::decode(FileId(0), &bytes);
    let (program, _) = radc_lang::cal::parse(FileId(0), &text);
    Some(CalFile {
        uri: Uri::from_file_path(path)?,
        path: path.to_path_buf(),
        index: CalIndex::new(&program),
        lines: LineIndex::new(&text),
        text,
    })
}

/// This calcomp document as a [`CalFile`].
pub fn this_file(doc: &Document<'_>) -> CalFile {
    CalFile {
        uri: doc.uri.clone(),
        path: PathBuf::from(doc.file.path(doc.db)),
        text: doc.text().to_string(),
        index: db::cal_index(doc.db, doc.file).clone(),
        lines: doc.lines().clone(),
    }
}

/// The function files a primitive loads, in order, found as the checks find them
/// (canonical paths; `.` and files not found are left out).
pub fn function_files(db: &dyn Db, scene_path: &Path, p: &Primitive) -> Vec<PathBuf> {
    let Some(ty) = schema::lookup(&p.kind.text) else {
        return Vec::new();
    };
    let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
    (0..words.len())
        .filter(|&i| {
            let kind = ty.strings.arg_in(i, &words).map(|(a, _)| a.kind);
            kind == Some(StringKind::File(FileKind::Cal)) && words[i] != "."
        })
        .filter_map(|i| db.aux_files().locate(words[i], FileKind::Cal, scene_path))
        .map(|f| rif::canonical(&f))
        .collect()
}

/// The calcomp names in a primitive's function arguments, with their spans.
pub fn names_in(text: &str, p: &Primitive) -> Vec<(Span, String)> {
    let Some(ty) = schema::lookup(&p.kind.text) else {
        return Vec::new();
    };
    let words: Vec<&str> = p.strings.items.iter().map(|w| w.text.as_str()).collect();
    let mut out = Vec::new();
    for (i, w) in p.strings.items.iter().enumerate() {
        let kind = ty.strings.arg_in(i, &words).map(|(a, _)| a.kind);
        if !matches!(kind, Some(StringKind::Function | StringKind::FunctionName)) {
            continue;
        }
        let source = text.get(w.span.range()).unwrap_or("");
        for (start, end) in identifiers(source) {
            let span = Span {
                file: w.span.file,
                start: w.span.start + start as u32,
                end: w.span.start + end as u32,
            };
            out.push((span, source[start..end].to_string()));
        }
    }
    out
}

/// The calcomp names in `source` (calexpr.c: a letter or back-quote, then letters,
/// digits, `_`, `.` and back-quotes), as byte ranges.
fn identifiers(source: &str) -> Vec<(usize, usize)> {
    let is_id = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '`');
    let mut out = Vec::new();
    let mut chars = source.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c.is_ascii_digit() || c == '.' {
            // A number (with its exponent) or a stray dot: skip the whole run.
            while let Some(&(_, d)) = chars.peek() {
                if !(is_id(d) || ((d == '+' || d == '-') && source[..i].ends_with(['e', 'E']))) {
                    break;
                }
                chars.next();
            }
            continue;
        }
        if c.is_ascii_alphabetic() || c == '`' {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek() {
                if !is_id(d) {
                    break;
                }
                end = j + d.len_utf8();
                chars.next();
            }
            out.push((i, end));
        }
    }
    out
}

/// The calcomp name under `offset` in a scene document, and the function files of
/// its primitive.
pub fn scene_name_at(doc: &Document<'_>, offset: usize) -> Option<(Span, String, Vec<PathBuf>)> {
    let (p, _, _) = doc.locate(offset)?;
    let (span, name) = names_in(doc.text(), p)
        .into_iter()
        .find(|(s, _)| s.start as usize <= offset && offset <= s.end as usize)?;
    let files = function_files(doc.db, Path::new(doc.file.path(doc.db)), p);
    Some((span, name, files))
}

/// The file that defines `name`, among a primitive's function files: the last one
/// loaded that defines it (a later definition replaces an earlier one).
pub fn defining_file(doc: &Document<'_>, files: &[PathBuf], name: &str) -> Option<CalFile> {
    files
        .iter()
        .rev()
        .filter_map(|path| load(doc, path))
        .find(|f| f.index.definition(name).is_some())
}

/// Every use of `name` from the workspace's scenes whose primitives load the
/// function file at `cal_path`.
pub fn scene_uses(doc: &Document<'_>, cal_path: &Path, name: &str) -> Vec<Location> {
    let mut out = Vec::new();
    for o in doc.workspace.iter().filter(|o| o.kind == Kind::Scene) {
        let text = o.file.text(doc.db);
        if !text.contains(name) {
            continue;
        }
        let scene_path = PathBuf::from(o.file.path(doc.db));
        let lines = db::line_index(doc.db, o.file);
        let at = |offset: u32| {
            let (line, character) = lines.line_utf16(text, offset as usize);
            Position { line, character }
        };
        for item in &db::parse_scene(doc.db, o.file).syntax.items {
            let Item::Primitive(p) = item else {
                continue;
            };
            let uses: Vec<Span> = names_in(text, p)
                .into_iter()
                .filter(|(_, n)| n == name)
                .map(|(s, _)| s)
                .collect();
            if uses.is_empty()
                || !function_files(doc.db, &scene_path, p)
                    .iter()
                    .any(|f| f == cal_path)
            {
                continue;
            }
            out.extend(uses.into_iter().map(|s| Location {
                uri: o.uri.clone(),
                range: Range {
                    start: at(s.start),
                    end: at(s.end),
                },
            }));
        }
    }
    out
}

/// Whether `name` can be a calcomp name (what rename accepts).
pub fn is_name(name: &str) -> bool {
    identifiers(name) == [(0, name.len())] && !name.starts_with('`')
}

/// A name every calcomp file sees without defining it.
pub struct LibraryName {
    pub name: &'static str,
    /// Parameters, for a function (the least it takes).
    pub arity: Option<usize>,
    /// One line: what it is and where it comes from.
    pub doc: String,
}

/// calcomp's library (calfunc.c), rcalc's `in`, the renderer's functions and ray
/// variables (func.c) and rayinit.cal's definitions, with their documentation.
pub fn library() -> Vec<LibraryName> {
    use radc_lang::cal::builtins::{
        Builtin, RAYINIT_NAMES, RENDERER_FUNCTIONS, RENDERER_VARIABLES,
    };
    let mut out: Vec<LibraryName> = Builtin::ALL
        .iter()
        .map(|b| LibraryName {
            name: b.name(),
            arity: Some(b.min_args()),
            doc: format!("{} (calcomp library)", b.doc()),
        })
        .collect();
    out.push(LibraryName {
        name: "in",
        arity: Some(1),
        doc: "in(n): rcalc's input column n; in(0) is the number of columns (rcalc)".into(),
    });
    out.extend(RENDERER_FUNCTIONS.iter().map(|f| LibraryName {
        name: f.name,
        arity: Some(f.arity),
        doc: format!("{} (renderer)", f.doc),
    }));
    out.extend(RENDERER_VARIABLES.iter().map(|v| LibraryName {
        name: v,
        arity: None,
        doc: format!("{v}: {} (renderer, per ray)", ray_variable(v)),
    }));
    out.extend(
        RAYINIT_NAMES
            .iter()
            .map(|(name, arity, constant)| LibraryName {
                name,
                arity: *arity,
                doc: match arity {
                    Some(n) => format!(
                        "{name}: a function of {n} argument{} defined in rayinit.cal{} (renderer)",
                        if *n == 1 { "" } else { "s" },
                        if *constant { ", constant" } else { "" }
                    ),
                    None => format!(
                        "{name}: a {} defined in rayinit.cal (renderer)",
                        if *constant { "constant" } else { "variable" }
                    ),
                },
            }),
    );
    out
}

/// What the renderer's per-ray variables hold (rayinit.cal's header, func.c).
fn ray_variable(name: &str) -> &'static str {
    match name {
        "Dx" | "Dy" | "Dz" => "ray direction",
        "Nx" | "Ny" | "Nz" => "surface normal",
        "Px" | "Py" | "Pz" => "intersection point",
        "T" => "distance from the ray's start",
        "Ts" => "distance from the eye (single ray)",
        "Rdot" => "cosine between the ray and the normal",
        "S" => "world scale of the primitive's transform",
        "Tx" | "Ty" | "Tz" => "world origin of the primitive's transform",
        "Ix" | "Iy" | "Iz" => "world i unit vector",
        "Jx" | "Jy" | "Jz" => "world j unit vector",
        "Kx" | "Ky" | "Kz" => "world k unit vector",
        "Lu" | "Lv" => "local (u, v) coordinates of the hit",
        "NxP" | "NyP" | "NzP" => "perturbed surface normal (BRDF functions)",
        "RdotP" => "perturbed dot product (BRDF functions)",
        "CrP" | "CgP" | "CbP" => "perturbed material colour (BRDF functions)",
        "DxA" | "DyA" | "DzA" => "direction to the light source (BRDF functions)",
        _ => "set by the renderer",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_names_but_not_numbers() {
        let src = "\"1.5e-3*refl(Dx) + a.b`c\"";
        let names: Vec<&str> = identifiers(src).iter().map(|&(s, e)| &src[s..e]).collect();
        assert_eq!(names, ["refl", "Dx", "a.b`c"]);
        assert!(is_name("x_1.y"));
        assert!(!is_name("1x"));
        assert!(!is_name("a b"));
    }
}
