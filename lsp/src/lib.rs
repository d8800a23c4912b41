//! radc's language server: a thin adapter from the Language Server Protocol to
//! `radc_lang`'s incremental database. Diagnostics, hover text, completion snippets and
//! formatting are all computed in `lang`; this crate converts positions and types, and
//! is the one place (besides the CLI) that looks at the disk: it answers whether
//! auxiliary files exist. It never runs a `!` command.

mod config;
mod diagnostics;
mod document;
mod handlers;
mod rif;
mod search_path;
mod server;
mod session;

use tower_lsp_server::{LspService, Server};

/// Serves the protocol over standard input and output until the client says `exit`.
pub fn run_stdio() -> std::io::Result<()> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()?;
    runtime.block_on(async {
        let (service, socket) = LspService::new(server::Backend::new);
        Server::new(tokio::io::stdin(), tokio::io::stdout(), socket)
            .serve(service)
            .await;
    });
    Ok(())
}
