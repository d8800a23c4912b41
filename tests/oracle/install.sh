#!/usr/bin/env bash
# Installs the reference oracle (Radiance binaries from PyPI's pyradiance) into .oracle/
# and prints the environment to use it. Idempotent.
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ ! -x .oracle/bin/python ] || ! .oracle/bin/python -c 'import pyradiance' 2>/dev/null; then
  python3 -m venv .oracle
  .oracle/bin/pip install -q pyradiance
fi
R=$(.oracle/bin/python -c 'import pyradiance, os; print(os.path.dirname(pyradiance.__file__))')
echo "oracle: $R"
