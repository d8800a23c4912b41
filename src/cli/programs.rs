//! radc under Radiance's program names, as busybox is under its applets' names: a link
//! named `rtrace` (or `oconv`, `rcalc`, `getinfo`, ...) to the `radc` binary runs the
//! radc command standing in for that program, so pipelines and scripts that call
//! Radiance's programs by name run unchanged with radc's links first on PATH.
//! `radc links DIR` makes the links; a program radc does not stand in for gets none, so
//! a real Radiance later on PATH serves it.
//!
//! Called by a Radiance name, radc does what the user asked of that program: `oconv`
//! and `xform` run the `!` commands of their scene files through `sh`, as Radiance's do
//! (radc's own subcommands run only its built-in generators unless given
//! `--allow-commands`).

use std::path::Path;
use std::process::ExitCode;

use super::USAGE_ERROR;

/// A Radiance program radc stands in for.
pub(super) struct Program {
    /// Radiance's name for it.
    pub name: &'static str,
    /// The radc command that does its job.
    command: &'static str,
    /// Whether, called by this name, `!` lines in scene files run through the shell.
    runs_commands: bool,
}

const fn program(name: &'static str, command: &'static str) -> Program {
    Program {
        name,
        command,
        runs_commands: false,
    }
}

/// Every program radc stands in for. A name is added here only when the command takes
/// that program's options and writes its outputs.
pub(super) const PROGRAMS: &[Program] = &[
    program("rtrace", "trace"),
    program("rpict", "render"),
    Program {
        name: "oconv",
        command: "build",
        runs_commands: true,
    },
    program("rcalc", "calc"),
    program("vwrays", "vwrays"),
    program("cnt", "cnt"),
    program("genbox", "genbox"),
    program("gendaylit", "gendaylit"),
    program("genprism", "genprism"),
    program("genrev", "genrev"),
    program("gensky", "gensky"),
    program("gensurf", "gensurf"),
    program("genworm", "genworm"),
    Program {
        name: "xform",
        command: "xform",
        runs_commands: true,
    },
    program("getinfo", "getinfo"),
    program("pfilt", "pfilt"),
    program("total", "total"),
    Program {
        name: "rlam",
        command: "rlam",
        runs_commands: true,
    },
    Program {
        name: "rsplit",
        command: "rsplit",
        runs_commands: true,
    },
    program("radcompare", "radcompare"),
    program("pvalue", "pvalue"),
    program("pflip", "pflip"),
    program("protate", "protate"),
    program("ra_ppm", "ra_ppm"),
    program("ra_rgbe", "ra_rgbe"),
    program("ra_xyze", "ra_xyze"),
];

/// The program a binary named `argv0` stands in for (`/usr/local/bin/rtrace` ->
/// rtrace); `None` for radc itself or a name radc does not know.
pub(super) fn called_as(argv0: &str) -> Option<&'static Program> {
    let name = Path::new(argv0).file_stem()?.to_str()?;
    PROGRAMS.iter().find(|p| p.name == name)
}

/// Runs `program` with the arguments Radiance's program would get.
/// The Radiance program radc was called as, once known (see [`printed_name`]).
static CALLED_AS: std::sync::OnceLock<&'static str> = std::sync::OnceLock::new();

/// The name a command gives itself where Radiance's program writes its `argv[0]` (a
/// header's command line, the padding after it): the program's name when radc was called
/// by it, `radc COMMAND` otherwise.
pub fn printed_name(command: &str) -> String {
    match CALLED_AS.get() {
        Some(name) => (*name).to_string(),
        None => format!("radc {command}"),
    }
}

pub(super) fn run(program: &Program, args: &[String]) -> ExitCode {
    let _ = CALLED_AS.set(program.name);
    let mut full = Vec::with_capacity(args.len() + 2);
    full.push(program.command.to_string());
    if program.runs_commands {
        full.push("--allow-commands".to_string());
    }
    full.extend(args.iter().cloned());
    super::dispatch(&full)
}

/// `radc links DIR`: a symbolic link to this binary in DIR for every program of
/// [`PROGRAMS`]. An existing link is replaced; any other file of that name is left
/// alone and reported, so a real Radiance installation is never overwritten.
pub(super) fn links(args: &[String]) -> ExitCode {
    let [dir] = args else {
        eprintln!("usage: radc links DIR");
        return ExitCode::from(USAGE_ERROR);
    };
    if dir == "--help" || dir == "-h" {
        println!(
            "usage: radc links DIR\n\nMakes a link named for each Radiance program radc stands in for \
             ({}) in DIR, pointing at this radc; put DIR first on PATH.",
            PROGRAMS
                .iter()
                .map(|p| p.name)
                .collect::<Vec<_>>()
                .join(" ")
        );
        return ExitCode::SUCCESS;
    }
    let exe = match std::env::current_exe().and_then(|p| p.canonicalize()) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("radc links: cannot find this program's path: {e}");
            return ExitCode::from(1);
        }
    };
    let dir = Path::new(dir);
    if let Err(e) = std::fs::create_dir_all(dir) {
        eprintln!("radc links: cannot make {}: {e}", dir.display());
        return ExitCode::from(1);
    }
    let mut failed = false;
    for p in PROGRAMS {
        let link = dir.join(p.name);
        match std::fs::symlink_metadata(&link) {
            Ok(m) if m.file_type().is_symlink() => {
                if let Err(e) = std::fs::remove_file(&link) {
                    eprintln!("radc links: cannot replace {}: {e}", link.display());
                    failed = true;
                    continue;
                }
            }
            Ok(_) => {
                eprintln!(
                    "radc links: {} exists and is not a link; left alone",
                    link.display()
                );
                failed = true;
                continue;
            }
            Err(_) => {}
        }
        if let Err(e) = symlink(&exe, &link) {
            eprintln!("radc links: cannot link {}: {e}", link.display());
            failed = true;
        }
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

#[cfg(unix)]
fn symlink(target: &Path, link: &Path) -> std::io::Result<()> {
    std::os::unix::fs::symlink(target, link)
}

#[cfg(not(unix))]
fn symlink(target: &Path, link: &Path) -> std::io::Result<()> {
    std::fs::copy(target, link).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_name_called_by_picks_the_program() {
        assert_eq!(
            called_as("/opt/radc/bin/rtrace").map(|p| p.command),
            Some("trace")
        );
        assert_eq!(called_as("oconv").map(|p| p.command), Some("build"));
        assert_eq!(called_as("rtrace.exe").map(|p| p.name), Some("rtrace"));
        assert!(called_as("radc").is_none());
        assert!(called_as("rcontrib").is_none(), "not stood in for: no link");
    }

    #[test]
    fn every_program_names_a_command() {
        for p in PROGRAMS {
            assert!(
                super::super::COMMANDS.iter().any(|c| c.name == p.command),
                "{} -> {}",
                p.name,
                p.command
            );
        }
    }
}
