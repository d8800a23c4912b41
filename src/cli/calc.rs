//! `radc calc`: rcalc, command-line compatible for the common options
//! (`-e -f -n -s -t -w -u -b -l -p -P -i{a,d,f} -o{a,d,f} -i format -o format -in -on`,
//! file arguments).
//! Syntax and resolution errors are diagnostics (exit 1); runtime warnings use rcalc's
//! own words on stderr; bad options exit 2.
//! Records are evaluated by the Cranelift JIT; `--interp` selects the reference
//! interpreter (the JIT also falls back to it, with a note, for programs it declines).

use super::USAGE_ERROR;
use super::report::{self, Sources};
use radc_jit::records::format::{self, Field};
use radc_jit::records::{Passive, RecordEncoding, RecordOptions};
use radc_lang::Diagnostic;
use radc_lang::cal::ir::Expr;
use radc_lang::cal::{Env, Host, Module};
use radc_lang::schema::FileKind;
use radc_lang::search_path::{Found, Policy, SearchPath};
use std::collections::HashMap;

use std::path::Path;
use std::process::ExitCode;

const USAGE: &str = "usage: radc calc [--interp][--threads N][-n][-w][-u][-tS][-s svar=sval][-e expr][-f source][-i{a|d|f}[N]][-o{a|d|f}][-in N][-on N] [file ..]";

pub fn run(args: &[String]) -> ExitCode {
    let mut module = Module::new(&Env {
        host: Host::Rcalc,
        fold: true,
        complete: true,
    });
    let mut sources = Sources::default();
    let mut diags: Vec<Diagnostic> = Vec::new();
    let mut o = RecordOptions {
        noinput: false,
        nowarn: false,
        unbuffered: false,
        sep: '\t',
        itype: RecordEncoding::Ascii,
        in_cols: 0,
        otype: RecordEncoding::Ascii,
        in_limit: 0,
        out_limit: 0,
        files: Vec::new(),
        record_format: None,
        input_format: None,
        strings: HashMap::new(),
        blanks_equal: true,
        passive: Passive::Off,
        ignore_eol: false,
        interp: false,
        threads: None,
        program: "radc calc".into(),
    };
    let mut i = 0;
    // rcalc reads options up to the first argument that does not start with '-', in
    // order: -n turns constant folding off for the expressions that follow it.
    while i < args.len() && args[i].starts_with('-') {
        let a = args[i].as_str();
        let mut value = || {
            i += 1;
            args.get(i).cloned()
        };
        match a {
            "-n" => {
                o.noinput = true;
                module.set_folding(false);
            }
            "--interp" => o.interp = true,
            "--threads" => match value().and_then(|v| v.parse::<usize>().ok()) {
                Some(n) if n >= 1 => o.threads = Some(n),
                _ => return usage("--threads needs a count of at least 1"),
            },
            "-w" => o.nowarn = !o.nowarn,
            "-u" => o.unbuffered = !o.unbuffered,
            "-b" => o.blanks_equal = !o.blanks_equal,
            "-p" => o.passive = Passive::Unmatched,
            "-P" => o.passive = Passive::AlsoRejected,
            "-l" => o.ignore_eol = !o.ignore_eol,
            "-e" => match value() {
                Some(expr) => add(&mut module, &mut sources, &mut diags, "-e".into(), expr),
                None => return usage("-e needs an expression"),
            },
            "-f" => match value() {
                Some(name) => match find_on_raypath(&name) {
                    Some(Found::File(path, ())) if path.is_dir() => {}
                    Some(Found::File(path, ())) => match std::fs::read(&path) {
                        Ok(bytes) => {
                            let text = String::from_utf8_lossy(&bytes).into_owned();
                            add(&mut module, &mut sources, &mut diags, name, text);
                        }
                        Err(e) => {
                            eprintln!("radc calc: {}: {e}", path.display());
                            return ExitCode::FAILURE;
                        }
                    },
                    // As the renderer does, radc's own library answers for a file
                    // that no RAYPATH folder holds (`-f rayinit.cal`).
                    Some(Found::Builtin(text)) => {
                        let shown = format!("{name} (built into radc)");
                        add(&mut module, &mut sources, &mut diags, shown, text.into());
                    }
                    None => {
                        eprintln!("radc calc: cannot find file '{name}' (searched RAYPATH)");
                        return ExitCode::FAILURE;
                    }
                },
                None => return usage("-f needs a file name"),
            },
            "-s" => match value() {
                // rcalc.c `svpreset`: a string variable for record formats.
                Some(eq) => {
                    if let Some((k, v)) = eq.split_once('=') {
                        o.strings.insert(k.to_string(), v.to_string());
                    }
                }
                None => return usage("-s needs svar=sval"),
            },
            "-o" => match value() {
                Some(spec) => {
                    match compile_format(&mut module, &mut sources, &mut diags, &spec, o.ignore_eol)
                    {
                        Ok(f) => {
                            o.otype = RecordEncoding::Ascii;
                            o.record_format = Some(f);
                        }
                        Err(code) => return code,
                    }
                }
                None => return usage("-o needs a format"),
            },
            "-i" => match value() {
                Some(spec) => match read_format_text(&spec).and_then(|t| {
                    format::parse(&t, o.ignore_eol).map_err(|e| {
                        eprintln!("radc calc: {e} in input format");
                        ExitCode::FAILURE
                    })
                }) {
                    Ok(fields) => {
                        o.itype = RecordEncoding::Ascii;
                        o.input_format = Some(fields);
                    }
                    Err(code) => return code,
                },
                None => return usage("-i needs a format"),
            },
            "-in" | "-on" => {
                let Some(n) = value().and_then(|v| v.parse::<u64>().ok()) else {
                    return usage(&format!("{a} needs a count"));
                };
                if a == "-in" {
                    o.in_limit = n;
                } else {
                    o.out_limit = n;
                }
            }
            _ if a.starts_with("-t") => o.sep = a[2..].chars().next().unwrap_or('\0'),
            _ if a.starts_with("-i") || a.starts_with("-o") => {
                let Some(f) = RecordEncoding::parse(&a[2..]) else {
                    return usage(&format!("unsupported format option '{a}'"));
                };
                if a.starts_with("-i") {
                    o.itype = f.0;
                    o.in_cols = f.1;
                } else {
                    o.otype = f.0;
                }
            }
            _ => return usage(&format!("unknown option '{a}'")),
        }
        i += 1;
    }
    o.files = args[i..].to_vec();
    if !diags.is_empty() {
        report::eprint(&diags, &sources);
    }
    if diags.iter().any(Diagnostic::is_error) {
        return ExitCode::FAILURE;
    }
    if !o.nowarn {
        for w in &module.parse_warnings {
            eprintln!("{w}");
        }
    }
    if o.passive != Passive::Off && (o.input_format.is_none() || o.record_format.is_none()) {
        eprintln!("radc calc: options -p and -P require -i and -o formats");
        return ExitCode::FAILURE;
    }
    if o.noinput && !o.files.is_empty() {
        eprintln!("radc calc: file argument(s) incompatible with -n");
        return ExitCode::FAILURE;
    }
    for name in ["recno", "outno"] {
        if module.lookup(name).is_some() {
            module.set_variable(name, 0.0);
        }
    }
    // An input format's number fields become variables, set per record.
    for f in o.input_format.iter().flatten() {
        if let Field::Number { expr: name, .. } = f {
            module.set_variable(name, 0.0);
        }
    }
    if !o.noinput {
        module.optimize();
    }
    // Deep recursion in calcomp is legal; give the evaluator a stack to match.
    let worker = std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(move || {
            let stdout = std::io::stdout();
            let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
            let mut err = std::io::stderr();
            match radc_jit::records::run(&module, &o, &mut out, &mut err) {
                Ok(()) => ExitCode::SUCCESS,
                Err(_) => ExitCode::FAILURE,
            }
        });
    match worker.map(|h| h.join()) {
        Ok(Ok(code)) => code,
        _ => {
            eprintln!("radc calc: evaluation failed");
            ExitCode::FAILURE
        }
    }
}

/// rcalc.c `readfmt`: an inline format if it holds a `$`, else a file holding one.
fn read_format_text(spec: &str) -> Result<String, ExitCode> {
    if spec.contains('$') {
        return Ok(spec.to_string());
    }
    match std::fs::read(spec) {
        Ok(b) if !b.is_empty() => Ok(String::from_utf8_lossy(&b).into_owned()),
        Ok(_) => {
            eprintln!("radc calc: {spec}: empty file");
            Err(ExitCode::FAILURE)
        }
        Err(e) => {
            eprintln!("radc calc: {spec}: cannot open: {e}");
            Err(ExitCode::FAILURE)
        }
    }
}

/// rcalc.c `readfmt`: an inline format if it holds a `$`, else a file holding one.
/// Number fields are compiled now, against the definitions made so far.
fn compile_format(
    module: &mut Module,
    sources: &mut Sources,
    diags: &mut Vec<Diagnostic>,
    spec: &str,
    ignore_eol: bool,
) -> Result<(Vec<Field>, Vec<Option<Expr>>), ExitCode> {
    let text = read_format_text(spec)?;
    let fields = format::parse(&text, ignore_eol).map_err(|e| {
        eprintln!("radc calc: {e} in output format");
        ExitCode::FAILURE
    })?;
    let mut exprs = Vec::with_capacity(fields.len());
    for f in &fields {
        exprs.push(match f {
            Field::Number { expr, .. } => {
                let file = sources.add("-o".into(), expr.clone());
                match module.add_expression(file, expr) {
                    Ok(e) => Some(e),
                    Err(d) => {
                        diags.extend(d);
                        None
                    }
                }
            }
            _ => None,
        });
    }
    Ok((fields, exprs))
}

fn add(m: &mut Module, s: &mut Sources, diags: &mut Vec<Diagnostic>, name: String, text: String) {
    diags.extend(m.add_source(s.next_id(), &text));
    s.add(name, text);
}

fn usage(why: &str) -> ExitCode {
    eprintln!("radc calc: {why}\n{USAGE}");
    ExitCode::from(USAGE_ERROR)
}

/// rcalc's `getpath` with `getrlibpath` (`Policy::Getpath`), then radc's library. A
/// directory is found too, as `getpath` does: `-f .` then reads nothing.
fn find_on_raypath(name: &str) -> Option<Found<()>> {
    let raypath = std::env::var_os("RAYPATH");
    SearchPath::new(Policy::Getpath, raypath.as_deref()).lookup(
        name,
        FileKind::Cal,
        None,
        Path::exists,
    )
}
