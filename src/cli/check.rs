//! `radc check`: lint scene files (and, with the calcomp front end, `.cal` files) for CI
//! and for people. Exit 0 when clean (warnings allowed), 1 on errors (or on warnings
//! with `--deny warnings`), 2 on usage errors.
//!
//! Files named on the command line are read in order as one scene, as oconv reads
//! them (so `radc check materials.mat room.rad` resolves the room's materials). Each
//! `.rad` file found under a directory argument is checked as a scene of its own.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use std::sync::Arc;

use radc_lang::db::{self, AuxFiles, Database};
use radc_lang::schema::FileKind;
use radc_lang::{Diagnostic, Severity};

use super::USAGE_ERROR;
use super::report::{self, Format, Sources};

const USAGE: &str =
    "usage: radc check [--format human|json] [--deny warnings] [--quiet] FILE|DIR...";

struct Options {
    format: Format,
    deny_warnings: bool,
    quiet: bool,
    paths: Vec<PathBuf>,
}

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        format: Format::Human,
        deny_warnings: false,
        quiet: false,
        paths: Vec::new(),
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--format" => match it.next().map(String::as_str) {
                Some("json") => o.format = Format::Json,
                Some("human") => o.format = Format::Human,
                other => return Err(format!("--format takes 'human' or 'json', not {other:?}")),
            },
            "--format=json" => o.format = Format::Json,
            "--format=human" => o.format = Format::Human,
            "--deny" => match it.next().map(String::as_str) {
                Some("warnings") => o.deny_warnings = true,
                other => return Err(format!("--deny takes 'warnings', not {other:?}")),
            },
            "--deny=warnings" | "-W" => o.deny_warnings = true,
            "-q" | "--quiet" => o.quiet = true,
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
    let mut db = Database::new(Arc::new(SearchPath::from_env()));
    let mut sources = Sources::default();
    let mut diags = Vec::new();
    let mut scene_files = Vec::new();
    for path in &opts.paths {
        if path.is_dir() {
            let mut found = Vec::new();
            collect_scenes(path, &mut found);
            found.sort();
            for f in found {
                check_scene(&mut db, &[f], &mut sources, &mut diags);
            }
        } else {
            scene_files.push(path.clone());
        }
    }
    if !scene_files.is_empty() {
        check_scene(&mut db, &scene_files, &mut sources, &mut diags);
    }
    diags.sort_by_key(|d| (d.span.file, d.span.start));
    report::print(&diags, &sources, opts.format);
    let errors = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    let warnings = diags.len() - errors;
    if opts.format == Format::Human && !opts.quiet {
        println!(
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

fn collect_scenes(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            collect_scenes(&p, out);
        } else if p.extension().is_some_and(|x| x == "rad") {
            out.push(p);
        }
    }
}

/// Reads `paths` and checks them in order as one scene, through the database the
/// language server uses too.
fn check_scene(
    db: &mut Database,
    paths: &[PathBuf],
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
) {
    let mut files = Vec::new();
    for path in paths {
        let name = path.display().to_string();
        match std::fs::read(path) {
            Ok(bytes) => {
                let file = db.add_file(name.clone(), String::new());
                let id = file.id(db);
                let (text, found) = radc_lang::source::decode(id, &bytes);
                diags.extend(found);
                db.set_text(file, text.clone());
                let added = sources.add(name, text);
                debug_assert_eq!(added, id);
                files.push(file);
            }
            Err(e) => {
                let id = db.add_file(name.clone(), String::new()).id(db);
                let added = sources.add(name.clone(), String::new());
                debug_assert_eq!(added, id);
                diags.push(Diagnostic::new(
                    radc_lang::diagnostic::E0305,
                    radc_lang::Span::new(id, 0..0),
                    format!("cannot read '{name}': {e}"),
                ));
            }
        }
    }
    let set = db.scene_set(files);
    diags.extend(db::check_scene_set(db, set).iter().cloned());
}

/// Finds auxiliary files as Radiance does, plus the scene's own folder: absolute
/// paths as they are; otherwise the folder of the scene file that names it, the
/// current folder, then each folder of RAYPATH.
struct SearchPath {
    raypath: Vec<PathBuf>,
}

impl SearchPath {
    fn from_env() -> Self {
        let raypath = std::env::var_os("RAYPATH")
            .map(|v| std::env::split_paths(&v).collect())
            .unwrap_or_default();
        SearchPath { raypath }
    }
}

impl AuxFiles for SearchPath {
    fn exists(&self, name: &str, _kind: FileKind, scene_path: &Path) -> bool {
        let p = Path::new(name);
        if p.is_absolute() {
            return p.exists();
        }
        scene_path
            .parent()
            .map(Path::to_path_buf)
            .into_iter()
            .chain(std::iter::once(PathBuf::from(".")))
            .chain(self.raypath.iter().cloned())
            .any(|d| d.join(p).exists())
    }
}
