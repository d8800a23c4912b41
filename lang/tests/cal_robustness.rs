//! Bad input never crashes: random calcomp-like text through the parser, the checks
//! and the evaluator. Deterministic (a fixed xorshift seed), so a failure reproduces.

use radc_lang::FileId;
use radc_lang::cal::eval::{Evaluator, NoInput};
use radc_lang::cal::{Env, Module, check};

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[(self.next() % items.len() as u64) as usize]
    }
}

const PIECES: &[&str] = &[
    "a",
    "b",
    "f",
    "g",
    "x",
    "sin",
    "if",
    "select",
    "max",
    "rand",
    "PI",
    "in",
    "$1",
    "$",
    "$0",
    "1",
    "0",
    ".5",
    "1e",
    "1e400",
    ".",
    "2.",
    "(",
    ")",
    "(",
    ")",
    ",",
    ";",
    "=",
    ":",
    "+",
    "-",
    "*",
    "/",
    "^",
    "{",
    "}",
    " ",
    "\n",
    "`",
    "a`",
    "`b",
    "é",
    "#",
    "f(x)=",
    "g(h,y)=h(y);",
    "f(f(",
    "a:",
    "a=",
    "$1=",
    "1/0",
    "0^-1",
    "(-8)^(1/3)",
    "sqrt(-1)",
];

#[test]
fn random_text_never_panics() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..4000 {
        let n = 1 + rng.next() % 40;
        let text: String = (0..n).map(|_| rng.pick(PIECES)).collect();
        for env in [Env::rcalc(), Env::renderer(), Env::bare().complete()] {
            let _ = check(FileId(0), &text, &env);
        }
        let mut m = Module::new(&Env::rcalc());
        let _ = m.add_source(FileId(0), &text);
        m.optimize();
        let mut ev = Evaluator::new(&m).with_max_depth(100);
        ev.next_record();
        for o in m.outputs().values() {
            let _ = ev.eval_top(&o.body, &mut NoInput);
        }
        for s in 0..m.symbols().len() {
            let _ = ev.variable(radc_lang::cal::ir::SymId(s as u32), &mut NoInput);
        }
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!("x = {}1{}", "(".repeat(100_000), ")".repeat(100_000));
    let d = check(FileId(0), &deep, &Env::rcalc());
    assert!(d.iter().any(|d| d.code.id == "E0501"));
    let long = format!("x = {}", vec!["1"; 50_000].join("^"));
    let d = check(FileId(0), &long, &Env::rcalc());
    assert!(d.iter().any(|d| d.code.id == "E0501"));
    let sum = format!("a = 1; $1 = {}", vec!["a"; 900].join("+"));
    let d = check(FileId(0), &sum, &Env::rcalc().complete());
    assert!(d.iter().all(|d| d.code.id != "E0501"), "{d:?}");
    // Unfolded (rcalc -n), the sum stays 900 levels deep; evaluation recurses, so it
    // runs on a thread with a stack as large as `radc calc` gives it.
    let value = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || {
            let mut m = Module::new(&Env::rcalc());
            m.set_folding(false);
            assert!(m.add_source(FileId(0), &sum).is_empty());
            let mut ev = Evaluator::new(&m);
            ev.eval_top(&m.outputs()[&1].body, &mut NoInput)
        })
        .map(|h| h.join());
    assert!(matches!(value, Ok(Ok(Ok(900.0)))));
}

#[test]
fn deep_constant_recursion_is_left_for_run_time() {
    let mut m = Module::new(&Env::rcalc());
    let d = m.add_source(FileId(0), "f(n) : if(n, 1 + f(n-1), 0); $1 = f(5000)");
    assert!(d.is_empty(), "{d:?}");
    assert!(m.outputs()[&1].body.as_num().is_none());
}

#[test]
fn fifty_nested_parentheses_are_fine() {
    let deep = format!("x = {}1{}", "(".repeat(50), ")".repeat(50));
    let d = check(FileId(0), &deep, &Env::rcalc());
    assert!(d.iter().all(|d| d.code.id != "E0501"));
}
