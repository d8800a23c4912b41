//! Scenes made of several files. Radiance projects list their files in a `rad` input
//! file (`.rif`): `materials = basic.mat`, then `scene = walls.rad table.rad`, read in
//! that order by oconv. A wall file opened on its own would use materials it does not
//! define, so a document listed by a `.rif` in its folder is checked together with the
//! rif's other files, exactly as `radc check basic.mat walls.rad table.rad` would be.

use std::path::{Path, PathBuf};

/// The `materials` then `scene` files of one rif text, in order, as written. `rad`
/// appends repeated assignments and matches variable names by their first three
/// letters, case-insensitively.
pub fn scene_files(rif: &str) -> Vec<String> {
    let mut materials = Vec::new();
    let mut scene = Vec::new();
    for line in rif.lines() {
        let line = line.split('#').next().unwrap_or("");
        let Some((name, value)) = line.split_once('=') else {
            continue;
        };
        let name = name.trim().to_ascii_lowercase();
        let list = match name.get(..3) {
            Some("mat") if "materials".starts_with(&name) => &mut materials,
            Some("sce") if "scene".starts_with(&name) => &mut scene,
            _ => continue,
        };
        list.extend(value.split_whitespace().map(String::from));
    }
    materials.extend(scene);
    materials
}

/// The files of the first `.rif` (by name) in the document's folder that lists the
/// document, resolved against that folder; `None` if no rif lists it.
pub fn scene_of(document: &Path) -> Option<Vec<PathBuf>> {
    let dir = document.parent()?;
    let mut rifs: Vec<PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "rif"))
        .collect();
    rifs.sort();
    let me = canonical(document);
    rifs.into_iter().find_map(|rif| {
        let text = std::fs::read_to_string(&rif).ok()?;
        let files: Vec<PathBuf> = scene_files(&text).iter().map(|f| dir.join(f)).collect();
        files.iter().any(|f| canonical(f) == me).then_some(files)
    })
}

pub fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn materials_come_first_and_assignments_append() {
        let rif = "# test\nOCTREE = x.oct\nscene = walls.rad table.rad\nmaterials = basic.mat\n\
                   scene = sky.rad # the sky\nSCE= lamp.rad\nmat=extra.mat\nview = def -vf v.vf\n";
        assert_eq!(
            scene_files(rif),
            [
                "basic.mat",
                "extra.mat",
                "walls.rad",
                "table.rad",
                "sky.rad",
                "lamp.rad"
            ]
        );
    }
}
