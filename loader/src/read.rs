//! Scene files read from disk, parsed and lowered in order as one scene, as oconv reads
//! them: each file streams from the parser into the lowering, auxiliary files are
//! found along the search path (`SceneFiles`) and `!` lines expanded (`Commands`).

use std::path::{Path, PathBuf};

use radc_lang::scene::{self, Keep, Lowering};
use radc_lang::{Diagnostic, FileId};

use crate::bundle::{BundledFile, RecordedExpansion, SceneBundle};
use crate::commands::Commands;
use crate::pending::PendingSources;
use crate::scene_files::SceneFiles;
use crate::sources::Sources;

/// Reads, parses and lowers `paths` in order as one scene. Each file streams from the
/// parser into the lowering; with `Keep::Modifiers` (all `radc check` needs) the
/// surfaces are checked and dropped, so a check holds little more than the text.
pub fn read_scene(
    paths: &[PathBuf],
    allow_commands: bool,
    keep: Keep,
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
) -> scene::ir::Scene {
    read_scene_bundled(paths, allow_commands, keep, sources, diags).0
}

/// [`read_scene`], and the scene as a [`SceneBundle`]: its files' texts and its
/// commands' outputs, enough to read the same scene again without the disk's scene
/// files or running anything.
pub fn read_scene_bundled(
    paths: &[PathBuf],
    allow_commands: bool,
    keep: Keep,
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
) -> (scene::ir::Scene, SceneBundle) {
    let mut read = Vec::new();
    let mut dirs = Vec::new();
    let mut files = Vec::new();
    for path in paths {
        let mut found = Vec::new();
        let Some(id) = read_source(path, sources, &mut found) else {
            diags.extend(found);
            continue;
        };
        let warn_unused = path.extension().is_none_or(|x| x != "mat");
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        files.push(BundledFile {
            name: path.display().to_string(),
            dir: absolute_dir(&dir).display().to_string(),
            text: sources.get(id).map_or_else(String::new, |s| s.text.clone()),
            warn_unused,
        });
        dirs.push((id, dir));
        read.push((id, found, warn_unused));
    }
    let (scene, expansions) = lower(
        read,
        dirs,
        Expanding::Run { allow_commands },
        keep,
        sources,
        diags,
    );
    let mut bundle = SceneBundle {
        files,
        expansions,
        meshes: Vec::new(),
    };
    bundle.stamp_meshes(&scene);
    (scene, bundle)
}

/// Reads the scene a [`SceneBundle`] holds, as [`read_scene`] read it when it was
/// built: its commands' outputs come from the bundle, nothing is run.
pub fn read_bundle(
    bundle: &SceneBundle,
    keep: Keep,
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
) -> scene::ir::Scene {
    let mut read = Vec::new();
    let mut dirs = Vec::new();
    for f in &bundle.files {
        let id = sources.add(f.name.clone(), f.text.clone());
        dirs.push((id, PathBuf::from(&f.dir)));
        read.push((id, Vec::new(), f.warn_unused));
    }
    let replay = Expanding::Replay(bundle.expansions.clone());
    lower(read, dirs, replay, keep, sources, diags).0
}

/// How `!` lines are answered.
enum Expanding {
    Run { allow_commands: bool },
    Replay(Vec<RecordedExpansion>),
}

/// Lowers the files read, in order, as one scene; the expansions made, in order.
fn lower(
    read: Vec<(FileId, Vec<Diagnostic>, bool)>,
    dirs: Vec<(FileId, PathBuf)>,
    expanding: Expanding,
    keep: Keep,
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
) -> (scene::ir::Scene, Vec<RecordedExpansion>) {
    let pending = PendingSources::new(sources.next_id().0);
    let commands = match expanding {
        Expanding::Run { allow_commands } => Commands::new(dirs.clone(), &pending, allow_commands),
        Expanding::Replay(recorded) => Commands::replaying(dirs.clone(), &pending, recorded),
    };
    let lookup = SceneFiles::new(dirs, &pending);
    let mut lowering = Lowering::new(&lookup, &commands, keep);
    for (id, found, warn_unused) in read {
        let text = sources.get(id).map_or("", |s| s.text.as_str());
        diags.extend(found);
        diags.extend(scene::parse_each(id, text, &mut |item| {
            lowering.item(item, warn_unused)
        }));
    }
    let (scene, more) = lowering.finish();
    drop(lookup);
    let recorded = commands.into_recorded();
    for (name, text) in pending.into_sources() {
        sources.add(name, text);
    }
    diags.extend(more);
    (scene, recorded)
}

/// `dir` made absolute (the current folder for an empty one), so a bundle read from
/// another folder finds what the scene's folder held.
fn absolute_dir(dir: &Path) -> PathBuf {
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf())
}

/// Reads a file the user named and decodes it, registering it as the next source.
/// An unreadable file is an E0305 diagnostic (registered empty), not a failure.
pub fn read_source(
    path: &Path,
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
) -> Option<FileId> {
    let name = path.display().to_string();
    match std::fs::read(path) {
        Ok(bytes) => {
            let (text, found) = radc_lang::source::decode_owned(sources.next_id(), bytes);
            diags.extend(found);
            Some(sources.add(name, text))
        }
        Err(e) => {
            let file = sources.add(name.clone(), String::new());
            diags.push(Diagnostic::new(
                radc_lang::diagnostic::E0305,
                radc_lang::Span::new(file, 0..0),
                format!("cannot read '{name}': {e}"),
            ));
            None
        }
    }
}
