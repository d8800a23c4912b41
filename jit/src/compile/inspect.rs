//! Looking inside the JIT's code, for people working on it: the Cranelift verifier in
//! release builds, each function's CLIF and machine code as text, and its machine code
//! as files (for `objdump -b binary -mi386:x86-64` against an instruction-level
//! `callgrind` profile). Off unless a front end turns it on ([`set`]); the `radc`
//! binary does for `RADC_JIT_VERIFY=1`, `RADC_JIT_DUMP=1` and `RADC_JIT_CODE_DIR=dir`.
//! The library never prints: listings go to the sink the front end gives.

use std::path::PathBuf;
use std::sync::OnceLock;

/// What to show of the generated code.
#[derive(Clone, Debug, Default)]
pub struct Inspection {
    /// Run Cranelift's verifier (always on in debug builds).
    pub verify: bool,
    /// Called with each function's CLIF, then its machine code, as text.
    pub listing: Option<fn(&str)>,
    /// Write each function's machine code to `dir/f<N>.bin`.
    pub code_dir: Option<PathBuf>,
}

static INSPECTION: OnceLock<Inspection> = OnceLock::new();

/// Turns inspection on for the process (the first call wins).
pub fn set(inspection: Inspection) {
    let _ = INSPECTION.set(inspection);
}

pub(crate) fn current() -> &'static Inspection {
    static NONE: Inspection = Inspection {
        verify: false,
        listing: None,
        code_dir: None,
    };
    INSPECTION.get().unwrap_or(&NONE)
}
