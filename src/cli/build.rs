//! `radc build`: oconv's role. Reads scene files as one scene (as `radc render` and
//! `radc trace` do: scenes with errors, or with what the renderer does not model, are
//! refused with their diagnostics), compiles it (reachable surfaces only, BVH built)
//! and writes the compiled scene file (`radc_renderer::scene_file`), which `render`
//! and `trace` load in place of the `.rad` files. A scene with functions (patterns,
//! textures) is stored as read instead (`radc_loader::bundle`): its functions are
//! compiled when it is rendered.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use radc_renderer::scene_file;

use super::USAGE_ERROR;
use super::load::load_scene_bundled;

const USAGE: &str = "usage: radc build [-w] [-f] [-n objlim] [-r maxres] [-b xmin ymin zmin size] \
[-o scene.rsc] scene.rad...";

struct Args {
    output: Option<PathBuf>,
    scenes: Vec<PathBuf>,
    warnings: bool,
    /// `--allow-commands`: run `!` lines other than the built-in generators.
    allow_commands: bool,
}

impl Args {
    fn load_options(&self) -> radc_loader::LoadOptions {
        radc_loader::LoadOptions {
            warnings: self.warnings,
            allow_commands: self.allow_commands,
        }
    }
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        output: None,
        scenes: Vec::new(),
        warnings: true,
        allow_commands: false,
    };
    let mut it = args.iter().map(String::as_str);
    while let Some(arg) = it.next() {
        match arg {
            "--allow-commands" => a.allow_commands = true,
            "-o" => a.output = Some(PathBuf::from(it.next().ok_or("-o needs a file name")?)),
            // oconv's -w turns warnings off.
            s if super::options::switch(s, "-w", &mut a.warnings) => {}
            // oconv's -f writes a frozen octree: a compiled scene always holds everything.
            "-f" => {}
            // oconv's octree limits: the BVH chooses its own leaves and depth.
            "-n" | "-r" => {
                super::options::number(&mut it, arg)?;
            }
            "-b" => {
                for _ in 0..4 {
                    super::options::number(&mut it, arg)?;
                }
            }
            "-i" => {
                return Err(
                    "-i (adding to an existing octree) is not supported: give all the \
                            scene files to one radc build"
                        .into(),
                );
            }
            "-help" | "--help" => return Err(String::new()),
            s if s.starts_with('-') && s.len() > 1 => return Err(format!("unknown option '{s}'")),
            path => a.scenes.push(PathBuf::from(path)),
        }
    }
    if a.scenes.is_empty() {
        return Err("no scene files".into());
    }
    Ok(a)
}

pub fn run(args: &[String]) -> ExitCode {
    super::options::with_deep_stacks(|| run_parsed(args))
}

fn run_parsed(args: &[String]) -> ExitCode {
    let a = match parse_args(args) {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("radc build: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    if a.output.is_none() && std::io::stdout().is_terminal() {
        eprintln!("radc build: not writing a binary scene to a terminal; use -o scene.rsc");
        return ExitCode::from(USAGE_ERROR);
    }
    let (scene, bundle) = match load_scene_bundled(&a.scenes, "build", a.load_options()) {
        Ok(s) => s,
        Err(code) => return code,
    };
    // The scene's functions are compiled when it is rendered, and a compiled scene
    // cannot hold them: such a scene is stored as it was read (its texts and its
    // commands' outputs), and read, checked and compiled again when loaded.
    // So is a scene with meshes: the bundle names the mesh files, which are read again
    // when it is loaded (and refused if they changed), so the file stays small.
    let stored_as_read = scene.functions.is_some() || scene.has_meshes();
    let encoded = match (stored_as_read, bundle) {
        (true, Some(bundle)) => bundle.encode(),
        (true, None) => {
            Err("a compiled scene with functions or meshes cannot be stored".to_string())
        }
        (false, _) => scene_file::encode(&scene).map_err(|e| e.to_string()),
    };
    let bytes = match encoded {
        Ok(b) => b,
        Err(e) => {
            eprintln!("radc build: {e}");
            return ExitCode::from(1);
        }
    };
    let written = match &a.output {
        Some(path) => write_replacing(path, &bytes),
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(&bytes).and_then(|_| out.flush())
        }
    };
    match written {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let name = a
                .output
                .as_deref()
                .map_or("standard output".into(), |p| p.display().to_string());
            eprintln!("radc build: cannot write {name}: {e}");
            ExitCode::from(1)
        }
    }
}

/// Writes through a temporary file beside `path` and renames it over `path`, so a
/// failed build never leaves a truncated scene file behind.
fn write_replacing(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(format!(".tmp{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    let result = std::fs::write(&tmp, bytes).and_then(|_| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
