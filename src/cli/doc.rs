//! `radc doc` and `radc explain`: the reference, printed from the same tables the
//! checker reads (the primitive schema and the diagnostic codes), so it cannot drift.

use std::io::Write;
use std::process::ExitCode;

use radc_lang::diagnostic::ALL_CODES;
use radc_lang::schema;

use super::USAGE_ERROR;

/// `radc doc types` (all primitive types), `radc doc TYPE` (one), `radc doc codes`.
pub fn doc(args: &[String]) -> ExitCode {
    let mut out = std::io::stdout().lock();
    let text = match args.first().map(String::as_str) {
        None | Some("types") => schema::markdown(),
        Some("codes") => codes_table(),
        Some(name) => match schema::lookup(name) {
            Some(t) => schema::hover(t),
            None => {
                let hint = radc_lang::diagnostic::suggest(name, schema::type_names())
                    .map(|s| format!(" (did you mean '{s}'?)"))
                    .unwrap_or_default();
                eprintln!("radc doc: no primitive type '{name}'{hint}; try 'radc doc types'");
                return ExitCode::from(USAGE_ERROR);
            }
        },
    };
    let _ = out.write_all(text.as_bytes());
    ExitCode::SUCCESS
}

/// `radc explain E0301`: what a diagnostic code means.
pub fn explain(args: &[String]) -> ExitCode {
    let Some(id) = args.first() else {
        eprintln!("usage: radc explain CODE   (for example: radc explain E0301)");
        return ExitCode::from(USAGE_ERROR);
    };
    match ALL_CODES
        .iter()
        .find(|c| c.id.eq_ignore_ascii_case(id) || c.name == id)
    {
        Some(c) => {
            let _ = writeln!(
                std::io::stdout(),
                "{} ({}, {}): {}",
                c.id,
                c.name,
                match c.severity {
                    radc_lang::Severity::Error => "error",
                    radc_lang::Severity::Warning => "warning",
                },
                c.summary
            );
            ExitCode::SUCCESS
        }
        None => {
            eprintln!("radc explain: no diagnostic code '{id}'; 'radc doc codes' lists them");
            ExitCode::from(USAGE_ERROR)
        }
    }
}

fn codes_table() -> String {
    let mut s = String::from("| code | name | severity | meaning |\n|---|---|---|---|\n");
    for c in ALL_CODES {
        let severity = match c.severity {
            radc_lang::Severity::Error => "error",
            radc_lang::Severity::Warning => "warning",
        };
        s.push_str(&format!(
            "| {} | {} | {severity} | {} |\n",
            c.id, c.name, c.summary
        ));
    }
    s
}
