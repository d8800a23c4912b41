//! Showing diagnostics: ariadne reports for people, JSON lines for CI. The words come
//! from `lang`; this module only lays them out.

use std::io::{IsTerminal, Write};

use ariadne::{Color, Config, IndexType, Label, Report, ReportKind};
use radc_lang::{Diagnostic, Severity};
pub use radc_loader::Sources;

/// How diagnostics are shown (`--format`): ariadne reports for people, JSON lines for
/// tools.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum ReportStyle {
    Human,
    Json,
}

pub fn print(diags: &[Diagnostic], sources: &Sources, format: ReportStyle) {
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let color = out.is_terminal() && std::env::var_os("NO_COLOR").is_none();
    print_to(diags, sources, format, color, &mut out);
}

/// Diagnostics to stderr, for commands whose stdout carries data (`radc trace`).
pub fn eprint(diags: &[Diagnostic], sources: &Sources) {
    if super::error_file::with_file(|f| {
        print_to(
            diags,
            sources,
            ReportStyle::Human,
            false,
            &mut std::io::BufWriter::new(f),
        )
    }) {
        return;
    }
    let stderr = std::io::stderr();
    let mut out = stderr.lock();
    let color = out.is_terminal() && std::env::var_os("NO_COLOR").is_none();
    print_to(diags, sources, ReportStyle::Human, color, &mut out);
}

fn print_to(
    diags: &[Diagnostic],
    sources: &Sources,
    format: ReportStyle,
    color: bool,
    out: &mut impl Write,
) {
    match format {
        ReportStyle::Json => {
            for d in diags {
                let _ = writeln!(out, "{}", json(d, sources));
            }
        }
        ReportStyle::Human => {
            // One line index per file for the whole run: building it per diagnostic
            // made tens of thousands of diagnostics on a big file take hours. Only
            // files a diagnostic points into are indexed (a clean 60 MB scene costs
            // nothing here).
            let mut shown = vec![false; sources.len()];
            for d in diags {
                for file in std::iter::once(d.span.file).chain(d.labels.iter().map(|l| l.span.file))
                {
                    if let Some(s) = shown.get_mut(file.0 as usize) {
                        *s = true;
                    }
                }
            }
            // By name, as the cache keys them: a later file of the same name still
            // replaces an earlier one, as when every file was in it.
            let names: std::collections::HashSet<&str> = sources
                .iter()
                .zip(&shown)
                .filter(|(_, shown)| **shown)
                .map(|(f, _)| f.name.as_str())
                .collect();
            let mut cache = ariadne::sources(
                sources
                    .iter()
                    .filter(|f| names.contains(f.name.as_str()))
                    .map(|f| (f.name.clone(), f.text.clone())),
            );
            for d in diags {
                human(d, sources, color, &mut cache, out);
            }
        }
    }
}

/// One diagnostic as a JSON object: code, severity, file, 1-based line/column of the
/// start and end, message, hint.
pub fn json(d: &Diagnostic, sources: &Sources) -> serde_json::Value {
    let (file, start, end) = match sources.get(d.span.file) {
        Some(s) => (
            s.name.clone(),
            s.lines().line_col(&s.text, d.span.start as usize),
            s.lines().line_col(&s.text, d.span.end as usize),
        ),
        None => (String::new(), (0, 0), (0, 0)),
    };
    serde_json::json!({
        "code": d.code.id,
        "name": d.code.name,
        "severity": match d.severity { Severity::Error => "error", Severity::Warning => "warning" },
        "file": file,
        "line": start.0,
        "column": start.1,
        "end_line": end.0,
        "end_column": end.1,
        "message": d.message,
        "hint": d.hint,
        "labels": d.labels.iter().map(|l| label_json(l, sources)).collect::<Vec<_>>(),
    })
}

fn label_json(l: &radc_lang::Label, sources: &Sources) -> serde_json::Value {
    let Some(s) = sources.get(l.span.file) else {
        return serde_json::json!({ "message": l.message });
    };
    let (line, column) = s.lines().line_col(&s.text, l.span.start as usize);
    serde_json::json!({
        "file": s.name,
        "line": line,
        "column": column,
        "message": l.message,
    })
}

fn human(
    d: &Diagnostic,
    sources: &Sources,
    color: bool,
    cache: &mut impl ariadne::Cache<String>,
    out: &mut impl Write,
) {
    let Some(src) = sources.get(d.span.file) else {
        let _ = writeln!(out, "{}[{}]: {}", severity_word(d), d.code.id, d.message);
        return;
    };
    let kind = match d.severity {
        Severity::Error => ReportKind::Error,
        Severity::Warning => ReportKind::Warning,
    };
    let main_color = match d.severity {
        Severity::Error => Color::Red,
        Severity::Warning => Color::Yellow,
    };
    // ariadne's multi-file cache wants owned ids.
    let name = src.name.clone();
    let clamp = |r: std::ops::Range<usize>| {
        let len = src.text.len();
        r.start.min(len)..r.end.min(len)
    };
    let mut report = Report::build(kind, (name.clone(), clamp(d.span.range())))
        .with_config(
            Config::new()
                .with_index_type(IndexType::Byte)
                .with_color(color),
        )
        .with_code(d.code.id)
        .with_message(&d.message)
        .with_label(
            Label::new((name.clone(), clamp(d.span.range())))
                .with_message(d.code.name)
                .with_color(main_color),
        );
    for l in &d.labels {
        let Some(other) = sources.get(l.span.file) else {
            continue;
        };
        let len = other.text.len();
        let r = l.span.start as usize..l.span.end as usize;
        report = report.with_label(
            Label::new((other.name.clone(), r.start.min(len)..r.end.min(len)))
                .with_message(&l.message)
                .with_color(Color::Blue),
        );
    }
    if let Some(h) = &d.hint {
        report = report.with_help(h);
    }
    if report.finish().write(cache, &mut *out).is_err() {
        let (line, col) = src.lines().line_col(&src.text, d.span.start as usize);
        let _ = writeln!(
            out,
            "{name}:{line}:{col}: {}[{}]: {}",
            severity_word(d),
            d.code.id,
            d.message
        );
    }
}

fn severity_word(d: &Diagnostic) -> &'static str {
    match d.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
    }
}
