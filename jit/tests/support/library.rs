//! Radiance's `.cal` library as JIT programs, shared by the compile-size test and the
//! "library compile" bench group so that both measure the same programs. Where the library
//! is (the oracle's) is `radc_oracle::library`'s business.

use radc_lang::FileId;
use radc_lang::cal::{Env, Module};
use std::path::{Path, PathBuf};

/// One program per library file: `rayinit.cal` then the file, with every name the
/// file defines as an entry point. Each is (file name, program, entry names); files
/// that do not check are left out, and a missing `rayinit.cal` gives none.
pub fn library_programs(lib: &Path) -> Vec<(String, Module, Vec<String>)> {
    let Ok(rayinit) = std::fs::read_to_string(lib.join("rayinit.cal")) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(lib)
        .map(|d| d.filter_map(Result::ok).map(|e| e.path()).collect())
        .unwrap_or_default();
    files.retain(|f| f.extension().is_some_and(|x| x == "cal"));
    files.sort();
    let mut out = Vec::new();
    for f in files {
        let Ok(text) = std::fs::read_to_string(&f) else {
            continue;
        };
        let mut m = Module::new(&Env::renderer());
        m.add_source(FileId(0), &rayinit);
        let d = m.add_source(FileId(1), &text);
        if d.iter().any(|d| d.is_error()) {
            continue;
        }
        m.optimize();
        let mut names: Vec<String> = m
            .symbols()
            .iter()
            .filter(|s| {
                s.stack
                    .last()
                    .is_some_and(|&d| m.def(d).span.file == FileId(1))
            })
            .map(|s| s.name.clone())
            .collect();
        names.dedup();
        let name = f
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        out.push((name, m, names));
    }
    out
}
