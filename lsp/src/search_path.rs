//! Where auxiliary files (function files, data, pictures, fonts, octrees) are looked
//! for, as Radiance's `getpath` does with RAYPATH, plus the scene's own folder: an
//! absolute name as it is; otherwise the scene's folder, the current folder, then each
//! RAYPATH folder. Only existence is checked; nothing is read or run.

use std::path::{Path, PathBuf};

use radc_lang::db::AuxFiles;
use radc_lang::schema::FileKind;

pub struct SearchPath {
    raypath: Vec<PathBuf>,
}

impl SearchPath {
    /// `raypath` from the client's settings, or else the `RAYPATH` variable.
    pub fn new(raypath: Option<Vec<PathBuf>>) -> Self {
        let raypath = raypath.unwrap_or_else(|| {
            std::env::var_os("RAYPATH")
                .map(|v| std::env::split_paths(&v).collect())
                .unwrap_or_default()
        });
        SearchPath { raypath }
    }
}

impl AuxFiles for SearchPath {
    fn exists(&self, name: &str, _kind: FileKind, scene_path: &Path) -> bool {
        let p = Path::new(name);
        if p.is_absolute() {
            return p.exists();
        }
        let scene_dir = scene_path.parent().map(Path::to_path_buf);
        scene_dir
            .into_iter()
            .chain(std::iter::once(PathBuf::from(".")))
            .chain(self.raypath.iter().cloned())
            .any(|d| d.join(p).exists())
    }
}
