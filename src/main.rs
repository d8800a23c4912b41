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
    inspect_jit_from_environment();
    cli::main(&argv0, &args)
}

/// The JIT's inspection switches, for people working on it (`jit::compile::inspect`):
/// `RADC_JIT_VERIFY=1`, `RADC_JIT_DUMP=1` (CLIF and machine code on stderr),
/// `RADC_JIT_CODE_DIR=dir` (machine code files).
fn inspect_jit_from_environment() {
    let on = |name: &str| std::env::var_os(name).is_some();
    if !(on("RADC_JIT_VERIFY") || on("RADC_JIT_DUMP") || on("RADC_JIT_CODE_DIR")) {
        return;
    }
    radc_jit::compile::inspect::set(radc_jit::compile::inspect::Inspection {
        verify: on("RADC_JIT_VERIFY"),
        listing: on("RADC_JIT_DUMP").then_some(|text: &str| eprintln!("{text}")),
        code_dir: std::env::var_os("RADC_JIT_CODE_DIR").map(std::path::PathBuf::from),
    });
}
