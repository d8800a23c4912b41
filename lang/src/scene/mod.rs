//! Scene files (`.rad`, `.mat`): lexing, parsing, lowering to the typed IR and checks.

pub mod command;
pub mod format;
pub mod functions;
pub mod ir;
pub mod lexer;
pub mod lower;
pub mod parser;
mod reader;
pub mod reparse;
pub mod scope;
pub mod support;
pub mod syntax;

pub use command::{CommandExpander, Expansion, NoCommands};
pub use lower::{AssumeFilesExist, FileLookup, Keep, LowerInput, Lowering, lower, lower_with};
pub use parser::{parse, parse_each};
pub use reparse::ParsedScene;
pub use support::RenderSupport;

use crate::diagnostic::Diagnostic;
use crate::source::FileId;

/// Parses and checks one file on its own: the whole front end in one call.
pub fn check_text(
    file: FileId,
    text: &str,
    files: &dyn FileLookup,
    warn_unused: bool,
) -> (ir::Scene, Vec<Diagnostic>) {
    let mut lowering = Lowering::new(files, &NoCommands, Keep::Everything);
    let mut diags = parse_each(file, text, &mut |item| lowering.item(item, warn_unused));
    let (scene, more) = lowering.finish();
    diags.extend(more);
    (scene, diags)
}
