#!/usr/bin/env bash
# Builds and checks the extension offline: install the locked packages, run the
# grammar tests, compile the client and package the .vsix. Not part of `cargo test`.
set -euo pipefail
cd "$(dirname "$0")"
npm ci --no-audit --no-fund
npm run test:grammar
npm run compile
npm run package
echo "packaged: $(pwd)/radc-radiance.vsix"
