//! The checks `radc check` (and the language server) report for calcomp text. Radiance
//! itself stops at the first syntax error and reports undefined names only when it
//! evaluates them, often deep into a render; these checks find them all at once.

use super::builtins::LibFn;
use super::deps;
use super::ir::{Callee, Def, DefId, Expr, Node, SymId};
use super::resolve::{Env, Module};
use super::syntax::DefKind;
use crate::diagnostic::{self, Diagnostic, suggest};
use crate::source::{FileId, Span};
use std::collections::{BTreeSet, HashMap, HashSet};

/// Check one `.cal` text in an environment. Unused definitions are reported only for
/// complete programs (a file with `$N =` outputs); a function file's users are elsewhere
/// (use [`check_with_entries`] when they are known).
pub fn check(file: FileId, text: &str, env: &Env) -> Vec<Diagnostic> {
    check_with_entries(file, text, env, None)
}

/// What `radc check FILE.cal` reports for a file on its own. A file is either for
/// the renderer (ray variables, rayinit.cal's names) or for rcalc and the generators
/// (`$N` outputs, `in(n)`): it is judged as the one it fits, preferring the renderer.
pub fn check_file(file: FileId, text: &str) -> Vec<Diagnostic> {
    let errors = |d: &Vec<Diagnostic>| d.iter().filter(|d| d.is_error()).count();
    let renderer = check(file, text, &Env::renderer());
    if errors(&renderer) == 0 {
        return renderer;
    }
    let rcalc = check(file, text, &Env::rcalc());
    if errors(&rcalc) < errors(&renderer) {
        rcalc
    } else {
        renderer
    }
}

/// [`check`], with the names a scene uses from this file as entry points: the other
/// definitions of the file are reported unused.
pub fn check_with_entries(
    file: FileId,
    text: &str,
    env: &Env,
    entries: Option<&[&str]>,
) -> Vec<Diagnostic> {
    // Folding reports bad constants, but folds away the calls the other checks look
    // at, so those run on an unfolded copy.
    let mut folded = Module::new(env);
    let mut diags = folded.add_source(file, text);
    let mut module = Module::new(&Env {
        fold: false,
        ..env.clone()
    });
    let _same_syntax_errors = module.add_source(file, text);
    let checker = Checker {
        m: &module,
        complete: env.complete,
        file,
        diags: &mut diags,
    };
    checker.run(entries);
    // A call with too few arguments that folding also tripped on is one problem.
    let arity: HashSet<(u32, u32)> = diags
        .iter()
        .filter(|d| d.code == diagnostic::E0602)
        .map(|d| (d.span.start, d.span.end))
        .collect();
    diags.retain(|d| d.code != diagnostic::E0701 || !arity.contains(&(d.span.start, d.span.end)));
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    diags
}

struct Checker<'a> {
    m: &'a Module,
    complete: bool,
    file: FileId,
    diags: &'a mut Vec<Diagnostic>,
}

impl Checker<'_> {
    fn run(mut self, entries: Option<&[&str]>) {
        let mine: Vec<DefId> = (0..self.m.defs().len() as u32)
            .map(DefId)
            .filter(|&d| {
                self.m.def(d).span.file == self.file && self.m.def(d).span != Span::default()
            })
            .collect();
        let mut undefined_reported = HashSet::new();
        for &id in &mine {
            let def = self.m.def(id);
            self.check_expr(&def.body, false, &mut undefined_reported);
            self.check_constant(def);
        }
        for o in self.m.outputs().values() {
            if o.span.file == self.file {
                self.check_top_expr(&o.body, &mut undefined_reported);
            }
        }
        self.check_redefinitions(&mine);
        self.check_unused(&mine, entries);
    }

    fn check_top_expr(&mut self, e: &Expr, reported: &mut HashSet<SymId>) {
        self.check_expr(e, false, reported);
    }

    fn is_defined(&self, s: SymId) -> bool {
        let sym = self.m.symbol(s);
        !sym.stack.is_empty() || sym.lib.is_some() || self.m.host_name(s).is_some()
    }

    fn undefined(
        &mut self,
        s: SymId,
        span: Span,
        as_function: bool,
        reported: &mut HashSet<SymId>,
    ) {
        if !reported.insert(s) {
            return;
        }
        let name = &self.m.symbol(s).name;
        let what = if as_function { "function" } else { "variable" };
        let mut d = if self.complete {
            Diagnostic::new(
                diagnostic::E0601,
                span,
                format!("{what} '{name}' is not defined"),
            )
        } else {
            Diagnostic::new(
                diagnostic::W0606,
                span,
                format!("{what} '{name}' is not defined in this file"),
            )
        };
        let known = self.m.known_names();
        match closest_name(name, &known, |k| self.m.library().any(|l| l.name() == k)) {
            Some(s) => d = d.with_hint(format!("did you mean '{s}'?")),
            None => {
                d = d.with_hint(
                    "define it in this file, or in a file loaded before this one (rcalc -f, a scene's function file list)",
                )
            }
        }
        self.diags.push(d);
    }

    fn check_expr(&mut self, e: &Expr, is_argument: bool, reported: &mut HashSet<SymId>) {
        match &e.node {
            Node::Var(s) => {
                if !self.is_defined(*s) {
                    self.undefined(*s, e.span, false, reported);
                } else if !is_argument && self.is_function_only(*s) {
                    let name = &self.m.symbol(*s).name;
                    self.diags.push(
                        Diagnostic::new(
                            diagnostic::E0603,
                            e.span,
                            format!("'{name}' is a function, used here as a variable"),
                        )
                        .with_hint(format!("call it: '{name}(...)'")),
                    );
                }
            }
            Node::Call { callee, args } => {
                if let Callee::Sym(s) = callee {
                    self.check_call(*s, args, e.span, reported);
                }
                for a in args {
                    self.check_expr(a, true, reported);
                }
                return;
            }
            _ => {}
        }
        for c in e.children() {
            self.check_expr(c, false, reported);
        }
    }

    /// A symbol whose only meaning is a function (user or library).
    fn is_function_only(&self, s: SymId) -> bool {
        match self.m.current_def(s) {
            Some(id) => self.m.def(id).is_function(),
            None => {
                self.m.symbol(s).lib.is_some()
                    || self.m.host_name(s).is_some_and(|h| h.arity.is_some())
            }
        }
    }

    fn check_call(&mut self, s: SymId, args: &[Expr], span: Span, reported: &mut HashSet<SymId>) {
        let m = self.m;
        let name = m.symbol(s).name.clone();
        let user = m
            .current_def(s)
            .map(|id| m.def(id))
            .filter(|d| d.is_function());
        let (needed, max) = match (user, m.symbol(s).lib, m.host_name(s)) {
            (Some(def), _, _) => {
                let nparams = def.params.as_ref().map_or(0, Vec::len);
                let used = max_arg_used(&def.body);
                (used.min(nparams), Some(nparams))
            }
            (None, Some(lib), _) => (lib.min_args(), lib.max_args()),
            (None, None, Some(h)) => match h.arity {
                Some(n) => (n, Some(n)),
                None => {
                    self.not_a_function(&name, span);
                    return;
                }
            },
            (None, None, None) => {
                if m.current_def(s).is_some() {
                    self.not_a_function(&name, span);
                } else {
                    self.undefined(s, span, true, reported);
                }
                return;
            }
        };
        if args.len() < needed {
            self.diags.push(
                Diagnostic::new(
                    diagnostic::E0602,
                    span,
                    format!(
                        "'{name}' uses {needed} argument{}, but this call passes {}",
                        if needed == 1 { "" } else { "s" },
                        args.len()
                    ),
                )
                .with_hint("Radiance stops with 'too few arguments' when the missing one is used"),
            );
        } else if let Some(max) = max.filter(|&max| args.len() > max) {
            self.diags.push(Diagnostic::new(
                diagnostic::W0605,
                span,
                format!(
                    "'{name}' takes {max} argument{}; {} extra {} ignored",
                    if max == 1 { "" } else { "s" },
                    args.len() - max,
                    if args.len() - max == 1 { "is" } else { "are" }
                ),
            ));
        }
    }

    fn not_a_function(&mut self, name: &str, span: Span) {
        self.diags.push(Diagnostic::new(
            diagnostic::E0603,
            span,
            format!("'{name}' is a variable, called here like a function"),
        ));
    }

    /// A `:` definition is evaluated once; if it reads a per-record or per-ray value,
    /// every later use sees the first one (and Radiance warns "assigned non-constant
    /// value" at run time).
    fn check_constant(&mut self, def: &Def) {
        if def.kind != DefKind::Constant {
            return;
        }
        if let Some((span, why)) = self.nonconstant(&def.body, &mut HashSet::new()) {
            self.diags.push(
                Diagnostic::new(
                    diagnostic::W0602,
                    def.name.span,
                    format!(
                        "'{}' is defined with ':' but depends on {why}",
                        def.name.name
                    ),
                )
                .with_label(span, "this changes per record or ray")
                .with_hint("use '=' for values that change, ':' only for true constants"),
            );
        }
    }

    fn nonconstant(&self, e: &Expr, seen: &mut HashSet<SymId>) -> Option<(Span, String)> {
        match &e.node {
            Node::Chan(n) => return Some((e.span, format!("input column ${n}"))),
            Node::Var(s) => {
                if let Some(why) = self.sym_nonconstant(*s, seen) {
                    return Some((e.span, why));
                }
            }
            Node::Call {
                callee: Callee::Sym(s),
                ..
            } => {
                if let Some(why) = self.sym_nonconstant(*s, seen) {
                    return Some((e.span, why));
                }
            }
            _ => {}
        }
        e.children()
            .into_iter()
            .find_map(|c| self.nonconstant(c, seen))
    }

    fn sym_nonconstant(&self, s: SymId, seen: &mut HashSet<SymId>) -> Option<String> {
        if !seen.insert(s) {
            return None;
        }
        let m = self.m;
        let name = &m.symbol(s).name;
        match m.current_def(s).map(|id| m.def(id)) {
            Some(d) if d.kind == DefKind::Assign => Some(format!("'{name}', defined with '='")),
            Some(d) => self.nonconstant(&d.body, seen).map(|(_, why)| why),
            None => match (m.symbol(s).lib, m.host_name(s)) {
                (Some(LibFn::Builtin(_)), _) => None,
                (Some(l), _) if !l.is_constant() => {
                    Some(format!("'{name}()', which is not constant"))
                }
                (_, Some(h)) if !h.constant => {
                    Some(format!("'{name}', which the renderer sets per ray"))
                }
                _ => None,
            },
        }
    }

    fn check_redefinitions(&mut self, mine: &[DefId]) {
        let mut first: HashMap<SymId, &Def> = HashMap::new();
        for &id in mine {
            let def = self.m.def(id);
            if let Some(prev) = first.get(&def.sym) {
                self.diags.push(
                    Diagnostic::new(
                        diagnostic::W0601,
                        def.name.span,
                        format!(
                            "'{}' is defined again; this definition replaces the earlier one",
                            def.name.name
                        ),
                    )
                    .with_label(prev.name.span, "first defined here"),
                );
            } else {
                first.insert(def.sym, def);
            }
            if def.is_function() && self.m.symbol(def.sym).lib.is_some() {
                self.diags.push(Diagnostic::new(
                    diagnostic::W0604,
                    def.name.span,
                    format!(
                        "'{}' replaces the library function of that name",
                        def.name.name
                    ),
                ));
            }
        }
    }

    fn check_unused(&mut self, mine: &[DefId], entries: Option<&[&str]>) {
        let m = self.m;
        let needed: BTreeSet<DefId> = match entries {
            Some(names) => deps::needed_by_names(m, names),
            None if !m.outputs().is_empty() => {
                let mut set = BTreeSet::new();
                for o in m.outputs().values() {
                    set.extend(deps::needed_by_expr(m, &o.body));
                }
                set.extend(deps::needed_by_names(m, &["cond"]));
                set
            }
            None => return,
        };
        for &id in mine {
            let def = m.def(id);
            let in_force = m.current_def(def.sym) == Some(id);
            if in_force && !needed.contains(&id) {
                self.diags.push(Diagnostic::new(
                    diagnostic::W0603,
                    def.name.span,
                    format!("'{}' is defined but never used", def.name.name),
                ));
            }
        }
    }
}

/// The "did you mean" candidate: `suggest`'s distance limit, then among equally close
/// names the library's own (`sqrt` before rayinit.cal's `Sqrt` or `sq` for `sqt`), the
/// same initial case, and the longer name; else a swap of two adjacent characters.
fn closest_name<'a>(
    name: &str,
    known: &[&'a str],
    is_library: impl Fn(&str) -> bool,
) -> Option<&'a str> {
    let candidates: Vec<&str> = known.iter().copied().filter(|k| *k != name).collect();
    let Some(best) = suggest(name, candidates.iter().copied()) else {
        return transposed(name, known);
    };
    let distance = diagnostic::edit_distance(name, best);
    let upper = |s: &str| s.chars().next().is_some_and(char::is_uppercase);
    candidates
        .into_iter()
        .filter(|k| diagnostic::edit_distance(name, k) == distance)
        .max_by_key(|k| {
            (
                is_library(k),
                upper(k) == upper(name),
                k.len(),
                std::cmp::Reverse(*k),
            )
        })
}

/// A known name that is `name` with two adjacent characters swapped (`scael` for
/// `scale`): the typo the edit-distance limit of `suggest` misses in short names.
fn transposed<'a>(name: &str, known: &[&'a str]) -> Option<&'a str> {
    let n: Vec<char> = name.chars().collect();
    known.iter().copied().find(|k| {
        let k: Vec<char> = k.chars().collect();
        if k.len() != n.len() {
            return false;
        }
        let diff: Vec<usize> = (0..n.len()).filter(|&i| n[i] != k[i]).collect();
        diff.len() == 2
            && diff[1] == diff[0] + 1
            && n[diff[0]] == k[diff[1]]
            && n[diff[1]] == k[diff[0]]
    })
}

/// The highest parameter number a function body uses.
fn max_arg_used(e: &Expr) -> usize {
    let own = match e.node {
        Node::Arg(n) => n as usize,
        Node::Call {
            callee: Callee::Arg(n),
            ..
        } => n as usize,
        _ => 0,
    };
    e.children()
        .into_iter()
        .map(max_arg_used)
        .fold(own, usize::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes(text: &str, env: &Env) -> Vec<&'static str> {
        check(FileId(0), text, env)
            .iter()
            .map(|d| d.code.id)
            .collect()
    }

    #[test]
    fn undefined_names_suggest_a_fix() {
        let d = check(FileId(0), "x = sqt(2) + y; y = 1", &Env::rcalc().complete());
        assert_eq!(d.len(), 1, "{d:?}");
        assert_eq!(d[0].code.id, "E0601");
        assert_eq!(d[0].hint.as_deref(), Some("did you mean 'sqrt'?"));
    }

    #[test]
    fn arity_counts_only_used_parameters() {
        assert_eq!(
            codes("f(a, b) = a; x = f(1)", &Env::rcalc()),
            Vec::<&str>::new()
        );
        assert_eq!(codes("f(a, b) = b; x = f(1)", &Env::rcalc()), ["E0602"]);
        assert_eq!(codes("x = atan2(1)", &Env::rcalc()), ["E0602"]);
        assert_eq!(codes("x = sin(1, 2)", &Env::rcalc()), ["W0605"]);
        assert_eq!(
            codes("x = max(1, 2, 3, 4)", &Env::rcalc()),
            Vec::<&str>::new()
        );
    }

    #[test]
    fn functions_passed_by_name_are_fine() {
        assert_eq!(
            codes("g(h, x) = h(x); y = g(sin, 1)", &Env::rcalc()),
            Vec::<&str>::new()
        );
        assert_eq!(codes("y = sin + 1", &Env::rcalc()), ["E0603"]);
        assert_eq!(codes("v = 1; y = v(2)", &Env::rcalc()), ["E0603"]);
    }

    #[test]
    fn constants_that_are_not() {
        assert_eq!(codes("a = $1; c : 2*a", &Env::rcalc()), ["W0602"]);
        assert_eq!(codes("c : Dx*2", &Env::renderer()), ["W0602"]);
        assert_eq!(
            codes("c : PI*2; d : c + sq(2)", &Env::renderer()),
            Vec::<&str>::new()
        );
    }

    #[test]
    fn redefinition_and_unused() {
        assert_eq!(codes("a = 1; a = 2; $1 = a", &Env::rcalc()), ["W0601"]);
        assert_eq!(codes("a = 1; b = 2; $1 = a", &Env::rcalc()), ["W0603"]);
        assert_eq!(codes("sin(x) = x; $1 = sin(1)", &Env::rcalc()), ["W0604"]);
        let d = check_with_entries(
            FileId(0),
            "a = b; b = 1; c = 2",
            &Env::rcalc(),
            Some(&["a"]),
        );
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].message, "'c' is defined but never used");
    }

    #[test]
    fn renderer_names_are_known_there_only() {
        assert_eq!(
            codes("x = Dx + noise3(Px, Py, Pz) + sq(2)", &Env::renderer()),
            Vec::<&str>::new()
        );
        assert_eq!(codes("x = Dx", &Env::rcalc()), ["W0606"]);
        assert_eq!(codes("x = Dx", &Env::rcalc().complete()), ["E0601"]);
    }

    #[test]
    fn syntax_and_fold_errors_are_reported_together() {
        assert_eq!(
            codes("a = 1 +; b = x/0; c = log(", &Env::rcalc()),
            ["E0501", "W0606", "E0604", "E0501"]
        );
    }
}
