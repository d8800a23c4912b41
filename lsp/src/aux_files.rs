//! The server's answers about the outside world, as `radc check` gives them: where
//! auxiliary files are (Radiance's `getpath` with RAYPATH, plus the scene's own
//! folder: an absolute name as it is; otherwise the scene's folder, the current folder,
//! then each RAYPATH folder), and the output of `!` lines that run one of radc's
//! built-in generators (in-process, pure). Any other command is never run.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use radc_generators::expansion::expansion;
use radc_lang::db::AuxFiles;
use radc_lang::scene::Expansion;
use radc_lang::schema::FileKind;
use radc_lang::search_path::{Found, Policy, SearchPath};
use radc_loader::generator_host::GeneratorHost;
use radc_loader::scene_files::MAX_AUX_FILE;

use crate::config::Config;

pub struct DiskAuxFiles {
    /// `Policy::SceneCurrentRaypath`, as `radc check` searches.
    search: SearchPath,
    /// The same folders in the order generators run from a scene search them
    /// (`Policy::SceneRaypath`, as `radc check` runs them).
    generator_search: SearchPath,
    generators: bool,
    overlay: Overlay,
}

/// Texts of open documents by canonical path: a scene reads the function file the
/// editor shows, saved or not.
#[derive(Clone, Default)]
pub struct Overlay(Arc<Mutex<HashMap<PathBuf, String>>>);

impl Overlay {
    /// Sets (or with `None` removes) the text of one file.
    pub fn set(&self, path: PathBuf, text: Option<String>) {
        let mut map = self.0.lock().unwrap_or_else(|e| e.into_inner());
        match text {
            Some(t) => map.insert(path, t),
            None => map.remove(&path),
        };
    }

    fn get(&self, path: &Path) -> Option<String> {
        let map = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if map.is_empty() {
            return None;
        }
        map.get(&crate::rif::canonical(path)).cloned()
    }
}

impl DiskAuxFiles {
    /// `raypath` from the client's settings, or else the `RAYPATH` variable; whether
    /// built-in generators expand.
    pub fn new(config: &Config, overlay: Overlay) -> Self {
        let raypath = config.raypath.clone().unwrap_or_else(|| {
            std::env::var_os("RAYPATH")
                .map(|v| std::env::split_paths(&v).collect())
                .unwrap_or_default()
        });
        DiskAuxFiles {
            search: SearchPath::with_folders(Policy::SceneCurrentRaypath, raypath.clone()),
            generator_search: SearchPath::with_folders(Policy::SceneRaypath, raypath),
            generators: config.generators,
            overlay,
        }
    }

    fn find(&self, name: &str, scene_path: &Path) -> Option<PathBuf> {
        self.search.find(name, scene_path.parent(), Path::exists)
    }

    /// A file on the search path, or else radc's built-in text of a library function
    /// file of that name (a user's file of that name wins, as in Radiance). Editors
    /// have no file to open for the built-in text, so `locate` does not report it.
    fn lookup(&self, name: &str, kind: FileKind, scene_path: &Path) -> Option<Found<()>> {
        self.search
            .lookup(name, kind, scene_path.parent(), Path::exists)
    }
}

impl AuxFiles for DiskAuxFiles {
    fn exists(&self, name: &str, kind: FileKind, scene_path: &Path) -> bool {
        self.lookup(name, kind, scene_path).is_some()
    }

    fn locate(&self, name: &str, _kind: FileKind, scene_path: &Path) -> Option<PathBuf> {
        self.find(name, scene_path)
    }

    fn read(&self, name: &str, kind: FileKind, scene_path: &Path) -> Option<String> {
        let path = match self.lookup(name, kind, scene_path)? {
            Found::File(path, ()) => path,
            Found::Builtin(text) => return Some(text.to_string()),
        };
        if let Some(text) = self.overlay.get(&path) {
            return Some(text);
        }
        if std::fs::metadata(&path).ok()?.len() > MAX_AUX_FILE {
            return None;
        }
        let bytes = std::fs::read(path).ok()?;
        Some(String::from_utf8_lossy(&bytes).into_owned())
    }

    fn read_head(
        &self,
        name: &str,
        kind: FileKind,
        scene_path: &Path,
        max: usize,
    ) -> Option<Vec<u8>> {
        use std::io::Read;
        let path = match self.lookup(name, kind, scene_path)? {
            Found::File(path, ()) => path,
            Found::Builtin(text) => return Some(text.bytes().take(max).collect()),
        };
        let file = std::fs::File::open(path).ok()?;
        let mut head = Vec::with_capacity(max.min(1 << 16));
        file.take(max as u64).read_to_end(&mut head).ok()?;
        Some(head)
    }

    fn expand(&self, command: &str, scene_path: &Path) -> Result<String, Expansion> {
        if !self.generators {
            return Err(Expansion::NotExpanded {
                reason: "expanding built-in generators is turned off in the settings".into(),
            });
        }
        let dir = scene_path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let mut host = GeneratorHost::new(dir, &self.generator_search);
        // The database numbers the output's file; `FileId(0)` stands in for it.
        match radc_generators::command::run_builtin(command, &mut host) {
            Some(result) => match expansion(result, &host.warnings, |_| radc_lang::FileId(0)) {
                Expansion::Text { text, .. } => Ok(text),
                other => Err(other),
            },
            None => Err(Expansion::NotExpanded {
                reason: "radc builds in genbox, gendaylit, genprism, genrev, gensky, gensurf, genworm and \
                         xform; the language server never runs other commands"
                    .into(),
            }),
        }
    }
}
