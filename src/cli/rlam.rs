//! `radc rlam`: Radiance's rlam (see `radc_jit::records::laminate`). Inputs are files,
//! `-` for standard input, or `!command`, which runs through `sh` only with
//! `--allow-commands` (given when radc is called as rlam, as rlam runs them).

use std::io::{BufReader, Write};
use std::process::{Child, ExitCode, Stdio};

use radc_jit::records::laminate::{LamInput, laminate};
use radc_lang::c_number::{atoi, atol};

const NAME: &str = "rlam";
/// lam.c's `MAXLINE`: the largest binary record.
const MAX_RECORD: i64 = 1 << 20;

pub fn run(args: &[String]) -> ExitCode {
    let (allow, args) = match args.first().map(String::as_str) {
        Some("--allow-commands") => (true, &args[1..]),
        _ => (false, args),
    };
    let fail = |message: String| {
        eprintln!("{NAME}: {message}");
        ExitCode::from(1)
    };
    let mut inputs: Vec<LamInput> = Vec::new();
    let mut children: Vec<Child> = Vec::new();
    let (mut count, mut unbuffered) = (0i64, false);
    let mut separator: &[u8] = b"\t";
    let mut size = 0i64;
    let mut i = 0;
    while i < args.len() {
        let a = &args[i];
        let b = a.as_bytes();
        if b.first() == Some(&b'-') {
            match b.get(1) {
                Some(b't') => {
                    separator = if b.len() > 2 { &b[2..] } else { b"\n" };
                }
                Some(b'u') => unbuffered = !unbuffered,
                Some(b'i') => {
                    let unit: i64 = match b.get(2) {
                        Some(b'n') => {
                            let Some(v) = args.get(i + 1) else {
                                return fail("bad option".into());
                            };
                            count = atol(v);
                            i += 2;
                            continue;
                        }
                        Some(b'f' | b'F') => 4,
                        Some(b'd' | b'D') => 8,
                        Some(b'i' | b'I') => 4,
                        Some(b'w' | b'W') => 2,
                        Some(b'b') => 1,
                        Some(b'a') => {
                            if b.len() > 3 {
                                -1
                            } else {
                                0
                            }
                        }
                        _ => return fail("bad option".into()),
                    };
                    size = unit;
                    if b.get(3).is_some_and(u8::is_ascii_digit) {
                        size *= i64::from(atoi(&a[3..]));
                    }
                    if size == -1 {
                        size = 0;
                    }
                    if size > MAX_RECORD {
                        return fail("input size too big".into());
                    }
                    if size > 0 {
                        separator = b"";
                    }
                }
                None => inputs.push(LamInput {
                    stream: Box::new(std::io::stdin().lock()),
                    separator: separator.to_vec(),
                    size,
                }),
                _ => return fail("bad option".into()),
            }
            i += 1;
            continue;
        }
        if let Some(command) = a.strip_prefix('!') {
            if !allow {
                return fail(format!(
                    "{a}: radc runs no commands without --allow-commands (or when called as rlam)"
                ));
            }
            let child = std::process::Command::new("sh")
                .arg("-c")
                .arg(command)
                .stdout(Stdio::piped())
                .spawn();
            let Ok(mut child) = child else {
                eprintln!("{a}: cannot start command");
                return ExitCode::from(1);
            };
            let Some(out) = child.stdout.take() else {
                eprintln!("{a}: cannot start command");
                return ExitCode::from(1);
            };
            inputs.push(LamInput {
                stream: Box::new(BufReader::new(out)),
                separator: separator.to_vec(),
                size,
            });
            children.push(child);
        } else {
            let Ok(f) = std::fs::File::open(a) else {
                eprintln!("{a}: cannot open file");
                return ExitCode::from(1);
            };
            inputs.push(LamInput {
                stream: Box::new(BufReader::new(f)),
                separator: separator.to_vec(),
                size,
            });
        }
        i += 1;
    }
    if inputs.is_empty() {
        return fail("no input streams".into());
    }
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let result = laminate(&mut inputs, &mut out, count, unbuffered);
    let _ = out.flush();
    drop(inputs);
    for mut c in children {
        let _ = c.wait();
    }
    match result {
        Ok(true) => {
            eprintln!("{NAME}: warning: premature EOD");
            ExitCode::SUCCESS
        }
        Ok(false) => ExitCode::SUCCESS,
        Err(_) => fail("write error on standard output".into()),
    }
}
