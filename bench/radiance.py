"""Where the benchmarks find real Radiance: one definition for every script here.

Radiance's programs on PATH win; otherwise the oracle venv that `bash
tests/oracle/install.sh` makes in `.oracle/` supplies them (pyradiance ships the
binaries under `bin/` and the `.cal` library under `lib/`).
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def radiance_env(*programs):
    """A copy of the environment with Radiance's programs on PATH and its library on
    RAYPATH. Exits with advice when one of `programs` cannot be found."""
    env = dict(os.environ)
    if programs and all(shutil.which(p) for p in programs):
        return env
    py = ROOT / ".oracle" / "bin" / "python"
    if not py.exists():
        wanted = programs[0] if programs else "Radiance"
        sys.exit(f"{wanted} not found: run `bash tests/oracle/install.sh` (or put Radiance on PATH)")
    pkg = subprocess.check_output(
        [str(py), "-c", "import pyradiance, os; print(os.path.dirname(pyradiance.__file__))"],
        text=True,
    ).strip()
    env["PATH"] = f"{pkg}/bin{os.pathsep}{env.get('PATH', '')}"
    env["RAYPATH"] = f".{os.pathsep}{pkg}/lib"
    return env
