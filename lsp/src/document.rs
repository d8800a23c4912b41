//! One open document as the handlers see it: its text and queries from the database,
//! and the conversions between LSP positions (line, UTF-16 column) and byte offsets.

use radc_lang::db::{self, Database, ParsedScene, SceneSet, SourceFile};
use radc_lang::scene::scope::{Definition, ModifierScope};
use radc_lang::scene::syntax::{Item, Primitive};
use radc_lang::schema::ArgSide;
use radc_lang::{LineIndex, Span};
use tower_lsp_server::ls_types::{Position, Range, Uri};

pub struct Document<'a> {
    pub db: &'a Database,
    pub file: SourceFile,
    pub uri: &'a Uri,
    /// The files read with this one as a scene (from a `.rif`), if any.
    pub scene: Option<SceneSet>,
    pub kind: Kind,
    /// Every open document and scene file read from disk (this one included), for
    /// requests that reach across files.
    pub workspace: Vec<OpenFile>,
}

/// What a document holds, by its extension: `.cal` is calcomp, `.rif` a rad input
/// file, anything else (including untitled documents) a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Scene,
    Cal,
    Rif,
}

impl Kind {
    pub fn of(uri: &Uri) -> Kind {
        let name = uri.as_str().rsplit('/').next().unwrap_or("");
        let ext = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("cal") => Kind::Cal,
            Some("rif") => Kind::Rif,
            _ => Kind::Scene,
        }
    }
}

/// One file of the workspace as the cross-file requests see it.
#[derive(Clone, Debug)]
pub struct OpenFile {
    pub uri: Uri,
    pub file: SourceFile,
    pub kind: Kind,
}

/// A definition and the file it is in.
#[derive(Clone, Copy, Debug)]
pub struct Target<'a> {
    pub file: SourceFile,
    pub def: &'a Definition,
}

/// What a byte offset points at inside a primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Part {
    Type,
    Name,
    Modifier,
    /// An argument count word; `None` for the integer count.
    Count(Option<ArgSide>),
    Arg(ArgSide, usize),
}

impl<'a> Document<'a> {
    pub fn text(&self) -> &'a str {
        self.file.text(self.db)
    }

    pub fn parsed(&self) -> &'a ParsedScene {
        db::parse_scene(self.db, self.file)
    }

    pub fn scope(&self) -> &'a ModifierScope {
        db::modifier_scope(self.db, self.file)
    }

    pub fn lines(&self) -> &'a LineIndex {
        db::line_index(self.db, self.file)
    }

    /// The byte offset of an LSP position, clamped into the text (a position past the
    /// end of a line means its end, as the protocol says).
    pub fn offset(&self, pos: Position) -> usize {
        let text = self.text();
        let lines = self.lines();
        let line = pos.line as usize;
        if line >= lines.line_count() {
            return text.len();
        }
        let start = lines.line_start(line);
        let rest = text.get(start..).unwrap_or("");
        let mut units = 0u32;
        for (i, c) in rest.char_indices() {
            if units >= pos.character || c == '\n' {
                return start + i;
            }
            units += c.len_utf16() as u32;
        }
        text.len()
    }

    pub fn position(&self, offset: usize) -> Position {
        self.position_in(self.file, offset)
    }

    pub fn range(&self, span: Span) -> Range {
        self.range_in(self.file, span)
    }

    /// A position in another file of the database (a file of the same scene).
    pub fn position_in(&self, file: SourceFile, offset: usize) -> Position {
        let lines = db::line_index(self.db, file);
        let (line, character) = lines.line_utf16(file.text(self.db), offset);
        Position { line, character }
    }

    pub fn range_in(&self, file: SourceFile, span: Span) -> Range {
        Range {
            start: self.position_in(file, span.start as usize),
            end: self.position_in(file, span.end as usize),
        }
    }

    /// The URI of a file of this document's scene.
    pub fn uri_of(&self, file: SourceFile) -> Uri {
        if file == self.file {
            return self.uri.clone();
        }
        if let Some(o) = self.workspace.iter().find(|o| o.file == file) {
            return o.uri.clone();
        }
        Uri::from_file_path(file.path(self.db)).unwrap_or_else(|| self.uri.clone())
    }

    /// Whether `id` is one of the files of this document's scene (not text brought in
    /// by a command or a function file).
    pub fn is_scene_file(&self, id: radc_lang::FileId) -> bool {
        match self.scene {
            Some(set) => set.files(self.db).iter().any(|f| f.id(self.db) == id),
            None => self.file.id(self.db) == id,
        }
    }

    /// The files read before this one in its `.rif` scene, in order.
    pub fn earlier_files(&self) -> Vec<SourceFile> {
        let Some(set) = self.scene else {
            return Vec::new();
        };
        set.files(self.db)
            .iter()
            .take_while(|f| **f != self.file)
            .copied()
            .collect()
    }

    /// The definition the word at `offset` names or refers to, and that word's span:
    /// in this file, or else (for a modifier this file does not define before the
    /// use) the last definition in the earlier files of its scene.
    pub fn target_at(&self, offset: usize) -> Option<(Span, Target<'a>)> {
        let scope = self.scope();
        if let Some((span, def)) = scope.symbol_at(offset) {
            let target = Target {
                file: self.file,
                def,
            };
            return Some((span, target));
        }
        let r = scope.reference_at(offset)?;
        Some((r.span, self.earlier_definition(&r.name)?))
    }

    /// The last definition of modifier `name` in the files read before this one.
    pub fn earlier_definition(&self, name: &str) -> Option<Target<'a>> {
        self.earlier_files().into_iter().rev().find_map(|file| {
            let def = db::modifier_scope(self.db, file).last_modifier(name)?;
            Some(Target { file, def })
        })
    }

    /// The whole text, for edits that replace it.
    pub fn full_range(&self) -> Range {
        Range {
            start: Position::new(0, 0),
            end: self.position(self.text().len()),
        }
    }

    /// The primitive whose word touches `offset`, which word it is, and its span.
    pub fn locate(&self, offset: usize) -> Option<(&'a Primitive, Part, Span)> {
        let touches = |s: Span| s.start as usize <= offset && offset <= s.end as usize;
        self.parsed().syntax.items.iter().find_map(|item| {
            let Item::Primitive(p) = item else {
                return None;
            };
            if !touches(p.span) {
                return None;
            }
            let heads = [
                (p.modifier.span, Part::Modifier),
                (p.kind.span, Part::Type),
                (p.name.span, Part::Name),
                (p.strings.count_span, Part::Count(Some(ArgSide::Strings))),
                (p.ints.count_span, Part::Count(None)),
                (p.reals.count_span, Part::Count(Some(ArgSide::Reals))),
            ];
            let strings = p.strings.items.iter().enumerate();
            let strings = strings.map(|(i, w)| (w.span, Part::Arg(ArgSide::Strings, i)));
            let reals = p.reals.items.iter().enumerate();
            let reals = reals.map(|(i, r)| (r.span, Part::Arg(ArgSide::Reals, i)));
            heads
                .into_iter()
                .chain(strings)
                .chain(reals)
                .find(|(s, _)| touches(*s))
                .map(|(s, part)| (p, part, s))
        })
    }
}

/// Builds a one-file database for handler tests.
#[cfg(test)]
pub fn with_document<T>(text: &str, f: impl FnOnce(&Document<'_>) -> T) -> T {
    let mut db = Database::default();
    let file = db.add_file("/scenes/test.rad", text);
    let uri: Uri = "file:///scenes/test.rad".parse().expect("a valid uri");
    f(&Document {
        db: &db,
        file,
        uri: &uri,
        scene: None,
        kind: Kind::Scene,
        workspace: Vec::new(),
    })
}

/// Builds a one-file database holding a calcomp document, for handler tests.
#[cfg(test)]
pub fn with_cal_document<T>(text: &str, f: impl FnOnce(&Document<'_>) -> T) -> T {
    let mut db = Database::default();
    let file = db.add_file("/scenes/test.cal", text);
    let uri: Uri = "file:///scenes/test.cal".parse().expect("a valid uri");
    f(&Document {
        db: &db,
        file,
        uri: &uri,
        scene: None,
        kind: Kind::Cal,
        workspace: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_utf16_units() {
        // '😀' is two UTF-16 units and four bytes.
        with_document("# 😀 x\nvoid", |doc| {
            assert_eq!(doc.offset(Position::new(0, 5)), 7);
            assert_eq!(doc.position(7), Position::new(0, 5));
            // Past the end of a line: its end; past the last line: the end of text.
            assert_eq!(doc.offset(Position::new(0, 99)), 8);
            assert_eq!(doc.offset(Position::new(7, 0)), 13);
            // Inside a surrogate pair: the character's start is never split.
            assert_eq!(doc.offset(Position::new(0, 3)), 6);
        });
    }

    #[test]
    fn locates_words_of_a_primitive() {
        let text = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\n";
        with_document(text, |doc| {
            let part = |offset| doc.locate(offset).map(|(_, part, _)| part);
            assert_eq!(part(0), Some(Part::Modifier));
            assert_eq!(part(6), Some(Part::Type));
            assert_eq!(part(14), Some(Part::Name));
            assert_eq!(part(17), Some(Part::Count(Some(ArgSide::Strings))));
            assert_eq!(part(19), Some(Part::Count(None)));
            assert_eq!(part(24), Some(Part::Arg(ArgSide::Reals, 0)));
        });
    }
}
