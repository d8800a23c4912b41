//! Scene files (`.rad`, `.mat`): lexing, parsing, lowering to the typed IR and checks.

pub mod command;
pub mod format;
pub mod functions;
pub mod ir;
pub mod lexer;
pub mod lower;
pub mod parser;
pub mod scope;
pub mod syntax;

pub use command::{CommandExpander, Expansion, NoCommands};
pub use lower::{AssumeFilesExist, FileLookup, LowerInput, lower, lower_with};
pub use parser::parse;

use crate::diagnostic::Diagnostic;
use crate::source::FileId;

/// Parses and checks one file on its own: the whole front end in one call.
pub fn check_text(
    file: FileId,
    text: &str,
    files: &dyn FileLookup,
    warn_unused: bool,
) -> (ir::Scene, Vec<Diagnostic>) {
    let (syntax, mut diags) = parse(file, text);
    let (scene, more) = lower(
        &[LowerInput {
            file,
            syntax: &syntax,
            warn_unused,
        }],
        files,
    );
    diags.extend(more);
    (scene, diags)
}
