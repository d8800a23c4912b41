//! calcomp, Radiance's function language (`.cal` files, `rcalc -e`, the expression
//! arguments of `*func` primitives): lexer, parser, name resolution, constant folding,
//! dependency graph, evaluation rules and the checks `radc check` reports.
//!
//! Flow: text -> [`lexer`] (logos) -> [`parser`] (chumsky, one statement at a time, so
//! one bad statement never hides the next) -> [`syntax::Program`] -> [`Module`]
//! ([`resolve`]: symbols with definition stacks, folding as calexpr.c folds while it
//! parses) -> [`ir`] -> [`eval`] (the semantics; `radc_jit::interp` drives it per record).
//!
//! Entry points:
//! - [`parse`]`(file, text) -> (Program, Vec<Diagnostic>)`: syntax only.
//! - [`check()`]`(file, text, &Env) -> Vec<Diagnostic>`: everything `radc check` reports
//!   for a `.cal` file; [`check_with_entries`] when a scene says which names it uses.
//! - [`Module::new`]`(&Env)`, then [`Module::add_source`] per file (in load order) and
//!   [`Module::add_expression`] for a primitive's expression arguments; then
//!   [`deps::needed_by_names`] for exactly the definitions some entry names need.
//!
//! The reproduced Radiance is the reference build (pyradiance's Radiance 6.0, compiled
//! with -ffast-math): where that build differs from the C source's intent (NaN
//! handling, signed zeros, argument evaluation order), the code says so and the
//! goldens in `tests/data/cal-semantics/` pin it.

pub mod builtins;
pub mod check;
pub mod deps;
pub mod eval;
pub mod fold;
pub mod ir;
pub mod lexer;
pub mod parser;
pub mod renderer_math;
pub mod resolve;
pub mod syntax;

pub use check::{check, check_with_entries};
pub use parser::{parse, parse_expr};
pub use resolve::{Env, Host, Module};
