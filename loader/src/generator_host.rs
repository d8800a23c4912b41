//! Files for generators run from a scene (`Policy::SceneRaypath`): relative to the
//! scene's folder, then RAYPATH, then radc's built-in function files (`-f rayinit.cal`
//! with no Radiance installed). What the generators would print on standard error is
//! kept as warnings. Commands nested in files xform reads are refused (the trait's
//! default). The CLI and the language server use this one host.

use std::path::PathBuf;

use radc_generators::{GenError, Host, read_on_path};
use radc_lang::search_path::SearchPath;

pub struct GeneratorHost<'a> {
    dir: PathBuf,
    search: &'a SearchPath,
    /// What the generators would have printed on standard error.
    pub warnings: Vec<String>,
}

impl<'a> GeneratorHost<'a> {
    pub fn new(dir: PathBuf, search: &'a SearchPath) -> Self {
        GeneratorHost {
            dir,
            search,
            warnings: Vec::new(),
        }
    }
}

impl Host for GeneratorHost<'_> {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        read_on_path(self.search, path, Some(&self.dir), |c| {
            std::fs::read(c).ok()
        })
    }

    /// A generator run from a scene has no input of its own (a pipeline's stages
    /// pass their text inside `run_builtin`).
    fn read_stdin(&mut self) -> Result<String, GenError> {
        Ok(String::new())
    }

    fn warn(&mut self, line: &str) {
        self.warnings.push(line.to_string());
    }
}
