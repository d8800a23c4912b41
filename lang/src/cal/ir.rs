//! The resolved calcomp IR: what Radiance holds after parsing. Names are linked to
//! symbols (a symbol is one fully qualified name with its stack of definitions, as in
//! caldefn.c's `VARDEF`), parameters to argument slots, `+` and `*` chains flattened,
//! and constants folded the way calexpr.c folds them. Evaluation (`eval.rs`) and the
//! JIT read only this.

use super::builtins::LibFn;
use super::syntax::{DefKind, Ident};
use crate::source::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SymId(pub u32);

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DefId(pub u32);

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub node: Node,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    Num(f64),
    /// Input column `$N`.
    Chan(u32),
    /// A variable, or a function named as an argument. Looked up through its symbol
    /// when evaluated, so the latest definition wins (caldefn.c `evariable`).
    Var(SymId),
    /// Parameter N (1-based) of the function being defined.
    Arg(u32),
    Call {
        callee: Callee,
        args: Vec<Expr>,
    },
    Neg(Box<Expr>),
    Sub(Box<Expr>, Box<Expr>),
    Div(Box<Expr>, Box<Expr>),
    Pow(Box<Expr>, Box<Expr>),
    /// `a + b + ...`, summed from 0 left to right (calexpr.c `eadd`): `-0 + -0` is 0.
    Sum(Vec<Expr>),
    /// `a * b * ...`, multiplied from 1 left to right (calexpr.c `emult`).
    Product(Vec<Expr>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Callee {
    Sym(SymId),
    /// Calling a parameter: the caller passed a function's name (calfunc.c `eargf`).
    Arg(u32),
}

impl Expr {
    pub fn num(v: f64, span: Span) -> Expr {
        Expr {
            node: Node::Num(v),
            span,
        }
    }

    pub fn as_num(&self) -> Option<f64> {
        match self.node {
            Node::Num(v) => Some(v),
            _ => None,
        }
    }

    pub fn children(&self) -> Vec<&Expr> {
        match &self.node {
            Node::Num(_) | Node::Chan(_) | Node::Var(_) | Node::Arg(_) => Vec::new(),
            Node::Call { args, .. } => args.iter().collect(),
            Node::Neg(a) => vec![a],
            Node::Sub(a, b) | Node::Div(a, b) | Node::Pow(a, b) => vec![a, b],
            Node::Sum(v) | Node::Product(v) => v.iter().collect(),
        }
    }

    /// Every symbol this expression names, as a variable or a callee.
    pub fn symbols(&self, out: &mut Vec<(SymId, Span)>) {
        match &self.node {
            Node::Var(s) => out.push((*s, self.span)),
            Node::Call {
                callee: Callee::Sym(s),
                ..
            } => out.push((*s, self.span)),
            _ => {}
        }
        for c in self.children() {
            c.symbols(out);
        }
    }
}

/// One definition statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Def {
    pub sym: SymId,
    pub name: Ident,
    /// Parameter names of a function definition.
    pub params: Option<Vec<Ident>>,
    pub kind: DefKind,
    pub body: Expr,
    pub span: Span,
    /// The value a `:` variable took when it was evaluated while parsing (to fold a
    /// later reference): Radiance keeps that value for good (caldefn.c `dvalue`).
    pub parse_time_value: Option<f64>,
}

impl Def {
    pub fn is_function(&self) -> bool {
        self.params.is_some()
    }
}

/// One fully qualified name.
#[derive(Clone, Debug, PartialEq)]
pub struct Symbol {
    pub name: String,
    /// Definitions in force, most recent last. `=` replaces the `=` definitions on top,
    /// `:` replaces all (caldefn.c `dclear`, `dremove`).
    pub stack: Vec<DefId>,
    /// The library function of this name, used when no definition is a function.
    pub lib: Option<LibFn>,
    /// Where the name was first referenced, for "undefined" diagnostics.
    pub first_use: Option<Span>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct OutputDef {
    pub channel: u32,
    pub body: Expr,
    pub span: Span,
}
