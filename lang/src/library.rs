//! Radiance's function files that radc's own generators write into their output and
//! that the renderer loads first, built in so that a user with no Radiance installed
//! can check and render a `gensky`, `gendaylit`, `genrev -s` or `gensurf -s` scene.
//!
//! The texts are radc's own, written from the published formulas (the Radiance
//! reference manual, the CIE and Perez sky papers, what each generator passes); they
//! agree with Radiance's files of the same names value for value (see
//! `tests/library_differential.rs`). As in Radiance, a file of the same name found on
//! the search path (the scene's folder, RAYPATH) wins: the built-in text is used only
//! when none is found, so lookups ask the file system first and [`builtin`] last.

use crate::source::FileId;

/// The built-in files, by the name a scene or generator gives.
pub static FILES: &[(&str, &str)] = &[
    ("rayinit.cal", include_str!("library/rayinit.cal")),
    ("skybright.cal", include_str!("library/skybright.cal")),
    ("perezlum.cal", include_str!("library/perezlum.cal")),
    ("surf.cal", include_str!("library/surf.cal")),
    ("rev.cal", include_str!("library/rev.cal")),
    ("tmesh.cal", include_str!("library/tmesh.cal")),
];

/// The file the renderer loads before any scene function file (func.c `initfunc`).
pub const RAYINIT: &str = "rayinit.cal";

/// Where built-in rayinit.cal's definitions live when a renderer environment loads
/// it, so that they are never mistaken for the user's (unused or redefined names,
/// spans shown). The CLI numbers sources up from 0 and the database numbers extra
/// files down from `u32::MAX - 1`; the one id left is the no-file id of a primitive
/// whose function file is `.`, which has no text and so no definitions.
pub const RAYINIT_FILE: FileId = FileId(u32::MAX);

/// The built-in text of a library file, for a name as a scene writes it (`name.cal`,
/// no folder). Names with a folder are the user's own files and never built in.
pub fn builtin(name: &str) -> Option<&'static str> {
    FILES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The names of the built-in files.
pub fn names() -> impl Iterator<Item = &'static str> {
    FILES.iter().map(|(n, _)| *n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cal::builtins::RAYINIT_NAMES;
    use crate::cal::{Env, Host, Module};

    #[test]
    fn every_file_parses_cleanly_in_the_renderer() {
        for (name, text) in FILES {
            let mut m = Module::new(&Env::renderer());
            let diags = m.load_function_file(FileId(0), name, text);
            assert!(diags.is_empty(), "{name}: {diags:?}");
        }
    }

    #[test]
    fn rayinit_defines_exactly_the_listed_names() {
        let mut m = Module::new(&Env {
            host: Host::Bare,
            fold: true,
            complete: false,
        });
        assert!(
            m.add_source(FileId(0), builtin(RAYINIT).unwrap())
                .is_empty()
        );
        let mut defined: Vec<(String, Option<usize>, bool)> = Vec::new();
        for d in m.defs() {
            let name = m.symbol(d.sym).name.clone();
            if name.contains('`') {
                continue;
            }
            let arity = d.params.as_ref().map(Vec::len);
            defined.push((name, arity, d.kind == crate::cal::syntax::DefKind::Constant));
        }
        let listed: Vec<(String, Option<usize>, bool)> = RAYINIT_NAMES
            .iter()
            .map(|(n, a, c)| (n.to_string(), *a, *c))
            .collect();
        defined.sort();
        let mut listed_sorted = listed.clone();
        listed_sorted.sort();
        assert_eq!(defined, listed_sorted);
    }

    /// In a renderer environment rayinit.cal's names are definitions, so a function
    /// file's constants built on them fold as Radiance folds them while loading.
    #[test]
    fn rayinit_names_are_definitions_in_the_renderer() {
        let mut m = Module::new(&Env::renderer());
        let text = "c : frac(2.75) + linterp(.5, 0, 4) + abs(-1) + and(1, -1) + DEGREE*180;";
        assert!(m.load_function_file(FileId(0), "t.cal", text).is_empty());
        let c = m
            .lookup("c")
            .and_then(|s| m.current_def(s))
            .map(|d| m.def(d));
        let value = c.and_then(|d| d.body.as_num().or(d.parse_time_value));
        assert_eq!(value, Some(0.75 + 2.0 + 1.0 - 1.0 + std::f64::consts::PI));
        for name in ["A1", "noise3a", "or", "Idx"] {
            let sym = m.lookup(name).expect(name);
            assert!(!m.symbol(sym).stack.is_empty(), "{name} has a definition");
            assert!(m.host_name(sym).is_none(), "{name} is not a host name");
        }
        assert!(
            !m.known_names().iter().any(|n| n.ends_with("`rayinit")),
            "helpers are never suggested"
        );
    }

    #[test]
    fn only_plain_file_names_are_built_in() {
        assert!(builtin("skybright.cal").is_some());
        assert!(builtin("lib/skybright.cal").is_none());
        assert!(builtin("skybright").is_none());
        assert_eq!(names().count(), FILES.len());
    }
}
