//! The calcomp syntax tree, as written: no names resolved, nothing folded. Every node
//! carries the byte span of its text so diagnostics and the editor can point at it.

use crate::source::Span;

/// A name as written, with its span. Names keep their back-quote context marks;
/// [`crate::cal::resolve`] interprets them.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

/// `=` is re-evaluated once per record (or ray); `:` is a constant, evaluated once
/// and folded into later expressions (caldefn.c `dvalue`, calexpr.c `rconst`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DefKind {
    Assign,
    Constant,
}

impl DefKind {
    pub fn symbol(self) -> char {
        match self {
            DefKind::Assign => '=',
            DefKind::Constant => ':',
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub statements: Vec<Statement>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Statement {
    /// `name = e`, `name : e`, `f(a, b) = e`.
    Definition(Definition),
    /// `$N = e`: rcalc's output column N.
    Output(Output),
}

impl Statement {
    pub fn span(&self) -> Span {
        match self {
            Statement::Definition(d) => d.span,
            Statement::Output(o) => o.span,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Definition {
    pub name: Ident,
    /// `Some` for a function definition (at least one parameter: `f() = 1` is a
    /// syntax error in Radiance).
    pub params: Option<Vec<Ident>>,
    pub kind: DefKind,
    pub body: Expr,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    pub channel: u32,
    pub channel_span: Span,
    pub body: Expr,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

impl BinOp {
    pub fn symbol(self) -> char {
        match self {
            BinOp::Add => '+',
            BinOp::Sub => '-',
            BinOp::Mul => '*',
            BinOp::Div => '/',
            BinOp::Pow => '^',
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Number(f64),
    /// `$N` on the right: input column N.
    Channel(u32),
    /// A variable, a parameter, or a function named as an argument.
    Name(Ident),
    Call {
        callee: Ident,
        args: Vec<Expr>,
    },
    /// Unary minus. Unary plus leaves no node.
    Neg(Box<Expr>),
    Binary {
        op: BinOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    /// Parentheses, kept so the tree stays faithful to the text (hover, formatting).
    Paren(Box<Expr>),
    /// Stands in for text that failed to parse.
    Error,
}

impl Expr {
    /// Visit every sub-expression, this one first.
    pub fn walk(&self, f: &mut dyn FnMut(&Expr)) {
        f(self);
        match &self.kind {
            ExprKind::Call { args, .. } => args.iter().for_each(|a| a.walk(f)),
            ExprKind::Neg(e) | ExprKind::Paren(e) => e.walk(f),
            ExprKind::Binary { lhs, rhs, .. } => {
                lhs.walk(f);
                rhs.walk(f);
            }
            _ => {}
        }
    }
}
