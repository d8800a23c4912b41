#!/usr/bin/env bash
# Re-runs every golden generator in --check mode against live Radiance: a golden that
# no longer matches the oracle fails CI. Each regen_*.py owns one golden set.
set -euo pipefail
cd "$(dirname "$0")/../.."
source tests/oracle/env.sh
status=0
for script in tests/oracle/regen_*.py; do
  [ -e "$script" ] || continue
  echo "-- $script --check"
  .oracle/bin/python "$script" --check || status=1
done
exit $status
