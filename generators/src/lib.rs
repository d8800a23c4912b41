//! Radiance's scene generators, reimplemented to print exactly what the C programs
//! print: `genbox`, `genprism`, `genrev`, `gensky`, `gensurf`, `genworm` and
//! `xform` (`src/gen/*.c` in Radiance). The curves of genrev, gensurf
//! and genworm are calcomp, evaluated by `radc_lang::cal`; deep calcomp recursion
//! needs a deep stack, so callers run those on a thread with one (as `radc genworm`
//! and `radc calc` do).
//!
//! "Exactly" is checked against the oracle build (pyradiance), which compiles Radiance
//! with `-ffast-math`: where that changes a sum's order enough to show in the printed
//! digits (`normalize()`, `multmat4()`), the code follows the compiled order and says so.
//!
//! Each generator is a pure function from its command-line arguments (without the
//! program name) to the scene text it would write on standard output. Anything from
//! outside (files named on the command line, standard input, `!` commands inside a
//! scene read by xform) comes through a [`Host`], so the library never does IO itself:
//! the CLI supplies a host over the file system, tests supply one over strings.

pub mod command;
mod curves;
pub mod genbox;
pub mod genprism;
pub mod genrev;
pub mod gensky;
pub mod gensurf;
pub mod genworm;
mod mesh;
pub mod printf;
mod wavefront;
pub mod words;
pub mod xform;

pub use genbox::genbox;
pub use genprism::genprism;
pub use genrev::genrev;
pub use gensky::gensky;
pub use gensurf::gensurf;
pub use genworm::genworm;
pub use xform::xform;

use std::fmt;

/// Why a generator produced no output. The message reads like the C program's own
/// complaint (usage line, "bad polygon", ...), without the program-name prefix.
#[derive(Clone, Debug, PartialEq)]
pub enum GenError {
    /// The arguments do not fit the program's usage; holds the usage line.
    Usage(String),
    /// The arguments parse but cannot be generated (too few vertices, ...).
    Invalid(String),
    /// A transform word is wrong: the diagnostic points at it (spans are byte offsets
    /// into the arguments joined by single spaces).
    Transform(Box<radc_lang::Diagnostic>),
    /// The input scene cannot be read (unknown type, bad argument list, ...).
    Scene(String),
    /// The host could not supply a file, standard input or a command's output.
    Host(String),
    /// A Radiance option radc does not reproduce yet.
    Unsupported(String),
}

impl fmt::Display for GenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GenError::Usage(u) => write!(f, "usage: {u}"),
            GenError::Transform(d) => write!(f, "{}: {}", d.code.id, d.message),
            GenError::Invalid(m)
            | GenError::Scene(m)
            | GenError::Host(m)
            | GenError::Unsupported(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for GenError {}

/// What a generator may ask of the outside world.
pub trait Host {
    /// The text of a file named by an argument or a nested command, as named (relative
    /// names are relative to the current directory, already joined with the folder of
    /// the file that named them).
    fn read_file(&mut self, path: &str) -> Result<String, GenError>;

    /// Standard input, read once (generators cache it).
    fn read_stdin(&mut self) -> Result<String, GenError>;

    /// The output of a `!` command inside a scene that is not one of the generators
    /// here. Refused unless the host allows running commands.
    fn run_command(&mut self, command: &str, _dir: &str) -> Result<String, GenError> {
        Err(GenError::Host(format!(
            "not running command \"{command}\": only genbox, genprism and xform are built in"
        )))
    }
}

/// A host with no files and no standard input, for generators that need neither.
pub struct NoHost;

impl Host for NoHost {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        Err(GenError::Host(format!("cannot open \"{path}\"")))
    }

    fn read_stdin(&mut self) -> Result<String, GenError> {
        Ok(String::new())
    }
}

/// The `printargs()` comment line that starts every generator's output.
fn command_comment(program: &str, args: &[String]) -> String {
    let mut out = String::from("# ");
    words::put_word(&mut out, program);
    for a in args {
        out.push(' ');
        words::put_word(&mut out, a);
    }
    out.push('\n');
    out
}
