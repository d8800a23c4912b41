// The VS Code side of radc: starts `radc lsp` and hands it the scene and calcomp
// documents.
// Everything the editor shows (diagnostics, hover, completion, formatting) comes from
// the server; this file only wires settings and the process.

import * as vscode from "vscode";
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
} from "vscode-languageclient/node";

let client: LanguageClient | undefined;

/// The settings the server reads (see lsp/src/config.rs), under a `radc` key.
function serverSettings(): object {
  const cfg = vscode.workspace.getConfiguration("radc");
  return {
    radc: {
      inlayHints: { enabled: cfg.get<boolean>("inlayHints.enabled", true) },
      generators: { enabled: cfg.get<boolean>("generators.enabled", true) },
      raypath: cfg.get<string[]>("raypath", []).length > 0 ? cfg.get<string[]>("raypath") : null,
    },
  };
}

function createClient(): LanguageClient {
  const cfg = vscode.workspace.getConfiguration("radc");
  const command = cfg.get<string>("server.path", "radc") || "radc";
  const serverOptions: ServerOptions = {
    run: { command, args: ["lsp"] },
    debug: { command, args: ["lsp"] },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: "file", language: "radiance" },
      { scheme: "untitled", language: "radiance" },
      { scheme: "file", language: "calcomp" },
    ],
    initializationOptions: serverSettings(),
    synchronize: {
      // Scene files of a .rif, and the function, data and picture files scenes name:
      // their changes on disk change diagnostics.
      fileEvents: vscode.workspace.createFileSystemWatcher(
        "**/*.{rif,rad,mat,cal,dat,hdr,pic,oct,rtm,xml,fnt}"
      ),
    },
  };
  return new LanguageClient("radc", "radc language server", serverOptions, clientOptions);
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  client = createClient();
  context.subscriptions.push(
    vscode.commands.registerCommand("radc.restartServer", async () => {
      await client?.stop();
      client = createClient();
      await client.start();
    }),
    vscode.workspace.onDidChangeConfiguration(async (e) => {
      if (!client) {
        return;
      }
      if (e.affectsConfiguration("radc.server.path")) {
        await vscode.commands.executeCommand("radc.restartServer");
      } else if (e.affectsConfiguration("radc")) {
        await client.sendNotification("workspace/didChangeConfiguration", {
          settings: serverSettings(),
        });
      }
    })
  );
  try {
    await client.start();
  } catch (err) {
    void vscode.window.showErrorMessage(
      `Could not start 'radc lsp' (set radc.server.path): ${String(err)}`
    );
  }
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
