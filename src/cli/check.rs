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

use radc_lang::scene::{self, Keep};
use radc_lang::{Diagnostic, Severity};

use super::USAGE_ERROR;
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
    let mut not_scenes = 0;
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
                    let scene = radc_loader::read_scene(
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
        } else if let Some(what) = radc_loader::picture_description(path) {
            // A picture read as scene text would be kilobytes of junk diagnostics.
            eprintln!(
                "radc check: {}: is {what}, not a scene file; 'radc getinfo' and \
                 'radc pvalue' read pictures",
                path.display()
            );
            not_scenes += 1;
        } else if let Some(what) = stored_scene(path) {
            eprintln!(
                "radc check: {}: is {what}, not scene text; check the scene files it was \
                 made from",
                path.display()
            );
            not_scenes += 1;
        } else {
            scene_files.push(path.clone());
        }
    }
    if !scene_files.is_empty() {
        let start = diags.len();
        let scene = radc_loader::read_scene(
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
    let errors = scene_errors + not_scenes;
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
    let Some(file) = radc_loader::read_source(path, sources, diags) else {
        return;
    };
    let Some(text) = sources.get(file).map(|s| s.text.as_str()) else {
        return;
    };
    diags.extend(radc_lang::cal::check::check_file(file, text));
}

/// What a scene argument is when it is not scene text: a scene file `radc build` wrote,
/// or a Radiance octree (read as text, either would be junk diagnostics).
fn stored_scene(path: &std::path::Path) -> Option<&'static str> {
    match radc_loader::file_kind(path) {
        radc_loader::Kind::Compiled | radc_loader::Kind::Bundle => {
            Some("a scene file made by 'radc build' (or radc as oconv)")
        }
        radc_loader::Kind::Octree => Some("a Radiance octree (made by oconv)"),
        radc_loader::Kind::Picture | radc_loader::Kind::Text => None,
    }
}
