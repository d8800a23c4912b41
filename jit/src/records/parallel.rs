//! Records on several cores. rcalc evaluates each record from its own columns, so a
//! program whose records cannot see each other can run in chunks on as many
//! threads, each with its own engine, and its output (warnings and errors included)
//! be written in input order exactly as one thread would write it.
//!
//! Records can see each other through `outno` (it counts what `cond` accepted
//! before), a `:` variable computed from input (kept from the first record that
//! evaluated it), and recursion (depth warnings are given once per run); programs
//! reaching any of these, and runs whose order of reading matters (`-u`, `-in`,
//! `-on`, input formats, `-p`, binary input, a terminal), stay on one thread.

use super::{Passive, RecordEncoding, RecordOptions, Scratch, Stop, evaluate};
use crate::RecordEngine;
use crate::interp::{Record, format_outputs};
use radc_lang::cal::Module;
use radc_lang::cal::deps;
use radc_lang::cal::eval::Warning;
use radc_lang::cal::syntax::DefKind;
use std::collections::BTreeSet;
use std::io::{BufRead, IsTerminal, Write};

/// Input bytes per chunk (a chunk ends at the first newline after this many).
const CHUNK_BYTES: usize = 1 << 18;

/// Native stack of each worker thread; with recursion excluded, generous.
const WORKER_STACK: usize = 64 << 20;

/// How many threads the run may use: 1 unless the run and the program allow more.
pub(super) fn threads_for(module: &Module, o: &RecordOptions) -> usize {
    let wanted = o
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get().min(8)));
    let run_allows = !o.noinput
        && !o.unbuffered
        && o.in_limit == 0
        && o.out_limit == 0
        && o.input_format.is_none()
        && o.passive == Passive::Off
        && o.itype == RecordEncoding::Ascii
        && (!o.files.is_empty() || !std::io::stdin().is_terminal())
        && !std::io::stdout().is_terminal();
    if wanted <= 1 || !run_allows || !records_are_independent(module, o) {
        1
    } else {
        wanted
    }
}

/// No definition the outputs, `cond` or the `-o` format reach uses `outno`, is a
/// `:` variable still to be computed, or is a recursive function.
fn records_are_independent(module: &Module, o: &RecordOptions) -> bool {
    let mut reached: BTreeSet<_> = module
        .outputs()
        .values()
        .flat_map(|out| deps::needed_by_expr(module, &out.body))
        .collect();
    reached.extend(deps::needed_by_names(module, &["cond"]));
    if let Some((_, exprs)) = &o.record_format {
        for e in exprs.iter().flatten() {
            reached.extend(deps::needed_by_expr(module, e));
        }
    }
    reached.iter().all(|&d| {
        let def = module.def(d);
        let name = module.symbol(def.sym).name.as_str();
        let kept_from_input =
            !def.is_function() && def.kind == DefKind::Constant && def.parse_time_value.is_none();
        let recursive = def.is_function() && deps::needed_by_expr(module, &def.body).contains(&d);
        name != "outno" && !kept_from_input && !recursive
    })
}

/// What one chunk of records wrote: output bytes, and the warnings and the error
/// (with the columns computed before it) at the byte offsets where they occurred.
#[derive(Default)]
struct ChunkOut {
    bytes: Vec<u8>,
    warnings: Vec<(usize, Vec<Warning>)>,
    failed: Option<(usize, String, crate::Error)>,
}

/// One input stream on `engines.len()` threads, written as one thread would.
pub(super) fn run_stream<E: RecordEngine + Send>(
    input: &mut dyn BufRead,
    engines: &mut [E],
    o: &RecordOptions,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<(), Stop> {
    let mut chunks: Vec<Vec<u8>> = vec![Vec::new(); engines.len()];
    let mut nrecs = 0u64;
    loop {
        let mut at_end = false;
        let mut filled = 0;
        for chunk in chunks.iter_mut() {
            at_end = read_chunk(input, chunk).map_err(|_| Stop::Failed)?;
            if !chunk.is_empty() {
                filled += 1;
            }
            if at_end {
                break;
            }
        }
        let mut firsts = Vec::with_capacity(filled);
        for chunk in &chunks[..filled] {
            firsts.push(nrecs);
            nrecs += memchr::memchr_iter(b'\n', chunk).count() as u64;
            nrecs += u64::from(chunk.last().is_some_and(|&c| c != b'\n'));
        }
        let results: Vec<ChunkOut> = std::thread::scope(|scope| {
            let mut jobs = engines
                .iter_mut()
                .zip(&chunks[..filled])
                .zip(&firsts)
                .map(|((engine, chunk), &first)| (engine, chunk.as_slice(), first));
            let Some(here) = jobs.next() else {
                return Vec::new();
            };
            let handles: Vec<_> = jobs
                .map(|(engine, chunk, first)| {
                    std::thread::Builder::new()
                        .stack_size(WORKER_STACK)
                        .spawn_scoped(scope, move || run_chunk(engine, chunk, first, o))
                })
                .collect();
            let mut results = vec![run_chunk(here.0, here.1, here.2, o)];
            for h in handles {
                results.push(match h.map(|h| h.join()) {
                    Ok(Ok(r)) => r,
                    _ => ChunkOut {
                        failed: Some((
                            0,
                            String::new(),
                            crate::Error::Eval(radc_lang::cal::eval::EvalError::NotAvailable(
                                "a worker thread".into(),
                            )),
                        )),
                        ..ChunkOut::default()
                    },
                });
            }
            results
        });
        for r in results {
            write_chunk(out, err, r, o)?;
        }
        if at_end {
            return Ok(());
        }
    }
}

/// Reads about [`CHUNK_BYTES`] of whole lines (the last line of the input may have
/// no newline). True at the end of the input.
fn read_chunk(input: &mut dyn BufRead, chunk: &mut Vec<u8>) -> std::io::Result<bool> {
    chunk.clear();
    loop {
        let buf = input.fill_buf()?;
        if buf.is_empty() {
            return Ok(true);
        }
        if chunk.len() >= CHUNK_BYTES
            && let Some(end) = memchr::memchr(b'\n', buf)
        {
            chunk.extend_from_slice(&buf[..=end]);
            input.consume(end + 1);
            return Ok(false);
        }
        let n = buf.len();
        chunk.extend_from_slice(buf);
        input.consume(n);
    }
}

fn run_chunk<E: RecordEngine>(
    engine: &mut E,
    chunk: &[u8],
    first: u64,
    o: &RecordOptions,
) -> ChunkOut {
    engine.set_records_before(first);
    let mut done = ChunkOut::default();
    let mut scratch = Scratch::default();
    let mut start = 0;
    while start < chunk.len() {
        let end = memchr::memchr(b'\n', &chunk[start..]).map_or(chunk.len(), |k| start + k + 1);
        let mut record = Record::from_bytes(&chunk[start..end], o.sep);
        start = end;
        let result = evaluate(engine, o, &mut record, None, &mut scratch);
        let warnings = engine.take_warnings();
        if !warnings.is_empty() {
            done.warnings.push((done.bytes.len(), warnings));
        }
        match result {
            Ok(true) => done.bytes.extend_from_slice(&scratch.bytes),
            Ok(false) => {}
            Err(e) => {
                let partial = format_outputs(&scratch.columns, o.sep);
                let partial = partial.trim_end_matches('\n').to_string();
                done.failed = Some((done.bytes.len(), partial, e));
                break;
            }
        }
    }
    done
}

/// Writes a chunk's output with its warnings and error where they came, as the
/// one-thread loop does (stdout flushed before each message).
fn write_chunk(
    out: &mut dyn Write,
    err: &mut dyn Write,
    chunk: ChunkOut,
    o: &RecordOptions,
) -> Result<(), Stop> {
    let mut at = 0;
    let write = |out: &mut dyn Write, bytes: &[u8]| out.write_all(bytes).map_err(|_| Stop::Failed);
    for (offset, warnings) in chunk.warnings {
        write(out, &chunk.bytes[at..offset])?;
        at = offset;
        if !o.nowarn {
            let _ = out.flush();
            for w in warnings {
                let _ = writeln!(err, "{w}");
            }
        }
    }
    if let Some((offset, partial, e)) = chunk.failed {
        write(out, &chunk.bytes[at..offset])?;
        let _ = out.write_all(partial.as_bytes());
        let _ = out.flush();
        let _ = writeln!(err, "{e}");
        return Err(Stop::Failed);
    }
    write(out, &chunk.bytes[at..])
}
