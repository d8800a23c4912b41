#!/usr/bin/env bash
# Builds and checks the extension offline: install the locked packages, run the
# grammar tests and the protocol test against `radc lsp` (RADC=path, default the
# workspace's target/debug/radc; skipped if absent), compile the client and package
# the .vsix. Not part of `cargo test`.
set -euo pipefail
cd "$(dirname "$0")"
npm ci --no-audit --no-fund
npm run test:grammar
npm run test:server
npm run compile
npm run package
echo "packaged: $(pwd)/radc-radiance.vsix"
