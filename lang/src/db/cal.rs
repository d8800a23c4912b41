//! Calcomp files in the database: their parse, the diagnostics `radc check FILE.cal`
//! reports, and an index of which word names which definition (navigation, rename,
//! hover in the editor). Each is a tracked query of the file's text alone, so editing
//! a scene never re-parses a `.cal` file and the other way round.

use std::collections::HashMap;

use super::{Db, SourceFile};
use crate::cal::ir::Node;
use crate::cal::syntax::{DefKind, Expr, ExprKind, Ident, Program, Statement};
use crate::cal::{self, Env, Module};
use crate::diagnostic::Diagnostic;
use crate::source::{self, Span};

/// A calcomp file's syntax tree and its syntax diagnostics.
#[derive(Clone, Debug, PartialEq)]
pub struct ParsedCal {
    pub program: Program,
    pub diagnostics: Vec<Diagnostic>,
}

/// The file's text as the checks read it (a NUL byte decoded as `radc check` decodes
/// a file read from disk).
fn clean_text(db: &dyn Db, file: SourceFile) -> String {
    let text = file.text(db);
    if text.contains('\0') {
        source::decode(file.id(db), text.as_bytes()).0
    } else {
        text.clone()
    }
}

#[salsa::tracked(returns(ref), no_eq)]
pub fn parse_cal(db: &dyn Db, file: SourceFile) -> ParsedCal {
    db.note_parse(file);
    let (program, diagnostics) = cal::parse(file.id(db), &clean_text(db, file));
    ParsedCal {
        program,
        diagnostics,
    }
}

/// Every diagnostic `radc check FILE.cal` reports for the file (same codes, messages
/// and order).
#[salsa::tracked(returns(ref), no_eq)]
pub fn check_cal(db: &dyn Db, file: SourceFile) -> Vec<Diagnostic> {
    db.note_parse(file);
    cal::check::check_file(file.id(db), &clean_text(db, file))
}

/// The value of each variable of the file that folds to a constant (as the renderer
/// folds it while loading the file), by name.
#[salsa::tracked(returns(ref), no_eq)]
pub fn cal_values(db: &dyn Db, file: SourceFile) -> HashMap<String, f64> {
    let id = file.id(db);
    let mut module = Module::new(&Env::renderer());
    let _ = module.add_source(id, &clean_text(db, file));
    let mut values = HashMap::new();
    for sym in module.symbols() {
        let Some(def) = sym.stack.last().map(|&d| module.def(d)) else {
            continue;
        };
        if def.is_function() || def.span.file != id {
            continue;
        }
        let value = match def.body.node {
            Node::Num(v) => Some(v),
            _ => def.parse_time_value,
        };
        if let Some(v) = value {
            values.insert(def.name.name.clone(), v);
        }
    }
    values
}

#[salsa::tracked(returns(ref), no_eq)]
pub fn cal_index(db: &dyn Db, file: SourceFile) -> CalIndex {
    CalIndex::new(&parse_cal(db, file).program)
}

/// One definition statement of a file.
#[derive(Clone, Debug, PartialEq)]
pub struct CalDef {
    pub name: String,
    pub name_span: Span,
    /// The whole statement.
    pub span: Span,
    pub params: Option<Vec<Ident>>,
    pub kind: DefKind,
}

/// What a name in a calcomp file stands for.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum CalName {
    /// A variable or function of the program (defined here, elsewhere, or built in).
    Global(String),
    /// Parameter `index` of the definition `def` (an index into [`CalIndex::defs`]).
    Param { def: usize, index: usize },
}

/// One word of the file that is a name: a definition's name, a parameter's
/// declaration, or a use.
#[derive(Clone, Debug, PartialEq)]
pub struct CalUse {
    pub span: Span,
    pub name: CalName,
    /// Written as a call (`f(x)`).
    pub call: bool,
    /// The defining occurrence (a definition's name or a parameter's declaration).
    pub defining: bool,
}

/// Which word names what, from the syntax tree alone (works on half-typed files: a
/// statement that does not parse is simply absent).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CalIndex {
    pub defs: Vec<CalDef>,
    /// Every name in the file, in text order.
    pub uses: Vec<CalUse>,
}

impl CalIndex {
    pub fn new(program: &Program) -> Self {
        let mut index = CalIndex::default();
        for statement in &program.statements {
            match statement {
                Statement::Definition(d) => {
                    let def = index.defs.len();
                    index.defs.push(CalDef {
                        name: d.name.name.clone(),
                        name_span: d.name.span,
                        span: d.span,
                        params: d.params.clone(),
                        kind: d.kind,
                    });
                    index.uses.push(CalUse {
                        span: d.name.span,
                        name: CalName::Global(d.name.name.clone()),
                        call: d.params.is_some(),
                        defining: true,
                    });
                    let params = d.params.as_deref().unwrap_or(&[]);
                    for (i, p) in params.iter().enumerate() {
                        index.uses.push(CalUse {
                            span: p.span,
                            name: CalName::Param { def, index: i },
                            call: false,
                            defining: true,
                        });
                    }
                    index.walk(&d.body, Some((def, params)));
                }
                Statement::Output(o) => index.walk(&o.body, None),
            }
        }
        index.uses.sort_by_key(|u| (u.span.start, u.span.end));
        index
    }

    fn walk(&mut self, body: &Expr, params: Option<(usize, &[Ident])>) {
        let resolve = |name: &str| match params {
            Some((def, ps)) => match ps.iter().rposition(|p| p.name == name) {
                Some(index) => CalName::Param { def, index },
                None => CalName::Global(name.to_string()),
            },
            None => CalName::Global(name.to_string()),
        };
        let mut found = Vec::new();
        body.walk(&mut |e| match &e.kind {
            ExprKind::Name(id) => found.push((id.span, resolve(&id.name), false)),
            ExprKind::Call { callee, .. } => {
                found.push((callee.span, resolve(&callee.name), true));
            }
            _ => {}
        });
        self.uses
            .extend(found.into_iter().map(|(span, name, call)| CalUse {
                span,
                name,
                call,
                defining: false,
            }));
    }

    /// The name whose word touches byte `offset`.
    pub fn at(&self, offset: usize) -> Option<&CalUse> {
        self.uses
            .iter()
            .find(|u| u.span.start as usize <= offset && offset <= u.span.end as usize)
    }

    /// The definition in force for a global name: the file's last one, since a later
    /// definition replaces an earlier one before anything is evaluated (caldefn.c).
    pub fn definition(&self, name: &str) -> Option<&CalDef> {
        self.defs.iter().rev().find(|d| d.name == name)
    }

    /// Every word that names `name` (definitions included), in text order.
    pub fn spans_of(&self, name: &CalName) -> Vec<Span> {
        self.uses
            .iter()
            .filter(|u| u.name == *name)
            .map(|u| u.span)
            .collect()
    }

    /// The span of the declaration of a name: a parameter's, or the global's
    /// definition in force.
    pub fn declaration(&self, name: &CalName) -> Option<Span> {
        match name {
            CalName::Global(n) => self.definition(n).map(|d| d.name_span),
            CalName::Param { def, index } => {
                let params = self.defs.get(*def)?.params.as_ref()?;
                params.get(*index).map(|p| p.span)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::db::Database;

    const TEXT: &str = "k : 2 * 3;\nf(x) = x * k;\ng = f(k) + y;\n";

    #[test]
    fn indexes_definitions_parameters_and_uses() {
        let mut db = Database::default();
        let file = db.add_file("a.cal", TEXT);
        let index = cal_index(&db, file);
        let names: Vec<&str> = index.defs.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(names, ["k", "f", "g"]);
        let k = CalName::Global("k".into());
        let starts: Vec<u32> = index.spans_of(&k).iter().map(|s| s.start).collect();
        assert_eq!(starts, [0, 22, 31]);
        // `x` in f's body is f's parameter.
        let x = index.at(18).map(|u| u.name.clone());
        assert_eq!(x, Some(CalName::Param { def: 1, index: 0 }));
        assert_eq!(
            index
                .declaration(&CalName::Param { def: 1, index: 0 })
                .map(|s| s.start),
            Some(13)
        );
        assert_eq!(cal_values(&db, file).get("k"), Some(&6.0));
        assert_eq!(cal_values(&db, file).get("g"), None);
    }

    #[test]
    fn diagnostics_are_radc_checks_and_parses_are_counted() {
        let mut db = Database::default();
        let file = db.add_file("/x/a.cal", "a = sinn(1);\n");
        let expected = cal::check::check_file(file.id(&db), "a = sinn(1);\n");
        assert_eq!(check_cal(&db, file), &expected);
        assert!(!expected.is_empty());
        cal_index(&db, file);
        cal_index(&db, file);
        check_cal(&db, file);
        // Once for the check, once for the index; memos are reused after that.
        assert_eq!(db.parse_counts(), [("/x/a.cal".to_string(), 2)]);
    }
}
