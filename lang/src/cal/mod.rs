//! calcomp, Radiance's function language (`.cal` files, `rcalc -e`, the expression
//! arguments of `*func` primitives): lexer, parser, name resolution, constant folding,
//! dependency graph and the checks `radc check` reports.

pub mod lexer;
pub mod parser;
pub mod syntax;

pub use parser::{parse, parse_expr};
pub mod builtins;
pub mod eval;
pub mod fold;
pub mod ir;
pub mod resolve;

pub use resolve::{Env, Host, Module};
pub mod check;
pub mod deps;

pub use check::{check, check_with_entries};
