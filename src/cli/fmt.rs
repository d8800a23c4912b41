//! `radc fmt`: prints each scene file laid out in Radiance's conventional form, or with
//! `--write` rewrites the files that change; `--check` only says which would change.
//! Exit 0 on success, 1 if a file could not be formatted (syntax errors, not UTF-8)
//! or, with `--check`, would change; 2 on usage errors.

use std::path::PathBuf;
use std::process::ExitCode;

use radc_lang::db::{self, Database};

use super::USAGE_ERROR;

const USAGE: &str = "usage: radc fmt [--write | --check] FILE...";

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Print,
    Write,
    Check,
}

pub fn run(args: &[String]) -> ExitCode {
    let mut mode = Mode::Print;
    let mut paths = Vec::new();
    for a in args {
        match a.as_str() {
            "-w" | "--write" => mode = Mode::Write,
            "--check" => mode = Mode::Check,
            "-h" | "--help" => {
                println!("{USAGE}");
                return ExitCode::SUCCESS;
            }
            s if s.starts_with('-') => {
                eprintln!("radc fmt: unknown option '{s}'\n{USAGE}");
                return ExitCode::from(USAGE_ERROR);
            }
            p => paths.push(PathBuf::from(p)),
        }
    }
    if paths.is_empty() {
        eprintln!("radc fmt: no files\n{USAGE}");
        return ExitCode::from(USAGE_ERROR);
    }
    let mut db = Database::default();
    let mut failed = false;
    for path in &paths {
        failed |= !format_one(&mut db, path, mode);
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// Formats one file; false if it could not be formatted or (with `--check`) would change.
fn format_one(db: &mut Database, path: &PathBuf, mode: Mode) -> bool {
    let name = path.display();
    let text = match std::fs::read(path).map(String::from_utf8) {
        Ok(Ok(text)) if !text.contains('\0') => text,
        Ok(_) => {
            eprintln!("radc fmt: {name}: not a UTF-8 text file; left unchanged");
            return false;
        }
        Err(e) => {
            eprintln!("radc fmt: cannot read '{name}': {e}");
            return false;
        }
    };
    let file = db.add_file(name.to_string(), text.clone());
    let Some(formatted) = db::format_scene(db, file) else {
        eprintln!("radc fmt: {name}: has syntax errors (see 'radc check'); left unchanged");
        return false;
    };
    match mode {
        Mode::Print => print!("{formatted}"),
        Mode::Check if *formatted != text => {
            println!("{name}");
            return false;
        }
        Mode::Check => {}
        Mode::Write if *formatted != text => {
            if let Err(e) = std::fs::write(path, formatted) {
                eprintln!("radc fmt: cannot write '{name}': {e}");
                return false;
            }
        }
        Mode::Write => {}
    }
    true
}
