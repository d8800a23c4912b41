//! `radc`: the command-line front end. Each subcommand lives in `cli/<name>.rs` and
//! parses its own arguments, so commands that mirror a Radiance program (`calc` for
//! rcalc, `genbox`, ...) can accept that program's option syntax unchanged.

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    cli::dispatch(&args)
}
