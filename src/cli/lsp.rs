//! `radc lsp`: the language server over stdio, for editors (see `editors/vscode`).

use std::process::ExitCode;

use super::USAGE_ERROR;

pub fn run(args: &[String]) -> ExitCode {
    // `--stdio` is what vscode-languageclient passes; it is the only transport.
    if let Some(other) = args.iter().find(|a| a.as_str() != "--stdio") {
        eprintln!("radc lsp: unknown option '{other}'\nusage: radc lsp [--stdio]");
        return ExitCode::from(USAGE_ERROR);
    }
    match radc_lsp::run_stdio() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("radc lsp: {e}");
            ExitCode::from(1)
        }
    }
}
