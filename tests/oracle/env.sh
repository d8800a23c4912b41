# Source this to put the oracle's Radiance programs on PATH and its library on RAYPATH.
_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
ORACLE_DIR=$("$_root/.oracle/bin/python" -c 'import pyradiance, os; print(os.path.dirname(pyradiance.__file__))')
export ORACLE_DIR PATH="$ORACLE_DIR/bin:$PATH" RAYPATH=".:$ORACLE_DIR/lib"
