//! `radc genbox`, `radc genprism`, `radc gensky`, `radc xform`: Radiance's generators, same options,
//! same output (see the `radc-generators` crate). This file is the host that gives
//! them files, standard input and, only with `--allow-commands`, a shell.

use radc_generators::{Failure, GenError, Host, read_on_path};
use radc_lang::search_path::{Policy, SearchPath};
use std::io::{Read, Write};
use std::process::ExitCode;

pub fn genbox(args: &[String]) -> ExitCode {
    finish("genbox", radc_generators::genbox(args))
}

pub fn gensky(args: &[String]) -> ExitCode {
    let mut host = FileHost::default();
    finish("gensky", radc_generators::gensky(args, &mut host))
}

pub fn gendaylit(args: &[String]) -> ExitCode {
    let mut host = FileHost::default();
    report(radc_generators::gendaylit(args, &mut host))
}

pub fn genworm(args: &[String]) -> ExitCode {
    let args = args.to_vec();
    let result = with_deep_stack(
        move || {
            let mut host = FileHost::default();
            radc_generators::genworm(&args, &mut host)
        },
        |e| Failure::new("genworm", e),
    );
    report(result)
}

pub fn genrev(args: &[String]) -> ExitCode {
    let args = args.to_vec();
    let result = with_deep_stack(
        move || {
            let mut host = FileHost::default();
            radc_generators::genrev(&args, &mut host)
        },
        |e| Failure::new("genrev", e),
    );
    report(result)
}

pub fn gensurf(args: &[String]) -> ExitCode {
    let args = args.to_vec();
    let result = with_deep_stack(
        move || {
            let mut host = FileHost::default();
            radc_generators::gensurf(&args, &mut host)
        },
        |e| Failure::new("gensurf", e),
    );
    report(result)
}

/// calcomp recursion is legal and can be deep (genworm's curves, or a genworm run by a
/// `!` line inside a scene given to xform): evaluate on a thread with a stack to match,
/// as `radc calc` does.
fn with_deep_stack<E: Send + 'static>(
    work: impl FnOnce() -> Result<String, E> + Send + 'static,
    lost: impl FnOnce(GenError) -> E,
) -> Result<String, E> {
    let worker = std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(work);
    match worker.map(|h| h.join()) {
        Ok(Ok(result)) => result,
        _ => Err(lost(GenError::Invalid("evaluation failed".into()))),
    }
}

pub fn genprism(args: &[String]) -> ExitCode {
    let mut host = FileHost::default();
    finish("genprism", radc_generators::genprism(args, &mut host))
}

/// `radc xform [--allow-commands] ARGS`: without the flag, `!` commands in a scene
/// other than genbox, genprism and xform are refused rather than run.
pub fn xform(args: &[String]) -> ExitCode {
    let mut host = FileHost::default();
    let args = match args.split_first() {
        Some((first, rest)) if first == "--allow-commands" => {
            host.allow_commands = true;
            rest.to_vec()
        }
        _ => args.to_vec(),
    };
    let result = with_deep_stack(
        move || radc_generators::xform(&args, &mut host),
        |e| Failure::new("xform", e),
    );
    report(result)
}

fn finish(program: &str, result: Result<String, GenError>) -> ExitCode {
    report(result.map_err(|e| Failure::new(program, e)))
}

/// Writes what the generator made (on failure, what it made before failing, as the
/// C programs leave it on standard output), then the failure in the C program's
/// words, and radc's own detail (the diagnostic, a hint) on indented lines after it.
/// The status is 1 for every failure, as Radiance's generators exit.
fn report(result: Result<String, Failure>) -> ExitCode {
    let (text, failure) = match result {
        Ok(text) => (text, None),
        Err(mut f) => (std::mem::take(&mut f.partial), Some(f)),
    };
    let mut out = std::io::stdout().lock();
    let written = out.write_all(text.as_bytes()).and_then(|()| out.flush());
    let Some(f) = failure else {
        return match written {
            Ok(()) => ExitCode::SUCCESS,
            Err(_) => ExitCode::FAILURE,
        };
    };
    eprintln!("{}", f.radiance_message());
    if let GenError::Transform { diagnostic: d, .. } = &f.error {
        eprintln!("  error[{}]: {}", d.code.id, d.message);
        if let Some(h) = &d.hint {
            eprintln!("  hint: {h}");
        }
    }
    ExitCode::FAILURE
}

/// Files from the file system (`Policy::CurrentRaypath`): relative names also
/// searched along RAYPATH as Radiance's `getpath()` does; radc's built-in function files when none is found.
#[derive(Default)]
struct FileHost {
    allow_commands: bool,
}

impl Host for FileHost {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        let raypath = std::env::var_os("RAYPATH");
        let search = SearchPath::new(Policy::CurrentRaypath, raypath.as_deref());
        read_on_path(&search, path, None, |c| std::fs::read(c).ok())
    }

    fn read_stdin(&mut self) -> Result<String, GenError> {
        let mut bytes = Vec::new();
        std::io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| GenError::Host(format!("cannot read standard input: {e}")))?;
        Ok(String::from_utf8_lossy(&bytes).into_owned())
    }

    fn warn(&mut self, line: &str) {
        eprintln!("{line}");
    }

    fn run_command(&mut self, command: &str, dir: &str) -> Result<String, Failure> {
        let program = radc_generators::command::program_of(command);
        if !self.allow_commands {
            return Err(Failure::new(
                "xform",
                GenError::Host(format!(
                    "not running \"{command}\": radc builds in genbox, gendaylit, genprism, genrev, \
                     gensky, gensurf, genworm and xform (pass --allow-commands first to run \
                     other commands with sh)"
                )),
            ));
        }
        let mut sh = std::process::Command::new("sh");
        sh.arg("-c").arg(command);
        if !dir.is_empty() {
            sh.current_dir(dir);
        }
        let output = sh.output().map_err(|e| {
            Failure::new(
                "xform",
                GenError::Host(format!("cannot execute \"{command}\": {e}")),
            )
        })?;
        std::io::stderr().write_all(&output.stderr).ok();
        let text = String::from_utf8_lossy(&output.stdout).into_owned();
        if output.status.success() {
            Ok(text)
        } else {
            // The command printed its own complaint on the stderr passed through.
            Err(Failure {
                program: program.to_string(),
                partial: text,
                error: GenError::Plain(String::new()),
            })
        }
    }
}
