//! The dependency graph: which definitions an entry point needs. A scene's `*func`
//! primitive names a few functions of a `.cal` file; only what they reach must be
//! compiled (and checked for that primitive).

use super::ir::{DefId, Expr, SymId};
use super::resolve::Module;
use std::collections::BTreeSet;

/// The definitions in force that `entries` reach, following variables, calls and
/// functions passed by name. Definitions that were replaced are never included:
/// evaluation only sees the latest (caldefn.c `dlookup` returns the top).
pub fn needed(module: &Module, entries: &[SymId]) -> BTreeSet<DefId> {
    let mut seen_syms = BTreeSet::new();
    let mut out = BTreeSet::new();
    let mut work: Vec<SymId> = entries.to_vec();
    while let Some(s) = work.pop() {
        if !seen_syms.insert(s) {
            continue;
        }
        if let Some(id) = module.current_def(s) {
            out.insert(id);
            push_refs(&module.def(id).body, &mut work);
        }
    }
    out
}

/// `needed` for the symbols an expression names (an output column, a `cond`).
pub fn needed_by_expr(module: &Module, e: &Expr) -> BTreeSet<DefId> {
    let mut syms = Vec::new();
    push_refs(e, &mut syms);
    needed(module, &syms)
}

/// Entry points by name as written; names that do not resolve are ignored.
pub fn needed_by_names(module: &Module, names: &[&str]) -> BTreeSet<DefId> {
    let syms: Vec<SymId> = names.iter().filter_map(|n| module.lookup(n)).collect();
    needed(module, &syms)
}

fn push_refs(e: &Expr, out: &mut Vec<SymId>) {
    let mut refs = Vec::new();
    e.symbols(&mut refs);
    out.extend(refs.into_iter().map(|(s, _)| s));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cal::resolve::Env;
    use crate::source::FileId;

    #[test]
    fn exactly_what_the_entries_reach() {
        let mut m = Module::new(&Env::bare());
        m.add_source(
            FileId(0),
            "a = b + f(c); b = 2*c; c = $1; f(x) = g(x); g(x) = x; unused = a; \
             h(p, x) = p(x); k = h(g, 1);",
        );
        let names = |set: BTreeSet<DefId>| {
            let mut v: Vec<String> = set
                .into_iter()
                .map(|d| m.def(d).name.name.clone())
                .collect();
            v.sort();
            v
        };
        assert_eq!(
            names(needed_by_names(&m, &["a"])),
            ["a", "b", "c", "f", "g"]
        );
        assert_eq!(names(needed_by_names(&m, &["k"])), ["g", "h", "k"]);
        assert_eq!(
            names(needed_by_names(&m, &["nosuch"])),
            Vec::<String>::new()
        );
    }

    #[test]
    fn function_files_have_their_own_context() {
        let mut m = Module::new(&Env::renderer());
        let d = m.load_function_file(
            FileId(1),
            "wood.cal",
            "grain = sq(Px) + k; k : 2; unused = 3",
        );
        assert!(d.is_empty(), "{d:?}");
        // The primitive's expression sees the file's names, then the global ones.
        let e = m
            .add_expression(FileId(2), "grain * PI")
            .unwrap_or_else(|_| Expr::num(0.0, Default::default()));
        let names: Vec<String> = needed_by_expr(&m, &e)
            .into_iter()
            .map(|d| m.symbol(m.def(d).sym).name.clone())
            .collect();
        // rayinit.cal's `sq` is a real definition (folded `PI` needs none).
        assert_eq!(names, ["Px", "sq", "grain`wood", "k`wood"]);
        m.set_context("");
        assert!(m.lookup("grain").is_none());
        assert!(m.lookup("grain`wood`").is_some());
    }

    #[test]
    fn replaced_definitions_are_not_needed() {
        let mut m = Module::new(&Env::bare());
        m.add_source(FileId(0), "a = old; a = new; old = 1; new = 2");
        let got: Vec<&str> = needed_by_names(&m, &["a"])
            .into_iter()
            .map(|d| m.def(d).name.name.as_str())
            .collect();
        assert_eq!(got, ["a", "new"]);
    }
}
