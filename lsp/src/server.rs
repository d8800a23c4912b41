//! The `LanguageServer` implementation: decodes each request, runs its handler against
//! the session, and publishes diagnostics after every edit.
//!
//! tower-lsp-server runs handlers concurrently, so the session sits behind one mutex
//! that no handler holds across an `await`: every handler runs to completion on the
//! state it saw. Text changes carry versions: a whole text older than the current one
//! is ignored, range edits (incremental sync) apply in arrival order (each handler
//! applies its edit before its first `await`). Diagnostics are
//! computed and sent under a second, async lock, each time from the current text, so
//! the last diagnostics a client receives are always those of its latest text. A
//! handler that panics (a bug) answers "nothing" instead of taking the server down.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer};

use radc_lang::db::ParseCount;

use crate::config::Config;
use crate::document::{Document, Kind};
use crate::handlers;
use crate::session::Session;

pub struct Backend {
    client: Client,
    session: Mutex<Session>,
    publishing: tokio::sync::Mutex<()>,
    /// Whether the client asks for `workspace/inlayHint/refresh` after a settings change.
    refresh_inlay_hints: AtomicBool,
}

impl Backend {
    pub fn new(client: Client) -> Self {
        Backend {
            client,
            session: Mutex::new(Session::default()),
            publishing: tokio::sync::Mutex::new(()),
            refresh_inlay_hints: AtomicBool::new(false),
        }
    }

    fn session(&self) -> MutexGuard<'_, Session> {
        self.session.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Runs a handler on one open document (a scene or a calcomp file: `.rif` files
    /// have no analysis); `None` if it is not open, or the handler panicked.
    fn read<T>(&self, uri: &Uri, f: impl FnOnce(&Document<'_>, &Config) -> Option<T>) -> Option<T> {
        let session = self.session();
        let doc = session.document(uri).filter(|d| d.kind != Kind::Rif)?;
        catch_unwind(AssertUnwindSafe(|| f(&doc, &session.config)))
            .ok()
            .flatten()
    }

    /// [`Backend::read`] for requests only scenes answer.
    fn read_scene<T>(
        &self,
        uri: &Uri,
        f: impl FnOnce(&Document<'_>, &Config) -> Option<T>,
    ) -> Option<T> {
        self.read(uri, |doc, config| {
            (doc.kind == Kind::Scene).then(|| f(doc, config)).flatten()
        })
    }

    /// The `radc/stats` request (when `RADC_LSP_STATS` is set): how many times each
    /// file was parsed (whole, or the statements an edit touched) and how many
    /// statements were read, so a benchmark can show that an edit re-parses only its
    /// file, and only the statements it touched.
    pub async fn stats(&self) -> Result<serde_json::Value> {
        if std::env::var_os("RADC_LSP_STATS").is_none() {
            return Ok(serde_json::Value::Null);
        }
        let stats = self.session().parse_stats();
        let map = |f: fn(&ParseCount) -> u64| -> serde_json::Map<String, serde_json::Value> {
            stats
                .iter()
                .map(|(path, c)| (path.clone(), f(c).into()))
                .collect()
        };
        Ok(serde_json::json!({
            "parses": map(|c| c.parses),
            "whole_parses": map(|c| c.whole),
            "statements_read": map(|c| c.statements),
        }))
    }

    fn write(&self, f: impl FnOnce(&mut Session)) {
        let mut session = self.session();
        let _ = catch_unwind(AssertUnwindSafe(|| f(&mut session)));
    }

    async fn publish_all(&self) {
        let uris = self.session().open_uris();
        for uri in uris {
            self.publish(uri).await;
        }
    }

    async fn publish(&self, uri: Uri) {
        let _order = self.publishing.lock().await;
        // Diagnostics and the version they belong to, read under one lock.
        let found = {
            let session = self.session();
            let version = session.version(&uri);
            let diagnostics = session
                .document(&uri)
                .filter(|doc| doc.kind != Kind::Rif)
                .and_then(|doc| {
                    catch_unwind(AssertUnwindSafe(|| crate::diagnostics::for_document(&doc))).ok()
                });
            diagnostics.map(|d| (d, version))
        };
        if let Some((diagnostics, version)) = found {
            self.client
                .publish_diagnostics(uri, diagnostics, version)
                .await;
        }
    }
}

fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Options(
            TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(TextDocumentSyncKind::INCREMENTAL),
                save: Some(TextDocumentSyncSaveOptions::Supported(true)),
                ..TextDocumentSyncOptions::default()
            },
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Left(true)),
        document_highlight_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions::default()),
        inlay_hint_provider: Some(OneOf::Left(true)),
        signature_help_provider: Some(SignatureHelpOptions {
            trigger_characters: Some(vec![" ".into()]),
            ..SignatureHelpOptions::default()
        }),
        document_formatting_provider: Some(OneOf::Left(true)),
        color_provider: Some(ColorProviderCapability::Simple(true)),
        workspace_symbol_provider: Some(OneOf::Left(true)),
        code_action_provider: Some(CodeActionProviderCapability::Simple(true)),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: handlers::semantic_tokens::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                range: None,
                ..SemanticTokensOptions::default()
            },
        )),
        ..ServerCapabilities::default()
    }
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let refresh = params
            .capabilities
            .workspace
            .as_ref()
            .and_then(|w| w.inlay_hint.as_ref())
            .and_then(|i| i.refresh_support);
        self.refresh_inlay_hints
            .store(refresh == Some(true), Ordering::Relaxed);
        if let Some(options) = &params.initialization_options {
            self.write(|s| s.configure(options));
        }
        Ok(InitializeResult {
            capabilities: capabilities(),
            server_info: Some(ServerInfo {
                name: "radc".into(),
                version: Some(env!("CARGO_PKG_VERSION").into()),
            }),
            ..InitializeResult::default()
        })
    }

    async fn shutdown(&self) -> Result<()> {
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        let d = params.text_document;
        self.write(|s| s.open(d.uri.clone(), d.version, d.text));
        self.publish(d.uri).await;
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let uri = params.text_document.uri;
        let version = params.text_document.version;
        self.write(|s| s.change(&uri, version, params.content_changes));
        if Kind::of(&uri) == Kind::Cal {
            // Scenes that load this function file read its new text.
            self.publish_all().await;
        } else {
            self.publish(uri).await;
        }
    }

    async fn did_save(&self, params: DidSaveTextDocumentParams) {
        // A save may create or remove a file another scene names.
        self.write(Session::file_system_changed);
        let uris = self.session().open_uris();
        for uri in uris {
            self.publish(uri).await;
        }
        let _ = params;
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        self.write(|s| s.close(&uri));
        self.client.publish_diagnostics(uri, Vec::new(), None).await;
    }

    async fn did_change_configuration(&self, params: DidChangeConfigurationParams) {
        self.write(|s| s.configure(&params.settings));
        let uris = self.session().open_uris();
        for uri in uris {
            self.publish(uri).await;
        }
        if self.refresh_inlay_hints.load(Ordering::Relaxed) {
            // The answer carries nothing; a client that fails it just keeps old hints.
            let _ = self.client.inlay_hint_refresh().await;
        }
    }

    async fn did_change_watched_files(&self, _: DidChangeWatchedFilesParams) {
        self.write(Session::file_system_changed);
        let uris = self.session().open_uris();
        for uri in uris {
            self.publish(uri).await;
        }
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let p = params.text_document_position_params;
        Ok(self.read(&p.text_document.uri, |doc, _| match doc.kind {
            Kind::Cal => handlers::cal_hover::hover(doc, p.position),
            _ => handlers::hover::hover(doc, p.position),
        }))
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        let p = params.text_document_position_params;
        Ok(self.read(&p.text_document.uri, |doc, _| match doc.kind {
            Kind::Cal => handlers::cal_definition::definition(doc, p.position),
            _ => handlers::definition::definition(doc, p.position),
        }))
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        let p = params.text_document_position;
        let declaration = params.context.include_declaration;
        Ok(self.read(&p.text_document.uri, |doc, _| match doc.kind {
            Kind::Cal => handlers::cal_references::references(doc, p.position, declaration),
            _ => handlers::references::references(doc, p.position, declaration),
        }))
    }

    async fn rename(&self, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
        let p = params.text_document_position;
        Ok(self.read(&p.text_document.uri, |doc, _| match doc.kind {
            Kind::Cal => handlers::cal_rename::rename(doc, p.position, &params.new_name),
            _ => handlers::rename::rename(doc, p.position, &params.new_name),
        }))
    }

    async fn document_highlight(
        &self,
        params: DocumentHighlightParams,
    ) -> Result<Option<Vec<DocumentHighlight>>> {
        let p = params.text_document_position_params;
        Ok(self.read_scene(&p.text_document.uri, |doc, _| {
            handlers::highlights::highlights(doc, p.position)
        }))
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        Ok(self.read(&params.text_document.uri, |doc, _| {
            let symbols = match doc.kind {
                Kind::Cal => handlers::cal_symbols::symbols(doc),
                _ => handlers::symbols::symbols(doc),
            };
            Some(DocumentSymbolResponse::Nested(symbols))
        }))
    }

    async fn symbol(
        &self,
        params: WorkspaceSymbolParams,
    ) -> Result<Option<WorkspaceSymbolResponse>> {
        let session = self.session();
        let found = catch_unwind(AssertUnwindSafe(|| {
            handlers::workspace_symbols::symbols(&session, &params.query)
        }));
        Ok(found.ok().map(WorkspaceSymbolResponse::Flat))
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        let p = params.text_document_position;
        Ok(self.read(&p.text_document.uri, |doc, _| {
            let items = match doc.kind {
                Kind::Cal => handlers::cal_completion::completion(doc, p.position),
                _ => handlers::completion::completion(doc, p.position),
            };
            items.map(CompletionResponse::Array)
        }))
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        Ok(self.read(&params.text_document.uri, |doc, _| {
            let tokens = handlers::semantic_tokens::tokens(doc);
            Some(SemanticTokensResult::Tokens(tokens))
        }))
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        Ok(self.read(&params.text_document.uri, |doc, _| {
            Some(handlers::code_actions::code_actions(
                doc,
                &params.context.diagnostics,
            ))
        }))
    }

    async fn signature_help(&self, params: SignatureHelpParams) -> Result<Option<SignatureHelp>> {
        let p = params.text_document_position_params;
        Ok(self.read_scene(&p.text_document.uri, |doc, _| {
            handlers::signature_help::signature_help(doc, p.position)
        }))
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        Ok(self.read_scene(&params.text_document.uri, |doc, config| {
            config
                .inlay_hints
                .then(|| handlers::inlay_hints::inlay_hints(doc, params.range))
        }))
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        Ok(self.read_scene(&params.text_document.uri, |doc, _| {
            handlers::formatting::formatting(doc)
        }))
    }

    async fn document_color(&self, params: DocumentColorParams) -> Result<Vec<ColorInformation>> {
        let found = self.read_scene(&params.text_document.uri, |doc, _| {
            Some(handlers::colors::document_colors(doc))
        });
        Ok(found.unwrap_or_default())
    }

    async fn color_presentation(
        &self,
        params: ColorPresentationParams,
    ) -> Result<Vec<ColorPresentation>> {
        let found = self.read_scene(&params.text_document.uri, |doc, _| {
            Some(handlers::colors::presentations(
                doc,
                params.color,
                params.range,
            ))
        });
        Ok(found.unwrap_or_default())
    }
}
