//! Subcommand dispatch. Exit codes: 0 success, 1 the input had errors, 2 usage error.

// First: its `errln!` macro is used by the modules below.
#[macro_use]
mod error_file;
mod build;
mod calc;
mod check;
mod cnt;
mod defaults;
mod doc;
mod fmt;
// `gen` is a reserved word in edition 2024, so the file is named for the task and the
// module for what it does.
#[path = "gen.rs"]
mod generate;
mod help;
mod load;
mod lsp;
mod options;
mod picture_tools;
pub(crate) mod programs;
mod radcompare;
mod render;
mod report;
mod rlam;
mod rsplit;
mod total;
mod trace;
mod vwrays;

use std::io::Write;
use std::process::ExitCode;

/// A subcommand: its name, a one-line summary for `radc help`, and its entry point
/// taking the arguments after the name.
struct Command {
    name: &'static str,
    summary: &'static str,
    run: fn(&[String]) -> ExitCode,
}

/// Every subcommand, in the order `radc help` lists them.
const COMMANDS: &[Command] = &[
    Command {
        name: "check",
        summary: "check scene files for errors (like oconv, but all errors at once)",
        run: check::run,
    },
    Command {
        name: "calc",
        summary: "evaluate calcomp expressions over records (rcalc-compatible)",
        run: calc::run,
    },
    Command {
        name: "build",
        summary: "compile scene files into a scene file render and trace load fast, like oconv",
        run: build::run,
    },
    Command {
        name: "trace",
        summary: "trace rays from stdin through a scene, like rtrace",
        run: trace::run,
    },
    Command {
        name: "render",
        summary: "render a scene to a Radiance picture, like rpict",
        run: render::run,
    },
    Command {
        name: "fmt",
        summary: "lay scene files out in Radiance's conventional form",
        run: fmt::run,
    },
    Command {
        name: "lsp",
        summary: "run the language server over standard input and output",
        run: lsp::run,
    },
    Command {
        name: "genbox",
        summary: "generate a box, as Radiance's genbox",
        run: generate::genbox,
    },
    Command {
        name: "gendaylit",
        summary: "generate a Perez all-weather sky and sun, as Radiance's gendaylit",
        run: generate::gendaylit,
    },
    Command {
        name: "genprism",
        summary: "generate an extruded polygon, as Radiance's genprism",
        run: generate::genprism,
    },
    Command {
        name: "genrev",
        summary: "generate a surface of revolution, as Radiance's genrev",
        run: generate::genrev,
    },
    Command {
        name: "gensky",
        summary: "generate a CIE sky and sun, as Radiance's gensky",
        run: generate::gensky,
    },
    Command {
        name: "gensurf",
        summary: "generate a parametric surface, as Radiance's gensurf",
        run: generate::gensurf,
    },
    Command {
        name: "genworm",
        summary: "generate a worm along a calcomp curve, as Radiance's genworm",
        run: generate::genworm,
    },
    Command {
        name: "xform",
        summary: "transform a scene, as Radiance's xform",
        run: generate::xform,
    },
    Command {
        name: "cnt",
        summary: "count through every combination of counters, as Radiance's cnt",
        run: cnt::run,
    },
    Command {
        name: "total",
        summary: "reduce columns of records to sums, means, products or extremes, as Radiance's total",
        run: total::run,
    },
    Command {
        name: "rlam",
        summary: "join the records of several inputs side by side, as Radiance's rlam",
        run: rlam::run,
    },
    Command {
        name: "rsplit",
        summary: "split the fields of standard input among several outputs, as Radiance's rsplit",
        run: rsplit::run,
    },
    Command {
        name: "vwrays",
        summary: "print the rays of a view or of a picture's view, as Radiance's vwrays",
        run: vwrays::run,
    },
    Command {
        name: "getinfo",
        summary: "print the header of Radiance files, as Radiance's getinfo",
        run: picture_tools::getinfo::run,
    },
    Command {
        name: "pfilt",
        summary: "resample a picture with a box or Gaussian filter and an exposure, as Radiance's pfilt",
        run: picture_tools::pfilt::run,
    },
    Command {
        name: "radcompare",
        summary: "compare Radiance files (text, pictures, binary values) within tolerances, as Radiance's radcompare",
        run: radcompare::run,
    },
    Command {
        name: "pvalue",
        summary: "convert picture pixels to numbers and back, as Radiance's pvalue",
        run: picture_tools::pvalue::run,
    },
    Command {
        name: "pflip",
        summary: "flip a picture left to right or top to bottom, as Radiance's pflip",
        run: picture_tools::pflip::run,
    },
    Command {
        name: "protate",
        summary: "turn a picture a quarter turn, as Radiance's protate",
        run: picture_tools::protate::run,
    },
    Command {
        name: "ra_ppm",
        summary: "convert pictures to and from Poskanzer pixmaps, as Radiance's ra_ppm",
        run: picture_tools::ra_ppm::run,
    },
    Command {
        name: "ra_rgbe",
        summary: "copy pictures with flat or run-length scanlines, as Radiance's ra_rgbe",
        run: picture_tools::ra_rgbe::run,
    },
    Command {
        name: "ra_xyze",
        summary: "convert pictures between RGBE and XYZE, as Radiance's ra_xyze",
        run: picture_tools::ra_xyze::run,
    },
    Command {
        name: "doc",
        summary: "primitive type reference: 'doc types', 'doc plastic', 'doc codes'",
        run: doc::doc,
    },
    Command {
        name: "explain",
        summary: "what a diagnostic code means: 'explain E0301'",
        run: doc::explain,
    },
    Command {
        name: "links",
        summary: "make links named rtrace, oconv, rcalc, ... to radc in a folder for PATH",
        run: programs::links,
    },
    Command {
        name: "help",
        summary: "list the commands",
        run: help,
    },
];

pub const USAGE_ERROR: u8 = 2;

/// The program's entry: called by a Radiance program's name (a link made by `radc
/// links`), radc behaves as that program; otherwise the first argument names the command.
pub fn main(argv0: &str, args: &[String]) -> ExitCode {
    match programs::called_as(argv0) {
        Some(program) => programs::run(program, args),
        None => dispatch(args),
    }
}

pub fn dispatch(args: &[String]) -> ExitCode {
    let Some(name) = args.first() else {
        help(&[]);
        return ExitCode::from(USAGE_ERROR);
    };
    let name = match name.as_str() {
        "-h" | "--help" => "help",
        "-V" | "--version" => {
            let _ = writeln!(std::io::stdout(), "radc {}", env!("CARGO_PKG_VERSION"));
            return ExitCode::SUCCESS;
        }
        n => n,
    };
    match COMMANDS.iter().find(|c| c.name == name) {
        // `--help` on every command: its options, exit 0.
        Some(c) if args.get(1).is_some_and(|a| a == "--help") && c.name != "help" => {
            help::command(c.name, c.summary)
        }
        Some(c) => (c.run)(&args[1..]),
        None => {
            eprintln!("radc: unknown command '{name}'; run 'radc help' for the list");
            ExitCode::from(USAGE_ERROR)
        }
    }
}

/// `radc help` lists the commands; `radc help COMMAND` is `radc COMMAND --help`.
fn help(args: &[String]) -> ExitCode {
    if let Some(name) = args.first() {
        return match COMMANDS.iter().find(|c| c.name == name) {
            Some(c) => help::command(c.name, c.summary),
            None => {
                eprintln!("radc help: unknown command '{name}'; run 'radc help' for the list");
                ExitCode::from(USAGE_ERROR)
            }
        };
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "radc {}: a toolchain for the RADIANCE languages\n\nusage: radc <command> [options]\n\ncommands:",
        env!("CARGO_PKG_VERSION")
    );
    for c in COMMANDS {
        let _ = writeln!(out, "  {:<10} {}", c.name, c.summary);
    }
    ExitCode::SUCCESS
}
