//! Which modifier each name in a file refers to, from the syntax tree alone: the
//! language server's go-to-definition, references, hover and completion read this.
//!
//! Radiance binds a modifier name to the most recent earlier definition
//! (`modobject.c` looks names up as it reads), so a later redefinition does not relink
//! earlier uses. This works on any syntax tree, including ones with unknown types and
//! errors, which is what an editor has while someone types.

use std::borrow::Cow;
use std::collections::HashMap;

use super::reparse::{Change, shift};
use super::syntax::{Item, SceneFile, Word};
use crate::schema::{self, Category, StringKind};
use crate::source::Span;

/// A named primitive or alias.
#[derive(Clone, Debug, PartialEq)]
pub struct Definition {
    pub name: String,
    /// The name word.
    pub name_span: Span,
    /// The whole statement.
    pub span: Span,
    /// The type keyword as written (`alias` for aliases); a known type's name is the
    /// schema's, not a copy (the scope of a big scene is rebuilt after each edit).
    pub type_name: Cow<'static, str>,
    /// Whether later primitives may use it as a modifier (surfaces cannot; unknown
    /// types are given the benefit of the doubt).
    pub is_modifier: bool,
}

/// A word naming a modifier, resolved to a definition index when one precedes it.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    pub name: String,
    pub span: Span,
    pub target: Option<usize>,
}

/// Every definition and modifier reference in one file, in source order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ModifierScope {
    pub definitions: Vec<Definition>,
    pub references: Vec<Reference>,
}

impl ModifierScope {
    pub fn new(file: &SceneFile) -> Self {
        Self::of(&file.items)
    }

    fn of(items: &[Item]) -> Self {
        let mut scope = ModifierScope {
            definitions: Vec::with_capacity(items.len()),
            references: Vec::with_capacity(items.len()),
        };
        let mut bound: HashMap<&str, usize> = HashMap::new();
        for item in items {
            match item {
                Item::Primitive(p) => {
                    scope.reference(&p.modifier, &bound);
                    let ty = schema::lookup(&p.kind.text);
                    if let Some(ty) = ty {
                        for (i, w) in p.strings.items.iter().enumerate() {
                            let kind = ty.strings.arg_at(i).map(|(a, _)| a.kind);
                            if kind == Some(StringKind::Modifier) {
                                scope.reference(w, &bound);
                            }
                        }
                    }
                    let is_modifier = ty.is_none_or(|t| t.category != Category::Surface);
                    let type_name = match ty {
                        Some(t) => Cow::Borrowed(t.name),
                        None => Cow::Owned(p.kind.text.clone()),
                    };
                    scope.define(&p.name, p.span, type_name, is_modifier, &mut bound);
                }
                Item::Alias(a) => {
                    scope.reference(&a.modifier, &bound);
                    scope.reference(&a.target, &bound);
                    scope.define(&a.name, a.span, Cow::Borrowed("alias"), true, &mut bound);
                }
                Item::Command(_) | Item::Comment(_) | Item::Error(_) => {}
            }
        }
        scope
    }

    fn reference(&mut self, word: &Word, bound: &HashMap<&str, usize>) {
        if matches!(word.text.as_str(), "void" | "inherit") {
            return;
        }
        self.references.push(Reference {
            name: word.text.clone(),
            span: word.span,
            target: bound.get(word.text.as_str()).copied(),
        });
    }

    fn define<'a>(
        &mut self,
        name: &'a Word,
        span: Span,
        type_name: Cow<'static, str>,
        is_modifier: bool,
        bound: &mut HashMap<&'a str, usize>,
    ) {
        let index = self.definitions.len();
        self.definitions.push(Definition {
            name: name.text.clone(),
            name_span: name.span,
            span,
            type_name,
            is_modifier,
        });
        if is_modifier {
            bound.insert(&name.text, index);
        }
    }

    /// Brings the scope up to date after an edit of the file (now `file`) that
    /// replaced some statements (`change`), when the new statements define and refer
    /// to the same names in the same order as the old ones (editing a number, say):
    /// then only spans move. Returns `false` (the scope is left as it was) when
    /// names changed, and it must be built again. The result is exactly
    /// `ModifierScope::new(file)` (tested with the random edits in `db`).
    pub fn edited(&mut self, file: &SceneFile, change: &Change) -> bool {
        let Some(window) = file.items.get(change.items.clone()) else {
            return false;
        };
        let new = ModifierScope::of(window);
        let replaced = |s: &Span| s.start >= change.old_start && s.start <= change.old_end;
        let d0 = self
            .definitions
            .partition_point(|d| d.span.start < change.old_start);
        let d1 = d0 + self.definitions[d0..].partition_point(|d| replaced(&d.span));
        let r0 = self
            .references
            .partition_point(|r| r.span.start < change.old_start);
        let r1 = r0 + self.references[r0..].partition_point(|r| replaced(&r.span));
        let (old_defs, old_refs) = (&self.definitions[d0..d1], &self.references[r0..r1]);
        if old_defs.len() != new.definitions.len() || old_refs.len() != new.references.len() {
            return false;
        }
        let same_defs = old_defs.iter().zip(&new.definitions).all(|(a, b)| {
            a.name == b.name && a.type_name == b.type_name && a.is_modifier == b.is_modifier
        });
        // Each reference is inside the statement of one definition: which one, and
        // its name, decide what it binds to.
        let owner = |defs: &[Definition], r: &Reference| {
            defs.partition_point(|d| d.span.start <= r.span.start)
        };
        let same_refs = old_refs
            .iter()
            .zip(&new.references)
            .all(|(a, b)| a.name == b.name && owner(old_defs, a) == owner(&new.definitions, b));
        if !same_defs || !same_refs {
            return false;
        }
        for (old, new) in self.definitions[d0..d1].iter_mut().zip(&new.definitions) {
            old.name_span = new.name_span;
            old.span = new.span;
        }
        for (old, new) in self.references[r0..r1].iter_mut().zip(&new.references) {
            old.span = new.span;
        }
        if change.delta != 0 {
            for d in &mut self.definitions[d1..] {
                shift(&mut d.name_span, change.delta);
                shift(&mut d.span, change.delta);
            }
            for r in &mut self.references[r1..] {
                shift(&mut r.span, change.delta);
            }
        }
        true
    }

    /// The definition named or referred to by the word at byte `offset`.
    pub fn definition_at(&self, offset: usize) -> Option<&Definition> {
        self.symbol_at(offset).map(|(_, d)| d)
    }

    /// The word at byte `offset` (its span) when it names or refers to a definition.
    pub fn symbol_at(&self, offset: usize) -> Option<(Span, &Definition)> {
        let hit = |s: &Span| s.start as usize <= offset && offset <= s.end as usize;
        if let Some(d) = self.definitions.iter().find(|d| hit(&d.name_span)) {
            return Some((d.name_span, d));
        }
        let r = self.references.iter().find(|r| hit(&r.span))?;
        Some((r.span, self.definitions.get(r.target?)?))
    }

    /// The modifier reference at byte `offset`, resolved or not.
    pub fn reference_at(&self, offset: usize) -> Option<&Reference> {
        let hit = |s: &Span| s.start as usize <= offset && offset <= s.end as usize;
        self.references.iter().find(|r| hit(&r.span))
    }

    /// The last modifier definition called `name` (what a later file sees).
    pub fn last_modifier(&self, name: &str) -> Option<&Definition> {
        self.definitions
            .iter()
            .rev()
            .find(|d| d.is_modifier && d.name == name)
    }

    /// The spans of every word naming `def` (its own name first), for references
    /// and highlighting.
    pub fn uses_of(&self, def: &Definition) -> Vec<Span> {
        let index = self.definitions.iter().position(|d| d == def);
        let mut spans = vec![def.name_span];
        spans.extend(
            self.references
                .iter()
                .filter(|r| r.target.is_some() && r.target == index)
                .map(|r| r.span),
        );
        spans
    }

    /// The modifiers a primitive starting at `offset` could use: the most recent
    /// definition of each name that ends before `offset`, in source order.
    pub fn visible_at(&self, offset: usize) -> Vec<&Definition> {
        let mut latest: HashMap<&str, usize> = HashMap::new();
        for (i, d) in self.definitions.iter().enumerate() {
            if d.is_modifier && (d.span.end as usize) <= offset {
                latest.insert(&d.name, i);
            }
        }
        let mut visible: Vec<usize> = latest.into_values().collect();
        visible.sort_unstable();
        visible
            .iter()
            .filter_map(|&i| self.definitions.get(i))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;

    const TEXT: &str = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\n\
                        red sphere ball\n0\n0\n4 0 0 0 1\n\
                        void plastic red\n0\n0\n5 .1 .1 .5 0 0\n\
                        red alias paint red\n\
                        paint sphere ball2\n0\n0\n4 0 0 3 1\n";

    fn scope() -> ModifierScope {
        ModifierScope::new(&crate::scene::parse(FileId(0), TEXT).0)
    }

    #[test]
    fn uses_bind_to_the_most_recent_earlier_definition() {
        let s = scope();
        let first_use = TEXT.find("red sphere").unwrap_or_default();
        let def = s.definition_at(first_use).map(|d| d.span.start);
        assert_eq!(def, Some(0));
        let alias_target = TEXT.rfind("red\npaint").unwrap_or_default();
        let second = TEXT.rfind("void plastic red").unwrap_or_default();
        assert_eq!(
            s.definition_at(alias_target).map(|d| d.span.start as usize),
            Some(second)
        );
    }

    #[test]
    fn uses_and_visibility() {
        let s = scope();
        let second = &s.definitions[2];
        // name, the alias's modifier and the alias's target.
        assert_eq!(s.uses_of(second).len(), 3);
        let names: Vec<&str> = s
            .visible_at(TEXT.len())
            .iter()
            .map(|d| d.name.as_str())
            .collect();
        assert_eq!(names, ["red", "paint"]);
        assert!(s.visible_at(0).is_empty());
    }
}
