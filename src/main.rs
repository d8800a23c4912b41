//! `radc`: the command-line front end. Each subcommand lives in `cli/<name>.rs` and
//! parses its own arguments, so commands that mirror a Radiance program (`calc` for
//! rcalc, `genbox`, ...) can accept that program's option syntax unchanged.

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    // Arguments that are not UTF-8 are taken lossily rather than panicking.
    let mut argv = std::env::args_os().map(|a| a.to_string_lossy().into_owned());
    let argv0 = argv.next().unwrap_or_default();
    let args: Vec<String> = argv.collect();
    cli::main(&argv0, &args)
}
