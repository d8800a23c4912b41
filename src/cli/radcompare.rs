//! `radc radcompare`: Radiance's radcompare (see `radc_picture::tools::radcompare`):
//! exit 0 when the files agree within the tolerances, 1 when they differ, 2 on trouble;
//! the differences on standard output.

use std::io::{Read, Write};
use std::process::ExitCode;

use radc_lang::c_number::atof;
use radc_picture::tools::radcompare::{CompareOptions, Input, compare};

pub fn run(args: &[String]) -> ExitCode {
    let prog = crate::cli::programs::printed_name("radcompare");
    let usage = || {
        eprintln!(
            "Usage: {prog} [-h][-c#][-s|-w|-v][-rel min_test][-rms epsilon][-max epsilon] reference test"
        );
        ExitCode::from(2)
    };
    let mut o = CompareOptions::default();
    let mut first_stdin = false;
    let mut a = 0;
    while a < args.len() && args[a].starts_with('-') {
        let b = args[a].as_bytes();
        let value = |a: usize| args.get(a + 1).map_or(0.0, |v| atof(v));
        match b.get(1) {
            Some(b'h') => o.ignore_header = !o.ignore_header,
            Some(b'n') => o.escape_newlines = !o.escape_newlines,
            Some(b'c') => o.comment = b.get(2).copied(),
            Some(b's') => o.report = 0,
            Some(b'w') => o.report = o.report.min(1),
            Some(b'v') => o.report = 3,
            Some(b'm') => {
                o.max_limit = value(a);
                a += 1;
            }
            Some(b'r') if b.get(2) == Some(&b'e') => {
                o.rel_min = value(a);
                a += 1;
            }
            Some(b'r') if b.get(2) == Some(&b'm') => {
                o.rms_limit = value(a);
                a += 1;
            }
            None => {
                first_stdin = true;
                break;
            }
            _ => return usage(),
        }
        a += 1;
    }
    if a + 2 != args.len() {
        return usage();
    }
    let (n1, n2) = (&args[a], &args[a + 1]);
    if n1 == n2 {
        if o.report >= 2 {
            println!("{prog}: warning - identical inputs given");
        }
        return ExitCode::SUCCESS;
    }
    let mut stdin = Vec::new();
    let uses_stdin = first_stdin || n2 == "-";
    if uses_stdin && std::io::stdin().lock().read_to_end(&mut stdin).is_err() {
        return ExitCode::from(2);
    }
    let read = |name: &str, from_stdin: bool| -> Option<(String, Vec<u8>)> {
        if from_stdin {
            return Some(("<stdin>".into(), stdin.clone()));
        }
        match std::fs::read(name) {
            Ok(d) => Some((name.to_string(), d)),
            Err(_) => {
                eprintln!("{name}: cannot open for reading");
                None
            }
        }
    };
    let Some((name1, data1)) = read(n1, first_stdin) else {
        return ExitCode::from(2);
    };
    let Some((name2, data2)) = read(n2, n2 == "-") else {
        return ExitCode::from(2);
    };
    let v = compare(
        &o,
        &prog,
        &Input {
            name: &name1,
            data: &data1,
        },
        &Input {
            name: &name2,
            data: &data2,
        },
    );
    let _ = std::io::stdout().write_all(v.report.as_bytes());
    ExitCode::from(v.status)
}
