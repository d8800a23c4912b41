//! `radc calc`: rcalc, command-line compatible for the common options
//! (`-e -f -n -s -t -w -u -b -l -p -P -i{a,d,f} -o{a,d,f} -i format -o format -in -on`,
//! file arguments).
//! Syntax and resolution errors are diagnostics (exit 1); runtime warnings use rcalc's
//! own words on stderr; bad options exit 2.
//! Records are evaluated by the Cranelift JIT; `--interp` selects the reference
//! interpreter (the JIT also falls back to it, with a note, for programs it declines).

mod format;
mod input_format;
mod parallel;

use super::USAGE_ERROR;
use super::report::{self, Sources};
use format::{Field, Value};
use radc_jit::compile::StartError;
use radc_jit::interp::{Interpreter, Outputs, Record, format_outputs, write_outputs};
use radc_jit::{JitProgram, RecordEngine};
use radc_lang::Diagnostic;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::ir::Expr;
use radc_lang::cal::{Env, Host, Module};
use radc_lang::schema::FileKind;
use radc_lang::search_path::{Found, Policy, SearchPath};
use std::collections::HashMap;
use std::io::{BufRead, Write};
use std::path::Path;
use std::process::ExitCode;

const USAGE: &str = "usage: radc calc [--interp][--threads N][-n][-w][-u][-tS][-s svar=sval][-e expr][-f source][-i{a|d|f}[N]][-o{a|d|f}][-in N][-on N] [file ..]";

/// Binary or text records (rcalc's `-id`, `-if`, `-od`, `-of`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum RecordEncoding {
    Ascii,
    Double { swap: bool },
    Float { swap: bool },
}

struct Options {
    noinput: bool,
    nowarn: bool,
    unbuffered: bool,
    sep: char,
    itype: RecordEncoding,
    in_cols: usize,
    otype: RecordEncoding,
    in_limit: u64,
    out_limit: u64,
    files: Vec<String>,
    /// `-o format`: its fields and the compiled expression of each number field.
    record_format: Option<(Vec<Field>, Vec<Option<Expr>>)>,
    /// `-i format`: the fields to match input against.
    input_format: Option<Vec<Field>>,
    /// `-s name=value`.
    strings: HashMap<String, String>,
    /// rcalc's `-b` (blanks compare equal), on by default.
    blanks_equal: bool,
    /// `-l`: ignore ends of lines in record formats.
    ignore_eol: bool,
    /// `-p`: pass unmatched input through; `-P`: also records `cond` rejects.
    passive: Passive,
    /// `--interp`: evaluate with the reference interpreter instead of the JIT.
    interp: bool,
    /// `--threads N`: at most this many threads (default: the machine's cores).
    threads: Option<usize>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Passive {
    Off,
    Unmatched,
    AlsoRejected,
}

pub fn run(args: &[String]) -> ExitCode {
    let mut module = Module::new(&Env {
        host: Host::Rcalc,
        fold: true,
        complete: true,
    });
    let mut sources = Sources::default();
    let mut diags: Vec<Diagnostic> = Vec::new();
    let mut o = Options {
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
        .spawn(move || execute(&module, &o));
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

fn parse_format(spec: &str) -> Option<(RecordEncoding, usize)> {
    let mut chars = spec.chars();
    let kind = chars.next()?;
    let rest: String = chars.collect();
    let cols = if rest.is_empty() {
        1
    } else {
        rest.parse().ok()?
    };
    let f = match kind {
        'a' => RecordEncoding::Ascii,
        'd' => RecordEncoding::Double { swap: false },
        'D' => RecordEncoding::Double { swap: true },
        'f' => RecordEncoding::Float { swap: false },
        'F' => RecordEncoding::Float { swap: true },
        _ => return None,
    };
    Some((f, cols))
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

/// Native stack the JIT's code may use on the evaluation thread (of 512 MiB).
const JIT_STACK_BUDGET: usize = 256 << 20;

/// Runs the records with the JIT, unless `--interp` asks for the reference
/// interpreter or the JIT declines the program (then with a note).
fn execute(module: &Module, o: &Options) -> ExitCode {
    let fields: Vec<&Expr> = o
        .record_format
        .iter()
        .flat_map(|(_, exprs)| exprs.iter().flatten())
        .collect();
    let named: Vec<&str> = o
        .input_format
        .iter()
        .flatten()
        .filter_map(|f| match f {
            Field::Number { expr, .. } => Some(expr.as_str()),
            _ => None,
        })
        .collect();
    let threads = parallel::threads_for(module, o);
    if !o.interp {
        let mut engines = Vec::with_capacity(threads);
        for _ in 0..threads {
            // Compiled once: the other threads' engines share the code.
            if let Some(first) = engines.first() {
                let fork = JitProgram::fork(first);
                engines.push(fork);
                continue;
            }
            match JitProgram::with_fields(module, MathErrors::default(), &fields, &named) {
                Ok(mut jit) => {
                    jit.set_stack_budget(JIT_STACK_BUDGET);
                    engines.push(jit);
                }
                Err(StartError::Program(e)) => {
                    eprintln!("{e}");
                    return ExitCode::FAILURE;
                }
                Err(StartError::Jit(e)) => {
                    if !o.nowarn {
                        eprintln!("radc calc: note: {e}; using the interpreter");
                    }
                    break;
                }
            }
        }
        if engines.len() == threads {
            return drive(&mut engines, o);
        }
    }
    let mut engines = Vec::with_capacity(threads);
    for _ in 0..threads {
        match Interpreter::new(module, MathErrors::default()) {
            Ok(i) => engines.push(i.with_fields(&fields)),
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::FAILURE;
            }
        }
    }
    drive(&mut engines, o)
}

/// Buffers reused from record to record: the `$N` values and the output bytes.
#[derive(Default)]
struct Scratch {
    columns: Outputs,
    bytes: Vec<u8>,
}

/// Runs the records on `engines` (one per thread; the first alone unless
/// [`parallel::threads_for`] allowed more).
fn drive<E: RecordEngine + Send>(engines: &mut [E], o: &Options) -> ExitCode {
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
    let mut scratch = Scratch::default();
    let mut stream = |input: &mut dyn BufRead, engines: &mut [E], out: &mut dyn Write| match engines
    {
        [engine] => run_stream(input, engine, o, out, &mut scratch),
        _ => parallel::run_stream(input, engines, o, out),
    };
    let status = if o.noinput {
        let Some(engine) = engines.first_mut() else {
            return ExitCode::FAILURE;
        };
        engine.begin_single();
        let r = produce(
            engine,
            o,
            &mut radc_lang::cal::eval::NoInput,
            None,
            &mut scratch,
        );
        emit(&mut out, engine, o, r.map(|()| true), &scratch)
    } else if o.files.is_empty() {
        let stdin = std::io::stdin();
        let mut input = std::io::BufReader::with_capacity(1 << 16, stdin.lock());
        stream(&mut input, engines, &mut out)
    } else {
        let mut status = Ok(());
        for f in &o.files {
            match std::fs::File::open(f) {
                Ok(file) => {
                    let mut input = std::io::BufReader::with_capacity(1 << 16, file);
                    // rcalc.c `execute` counts records (recno, -in, -on) per file.
                    engines.iter_mut().for_each(|e| e.start_file());
                    status = stream(&mut input, engines, &mut out);
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
        (Ok(()), Err(_)) => ExitCode::FAILURE,
        (Err(Stop::Failed), _) => ExitCode::FAILURE,
    }
}

/// Why record processing stopped early: an evaluation error (already reported) or a
/// write failure. Either way the exit status is 1.
enum Stop {
    Failed,
}

fn run_stream<E: RecordEngine>(
    input: &mut dyn BufRead,
    engine: &mut E,
    o: &Options,
    out: &mut dyn Write,
    scratch: &mut Scratch,
) -> Result<(), Stop> {
    if let Some(fields) = &o.input_format {
        return run_matched(input, fields, engine, o, out, scratch);
    }
    let mut nrecs = 0u64;
    let mut nout = 0u64;
    let sep = if o.itype == RecordEncoding::Ascii {
        o.sep
    } else {
        ' '
    };
    let mut one = |line: &[u8], engine: &mut E, scratch: &mut Scratch| -> Result<bool, Stop> {
        nrecs += 1;
        let mut record = Record::from_bytes(line, sep);
        let result = evaluate(engine, o, &mut record, None, scratch);
        let produced = matches!(result, Ok(true));
        emit(out, engine, o, result, scratch)?;
        nout += u64::from(produced);
        // At a limit this file is done; rcalc goes on with the next.
        Ok(!((o.in_limit > 0 && nrecs >= o.in_limit) || (o.out_limit > 0 && nout >= o.out_limit)))
    };
    // A line that straddles the reader's buffer is gathered here; others are read
    // where they lie.
    let mut line = Vec::with_capacity(256);
    loop {
        if o.itype != RecordEncoding::Ascii {
            line.clear();
            if !read_binary(input, o.itype, o.in_cols, &mut line) || !one(&line, engine, scratch)? {
                return Ok(());
            }
            continue;
        }
        let buf = match input.fill_buf() {
            Ok(b) => b,
            Err(_) => return Err(Stop::Failed),
        };
        if buf.is_empty() {
            // The last line, without its newline.
            if !line.is_empty() {
                one(&line, engine, scratch)?;
            }
            return Ok(());
        }
        let Some(end) = memchr::memchr(b'\n', buf) else {
            line.extend_from_slice(buf);
            let n = buf.len();
            input.consume(n);
            continue;
        };
        let more = if line.is_empty() {
            one(&buf[..=end], engine, scratch)?
        } else {
            line.extend_from_slice(&buf[..=end]);
            let more = one(&line, engine, scratch)?;
            line.clear();
            more
        };
        input.consume(end + 1);
        if !more {
            return Ok(());
        }
    }
}

/// Records found by an `-i` format (rcalc.c `getrec`); `$N` is then an error.
fn run_matched<E: RecordEngine>(
    input: &mut dyn BufRead,
    fields: &[Field],
    engine: &mut E,
    o: &Options,
    out: &mut dyn Write,
    scratch: &mut Scratch,
) -> Result<(), Stop> {
    let mut text = Vec::new();
    if input.read_to_end(&mut text).is_err() {
        return Err(Stop::Failed);
    }
    let mut matcher = input_format::Matcher::new(
        fields.to_vec(),
        &text,
        o.blanks_equal,
        o.ignore_eol,
        &o.strings,
    );
    let (mut nrecs, mut nout) = (0u64, 0u64);
    while let Some(m) = {
        let next = matcher.next_record();
        if o.passive != Passive::Off && out.write_all(&matcher.skipped).is_err() {
            return Err(Stop::Failed);
        }
        matcher.skipped.clear();
        next
    } {
        nrecs += 1;
        for (name, v) in &m.numbers {
            engine.set_named(name, *v);
        }
        let mut no_columns = radc_lang::cal::eval::NoInput;
        let result = evaluate(engine, o, &mut no_columns, Some(&m.strings), scratch);
        let produced = matches!(result, Ok(true));
        let rejected = matches!(result, Ok(false));
        emit(out, engine, o, result, scratch)?;
        if rejected && o.passive == Passive::AlsoRejected && out.write_all(&m.text).is_err() {
            return Err(Stop::Failed);
        }
        nout += u64::from(produced);
        if (o.in_limit > 0 && nrecs >= o.in_limit) || (o.out_limit > 0 && nout >= o.out_limit) {
            return Ok(()); // this file is done; rcalc goes on with the next
        }
    }
    Ok(())
}

/// Binary input records are turned into blank-separated text with full precision
/// (into `text`), so one record reader serves both. False at the end of the input.
fn read_binary(
    input: &mut dyn BufRead,
    f: RecordEncoding,
    cols: usize,
    text: &mut Vec<u8>,
) -> bool {
    let (size, swap) = match f {
        RecordEncoding::Double { swap } => (8, swap),
        RecordEncoding::Float { swap } => (4, swap),
        RecordEncoding::Ascii => return false,
    };
    let mut buf = [0u8; 8];
    for _ in 0..cols.max(1) {
        let word = &mut buf[..size];
        if input.read_exact(word).is_err() {
            return false;
        }
        if swap {
            word.reverse();
        }
        let v = match *word {
            [a, b, c, d, e, f, g, h] => f64::from_ne_bytes([a, b, c, d, e, f, g, h]),
            [a, b, c, d] => f64::from(f32::from_ne_bytes([a, b, c, d])),
            _ => return false,
        };
        let _ = write!(text, "{v:e} ");
    }
    text.push(b'\n');
    true
}

/// One record: its condition, then, if accepted, its output into `scratch` (see
/// [`produce`]). `Ok(false)` is a record the condition rejected.
fn evaluate<E: RecordEngine>(
    engine: &mut E,
    o: &Options,
    input: &mut dyn radc_lang::cal::eval::Input,
    record_strings: Option<&HashMap<String, String>>,
    scratch: &mut Scratch,
) -> Result<bool, radc_jit::Error> {
    if !engine.begin_record(input)? {
        return Ok(false);
    }
    produce(engine, o, input, record_strings, scratch).map(|()| true)
}

/// The output of an accepted record (rcalc.c `putout`), into `scratch.bytes`: the
/// `$N` columns, or the `-o` format filled in. After an error, `scratch.columns`
/// holds the columns computed before it.
fn produce<E: RecordEngine>(
    engine: &mut E,
    o: &Options,
    input: &mut dyn radc_lang::cal::eval::Input,
    record_strings: Option<&HashMap<String, String>>,
    scratch: &mut Scratch,
) -> Result<(), radc_jit::Error> {
    scratch.bytes.clear();
    scratch.columns.clear();
    let Some((fields, exprs)) = &o.record_format else {
        engine.outputs_into(input, &mut scratch.columns)?;
        match o.otype {
            RecordEncoding::Ascii => write_outputs(&mut scratch.bytes, &scratch.columns, o.sep),
            binary => binary_record(&mut scratch.bytes, &scratch.columns, binary),
        }
        return Ok(());
    };
    let mut numbers = Vec::with_capacity(fields.len());
    let mut k = 0;
    for e in exprs {
        numbers.push(match e {
            Some(_) => {
                k += 1;
                engine.field(k - 1, input)?
            }
            None => 0.0,
        });
    }
    let mut values = Vec::with_capacity(fields.len());
    for (f, n) in fields.iter().zip(&numbers) {
        values.push(match f {
            Field::Literal(_) => Value::Literal,
            Field::Number { .. } => Value::Number(*n),
            Field::Text { name, .. } => match record_strings
                .and_then(|r| r.get(name))
                .or_else(|| o.strings.get(name))
            {
                Some(v) => Value::Text(v),
                None => {
                    return Err(radc_jit::Error::UndefinedString(name.clone()));
                }
            },
        });
    }
    let text = format::render(fields, &values, o.blanks_equal);
    scratch.bytes.extend_from_slice(text.as_bytes());
    Ok(())
}

/// Writes a record's warnings, then its output (`Ok(true)`), nothing for a record
/// `cond` rejected (`Ok(false)`), or the columns computed before an error and the
/// error.
fn emit<E: RecordEngine>(
    out: &mut dyn Write,
    engine: &mut E,
    o: &Options,
    result: Result<bool, radc_jit::Error>,
    scratch: &Scratch,
) -> Result<(), Stop> {
    let warnings = engine.take_warnings();
    if !o.nowarn && !warnings.is_empty() {
        let _ = out.flush();
        for w in warnings {
            eprintln!("{w}");
        }
    }
    match result {
        Ok(true) => {
            if out.write_all(&scratch.bytes).is_err() {
                return Err(Stop::Failed);
            }
            if o.unbuffered && out.flush().is_err() {
                return Err(Stop::Failed);
            }
            Ok(())
        }
        Ok(false) => Ok(()),
        Err(e) => {
            let partial = format_outputs(&scratch.columns, o.sep);
            let _ = out.write_all(partial.trim_end_matches('\n').as_bytes());
            let _ = out.flush();
            eprintln!("{e}");
            Err(Stop::Failed)
        }
    }
}

/// rcalc.c `bchanset`: missing columns are written as zeros.
fn binary_record(bytes: &mut Vec<u8>, values: &[(u32, f64)], f: RecordEncoding) {
    let mut col = 0u32;
    for &(n, v) in values {
        col += 1;
        while col < n {
            encode(bytes, 0.0, f);
            col += 1;
        }
        encode(bytes, v, f);
    }
}

fn encode(bytes: &mut Vec<u8>, v: f64, f: RecordEncoding) {
    let (mut word, len) = match f {
        RecordEncoding::Double { .. } => (v.to_ne_bytes(), 8),
        _ => {
            let mut w = [0u8; 8];
            w[..4].copy_from_slice(&(v as f32).to_ne_bytes());
            (w, 4)
        }
    };
    let word = &mut word[..len];
    if matches!(
        f,
        RecordEncoding::Double { swap: true } | RecordEncoding::Float { swap: true }
    ) {
        word.reverse();
    }
    bytes.extend_from_slice(word);
}
