//! rcalc's record loop (rcalc.c `execute`, `putout`), one for both engines: records
//! read from the input files (text lines, `-i` formats, binary `-id`/`-if`), each
//! evaluated by a [`RecordEngine`] (the JIT, or the reference interpreter when asked
//! or when the JIT declines the program) and written as `$N` columns, an `-o` format or
//! binary. Independent records run on several threads ([`parallel`]) with output,
//! warnings and errors in input order, byte for byte as one thread writes them. The
//! caller gives the output and the message streams; nothing here prints.

pub mod format;
pub mod input_format;
pub mod laminate;
mod parallel;
pub mod split;
pub mod total;

use std::collections::HashMap;
use std::io::{BufRead, Write};

use format::{Field, Value};
use radc_lang::cal::Module;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::ir::Expr;

use crate::compile::StartError;
use crate::interp::{Interpreter, Outputs, Record, format_outputs, write_outputs};
use crate::{JitProgram, RecordEngine};

/// Binary or text records (rcalc's `-id`, `-if`, `-od`, `-of`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordEncoding {
    Ascii,
    Double { swap: bool },
    Float { swap: bool },
}

pub struct RecordOptions {
    pub noinput: bool,
    pub nowarn: bool,
    pub unbuffered: bool,
    pub sep: char,
    pub itype: RecordEncoding,
    pub in_cols: usize,
    pub otype: RecordEncoding,
    pub in_limit: u64,
    pub out_limit: u64,
    /// The input files, read in order (none: standard input).
    pub files: Vec<String>,
    /// `-o format`: its fields and the compiled expression of each number field.
    pub record_format: Option<(Vec<Field>, Vec<Option<Expr>>)>,
    /// `-i format`: the fields to match input against.
    pub input_format: Option<Vec<Field>>,
    /// `-s name=value`.
    pub strings: HashMap<String, String>,
    /// rcalc's `-b` (blanks compare equal), on by default.
    pub blanks_equal: bool,
    /// `-l`: ignore ends of lines in record formats.
    pub ignore_eol: bool,
    /// `-p`: pass unmatched input through; `-P`: also records `cond` rejects.
    pub passive: Passive,
    /// `--interp`: evaluate with the reference interpreter instead of the JIT.
    pub interp: bool,
    /// `--threads N`: at most this many threads (default: the machine's cores).
    pub threads: Option<usize>,
    /// The name messages start with (`radc calc`, or `rcalc` when radc is called so).
    pub program: String,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Passive {
    Off,
    Unmatched,
    AlsoRejected,
}

impl RecordEncoding {
    /// rcalc's `-i`/`-o` format letters after the option (`a`, `d`, `D`, `f`, `F`, with
    /// a column count for input): the encoding and the count (1 by default).
    pub fn parse(spec: &str) -> Option<(RecordEncoding, usize)> {
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
}

/// Native stack the JIT's code may use on the evaluation thread (of 512 MiB).
const JIT_STACK_BUDGET: usize = 256 << 20;

/// Runs the records with the JIT, unless `--interp` asks for the reference
/// interpreter or the JIT declines the program (then with a note).
pub fn run(
    module: &Module,
    o: &RecordOptions,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<(), Failed> {
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
                    let _ = writeln!(err, "{e}");
                    return Err(Failed);
                }
                Err(StartError::Jit(e)) => {
                    if !o.nowarn {
                        let _ = writeln!(err, "{}: note: {e}; using the interpreter", o.program);
                    }
                    break;
                }
            }
        }
        if engines.len() == threads {
            return drive(&mut engines, o, out, err);
        }
    }
    let mut engines = Vec::with_capacity(threads);
    for _ in 0..threads {
        match Interpreter::new(module, MathErrors::default()) {
            Ok(i) => engines.push(i.with_fields(&fields)),
            Err(e) => {
                let _ = writeln!(err, "{e}");
                return Err(Failed);
            }
        }
    }
    drive(&mut engines, o, out, err)
}

/// Buffers reused from record to record: the `$N` values and the output bytes.
#[derive(Default)]
struct Scratch {
    columns: Outputs,
    bytes: Vec<u8>,
}

/// Runs the records on `engines` (one per thread; the first alone unless
/// [`parallel::threads_for`] allowed more).
fn drive<E: RecordEngine + Send>(
    engines: &mut [E],
    o: &RecordOptions,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<(), Failed> {
    let mut scratch = Scratch::default();
    let mut stream = |input: &mut dyn BufRead,
                      engines: &mut [E],
                      out: &mut dyn Write,
                      err: &mut dyn Write| match engines {
        [engine] => run_stream(input, engine, o, out, err, &mut scratch),
        _ => parallel::run_stream(input, engines, o, out, err),
    };
    let status = if o.noinput {
        let Some(engine) = engines.first_mut() else {
            return Err(Failed);
        };
        engine.begin_single();
        let r = produce(
            engine,
            o,
            &mut radc_lang::cal::eval::NoInput,
            None,
            &mut scratch,
        );
        emit(out, err, engine, o, r.map(|()| true), &scratch)
    } else if o.files.is_empty() {
        let stdin = std::io::stdin();
        let mut input = std::io::BufReader::with_capacity(1 << 16, stdin.lock());
        stream(&mut input, engines, out, err)
    } else {
        let mut status = Ok(());
        for f in &o.files {
            match std::fs::File::open(f) {
                Ok(file) => {
                    let mut input = std::io::BufReader::with_capacity(1 << 16, file);
                    // rcalc.c `execute` counts records (recno, -in, -on) per file.
                    engines.iter_mut().for_each(|e| e.start_file());
                    status = stream(&mut input, engines, out, err);
                }
                Err(e) => {
                    let _ = out.flush();
                    let _ = writeln!(err, "{}: {f}: cannot open: {e}", o.program);
                    return Err(Failed);
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
        (Ok(()), Ok(())) => Ok(()),
        _ => Err(Failed),
    }
}

/// Why record processing stopped early: an evaluation error (already reported) or a
/// write failure. Either way the exit status is 1.
enum Stop {
    Failed,
}

/// The run stopped on an error, already written to the messages (rcalc exits 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Failed;

fn run_stream<E: RecordEngine>(
    input: &mut dyn BufRead,
    engine: &mut E,
    o: &RecordOptions,
    out: &mut dyn Write,
    err: &mut dyn Write,
    scratch: &mut Scratch,
) -> Result<(), Stop> {
    if let Some(fields) = &o.input_format {
        return run_matched(input, fields, engine, o, out, err, scratch);
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
        emit(out, err, engine, o, result, scratch)?;
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
    o: &RecordOptions,
    out: &mut dyn Write,
    err: &mut dyn Write,
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
        emit(out, err, engine, o, result, scratch)?;
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
    o: &RecordOptions,
    input: &mut dyn radc_lang::cal::eval::Input,
    record_strings: Option<&HashMap<String, String>>,
    scratch: &mut Scratch,
) -> Result<bool, crate::Error> {
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
    o: &RecordOptions,
    input: &mut dyn radc_lang::cal::eval::Input,
    record_strings: Option<&HashMap<String, String>>,
    scratch: &mut Scratch,
) -> Result<(), crate::Error> {
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
                    return Err(crate::Error::UndefinedString(name.clone()));
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
    err: &mut dyn Write,
    engine: &mut E,
    o: &RecordOptions,
    result: Result<bool, crate::Error>,
    scratch: &Scratch,
) -> Result<(), Stop> {
    let warnings = engine.take_warnings();
    if !o.nowarn && !warnings.is_empty() {
        let _ = out.flush();
        for w in warnings {
            let _ = writeln!(err, "{w}");
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
            let _ = writeln!(err, "{e}");
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
