//! Modifier names: which definition each use binds to (the most recent earlier
//! one, as `modobject.c` looks them up), aliases, redefinitions, and the
//! definitions nothing uses. Name errors are explained from what the name is
//! instead (a surface, a reserved word), so surface names are remembered here too.

use std::collections::HashMap;

use super::Lowering;
use crate::diagnostic::{self as codes, Diagnostic, suggest};
use crate::scene::ir::{ModRef, Prim, PrimId, PrimKind};
use crate::scene::syntax::{Alias, Primitive, Word};
use crate::schema::{self, Category, PrimitiveType, StringKind};
use crate::source::Span;
use crate::transform::Transform;

/// Surface names and where they were defined, only ever read to explain an error.
/// They are stored packed, and indexed on the first error that needs them.
#[derive(Default)]
pub(super) struct SurfaceNames {
    packed: String,
    /// End of each name in `packed`, and its span.
    ends: Vec<(usize, Span)>,
    index: Option<HashMap<String, Span>>,
}

impl SurfaceNames {
    pub(super) fn insert(&mut self, name: &str, span: Span) {
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
    pub(super) fn get(&mut self, name: &str) -> Option<Span> {
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

impl Lowering<'_> {
    /// Records a new primitive and, for modifiers, binds its name.
    pub(super) fn define(&mut self, prim: Prim, name: &Word, warn_unused: bool) {
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

    pub(super) fn resolve_modifier(&mut self, word: &Word, schema: &PrimitiveType) -> ModRef {
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

    pub(super) fn alias(&mut self, a: &Alias, warn_unused: bool) {
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
            frame: None,
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

    pub(super) fn string_modifier_refs(
        &mut self,
        p: &Primitive,
        schema: &PrimitiveType,
    ) -> Vec<PrimId> {
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

    pub(super) fn report_unused(&mut self) {
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
}

#[cfg(test)]
mod tests {
    use crate::scene::ir::{ModRef, PrimKind};
    use crate::scene::lower::tests::{PAINT, check};

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
    fn unused_modifiers_are_warned_and_reachability_skips_them() {
        let text =
            format!("{PAINT}void plastic spare 0 0 5 .5 .5 .5 0 0\npaint sphere s 0 0 4 0 0 0 1\n");
        let (scene, codes) = check(&text);
        assert_eq!(codes, vec!["W0301"]);
        assert_eq!(scene.reachable(), vec![true, false, true]);
    }
}
