//! Scene files (`.rad`, `.mat`): lexing, parsing, lowering to the typed IR and checks.

pub mod lexer;
pub mod parser;
pub mod syntax;

pub use parser::parse;
