//! `!command` lines. Radiance runs them through the shell and reads their output as
//! scene text. radc instead asks a [`CommandExpander`] supplied by its caller: the CLI
//! plugs in the built-in generators (and, only with `--allow-commands`, a shell); the
//! language server plugs in generators only. `lang` itself never runs anything.

use crate::source::FileId;

/// What became of a command line.
pub enum Expansion {
    /// The command's output, registered by the expander as a file of its own (so
    /// diagnostics inside it can be shown against that text).
    Text { file: FileId, text: String },
    /// Not a built-in generator, and running other commands is not allowed here: a
    /// warning when only checking, an error when the scene is to be built.
    NotExpanded { reason: String },
    /// The command was understood but failed (bad generator arguments, a missing
    /// input file): a warning, as oconv only warns about a command's bad status.
    Failed {
        message: String,
        hint: Option<String>,
    },
    /// The command wrote `text` and then failed, or something it ran failed: Radiance
    /// reads what was written (the generators write as they go) and warns, so the
    /// text is lowered in place and the failure is a warning on the command.
    Partial {
        file: FileId,
        text: String,
        message: String,
        hint: Option<String>,
    },
    /// The command includes, directly or through nested commands, the file it sits in.
    Cycle { message: String },
}

pub trait CommandExpander {
    /// Expands `command` (the text after `!`, continuation lines joined) that appears
    /// in `from`. `depth` counts nested expansions so expanders can stop runaway
    /// recursion.
    fn expand(&self, command: &str, from: FileId, depth: u32) -> Expansion;
}

/// Expands nothing: every command is reported as not expanded.
pub struct NoCommands;

impl CommandExpander for NoCommands {
    fn expand(&self, _: &str, _: FileId, _: u32) -> Expansion {
        Expansion::NotExpanded {
            reason: "radc does not run commands here".into(),
        }
    }
}

/// Nested expansions deeper than this are reported as a likely include cycle.
pub const MAX_DEPTH: u32 = 32;
