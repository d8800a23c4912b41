//! Where an auxiliary file a scene, a generator or `radc calc -f` names is looked
//! for: one type for every front end, with the order each of them follows as an
//! explicit [`Policy`] (Radiance's programs differ: rcalc's `getpath` searches
//! RAYPATH only, the renderers' files are relative to where the scene is read).
//!
//! `lang` does no IO: a [`SearchPath`] lists the candidate paths in order, and the
//! caller says which exist or can be read. After the file system, radc's built-in
//! library ([`crate::library::builtin`]) answers for a name no folder holds, so a
//! user's file of that name wins, as in Radiance.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};

use crate::library;
use crate::schema::FileKind;

/// The order in which folders are searched for a relative name. An absolute name is
/// always taken as it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Policy {
    /// `radc check` and the language server: the folder of the scene that names the
    /// file, the current folder, then each RAYPATH folder (Radiance's `getpath` on
    /// RAYPATH, plus the scene's own folder, so a scene checks where it lies).
    SceneCurrentRaypath,
    /// Generators run from a scene's `!` line: the scene's folder (where the command
    /// runs), then each RAYPATH folder.
    SceneRaypath,
    /// `radc gen`: the name as given (the current folder), then each RAYPATH folder.
    CurrentRaypath,
    /// rcalc's `-f` (`getpath` with `getrlibpath`): names starting `./` or `../` (and
    /// `.`) as given, others in each RAYPATH folder (an empty entry is the current
    /// folder); the current folder alone when RAYPATH is unset.
    Getpath,
}

/// A policy and the RAYPATH folders it searches.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SearchPath {
    policy: Policy,
    raypath: Vec<PathBuf>,
}

/// What a lookup found: a file, or radc's own text of a library file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Found<T> {
    File(PathBuf, T),
    Builtin(&'static str),
}

impl SearchPath {
    /// The folders of a `RAYPATH` value (`std::env::var_os("RAYPATH")`), split as the
    /// platform splits paths.
    pub fn new(policy: Policy, raypath: Option<&OsStr>) -> Self {
        let raypath = match raypath {
            Some(v) => std::env::split_paths(v).collect(),
            None if policy == Policy::Getpath => vec![PathBuf::from(".")],
            None => Vec::new(),
        };
        SearchPath { policy, raypath }
    }

    /// Folders given directly (the language server's `raypath` setting).
    pub fn with_folders(policy: Policy, raypath: Vec<PathBuf>) -> Self {
        SearchPath { policy, raypath }
    }

    pub fn policy(&self) -> Policy {
        self.policy
    }

    /// The paths to try for `name`, in order; `scene_dir` is the folder of the scene
    /// (or of the command's scene) that names it, where the policy starts there.
    pub fn candidates(&self, name: &str, scene_dir: Option<&Path>) -> Vec<PathBuf> {
        let p = Path::new(name);
        if p.is_absolute() {
            return vec![p.to_path_buf()];
        }
        let raypath = self.raypath.iter().map(|d| d.join(p));
        match self.policy {
            Policy::SceneCurrentRaypath => scene_dir
                .map(|d| d.join(p))
                .into_iter()
                .chain(std::iter::once(Path::new(".").join(p)))
                .chain(raypath)
                .collect(),
            Policy::SceneRaypath => scene_dir
                .map(|d| d.join(p))
                .into_iter()
                .chain(raypath)
                .collect(),
            Policy::CurrentRaypath => std::iter::once(p.to_path_buf()).chain(raypath).collect(),
            Policy::Getpath => {
                if name.starts_with("./") || name.starts_with("../") || name == "." {
                    return vec![p.to_path_buf()];
                }
                self.raypath
                    .iter()
                    .map(|d| {
                        if d.as_os_str().is_empty() {
                            Path::new(".")
                        } else {
                            d
                        }
                    })
                    .map(|d| d.join(p))
                    .collect()
            }
        }
    }

    /// The first candidate that `exists`.
    pub fn find(
        &self,
        name: &str,
        scene_dir: Option<&Path>,
        exists: impl Fn(&Path) -> bool,
    ) -> Option<PathBuf> {
        self.candidates(name, scene_dir)
            .into_iter()
            .find(|c| exists(c))
    }

    /// A file of `kind` found on the path, or else, for a function file, radc's
    /// built-in text of that name.
    pub fn lookup(
        &self,
        name: &str,
        kind: FileKind,
        scene_dir: Option<&Path>,
        exists: impl Fn(&Path) -> bool,
    ) -> Option<Found<()>> {
        match self.find(name, scene_dir, exists) {
            Some(path) => Some(Found::File(path, ())),
            None if kind == FileKind::Cal => library::builtin(name).map(Found::Builtin),
            None => None,
        }
    }

    /// The text of the first candidate that `read` can read (invalid UTF-8 read as
    /// U+FFFD, as the generators read files), or else radc's built-in text of that
    /// name: how generators' hosts read the files they are given.
    pub fn read_text(
        &self,
        name: &str,
        scene_dir: Option<&Path>,
        read: impl Fn(&Path) -> Option<Vec<u8>>,
    ) -> Option<Found<String>> {
        for c in self.candidates(name, scene_dir) {
            if let Some(bytes) = read(&c) {
                return Some(Found::File(c, String::from_utf8_lossy(&bytes).into_owned()));
            }
        }
        library::builtin(name).map(Found::Builtin)
    }
}

impl Found<String> {
    pub fn into_text(self) -> String {
        match self {
            Found::File(_, text) => text,
            Found::Builtin(text) => text.to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(dirs: &[&str]) -> Vec<PathBuf> {
        dirs.iter().map(PathBuf::from).collect()
    }

    fn names(c: Vec<PathBuf>) -> Vec<String> {
        c.iter().map(|p| p.display().to_string()).collect()
    }

    #[test]
    fn each_policy_searches_in_its_order() {
        let dirs = path(&["/lib/ray", ""]);
        let scene = Some(Path::new("scenes"));
        let order = |policy| {
            names(SearchPath::with_folders(policy, dirs.clone()).candidates("a.cal", scene))
        };
        assert_eq!(
            order(Policy::SceneCurrentRaypath),
            ["scenes/a.cal", "./a.cal", "/lib/ray/a.cal", "a.cal"]
        );
        assert_eq!(
            order(Policy::SceneRaypath),
            ["scenes/a.cal", "/lib/ray/a.cal", "a.cal"]
        );
        assert_eq!(
            order(Policy::CurrentRaypath),
            ["a.cal", "/lib/ray/a.cal", "a.cal"]
        );
        assert_eq!(order(Policy::Getpath), ["/lib/ray/a.cal", "./a.cal"]);
    }

    #[test]
    fn absolute_and_dotted_names_are_taken_as_given() {
        for policy in [
            Policy::SceneCurrentRaypath,
            Policy::SceneRaypath,
            Policy::CurrentRaypath,
            Policy::Getpath,
        ] {
            let s = SearchPath::with_folders(policy, path(&["/lib"]));
            assert_eq!(
                names(s.candidates("/x/a.cal", Some(Path::new("d")))),
                ["/x/a.cal"]
            );
        }
        let s = SearchPath::with_folders(Policy::Getpath, path(&["/lib"]));
        assert_eq!(names(s.candidates("./a.cal", None)), ["./a.cal"]);
        assert_eq!(names(s.candidates("../a.cal", None)), ["../a.cal"]);
    }

    #[test]
    fn getpath_without_raypath_is_the_current_folder() {
        let s = SearchPath::new(Policy::Getpath, None);
        assert_eq!(names(s.candidates("a.cal", None)), ["./a.cal"]);
        let s = SearchPath::new(Policy::SceneCurrentRaypath, None);
        assert_eq!(names(s.candidates("a.cal", None)), ["./a.cal"]);
    }

    #[test]
    fn a_file_on_the_path_wins_over_the_library() {
        let s = SearchPath::new(Policy::SceneCurrentRaypath, None);
        let none = |_: &Path| false;
        assert!(matches!(
            s.lookup("rayinit.cal", FileKind::Cal, None, none),
            Some(Found::Builtin(_))
        ));
        assert_eq!(s.lookup("rayinit.cal", FileKind::Data, None, none), None);
        assert_eq!(
            s.lookup("rayinit.cal", FileKind::Cal, None, |_| true),
            Some(Found::File(PathBuf::from("./rayinit.cal"), ()))
        );
        let mine = s.read_text("rayinit.cal", None, |_| Some(b"x = 1;".to_vec()));
        assert_eq!(mine.map(Found::into_text).as_deref(), Some("x = 1;"));
        let builtin = s.read_text("rayinit.cal", None, |_| None);
        assert_eq!(
            builtin.map(Found::into_text).as_deref(),
            library::builtin("rayinit.cal")
        );
    }
}
