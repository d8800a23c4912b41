//! The Radiance languages as data: scene files (`.rad`) and calcomp (`.cal`).
//!
//! `lang` never does IO except through the text handed to it, never prints and never
//! spawns a process: the CLI and the language server are the only places that touch
//! the outside world, so both see exactly the same diagnostics.

pub mod c_number;
pub mod cal;
pub mod compiled;
pub mod datafile;
pub mod db;
pub mod diagnostic;
pub mod library;
pub mod scene;
pub mod schema;
pub mod search_path;
pub mod source;
pub mod transform;

pub use diagnostic::{Code, Diagnostic, Label, Severity};
pub use source::{FileId, LineIndex, Span};
