//! `radc calc`: rcalc, command-line compatible for the common options
//! (`-e -f -n -s -t -w -u -i{a,d,f} -o{a,d,f} -in -on`, file arguments).
//! Syntax and resolution errors are diagnostics (exit 1); runtime warnings use rcalc's
//! own words on stderr; bad options exit 2.
//! Records are evaluated by the Cranelift JIT; `--interp` selects the reference
//! interpreter (the JIT also falls back to it, with a note, for programs it declines).

use super::USAGE_ERROR;
use radc_jit::compile::StartError;
use radc_jit::interp::{Interpreter, Outputs, Record, format_outputs};
use radc_jit::{JitProgram, RecordEngine};
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::{Env, Host, Module};
use radc_lang::{Diagnostic, FileId};
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage: radc calc [--interp][-n][-w][-u][-tS][-s svar=sval][-e expr][-f source][-i{a|d|f}[N]][-o{a|d|f}][-in N][-on N] [file ..]";

/// Binary or text records (rcalc's `-id`, `-if`, `-od`, `-of`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Ascii,
    Double { swap: bool },
    Float { swap: bool },
}

struct Options {
    noinput: bool,
    nowarn: bool,
    unbuffered: bool,
    sep: char,
    itype: Format,
    in_cols: usize,
    otype: Format,
    in_limit: u64,
    out_limit: u64,
    files: Vec<String>,
    /// Evaluate with the reference interpreter instead of the JIT.
    interp: bool,
}

/// The texts compiled so far, by `FileId`, for rendering diagnostics.
struct Sources {
    names: Vec<String>,
    texts: Vec<String>,
}

pub fn run(args: &[String]) -> ExitCode {
    let mut module = Module::new(&Env {
        host: Host::Rcalc,
        fold: true,
        complete: false,
    });
    let mut sources = Sources {
        names: Vec::new(),
        texts: Vec::new(),
    };
    let mut diags: Vec<Diagnostic> = Vec::new();
    let mut o = Options {
        noinput: false,
        nowarn: false,
        unbuffered: false,
        sep: '\t',
        itype: Format::Ascii,
        in_cols: 0,
        otype: Format::Ascii,
        in_limit: 0,
        out_limit: 0,
        files: Vec::new(),
        interp: false,
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
            "-w" => o.nowarn = !o.nowarn,
            "-u" => o.unbuffered = !o.unbuffered,
            "-b" | "-l" => {}
            "-e" => match value() {
                Some(expr) => add(&mut module, &mut sources, &mut diags, "-e".into(), expr),
                None => return usage("-e needs an expression"),
            },
            "-f" => match value() {
                Some(name) => match find_on_raypath(&name) {
                    Some(path) => match std::fs::read(&path) {
                        Ok(bytes) => {
                            let text = String::from_utf8_lossy(&bytes).into_owned();
                            add(&mut module, &mut sources, &mut diags, name, text);
                        }
                        Err(e) => {
                            eprintln!("radc calc: {}: {e}", path.display());
                            return ExitCode::FAILURE;
                        }
                    },
                    None => {
                        eprintln!("radc calc: cannot find file '{name}' (searched RAYPATH)");
                        return ExitCode::FAILURE;
                    }
                },
                None => return usage("-f needs a file name"),
            },
            "-s" => {
                // String variables only matter to -i/-o record formats.
                if value().is_none() {
                    return usage("-s needs svar=sval");
                }
            }
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
                let Some(f) = parse_format(&a[2..]) else {
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
        render(&sources, &diags);
    }
    if diags.iter().any(Diagnostic::is_error) {
        return ExitCode::FAILURE;
    }
    if !o.nowarn {
        for w in &module.parse_warnings {
            eprintln!("{w}");
        }
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
    if !o.noinput {
        module.optimize();
    }
    // Deep recursion in calcomp is legal; give the evaluator a stack to match.
    let worker = std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(move || execute(&module, &o));
    match worker.map(|h| h.join()) {
        Ok(Ok(code)) => code,
        _ => {
            eprintln!("radc calc: evaluation failed");
            ExitCode::FAILURE
        }
    }
}

fn add(m: &mut Module, s: &mut Sources, diags: &mut Vec<Diagnostic>, name: String, text: String) {
    let file = FileId(s.texts.len() as u32);
    diags.extend(m.add_source(file, &text));
    s.names.push(name);
    s.texts.push(text);
}

fn parse_format(spec: &str) -> Option<(Format, usize)> {
    let mut chars = spec.chars();
    let kind = chars.next()?;
    let rest: String = chars.collect();
    let cols = if rest.is_empty() {
        1
    } else {
        rest.parse().ok()?
    };
    let f = match kind {
        'a' => Format::Ascii,
        'd' => Format::Double { swap: false },
        'D' => Format::Double { swap: true },
        'f' => Format::Float { swap: false },
        'F' => Format::Float { swap: true },
        _ => return None,
    };
    Some((f, cols))
}

fn usage(why: &str) -> ExitCode {
    eprintln!("radc calc: {why}\n{USAGE}");
    ExitCode::from(USAGE_ERROR)
}

/// rcalc's `getpath` with `getrlibpath`: absolute and `./` names as given, others
/// searched in each RAYPATH directory (the current one if RAYPATH is unset).
fn find_on_raypath(name: &str) -> Option<PathBuf> {
    let p = Path::new(name);
    if p.is_absolute() || name.starts_with("./") || name.starts_with("../") {
        return p.is_file().then(|| p.to_path_buf());
    }
    let raypath = std::env::var("RAYPATH").unwrap_or_else(|_| ".".into());
    raypath
        .split(':')
        .map(|d| Path::new(if d.is_empty() { "." } else { d }).join(name))
        .find(|c| c.is_file())
}

/// Native stack the JIT's code may use on the evaluation thread (of 512 MiB).
const JIT_STACK_BUDGET: usize = 256 << 20;

/// The JIT unless `--interp` asks for the interpreter or the JIT declines the program.
fn engine<'m>(module: &'m Module, o: &Options) -> Result<Box<dyn RecordEngine + 'm>, String> {
    if !o.interp {
        match JitProgram::new(module, MathErrors::default()) {
            Ok(mut jit) => {
                jit.set_stack_budget(JIT_STACK_BUDGET);
                return Ok(Box::new(jit));
            }
            Err(StartError::Program(e)) => return Err(e.to_string()),
            Err(StartError::Jit(e)) => {
                eprintln!("radc calc: note: {e}; using the interpreter");
            }
        }
    }
    match Interpreter::new(module, MathErrors::default()) {
        Ok(i) => Ok(Box::new(i)),
        Err(e) => Err(e.to_string()),
    }
}

fn execute(module: &Module, o: &Options) -> ExitCode {
    let mut engine = match engine(module, o) {
        Ok(e) => e,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let interp = engine.as_mut();
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let status = if o.noinput {
        let r = interp.single().map(Some);
        emit(&mut out, interp, o, r)
    } else if o.files.is_empty() {
        let stdin = std::io::stdin();
        let mut input = stdin.lock();
        run_stream(&mut input, interp, o, &mut out)
    } else {
        let mut status = Ok(());
        for f in &o.files {
            match std::fs::File::open(f) {
                Ok(file) => {
                    let mut input = std::io::BufReader::new(file);
                    status = run_stream(&mut input, interp, o, &mut out);
                }
                Err(e) => {
                    let _ = out.flush();
                    eprintln!("radc calc: {f}: cannot open: {e}");
                    return ExitCode::FAILURE;
                }
            }
            if status.is_err() {
                break;
            }
        }
        status
    };
    let flushed = out.flush();
    match (status, flushed) {
        (Ok(()), Ok(())) => ExitCode::SUCCESS,
        (Err(Stop::Done), _) => ExitCode::SUCCESS,
        (Ok(()), Err(_)) => ExitCode::FAILURE,
        (Err(Stop::Failed), _) => ExitCode::FAILURE,
    }
}

enum Stop {
    /// `-in`/`-on` limit reached.
    Done,
    Failed,
}

fn run_stream(
    input: &mut dyn BufRead,
    interp: &mut dyn RecordEngine,
    o: &Options,
    out: &mut dyn Write,
) -> Result<(), Stop> {
    let mut nrecs = 0u64;
    let mut nout = 0u64;
    let mut line = Vec::new();
    loop {
        let text: String = match o.itype {
            Format::Ascii => {
                line.clear();
                match input.read_until(b'\n', &mut line) {
                    Ok(0) => return Ok(()),
                    Ok(_) => String::from_utf8_lossy(&line).into_owned(),
                    Err(_) => return Err(Stop::Failed),
                }
            }
            binary => match read_binary(input, binary, o.in_cols) {
                Some(t) => t,
                None => return Ok(()),
            },
        };
        nrecs += 1;
        let sep = if o.itype == Format::Ascii { o.sep } else { ' ' };
        let mut record = Record::new(&text, sep);
        let result = interp.record(&mut record);
        let produced = matches!(result, Ok(Some(_)));
        emit(out, interp, o, result)?;
        if produced {
            nout += 1;
        }
        if (o.in_limit > 0 && nrecs >= o.in_limit) || (o.out_limit > 0 && nout >= o.out_limit) {
            return Err(Stop::Done);
        }
    }
}

/// Binary input records are turned into blank-separated text with full precision, so
/// one record reader serves both.
fn read_binary(input: &mut dyn BufRead, f: Format, cols: usize) -> Option<String> {
    let (size, swap) = match f {
        Format::Double { swap } => (8, swap),
        Format::Float { swap } => (4, swap),
        Format::Ascii => return None,
    };
    let mut buf = vec![0u8; size * cols.max(1)];
    input.read_exact(&mut buf).ok()?;
    let mut text = String::new();
    for chunk in buf.chunks(size) {
        let mut b = chunk.to_vec();
        if swap {
            b.reverse();
        }
        let v = if size == 8 {
            f64::from_ne_bytes(b.try_into().ok()?)
        } else {
            f64::from(f32::from_ne_bytes(b.try_into().ok()?))
        };
        text.push_str(&format!("{v:e} "));
    }
    text.push('\n');
    Some(text)
}

fn emit(
    out: &mut dyn Write,
    interp: &mut dyn RecordEngine,
    o: &Options,
    result: Result<Option<Outputs>, radc_jit::Error>,
) -> Result<(), Stop> {
    let warnings = interp.take_warnings();
    if !o.nowarn && !warnings.is_empty() {
        let _ = out.flush();
        for w in warnings {
            eprintln!("{w}");
        }
    }
    match result {
        Ok(Some(values)) => {
            let written = match o.otype {
                Format::Ascii => out.write_all(format_outputs(&values, o.sep).as_bytes()),
                binary => out.write_all(&binary_record(&values, binary)),
            };
            if written.is_err() {
                return Err(Stop::Failed);
            }
            if o.unbuffered && out.flush().is_err() {
                return Err(Stop::Failed);
            }
            Ok(())
        }
        Ok(None) => Ok(()),
        Err(e) => {
            let partial = format_outputs(&interp.take_partial(), o.sep);
            let _ = out.write_all(partial.trim_end_matches('\n').as_bytes());
            let _ = out.flush();
            eprintln!("{e}");
            Err(Stop::Failed)
        }
    }
}

/// rcalc.c `bchanset`: missing columns are written as zeros.
fn binary_record(values: &[(u32, f64)], f: Format) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut col = 0u32;
    for &(n, v) in values {
        col += 1;
        while col < n {
            bytes.extend(encode(0.0, f));
            col += 1;
        }
        bytes.extend(encode(v, f));
    }
    bytes
}

fn encode(v: f64, f: Format) -> Vec<u8> {
    let mut b = match f {
        Format::Double { .. } => v.to_ne_bytes().to_vec(),
        _ => (v as f32).to_ne_bytes().to_vec(),
    };
    if matches!(
        f,
        Format::Double { swap: true } | Format::Float { swap: true }
    ) {
        b.reverse();
    }
    b
}

fn render(sources: &Sources, diags: &[Diagnostic]) {
    use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};
    for d in diags {
        let file = d.span.file.0 as usize;
        let (Some(name), Some(text)) = (sources.names.get(file), sources.texts.get(file)) else {
            eprintln!("{}: {}", d.code.id, d.message);
            continue;
        };
        let kind = if d.is_error() {
            ReportKind::Error
        } else {
            ReportKind::Warning
        };
        let id = name.as_str();
        let mut report = Report::build(kind, (id, d.span.range()))
            .with_config(
                Config::new()
                    .with_index_type(IndexType::Byte)
                    .with_color(false),
            )
            .with_code(d.code.id)
            .with_message(&d.message)
            .with_label(Label::new((id, d.span.range())).with_message(&d.message));
        for l in &d.labels {
            report = report.with_label(Label::new((id, l.span.range())).with_message(&l.message));
        }
        if let Some(h) = &d.hint {
            report = report.with_help(h);
        }
        let mut buf = Vec::new();
        if report
            .finish()
            .write((id, Source::from(text.as_str())), &mut buf)
            .is_ok()
        {
            let _ = std::io::stderr().write_all(&buf);
        } else {
            eprintln!("{}: {}", d.code.id, d.message);
        }
    }
}
