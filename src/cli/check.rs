//! `radc check`: lint scene files (and, with the calcomp front end, `.cal` files) for CI
//! and for people. Exit 0 when clean (warnings allowed), 1 on errors (or on warnings
//! with `--deny warnings`), 2 on usage errors.
//!
//! Files named on the command line are read in order as one scene, as oconv reads
//! them (so `radc check materials.mat room.rad` resolves the room's materials). Each
//! `.rad` file found under a directory argument is checked as a scene of its own.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use radc_lang::scene::{self, FileLookup, Keep, Lowering};
use radc_lang::schema::FileKind;
use radc_lang::search_path::{Found, Policy, SearchPath};
use radc_lang::{Diagnostic, FileId, Severity};

use super::USAGE_ERROR;
use super::expand::{Commands, PendingSources};
use super::report::{self, ReportStyle, Sources};

const USAGE: &str =
    "usage: radc check [--format human|json] [--deny warnings] [--quiet] FILE|DIR...";

struct Options {
    format: ReportStyle,
    deny_warnings: bool,
    quiet: bool,
    allow_commands: bool,
    paths: Vec<PathBuf>,
}

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        format: ReportStyle::Human,
        deny_warnings: false,
        quiet: false,
        allow_commands: false,
        paths: Vec::new(),
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--format" => match it.next().map(String::as_str) {
                Some("json") => o.format = ReportStyle::Json,
                Some("human") => o.format = ReportStyle::Human,
                other => return Err(format!("--format takes 'human' or 'json', not {other:?}")),
            },
            "--format=json" => o.format = ReportStyle::Json,
            "--format=human" => o.format = ReportStyle::Human,
            "--deny" => match it.next().map(String::as_str) {
                Some("warnings") => o.deny_warnings = true,
                other => return Err(format!("--deny takes 'warnings', not {other:?}")),
            },
            "--deny=warnings" | "-W" => o.deny_warnings = true,
            "-q" | "--quiet" => o.quiet = true,
            "--allow-commands" => o.allow_commands = true,
            "-h" | "--help" => return Err(String::new()),
            s if s.starts_with('-') && s != "-" => return Err(format!("unknown option '{s}'")),
            path => o.paths.push(PathBuf::from(path)),
        }
    }
    if o.paths.is_empty() {
        return Err("no files to check".into());
    }
    Ok(o)
}

pub fn run(args: &[String]) -> ExitCode {
    let opts = match parse_args(args) {
        Ok(o) => o,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("radc check: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    let mut sources = Sources::default();
    let mut diags = Vec::new();
    let mut scene_files = Vec::new();
    let mut pictures = 0;
    for path in &opts.paths {
        if path.is_dir() {
            let mut found = Vec::new();
            collect_scenes(path, &mut found);
            found.sort();
            for f in found {
                if is_cal(&f) {
                    check_cal(&f, &mut sources, &mut diags);
                } else {
                    let start = diags.len();
                    let scene = check_scene(
                        &[f],
                        opts.allow_commands,
                        Keep::Modifiers,
                        &mut sources,
                        &mut diags,
                    );
                    let refusals = render_refusals(&scene, &diags[start..]);
                    diags.extend(refusals);
                }
            }
        } else if is_cal(path) {
            check_cal(path, &mut sources, &mut diags);
        } else if let Some(what) = super::build::picture_description(path) {
            // A picture read as scene text would be kilobytes of junk diagnostics.
            eprintln!(
                "radc check: {}: is {what}, not a scene file; 'radc getinfo' and \
                 'radc pvalue' read pictures",
                path.display()
            );
            pictures += 1;
        } else {
            scene_files.push(path.clone());
        }
    }
    if !scene_files.is_empty() {
        let start = diags.len();
        let scene = check_scene(
            &scene_files,
            opts.allow_commands,
            Keep::Modifiers,
            &mut sources,
            &mut diags,
        );
        let refusals = render_refusals(&scene, &diags[start..]);
        diags.extend(refusals);
    }
    diags.sort_by_key(|d| (d.span.file, d.span.start));
    report::print(&diags, &sources, opts.format);
    let scene_errors = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    let warnings = diags.len() - scene_errors;
    let errors = scene_errors + pictures;
    if opts.format == ReportStyle::Human && !opts.quiet {
        // A closed pipe (`radc check ... | head`) is not an error worth a panic.
        let _ = writeln!(
            std::io::stdout(),
            "{} error{}, {} warning{}",
            errors,
            if errors == 1 { "" } else { "s" },
            warnings,
            if warnings == 1 { "" } else { "s" }
        );
    }
    if errors > 0 || (opts.deny_warnings && warnings > 0) {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// W0307 for what `radc trace`/`radc render` would refuse, by the renderer's own
/// judgement.
fn render_refusals(scene: &scene::ir::Scene, diags: &[Diagnostic]) -> Vec<Diagnostic> {
    scene::support::refusal_diagnostics(scene, diags, &radc_renderer::RendererSupport)
}

fn collect_scenes(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            collect_scenes(&p, out);
        } else if p.extension().is_some_and(|x| x == "rad" || x == "cal") {
            out.push(p);
        }
    }
}

fn is_cal(path: &Path) -> bool {
    path.extension().is_some_and(|x| x == "cal")
}

/// Checks a calcomp file on its own. Names it leaves to its users (a scene, an rcalc
/// command line) are noted, not errors.
fn check_cal(path: &Path, sources: &mut Sources, diags: &mut Vec<Diagnostic>) {
    let Some(file) = read_source(path, sources, diags) else {
        return;
    };
    let Some(text) = sources.get(file).map(|s| s.text.as_str()) else {
        return;
    };
    diags.extend(radc_lang::cal::check::check_file(file, text));
}

/// Reads, parses and lowers `paths` in order as one scene. Each file streams from the
/// parser into the lowering; with `Keep::Modifiers` (all `radc check` needs) the
/// surfaces are checked and dropped, so a check holds little more than the text.
pub(super) fn check_scene(
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
fn read_source(path: &Path, sources: &mut Sources, diags: &mut Vec<Diagnostic>) -> Option<FileId> {
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

/// Auxiliary files on disk, found along the search path of `radc check` and the
/// language server (`Policy::SceneCurrentRaypath`: the folder of the scene file that
/// names it, the current folder, then each folder of RAYPATH).
struct SceneFiles<'a> {
    scene_dirs: Vec<(FileId, PathBuf)>,
    search: SearchPath,
    pending: &'a PendingSources,
}

impl<'a> SceneFiles<'a> {
    fn new(scene_dirs: Vec<(FileId, PathBuf)>, pending: &'a PendingSources) -> Self {
        let raypath = std::env::var_os("RAYPATH");
        SceneFiles {
            scene_dirs,
            search: SearchPath::new(Policy::SceneCurrentRaypath, raypath.as_deref()),
            pending,
        }
    }

    fn scene_dir(&self, from: FileId) -> Option<PathBuf> {
        self.scene_dirs
            .iter()
            .find(|(f, _)| *f == from)
            .map(|(_, d)| d.clone())
            .or_else(|| self.pending.dir_of(from))
    }

    fn find(&self, name: &str, from: FileId) -> Option<PathBuf> {
        let dir = self.scene_dir(from);
        self.search.find(name, dir.as_deref(), Path::exists)
    }

    /// radc's own text of a library function file, used only when no file of that
    /// name is on the search path.
    fn builtin(&self, name: &str, kind: FileKind, from: FileId) -> Option<&'static str> {
        let dir = self.scene_dir(from);
        match self
            .search
            .lookup(name, kind, dir.as_deref(), Path::exists)?
        {
            Found::Builtin(text) => Some(text),
            Found::File(..) => None,
        }
    }
}

/// Auxiliary files larger than this are not read for content checks.
const MAX_AUX_FILE: u64 = 64 << 20;

impl FileLookup for SceneFiles<'_> {
    fn exists(&self, name: &str, kind: FileKind, from: FileId) -> bool {
        self.find(name, from).is_some() || self.builtin(name, kind, from).is_some()
    }

    fn read(&self, name: &str, kind: FileKind, from: FileId) -> Option<String> {
        if let Some(text) = self.builtin(name, kind, from) {
            return Some(text.to_string());
        }
        let path = self.find(name, from)?;
        if std::fs::metadata(&path).ok()?.len() > MAX_AUX_FILE {
            return None;
        }
        let bytes = std::fs::read(path).ok()?;
        Some(String::from_utf8_lossy(&bytes).into_owned())
    }

    fn load(&self, name: &str, kind: FileKind, from: FileId) -> Option<(FileId, String)> {
        if let Some(text) = self.builtin(name, kind, from) {
            let shown = format!("{name} (built into radc)");
            let id = self.pending.add(shown, text.to_string(), PathBuf::new());
            return Some((id, text.to_string()));
        }
        let text = self.read(name, kind, from)?;
        let dir = self
            .find(name, from)
            .and_then(|p| p.parent().map(Path::to_path_buf))
            .unwrap_or_default();
        Some((self.pending.add(name.to_string(), text.clone(), dir), text))
    }

    fn read_head(&self, name: &str, kind: FileKind, from: FileId, max: usize) -> Option<Vec<u8>> {
        use std::io::Read;
        if let Some(text) = self.builtin(name, kind, from) {
            return Some(text.bytes().take(max).collect());
        }
        let file = std::fs::File::open(self.find(name, from)?).ok()?;
        let mut head = Vec::with_capacity(max);
        file.take(max as u64).read_to_end(&mut head).ok()?;
        Some(head)
    }
}
