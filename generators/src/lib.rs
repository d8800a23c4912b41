//! Radiance's scene generators, reimplemented to print exactly what the C programs
//! print: `genbox`, `gendaylit`, `genprism`, `genrev`, `gensky`, `gensurf`, `genworm` and
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
pub mod expansion;
pub mod genbox;
pub mod gendaylit;
pub mod genprism;
pub mod genrev;
pub mod gensky;
pub mod gensurf;
pub mod genworm;
mod mesh;
mod sun;
mod wavefront;
pub mod words;
pub mod xform;

pub use genbox::genbox;
pub use gendaylit::gendaylit;
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
    /// into the arguments joined by single spaces); `at` is the option word xform
    /// names in its "command line error at" message.
    Transform {
        diagnostic: Box<radc_lang::Diagnostic>,
        at: String,
    },
    /// A complaint the C program prints as it is, without its name (calcomp's
    /// "x: undefined variable", gensurf's "file: bad number of data points").
    Plain(String),
    /// The input scene cannot be read (unknown type, bad argument list, ...).
    Scene(String),
    /// The host could not supply a file, standard input or a command's output.
    Host(String),
    /// A Radiance option radc does not reproduce yet.
    Unsupported(String),
    /// `!` commands or argument files nested too deep: a file that includes itself.
    /// Fatal however deep it happens (Radiance would recurse until it runs out).
    Nesting(String),
}

impl fmt::Display for GenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GenError::Usage(u) => write!(f, "usage: {u}"),
            GenError::Transform { diagnostic: d, .. } => {
                write!(f, "{}: {}", d.code.id, d.message)
            }
            GenError::Invalid(m)
            | GenError::Plain(m)
            | GenError::Scene(m)
            | GenError::Host(m)
            | GenError::Nesting(m)
            | GenError::Unsupported(m) => f.write_str(m),
        }
    }
}

impl GenError {
    /// What the C program `program` prints on standard error when it fails this way
    /// (one or more lines, without the final newline): `Usage: ...` for a usage
    /// error (gensky's `Use error - why` first), `xform: command line error at '-t'`
    /// for a bad transform, else `program: message`.
    pub fn radiance_message(&self, program: &str) -> String {
        match self {
            GenError::Usage(u) => match u.split_once('\n') {
                Some((why, usage)) if program == "gensky" => {
                    format!("gensky: Use error - {why}\nUsage: {usage}")
                }
                _ => format!("Usage: {u}"),
            },
            GenError::Transform { at, .. } => format!("{program}: command line error at '{at}'"),
            GenError::Plain(m) => m.clone(),
            other => format!("{program}: {other}"),
        }
    }
}

/// A generator that failed after writing some output: Radiance's programs write as
/// they go, so what came before the failure reaches standard output (and a scene
/// that runs them), and the caller keeps it.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The program that failed (in a pipeline, the stage), for its messages.
    pub program: String,
    /// What was written before the failure.
    pub partial: String,
    pub error: GenError,
}

impl Failure {
    /// A failure before any output.
    pub fn new(program: &str, error: GenError) -> Self {
        Failure {
            program: program.to_string(),
            partial: String::new(),
            error,
        }
    }

    /// Runs `write` (a generator writing into a buffer as the C program writes to
    /// standard output) and keeps what it wrote before failing.
    pub(crate) fn keeping_partial(
        program: &str,
        write: impl FnOnce(&mut String) -> Result<(), GenError>,
    ) -> Result<String, Failure> {
        let mut out = String::new();
        match write(&mut out) {
            Ok(()) => Ok(out),
            Err(error) => Err(Failure {
                program: program.to_string(),
                partial: out,
                error,
            }),
        }
    }

    /// [`GenError::radiance_message`] for the program that failed.
    pub fn radiance_message(&self) -> String {
        self.error.radiance_message(&self.program)
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

    /// A line the C programs would print on standard error and go on: warnings
    /// (`xform: (file): warning - empty file`), and the messages of `!` commands that
    /// failed inside a scene xform reads (Radiance's children share its stderr).
    /// Worded as Radiance words them, program name included. Hosts that wrap another
    /// host must pass these on.
    fn warn(&mut self, line: &str);

    /// The output of a `!` command inside a scene that is not one of the generators
    /// here (or, if it fails, what it wrote before failing). Refused unless the host
    /// allows running commands.
    fn run_command(&mut self, command: &str, _dir: &str) -> Result<String, Failure> {
        Err(Failure::new(
            "xform",
            GenError::Host(format!(
                "not running command \"{command}\": radc builds in genbox, gendaylit, genprism, genrev, \
                 gensky, gensurf, genworm and xform"
            )),
        ))
    }
}

/// How hosts answer [`Host::read_file`]: the first candidate of `search` (from the
/// folder `dir` where the policy starts there) that `read` can read, or else radc's
/// built-in library file of that name; `read` is the host's file system.
pub fn read_on_path(
    search: &radc_lang::search_path::SearchPath,
    path: &str,
    dir: Option<&std::path::Path>,
    read: impl Fn(&std::path::Path) -> Option<Vec<u8>>,
) -> Result<String, GenError> {
    search
        .read_text(path, dir, read)
        .map(radc_lang::search_path::Found::into_text)
        .ok_or_else(|| GenError::Host(format!("cannot find file \"{path}\"")))
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

    fn warn(&mut self, _line: &str) {}
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
