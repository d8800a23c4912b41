//! radc's language server: a thin adapter from the Language Server Protocol to
//! `radc_lang`'s incremental database. Diagnostics, hover text, completion snippets and
//! formatting are all computed in `lang`; this crate converts positions and types, and
//! is the one place (besides the CLI) that looks at the disk: it answers whether
//! auxiliary files exist. It never runs a `!` command.

mod aux_files;
mod calcomp;
mod config;
mod diagnostics;
mod document;
mod framing;
mod handlers;
mod rif;
mod server;
mod session;

use tower_lsp_server::{LspService, Server};

/// Generators evaluate calcomp curves recursively: the server runs on a thread with a
/// deep stack, as `radc genworm` does (reserved, not committed, memory).
const STACK: usize = 512 << 20;

/// Serves the protocol over standard input and output until the client says `exit`.
pub fn run_stdio() -> std::io::Result<()> {
    std::thread::Builder::new()
        .name("radc-lsp".into())
        .stack_size(STACK)
        .spawn(serve_stdio)?
        .join()
        .unwrap_or_else(|_| Err(std::io::Error::other("the server thread panicked")))
}

fn serve_stdio() -> std::io::Result<()> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()?;
    runtime.block_on(async {
        let (input, guarded) = tokio::io::duplex(1 << 16);
        tokio::spawn(framing::forward_valid_frames(tokio::io::stdin(), guarded));
        let (service, socket) = LspService::build(server::Backend::new)
            .custom_method("radc/stats", server::Backend::stats)
            .finish();
        Server::new(input, tokio::io::stdout(), socket)
            .serve(service)
            .await;
    });
    // The stdin reader may still be blocked in a read: do not wait for it.
    runtime.shutdown_timeout(std::time::Duration::from_millis(100));
    Ok(())
}
