//! calcomp evaluation speed: the reference interpreter against the JIT, per record
//! (every output column of the program evaluated once, on a fresh record clock: the
//! interpreter column by column, the JIT by its `$*` entry as `radc calc` runs it), on
//! functions of Radiance's `.cal` library and a typical pattern function; plus the
//! JIT's compile time. Library programs need the oracle (`tests/oracle/install.sh`);
//! without it only the self-contained programs run.
//!
//! Then "library compile": every definition of every `.cal` file of the library
//! compiled, one program per file (after `rayinit.cal`, as the renderer loads it); and
//! "inline budget": the compile time of xyz_rgb.cal's colour conversion (the program that
//! once took 1.8 s to compile) at several inlining budgets, with the code size of each
//! printed before it runs (`jit/tests/jit_compile_size.rs` holds the bounds as tests).
//!
//! To profile one program, run a single group for a fixed time under the profiler:
//! `valgrind --tool=callgrind target/release/deps/calc-* --bench --profile-time 10 'sun.cal'`
//! (the per-record groups time the JIT and the interpreter on the same rows).
//!
//! Times are the bench thread's CPU time, not wall-clock time (see [`CpuTime`]).
//!
//! Run: `cargo bench -p radc-jit --bench calc` (numbers in BENCHMARKS.md, "calcomp JIT").

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use radc_jit::Jit;
use radc_lang::FileId;
use radc_lang::cal::eval::{Errno, EvalError, Evaluator, Input};
use radc_lang::cal::{Env, Module};
use std::hint::black_box;
use std::path::PathBuf;

#[path = "../tests/support/library.rs"]
mod library;
use library::library_programs;
use radc_oracle::library as library_dir;

/// The machine is shared: wall-clock time mostly measures the other processes, so
/// this bench measures the thread's own CPU time (`CLOCK_THREAD_CPUTIME_ID`; the
/// first field of `/proc/thread-self/schedstat`, used before, reads 0 on kernels
/// without scheduler statistics).
struct CpuTime;

/// This thread's CPU time in nanoseconds, 0 where it cannot be read.
fn thread_cpu_ns() -> u64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec for the duration of the call.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    if rc != 0 {
        return 0;
    }
    (ts.tv_sec as u64) * 1_000_000_000 + ts.tv_nsec as u64
}

impl Measurement for CpuTime {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        thread_cpu_ns()
    }
    fn end(&self, start: u64) -> u64 {
        thread_cpu_ns().saturating_sub(start)
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &CpuFormatter
    }
}

/// Nanoseconds, scaled as criterion scales wall time.
struct CpuFormatter;

impl ValueFormatter for CpuFormatter {
    fn scale_values(&self, typical: f64, values: &mut [f64]) -> &'static str {
        let (div, unit) = if typical < 1e3 {
            (1.0, "ns")
        } else if typical < 1e6 {
            (1e3, "µs")
        } else if typical < 1e9 {
            (1e6, "ms")
        } else {
            (1e9, "s")
        };
        values.iter_mut().for_each(|v| *v /= div);
        unit
    }
    fn scale_throughputs(&self, _: f64, _: &Throughput, values: &mut [f64]) -> &'static str {
        self.scale_for_machines(values)
    }
    fn scale_for_machines(&self, _: &mut [f64]) -> &'static str {
        "ns"
    }
}

/// Input columns already parsed, so only evaluation is timed.
struct Columns<'a>(&'a [f64]);

impl Input for Columns<'_> {
    fn column(&mut self, n: u32) -> Result<(f64, Option<Errno>), EvalError> {
        Ok((self.0.get(n as usize - 1).copied().unwrap_or(0.0), None))
    }
    fn column_count(&mut self) -> Result<f64, EvalError> {
        Ok(self.0.len() as f64)
    }
}

struct Program {
    name: &'static str,
    /// `.cal` files from the library, loaded in order.
    files: &'static [&'static str],
    expr: &'static str,
    rows: Vec<Vec<f64>>,
}

/// Bricks with mortar and a little shading: the kind of expression a `brightfunc`
/// pattern evaluates per ray (self-contained, like a scene's own .cal file).
const PATTERN: &str = "Px=$1;Py=$2;Pz=$3;\
    frac(x) : x - floor(x); and(a,b) : if(a, b, a);\
    mortar : 0.02; bw : 0.2; bh : 0.1;\
    row = floor(Pz/bh); shift = if(frac(row/2) - 0.25, 0.5, 0);\
    bx = frac(Px/bw + shift); bz = frac(Pz/bh);\
    inbrick = and(bx - mortar/bw, bz - mortar/bh);\
    grain = 0.9 + 0.1*sin(Px*40 + 3*cos(Pz*25)) * cos(Py*17);\
    $1 = if(inbrick, grain * (0.7 + 0.3*rand(row*37 + floor(Px/bw + shift))), 0.35)";

/// The rcalc comparison of bench/jit_report.sh: a two-argument function with trig,
/// sqrt and exp.
const TWO_ARG: &str = "f(x,y) = sqrt(x*x + y*y) * sin(x) * cos(y) + exp(-x*y/100); $1 = f($1, $2)";

fn grid(n: usize, f: impl Fn(f64) -> Vec<f64>) -> Vec<Vec<f64>> {
    (0..n).map(|i| f(i as f64 / n as f64)).collect()
}

fn programs() -> Vec<Program> {
    vec![
        Program {
            name: "skybright.cal (CIE clear sky)",
            files: &["rayinit.cal", "skybright.cal"],
            expr: "Dx=$1;Dy=$2;Dz=$3;A1=1;A2=3.2;A3=0.2;A4=0.9;A5=0.3;A6=0.4;A7=0.866;$1=skybr",
            rows: grid(64, |t| {
                let (a, z) = (t * std::f64::consts::TAU, 0.05 + 0.9 * t);
                vec![
                    a.cos() * (1.0 - z * z).sqrt(),
                    a.sin() * (1.0 - z * z).sqrt(),
                    z,
                ]
            }),
        },
        Program {
            name: "perezlum.cal (Perez sky)",
            files: &["rayinit.cal", "perezlum.cal"],
            expr: "Dx=$1;Dy=$2;Dz=$3;A1=1.2;A2=0.2;A3=-1;A4=-0.32;A5=10;A6=-3;A7=0.45;\
                   A8=0.5;A9=0.1;A10=0.86;$1=skybright",
            rows: grid(64, |t| {
                let (a, z) = (t * std::f64::consts::TAU, 0.05 + 0.9 * t);
                vec![
                    a.cos() * (1.0 - z * z).sqrt(),
                    a.sin() * (1.0 - z * z).sqrt(),
                    z,
                ]
            }),
        },
        Program {
            name: "sun.cal (solar position)",
            files: &["sun.cal"],
            expr: "MONTH=$1;DAY=$2;TIME=$3;$1=SALT;$2=SAZI;$3=HALFDAY",
            rows: grid(64, |t| {
                vec![1.0 + (t * 12.0).floor(), 1.0 + t * 27.0, 6.0 + 12.0 * t]
            }),
        },
        Program {
            name: "cielab.cal (XYZ to L*a*b*)",
            files: &["cielab.cal"],
            expr: "$1=Ls($2);$2=as($1,$2,$3);$3=bs($1,$2,$3);$4=Cs($1,$2,$3);$5=bfunc($1)",
            rows: grid(64, |t| vec![0.1 + t, 0.005 + 0.9 * t, 1.2 - t]),
        },
        Program {
            name: "reinhart.cal (sky patch index)",
            files: &["reinhart.cal"],
            expr: "Dx=$1;Dy=$2;Dz=$3;$1=rbin;$2=r_row",
            rows: grid(64, |t| {
                let (a, z) = (t * std::f64::consts::TAU, 0.02 + 0.95 * t);
                vec![
                    a.cos() * (1.0 - z * z).sqrt(),
                    a.sin() * (1.0 - z * z).sqrt(),
                    z,
                ]
            }),
        },
        Program {
            name: "pattern (bricks)",
            files: &[],
            expr: PATTERN,
            rows: grid(64, |t| vec![t * 3.1, 1.0 - t, t * 1.7]),
        },
        Program {
            name: "two-argument function",
            files: &[],
            expr: TWO_ARG,
            rows: grid(64, |t| vec![t * 10.0, 5.0 - t * 3.0]),
        },
    ]
}

/// As `radc calc` builds it: `MF:4` for reinhart.cal comes first, like rcalc's `-e`.
fn module(p: &Program, lib: Option<&PathBuf>) -> Option<Module> {
    let mut m = Module::new(&Env::rcalc());
    let mut file = 0;
    if p.files.contains(&"reinhart.cal") {
        m.add_source(FileId(file), "MF:4");
        file += 1;
    }
    for f in p.files {
        let text = std::fs::read_to_string(lib?.join(f)).ok()?;
        m.add_source(FileId(file), &text);
        file += 1;
    }
    let d = m.add_source(FileId(file), p.expr);
    if d.iter().any(|d| d.is_error()) {
        return None;
    }
    m.optimize();
    Some(m)
}

fn bench(c: &mut Criterion<CpuTime>) {
    let lib = library_dir();
    if lib.is_none() {
        eprintln!("notice: no .oracle/ library: only the self-contained programs run");
    }
    for p in programs() {
        let Some(m) = module(&p, lib.as_ref()) else {
            continue;
        };
        let names = ["$*"];
        let Ok(compiled) = Jit::new().compile(&m, &names) else {
            eprintln!("notice: {}: not compiled", p.name);
            continue;
        };
        let Some(all) = compiled.entry("$*") else {
            continue;
        };
        eprintln!(
            "{}: {} Cranelift instructions",
            p.name,
            compiled.instruction_count()
        );
        let bodies: Vec<_> = m.outputs().values().map(|o| &o.body).collect();
        let mut group = c.benchmark_group(p.name);
        let mut ev = Evaluator::new(&m);
        let mut i = 0;
        group.bench_function("interpreter (ns/record)", |b| {
            b.iter(|| {
                let row = &p.rows[i % p.rows.len()];
                i += 1;
                ev.next_record();
                let mut input = Columns(row);
                for body in &bodies {
                    black_box(ev.eval_top(body, &mut input).unwrap_or(0.0));
                }
            })
        });
        let mut ctx = compiled.context();
        let mut i = 0;
        let mut out = Vec::new();
        group.bench_function("JIT (ns/record)", |b| {
            b.iter(|| {
                let row = &p.rows[i % p.rows.len()];
                i += 1;
                ctx.next_record();
                let mut input = Columns(row);
                out.clear();
                let ok = compiled.eval_outputs(all, &mut ctx, &mut input, &mut out);
                black_box((ok.is_ok(), &out));
            })
        });
        group.bench_function("JIT compile", |b| {
            b.iter(|| black_box(Jit::new().compile(&m, &names).is_ok()))
        });
        group.finish();
    }
}

fn bench_library(c: &mut Criterion<CpuTime>) {
    let Some(lib) = library_dir() else {
        return;
    };
    let programs: Vec<(Module, Vec<String>)> = library_programs(&lib)
        .into_iter()
        .map(|(_, m, names)| (m, names))
        .collect();
    let mut functions = 0;
    let mut entries = 0;
    let mut instructions = 0;
    for (m, names) in &programs {
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        entries += names.len();
        match Jit::new().compile(m, &names) {
            Ok(c) => {
                functions += c.function_count();
                instructions += c.instruction_count();
            }
            Err(e) => eprintln!("notice: library program not compiled: {e}"),
        }
    }
    eprintln!(
        "library: {} files, {entries} entry points, {functions} variable and function \
         bodies, {instructions} Cranelift instructions",
        programs.len()
    );
    let mut group = c.benchmark_group("library compile");
    group.sample_size(10);
    group.bench_function("every .cal file, every definition", |b| {
        b.iter(|| {
            for (m, names) in &programs {
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                black_box(Jit::new().compile(m, &names).is_ok());
            }
        })
    });
    group.finish();
}

/// xyz_rgb.cal's four outputs as `radc calc -f xyz_rgb.cal -e '$1=X($1,$2,$3);...'` builds
/// them, compiled at inlining budgets from none to six times the default (1000 nodes).
fn bench_inline_budget(c: &mut Criterion<CpuTime>) {
    let Some(text) =
        library_dir().and_then(|lib| std::fs::read_to_string(lib.join("xyz_rgb.cal")).ok())
    else {
        return;
    };
    let mut m = Module::new(&Env::rcalc());
    m.add_source(FileId(0), &text);
    let d = m.add_source(
        FileId(1),
        "$1=X($1,$2,$3);$2=Y($1,$2,$3);$3=Z($1,$2,$3);$4=luminance($1,$2,$3)",
    );
    if d.iter().any(|d| d.is_error()) {
        eprintln!("notice: xyz_rgb.cal does not check");
        return;
    }
    m.optimize();
    let mut group = c.benchmark_group("inline budget (xyz_rgb.cal)");
    group.sample_size(10);
    for budget in [0, 250, 500, 1000, 2000, 3000, 6000] {
        let compile = || Jit::new().with_inline_budget(budget).compile(&m, &["$*"]);
        match compile() {
            Ok(p) => eprintln!("budget {budget}: {} instructions", p.instruction_count()),
            Err(e) => {
                eprintln!("notice: budget {budget}: not compiled: {e}");
                continue;
            }
        }
        group.bench_function(format!("budget {budget}"), |b| {
            b.iter(|| black_box(compile().is_ok()))
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().with_measurement(CpuTime);
    targets = bench, bench_library, bench_inline_budget
}
criterion_main!(benches);
