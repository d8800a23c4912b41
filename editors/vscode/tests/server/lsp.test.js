// Drives `radc lsp` with the protocol library the VS Code client uses, offline: the
// server must speak to vscode-languageclient's JSON-RPC exactly as to the Rust tests.
// RADC names the binary (default: the workspace's debug build).
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const fs = require("node:fs");
const { spawn } = require("node:child_process");
const {
  createProtocolConnection,
  StreamMessageReader,
  StreamMessageWriter,
} = require("vscode-languageserver-protocol/node");

const radc = process.env.RADC || path.join(__dirname, "../../../../target/debug/radc");

test("initialize, diagnostics, hover, shutdown", { skip: !fs.existsSync(radc) && `no ${radc}` }, async () => {
  const server = spawn(radc, ["lsp"], { stdio: ["pipe", "pipe", "inherit"] });
  const connection = createProtocolConnection(
    new StreamMessageReader(server.stdout),
    new StreamMessageWriter(server.stdin)
  );
  const diagnostics = new Promise((resolve) =>
    connection.onNotification("textDocument/publishDiagnostics", resolve)
  );
  connection.listen();

  const init = await connection.sendRequest("initialize", {
    processId: null,
    rootUri: null,
    capabilities: {},
    initializationOptions: { radc: { inlayHints: { enabled: true } } },
  });
  assert.strictEqual(init.serverInfo.name, "radc");
  await connection.sendNotification("initialized", {});

  const uri = "file:///tmp/radc-node-test.rad";
  const text = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\n\nred sphere ball\n0\n0\n3 0 0 0\n";
  await connection.sendNotification("textDocument/didOpen", {
    textDocument: { uri, languageId: "radiance", version: 1, text },
  });
  const published = await diagnostics;
  assert.deepStrictEqual(
    published.diagnostics.map((d) => [d.code, d.message]),
    [["E0202", "sphere takes 4 real arguments, found 3"]]
  );

  const hover = await connection.sendRequest("textDocument/hover", {
    textDocument: { uri },
    position: { line: 0, character: 7 },
  });
  assert.match(hover.contents.value, /^\*\*plastic\*\* \(material\)/);

  await connection.sendRequest("shutdown");
  await connection.sendNotification("exit");
  const code = await new Promise((resolve) => server.on("exit", resolve));
  assert.strictEqual(code, 0);
  connection.dispose();
});
