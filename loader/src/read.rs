//! Scene files read from disk, parsed and lowered in order as one scene, as oconv reads
//! them: each file streams from the parser into the lowering, auxiliary files are
//! found along the search path (`SceneFiles`) and `!` lines expanded (`Commands`).

use std::path::{Path, PathBuf};

use radc_lang::scene::{self, Keep, Lowering};
use radc_lang::{Diagnostic, FileId};

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
    let mut read = Vec::new();
    let mut dirs = Vec::new();
    for path in paths {
        let mut found = Vec::new();
        let Some(id) = read_source(path, sources, &mut found) else {
            diags.extend(found);
            continue;
        };
        let warn_unused = path.extension().is_none_or(|x| x != "mat");
        dirs.push((id, path.parent().map(Path::to_path_buf).unwrap_or_default()));
        read.push((id, found, warn_unused));
    }
    let pending = PendingSources::new(sources.next_id().0);
    let commands = Commands::new(dirs.clone(), &pending, allow_commands);
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
    drop((commands, lookup));
    for (name, text) in pending.into_sources() {
        sources.add(name, text);
    }
    diags.extend(more);
    scene
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
