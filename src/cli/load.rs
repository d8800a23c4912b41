//! The scene a rendering command was given, loaded by `radc_loader` and reported as
//! the command reports it: diagnostics on stderr, then why nothing is rendered.

use std::path::PathBuf;
use std::process::ExitCode;

use radc_loader::{LoadError, LoadOptions, SceneBundle};
use radc_renderer::Scene;

use super::USAGE_ERROR;
use super::report;

/// The compiled scene `paths` name, or the exit code after reporting why there is none.
pub(super) fn load_scene(
    paths: &[PathBuf],
    command: &str,
    options: LoadOptions,
) -> Result<Scene, ExitCode> {
    load_scene_bundled(paths, command, options).map(|(scene, _)| scene)
}

/// [`load_scene`], and the scene as read, for `radc build` to store when a compiled
/// scene cannot hold it (`None` when a compiled scene was loaded).
pub(super) fn load_scene_bundled(
    paths: &[PathBuf],
    command: &str,
    options: LoadOptions,
) -> Result<(Scene, Option<SceneBundle>), ExitCode> {
    let load = radc_loader::load_scene(paths, options);
    report::eprint(&load.diagnostics, &load.sources);
    let bundle = load.bundle;
    load.scene
        .map(|scene| (scene, bundle))
        .map_err(|e| match e {
            LoadError::Usage(m) => {
                errln!("radc {command}: {m}");
                ExitCode::from(USAGE_ERROR)
            }
            LoadError::Refused(messages) => {
                for m in messages {
                    errln!("radc {command}: {m}");
                }
                ExitCode::from(1)
            }
        })
}

/// Prints what evaluating the scene's functions warned of (once each), as rtrace
/// prints them; an evaluation that failed outright (Radiance stops there) makes the
/// exit status 1.
pub(super) fn report_functions(scene: &Scene, command: &str) -> ExitCode {
    let Some(functions) = scene.functions.as_deref() else {
        return ExitCode::SUCCESS;
    };
    let (messages, failed) = functions.take_messages();
    for m in messages {
        errln!("radc {command}: {m}");
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
