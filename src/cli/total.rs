//! `radc total`: Radiance's total (see `radc_jit::records::total`), with its options,
//! messages and exit statuses (1 for a usage error or unreadable standard input, 2 when
//! a named file cannot be opened, after the others are done).

use std::io::{Read, Write};
use std::process::ExitCode;

use radc_jit::records::total::{MAX_COLUMNS, Numbers, Reduce, TotalOptions, total};
use radc_lang::c_number::{atof, atoi, atol};

const USAGE: &str = "Usage: total [-m][-sE|p|u|l][-tC][-i{f|d}[N]][-o{f|d}][-count [-r]] [file..]";

fn columns(word: &str) -> Result<usize, String> {
    let n = match word.as_bytes().first() {
        Some(c) if c.is_ascii_digit() => atoi(word).max(0) as usize,
        _ => 1,
    };
    if n > MAX_COLUMNS {
        return Err("total: too many input columns".into());
    }
    Ok(n)
}

fn parse(args: &[String]) -> Result<(TotalOptions, usize), String> {
    let mut o = TotalOptions::default();
    let mut a = 0;
    while let Some(arg) = args.get(a).filter(|w| w.starts_with('-')) {
        let b = arg.as_bytes();
        let next = |a: usize| args.get(a + 1).map(String::as_str).ok_or(USAGE.to_string());
        match b.get(1) {
            Some(c) if c.is_ascii_digit() => o.count = atoi(&arg[1..]).max(0) as usize,
            Some(b'm') => o.mean = !o.mean,
            Some(b'p') => o.reduce = Reduce::Multiply,
            Some(b's') => o.power = atof(&arg[2..]),
            Some(b'u') => o.reduce = Reduce::Max,
            Some(b'l') => o.reduce = Reduce::Min,
            Some(b't') => o.separator = b.get(2).copied().unwrap_or(0),
            Some(b'r') => o.running = !o.running,
            Some(b'i') => match b.get(2) {
                Some(b'n') => {
                    o.in_limit = atol(next(a)?).max(0) as usize;
                    a += 1;
                }
                Some(b'a') => o.input = Numbers::Text,
                Some(b'd') => o.input = Numbers::Double(columns(&arg[3..])?),
                Some(b'f') => o.input = Numbers::Float(columns(&arg[3..])?),
                _ => return Err(USAGE.into()),
            },
            Some(b'o') => match b.get(2) {
                Some(b'n') => {
                    o.out_limit = atol(next(a)?).max(0) as usize;
                    a += 1;
                }
                Some(b'a') => o.output = Numbers::Text,
                Some(b'd') => o.output = Numbers::Double(0),
                Some(b'f') => o.output = Numbers::Float(0),
                _ => return Err(USAGE.into()),
            },
            _ => return Err(USAGE.into()),
        }
        a += 1;
    }
    if o.power != 0.0 && o.reduce != Reduce::Add {
        return Err("total: -sE option requires summation".into());
    }
    if o.mean && o.reduce == Reduce::Max {
        return Err("total: average maximum?!".into());
    }
    if o.mean && o.reduce == Reduce::Min {
        return Err("total: average minimum?!".into());
    }
    Ok((o, a))
}

pub fn run(args: &[String]) -> ExitCode {
    let (o, first) = match parse(args) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(1);
        }
    };
    let mut status = 0u8;
    let mut records = 0usize;
    let mut stdout = std::io::stdout().lock();
    let mut emit = |out: &[u8]| stdout.write_all(out).and_then(|()| stdout.flush()).is_ok();
    let files = &args[first..];
    if files.is_empty() {
        let mut data = Vec::new();
        if std::io::stdin().lock().read_to_end(&mut data).is_err() {
            return ExitCode::from(1);
        }
        let mut out = Vec::new();
        total(&o, &data, &mut out, &mut records);
        if !emit(&out) {
            return ExitCode::from(1);
        }
    }
    for f in files {
        if o.out_limit > 0 && records >= o.out_limit {
            break;
        }
        let Ok(data) = std::fs::read(f) else {
            eprintln!("{f}: cannot open");
            status = 2;
            continue;
        };
        let mut out = Vec::new();
        total(&o, &data, &mut out, &mut records);
        if !emit(&out) {
            return ExitCode::from(1);
        }
    }
    ExitCode::from(status)
}
