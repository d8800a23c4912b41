//! A scene ready to render, from the arguments `radc trace`, `render` and `build` are
//! given: a compiled scene (`.rsc`) loaded as it is, or scene files read, checked and
//! compiled. Scenes with errors, with `!` lines not run, or with what the renderer does
//! not model are refused; octrees and pictures are refused by name. The messages are
//! the caller's to print (after the diagnostics, with its own name before them).

use std::path::PathBuf;

use radc_lang::scene::Keep;
use radc_lang::{Diagnostic, Severity};
use radc_renderer::{Scene, scene_file};

use crate::bundle::SceneBundle;
use crate::kind::{Kind, file_kind, picture_description};
use crate::read::{read_bundle, read_scene_bundled};
use crate::sources::Sources;

/// How scene files are read.
#[derive(Clone, Copy, Debug, Default)]
pub struct LoadOptions {
    /// Report warnings (errors, and `!` lines not run, are always reported).
    pub warnings: bool,
    /// Run `!` lines other than radc's built-in generators through `sh`.
    pub allow_commands: bool,
}

/// Why there is no scene.
#[derive(Debug)]
pub enum LoadError {
    /// The arguments cannot be used together (the caller's usage error).
    Usage(String),
    /// The scene cannot be rendered: one message each.
    Refused(Vec<String>),
}

/// The outcome of [`load_scene`]: what was read, what was found, and the scene.
pub struct SceneLoad {
    pub sources: Sources,
    /// Sorted by file and position; warnings only if asked for.
    pub diagnostics: Vec<Diagnostic>,
    pub scene: Result<Scene, LoadError>,
    /// The scene as read (its texts and commands' outputs), for `radc build` to store
    /// where a compiled scene cannot hold it; `None` when a compiled scene was loaded.
    pub bundle: Option<SceneBundle>,
}

/// A scene file `radc build` wrote.
enum Stored {
    Scene(Box<Scene>),
    Bundle(SceneBundle),
}

/// Loads the scene `paths` name (see the module doc).
pub fn load_scene(paths: &[PathBuf], options: LoadOptions) -> SceneLoad {
    let mut sources = Sources::default();
    let mut diags = Vec::new();
    let (ir, bundle) = match load_compiled(paths) {
        Some(Ok(Stored::Scene(scene))) => {
            return SceneLoad {
                sources,
                diagnostics: Vec::new(),
                scene: Ok(*scene),
                bundle: None,
            };
        }
        Some(Err(e)) => {
            return SceneLoad {
                sources,
                diagnostics: Vec::new(),
                scene: Err(e),
                bundle: None,
            };
        }
        Some(Ok(Stored::Bundle(bundle))) => {
            let ir = read_bundle(&bundle, Keep::Everything, &mut sources, &mut diags);
            if let Some(changed) = bundle.changed_mesh(&ir) {
                return SceneLoad {
                    sources,
                    diagnostics: diags,
                    scene: Err(LoadError::Refused(vec![changed])),
                    bundle: None,
                };
            }
            (ir, bundle)
        }
        None => read_scene_bundled(
            paths,
            options.allow_commands,
            Keep::Everything,
            &mut sources,
            &mut diags,
        ),
    };
    diags.sort_by_key(|d| (d.span.file, d.span.start));
    // A `!` command's output is part of the scene Radiance renders; without it the
    // numbers would be silently wrong.
    let not_run = |d: &Diagnostic| d.code.id == radc_lang::diagnostic::W0303.id;
    let unexpanded = diags.iter().filter(|d| not_run(d)).count();
    if !options.warnings {
        diags.retain(|d| d.severity == Severity::Error || not_run(d));
    }
    let scene = if diags.iter().any(|d| d.severity == Severity::Error) {
        Err(LoadError::Refused(vec![
            "the scene has errors; nothing rendered".into(),
        ]))
    } else if unexpanded > 0 {
        Err(LoadError::Refused(vec![format!(
            "the scene has {unexpanded} '!' command line(s) radc does not run, so it would \
             render without what they make; run them and include their output"
        )]))
    } else {
        Scene::compile(&ir).map_err(|problems| {
            LoadError::Refused(
                problems
                    .iter()
                    .map(|p| {
                        let place = ir
                            .get(p.prim)
                            .and_then(|prim| {
                                let s = sources.get(prim.span.file)?;
                                let (line, col) =
                                    s.lines().line_col(&s.text, prim.span.start as usize);
                                Some(format!("{}:{line}:{col}: ", s.name))
                            })
                            .unwrap_or_default();
                        format!("{place}cannot render {p}")
                    })
                    .collect(),
            )
        })
    };
    SceneLoad {
        sources,
        diagnostics: diags,
        scene,
        bundle: Some(bundle),
    }
}

/// The compiled scene, if the scene arguments name one (by its magic bytes or a `.rsc`
/// extension); `None` when they are scene text. Octrees and pictures are refused by
/// name rather than parsed as text.
fn load_compiled(paths: &[PathBuf]) -> Option<Result<Stored, LoadError>> {
    let refused = |m: String| Some(Err(LoadError::Refused(vec![m])));
    let kinds: Vec<Kind> = paths.iter().map(|p| file_kind(p)).collect();
    let first = |kind: Kind| {
        paths
            .iter()
            .zip(&kinds)
            .find_map(|(p, k)| (*k == kind).then_some(p))
    };
    if let Some(p) = first(Kind::Octree) {
        return refused(format!(
            "{}: is a Radiance octree (made by oconv), which radc does not read; give the \
             scene's .rad files, or compile them with 'radc build'",
            p.display()
        ));
    }
    if let Some(p) = first(Kind::Picture) {
        let what = picture_description(p).unwrap_or_else(|| "a Radiance picture".into());
        return refused(format!(
            "{}: is {what}, not a scene; 'radc getinfo' and 'radc pvalue' read pictures, and \
             'radc render -o x.png {}' makes a PNG of one",
            p.display(),
            p.display()
        ));
    }
    let compiled = first(Kind::Compiled).or_else(|| first(Kind::Bundle))?;
    if paths.len() > 1 {
        return Some(Err(LoadError::Usage(format!(
            "{}: a compiled scene must be the only scene argument",
            compiled.display()
        ))));
    }
    let bundled = kinds.first() == Some(&Kind::Bundle);
    let loaded = std::fs::read(compiled)
        .map_err(|e| format!("cannot read it: {e}"))
        .and_then(|bytes| {
            if bundled {
                SceneBundle::decode(&bytes).map(Stored::Bundle)
            } else {
                scene_file::decode(&bytes)
                    .map(|s| Stored::Scene(Box::new(s)))
                    .map_err(|e| e.to_string())
            }
        });
    Some(loaded.map_err(|e| LoadError::Refused(vec![format!("{}: {e}", compiled.display())])))
}
