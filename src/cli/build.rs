//! `radc build`: oconv's role. Reads scene files as one scene (as `radc render` and
//! `radc trace` do: scenes with errors, or with what the renderer does not model, are
//! refused with their diagnostics), compiles it (reachable surfaces only, BVH built)
//! and writes the compiled scene file (`radc_renderer::scene_file`), which `render`
//! and `trace` load in place of the `.rad` files.

use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use radc_renderer::Scene;
use radc_renderer::scene_file;

use super::USAGE_ERROR;

const USAGE: &str = "usage: radc build [-w] [-f] [-n objlim] [-r maxres] [-b xmin ymin zmin size] \
[-o scene.rsc] scene.rad...";

struct Args {
    output: Option<PathBuf>,
    scenes: Vec<PathBuf>,
    warnings: bool,
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        output: None,
        scenes: Vec::new(),
        warnings: true,
    };
    let mut it = args.iter().map(String::as_str);
    while let Some(arg) = it.next() {
        match arg {
            "-o" => a.output = Some(PathBuf::from(it.next().ok_or("-o needs a file name")?)),
            // oconv's -w turns warnings off.
            s if super::trace::switch(s, "-w", &mut a.warnings) => {}
            // oconv's -f writes a frozen octree: a compiled scene always holds everything.
            "-f" => {}
            // oconv's octree limits: the BVH chooses its own leaves and depth.
            "-n" | "-r" => {
                super::trace::number(&mut it, arg)?;
            }
            "-b" => {
                for _ in 0..4 {
                    super::trace::number(&mut it, arg)?;
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
    super::trace::with_deep_stacks(|| run_parsed(args))
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
    let scene = match super::trace::load_scene(&a.scenes, "build", a.warnings) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if scene.functions.is_some() {
        eprintln!(
            "radc build: the scene's patterns are compiled at render time, and a compiled \
             scene file cannot hold them yet; trace or render the scene files instead"
        );
        return ExitCode::from(1);
    }
    let bytes = match scene_file::encode(&scene) {
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

/// What a scene argument is, from its first bytes.
enum Kind {
    Compiled,
    Octree,
    Picture,
    Text,
}

/// What a file is when it is a Radiance picture: "a Radiance picture (W by H, FORMAT)",
/// read from its header and resolution line (in its first 4 KiB); `None` otherwise.
pub(super) fn picture_description(path: &Path) -> Option<String> {
    let mut head = [0u8; 4096];
    let n = std::fs::File::open(path)
        .and_then(|mut f| read_up_to(&mut f, &mut head))
        .ok()?;
    describe_picture(&head[..n])
}

fn describe_picture(head: &[u8]) -> Option<String> {
    // Radiance's pictures start with the magic line; a scene that opens with comments
    // and an empty line must not be taken for a header.
    if !head.starts_with(b"#?") {
        return None;
    }
    let (header, end) = radc_picture::Header::parse(head).ok()?;
    let format = header.format();
    if format
        .as_deref()
        .is_some_and(|f| !radc_picture::Picture::is_format(f))
    {
        return None;
    }
    let (res, _) = radc_picture::Resolution::parse(&head[end..])?;
    let format = format.unwrap_or_else(|| radc_picture::Format::RGBE.into());
    Some(format!(
        "a Radiance picture ({} by {} pixels, {format})",
        res.x, res.y
    ))
}

fn kind(path: &Path) -> Kind {
    let mut head = [0u8; 4096];
    let n = std::fs::File::open(path)
        .and_then(|mut f| read_up_to(&mut f, &mut head))
        .unwrap_or(0);
    let head = &head[..n];
    let text = String::from_utf8_lossy(head);
    if scene_file::looks_compiled(head) || path.extension().is_some_and(|e| e == "rsc") {
        Kind::Compiled
    } else if text.starts_with("#?RADIANCE") && text.contains("FORMAT=Radiance_octree") {
        Kind::Octree
    } else if describe_picture(head).is_some() {
        Kind::Picture
    } else {
        Kind::Text
    }
}

fn read_up_to(f: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match f.read(&mut buf[n..])? {
            0 => break,
            k => n += k,
        }
    }
    Ok(n)
}

/// The compiled scene, if the scene arguments name one (by its magic bytes or a `.rsc`
/// extension); `None` when they are scene text. Octrees are refused by name rather than
/// parsed as text.
pub(super) fn load_compiled(paths: &[PathBuf], command: &str) -> Option<Result<Scene, ExitCode>> {
    let kinds: Vec<Kind> = paths.iter().map(|p| kind(p)).collect();
    if let Some(p) = paths
        .iter()
        .zip(&kinds)
        .find_map(|(p, k)| matches!(k, Kind::Octree).then_some(p))
    {
        errln!(
            "radc {command}: {}: is a Radiance octree (made by oconv), which radc does not \
             read; give the scene's .rad files, or compile them with 'radc build'",
            p.display()
        );
        return Some(Err(ExitCode::from(1)));
    }
    if let Some(p) = paths
        .iter()
        .zip(&kinds)
        .find_map(|(p, k)| matches!(k, Kind::Picture).then_some(p))
    {
        let what = picture_description(p).unwrap_or_else(|| "a Radiance picture".into());
        errln!(
            "radc {command}: {}: is {what}, not a scene; 'radc getinfo' and 'radc pvalue' \
             read pictures, and 'radc render -o x.png {}' makes a PNG of one",
            p.display(),
            p.display()
        );
        return Some(Err(ExitCode::from(1)));
    }
    let compiled = paths
        .iter()
        .zip(&kinds)
        .find_map(|(p, k)| matches!(k, Kind::Compiled).then_some(p))?;
    if paths.len() > 1 {
        errln!(
            "radc {command}: {}: a compiled scene must be the only scene argument",
            compiled.display()
        );
        return Some(Err(ExitCode::from(USAGE_ERROR)));
    }
    let loaded = std::fs::read(compiled)
        .map_err(|e| format!("cannot read it: {e}"))
        .and_then(|bytes| scene_file::decode(&bytes).map_err(|e| e.to_string()));
    Some(loaded.map_err(|e| {
        errln!("radc {command}: {}: {e}", compiled.display());
        ExitCode::from(1)
    }))
}
