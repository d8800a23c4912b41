//! Compile cost stays bounded: the code the JIT generates for a program (Cranelift
//! instructions, counted before optimisation, so independent of the machine's load)
//! must not blow up with inlining. Programs whose derived variables are used in many
//! branches once took seconds to compile (xyz_rgb.cal: 1.8 s in release, over 30 s in
//! debug) before inlining got a per-program budget.

use radc_jit::interp::{Interpreter, Record};
use radc_jit::{Jit, JitProgram, RecordEngine};
use radc_lang::FileId;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::{Env, Module};

#[path = "support/library.rs"]
mod library;
use library::library_programs;

fn module(sources: &[&str], env: &Env) -> Module {
    let mut m = Module::new(env);
    for (i, s) in sources.iter().enumerate() {
        let d = m.add_source(FileId(i as u32), s);
        assert!(d.iter().all(|d| !d.is_error()), "{d:?}");
    }
    m.optimize();
    m
}

/// Derived constants from a table, combined in a nine-way `select` (every case a
/// separate branch), called three times by three functions: the shape of a colour
/// space conversion. Every variable is small enough to inline on its own.
const CHAINS: &str = "
    tab(i) = select(i, 0.64, 0.33, 0.29, 0.60, 0.15, 0.06, 0.3127, 0.329);
    xr = tab(1); yr = tab(2); xg = tab(3); yg = tab(4);
    xb = tab(5); yb = tab(6); xw = tab(7); yw = tab(8);
    d = xr*(yg - yb) + xg*(yb - yr) + xb*(yr - yg);
    cr = (1/yw) * (xw*(yg - yb) - yw*(xg - xb) + xg*yb - xb*yg);
    cg = (1/yw) * (xw*(yb - yr) - yw*(xb - xr) - xr*yb + xb*yr);
    cb = (1/yw) * (xw*(yr - yg) - yw*(xr - xg) + xr*yg - xg*yr);
    m(i, j) = select(i*3 + j + 1,
        (yg - yb - xb*yg + yb*xg)/cr, (xb - xg - xb*yg + xg*yb)/cr, (xg*yb - xb*yg)/cr,
        (yb - yr - yb*xr + yr*xb)/cg, (xr - xb - xr*yb + xb*yr)/cg, (xb*yr - xr*yb)/cg,
        (yr - yg - yr*xg + yg*xr)/cb, (xg - xr - xg*yr + xr*yg)/cb, (xr*yg - xg*yr)/cb);
    pos(x) : if(x, x, 0);
    r(x, y, z) = pos(m(0,0)*x + m(0,1)*y + m(0,2)*z);
    g(x, y, z) = pos(m(1,0)*x + m(1,1)*y + m(1,2)*z);
    b(x, y, z) = pos(m(2,0)*x + m(2,1)*y + m(2,2)*z);
    lum(x, y, z) = (d*x + cr*y + cb*z) / cg;
    $1 = r($1, $2, $3); $2 = g($1, $2, $3); $3 = b($1, $2, $3); $4 = lum($1, $2, $3)";

#[test]
fn inlining_is_bounded_per_program() {
    let m = module(&[CHAINS], &Env::rcalc());
    let budgeted = Jit::new().compile(&m, &["$*"]).expect("compiles");
    let unbounded = Jit::new()
        .with_inline_budget(usize::MAX)
        .compile(&m, &["$*"])
        .expect("compiles");
    let none = Jit::new()
        .with_inline_budget(0)
        .compile(&m, &["$*"])
        .expect("compiles");
    let (b, u, n) = (
        budgeted.instruction_count(),
        unbounded.instruction_count(),
        none.instruction_count(),
    );
    eprintln!("instructions: budget {b}, no budget {u}, no inlining {n}");
    // Without the budget the same program generates several times the code: this
    // program is a real test of the bound.
    assert!(u > 3 * b, "budget {b}, no budget {u}");
    // With it, at most a few times what no inlining at all generates.
    assert!(b < 5 * n, "budget {b}, no inlining {n}");
    // And every setting computes the same.
    let row = [0.3, 0.5, 0.2];
    let mut want = None;
    for c in [&budgeted, &unbounded, &none] {
        let mut ctx = c.context();
        ctx.next_record();
        let mut out = Vec::new();
        let all = c.entry("$*").expect("entry");
        c.eval_outputs(all, &mut ctx, &mut Cols(&row), &mut out)
            .expect("evaluates");
        let bits: Vec<u64> = out.iter().map(|v| v.to_bits()).collect();
        assert_eq!(*want.get_or_insert(bits.clone()), bits);
    }
}

struct Cols<'a>(&'a [f64]);

impl radc_lang::cal::eval::Input for Cols<'_> {
    fn column(
        &mut self,
        n: u32,
    ) -> Result<(f64, Option<radc_lang::cal::eval::Errno>), radc_lang::cal::eval::EvalError> {
        Ok((self.0.get(n as usize - 1).copied().unwrap_or(0.0), None))
    }
    fn column_count(&mut self) -> Result<f64, radc_lang::cal::eval::EvalError> {
        Ok(self.0.len() as f64)
    }
}

/// The same through `radc calc`'s engine, against the interpreter.
#[test]
fn bounded_program_agrees_with_the_interpreter() {
    let m = module(&[CHAINS], &Env::rcalc());
    let mut jit = JitProgram::new(&m, MathErrors::ErrnoOnly).expect("compiles");
    let mut interp = Interpreter::new(&m, MathErrors::ErrnoOnly).expect("starts");
    for line in ["0.3 0.5 0.2\n", "1 1 1\n", "-2 0 1e300\n", "0 0 0\n"] {
        let a = RecordEngine::record(&mut jit, &mut Record::new(line, ' '));
        let b = RecordEngine::record(&mut interp, &mut Record::new(line, ' '));
        let bits = |r: &Result<Option<Vec<(u32, f64)>>, radc_jit::Error>| {
            format!(
                "{:?}",
                r.as_ref().map(|o| o
                    .as_ref()
                    .map(|v| v.iter().map(|(c, x)| (*c, x.to_bits())).collect::<Vec<_>>()))
            )
        };
        assert_eq!(bits(&a), bits(&b), "{line}");
    }
}

/// The program that took 1.8 s to compile: `radc calc -f xyz_rgb.cal -e
/// '$1=X($1,$2,$3);$2=Y($1,$2,$3);$3=Z($1,$2,$3);$4=luminance($1,$2,$3)'`.
#[test]
fn xyz_rgb_compiles_small() {
    let Some(lib) = radc_oracle::library_or_skip("jit_compile_size::xyz_rgb_compiles_small") else {
        return;
    };
    let text = std::fs::read_to_string(lib.join("xyz_rgb.cal"))
        .unwrap_or_else(|e| panic!("the oracle's library has no xyz_rgb.cal: {e}"));
    let m = module(
        &[
            &text,
            "$1=X($1,$2,$3);$2=Y($1,$2,$3);$3=Z($1,$2,$3);$4=luminance($1,$2,$3)",
        ],
        &Env::rcalc(),
    );
    let c = JitProgram::new(&m, MathErrors::ErrnoOnly);
    assert!(c.is_ok());
    let c = Jit::new().compile(&m, &["$*"]).expect("compiles");
    let n = c.instruction_count();
    eprintln!("xyz_rgb.cal: {n} instructions");
    // 11,207 with the default budget (1000 nodes); 34,325 at 3000 nodes, which
    // took 84 ms to compile; 130,000 with no budget.
    assert!(n < 16_000, "{n} instructions");
}

/// Every library file, every definition an entry point: none generates more than a
/// bounded amount of code.
#[test]
fn every_library_file_compiles_small() {
    let Some(lib) =
        radc_oracle::library_or_skip("jit_compile_size::every_library_file_compiles_small")
    else {
        return;
    };
    let programs = library_programs(&lib);
    assert!(
        programs.len() > 50,
        "only {} library programs from {}",
        programs.len(),
        lib.display()
    );
    let mut worst = (0, String::new());
    for (name, m, names) in programs {
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let Ok(c) = Jit::new().compile(&m, &names) else {
            continue;
        };
        let n = c.instruction_count();
        if n > worst.0 {
            worst = (n, name);
        }
    }
    eprintln!(
        "largest library file: {} ({} instructions)",
        worst.1, worst.0
    );
    // rayinit.cal, every definition: 15,582 with the default budget.
    assert!(worst.0 < 24_000, "{} instructions for {}", worst.0, worst.1);
}
