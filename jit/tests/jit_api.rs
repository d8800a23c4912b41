//! The JIT's safe API: entry points by name, calls with arguments, host variables,
//! contexts, limits, and errors instead of crashes.

use radc_jit::{Jit, JitError};
use radc_lang::FileId;
use radc_lang::cal::eval::{EvalError, Warning};
use radc_lang::cal::{Env, Module};

fn module(src: &str) -> Module {
    let mut m = Module::new(&Env::rcalc());
    let d = m.add_source(FileId(0), src);
    assert!(d.iter().all(|d| !d.is_error()), "{d:?}");
    m.optimize();
    m
}

#[test]
fn variables_functions_and_outputs_by_name() {
    let m = module("a = 2*b; b = 3; sq(x) = x*x; hyp(x, y) = sqrt(sq(x) + sq(y)); $2 = a + 1");
    let c = Jit::new()
        .compile(&m, &["a", "hyp", "$2"])
        .expect("compiles");
    let mut ctx = c.context();
    ctx.next_record();
    let a = c.entry("a").expect("a");
    assert_eq!(c.eval_no_input(a, &mut ctx), Ok(6.0));
    let hyp = c.entry("hyp").expect("hyp");
    let mut none = radc_lang::cal::eval::NoInput;
    assert_eq!(c.call(hyp, &[3.0, 4.0], &mut ctx, &mut none), Ok(5.0));
    assert_eq!(
        c.call(hyp, &[3.0], &mut ctx, &mut none),
        Err(EvalError::TooFewArguments("hyp".into()))
    );
    let out = c.entry("$2").expect("$2");
    assert_eq!(c.eval_no_input(out, &mut ctx), Ok(7.0));
}

#[test]
fn unknown_entries_are_errors() {
    let m = module("a = 1; $1 = a");
    assert!(matches!(
        Jit::new().compile(&m, &["nosuch"]),
        Err(JitError::UnknownEntry(_))
    ));
    assert!(matches!(
        Jit::new().compile(&m, &["$3"]),
        Err(JitError::UnknownEntry(_))
    ));
}

#[test]
fn only_reachable_definitions_are_compiled() {
    let m = module(
        "a = b + f(c); b = 2*c; c = $1; f(x) = g(x); g(x) = x; unused = a*nosuch; \
         other(x) = x + 1; h(p, x) = p(x); k = h(g, 1)",
    );
    let c = Jit::new().compile(&m, &["a"]).expect("compiles");
    // a, b, c, f, g
    assert_eq!(c.function_count(), 5);
    let c = Jit::new().compile(&m, &["k"]).expect("compiles");
    // k, h, g
    assert_eq!(c.function_count(), 3);
}

#[test]
fn host_variables_come_from_the_context() {
    let mut m = module("$1 = recno * 2");
    m.set_variable("recno", 0.0);
    let c = Jit::new()
        .with_host_variables(&["recno", "nosuch"])
        .compile(&m, &["$1"])
        .expect("compiles");
    let mut ctx = c.context();
    let k = c.host_index("recno").expect("recno resolves");
    assert_eq!(c.host_index("nosuch"), None);
    ctx.set_host(k, 21.0);
    ctx.next_record();
    let e = c.entry("$1").expect("$1");
    assert_eq!(c.eval_no_input(e, &mut ctx), Ok(42.0));
}

#[test]
fn values_are_cached_per_record() {
    // Each fresh evaluation of `x` divides by zero once, and warns.
    let m = module("x = 1/z + 1; z = 0; y = x + x");
    let c = Jit::new().compile(&m, &["y"]).expect("compiles");
    let mut ctx = c.context();
    let y = c.entry("y").expect("y");
    ctx.next_record();
    assert_eq!(c.eval_no_input(y, &mut ctx), Ok(2.0));
    assert_eq!(c.eval_no_input(y, &mut ctx), Ok(2.0));
    assert_eq!(ctx.take_warnings(), [Warning::DivisionByZero]);
    ctx.next_record();
    assert_eq!(c.eval_no_input(y, &mut ctx), Ok(2.0));
    assert_eq!(ctx.take_warnings(), [Warning::DivisionByZero]);
}

#[test]
fn a_context_belongs_to_its_program() {
    let m = module("a = 1");
    let c1 = Jit::new().compile(&m, &["a"]).expect("compiles");
    let c2 = Jit::new().compile(&m, &["a"]).expect("compiles");
    let mut ctx = c2.context();
    let a = c1.entry("a").expect("a");
    assert!(c1.eval_no_input(a, &mut ctx).is_err());
}

#[test]
fn runaway_recursion_is_an_error_not_a_crash() {
    let m = module("down(n) = if(n, 1 + down(n-1), 0); selfref = selfref + 1");
    let c = Jit::new()
        .compile(&m, &["down", "selfref"])
        .expect("compiles");
    let mut ctx = c.context();
    ctx.next_record();
    let mut none = radc_lang::cal::eval::NoInput;
    let down = c.entry("down").expect("down");
    assert_eq!(c.call(down, &[50.0], &mut ctx, &mut none), Ok(50.0));
    let deep = c.call(down, &[1e7], &mut ctx, &mut none);
    assert!(matches!(deep, Err(EvalError::TooDeep(_))), "{deep:?}");
    // A variable referring to itself sees its previous value (caldefn.c stamps it
    // before evaluating): it counts records instead of recursing.
    let s = c.entry("selfref").expect("selfref");
    assert_eq!(c.eval_no_input(s, &mut ctx), Ok(1.0));
    assert_eq!(c.eval_no_input(s, &mut ctx), Ok(1.0));
    ctx.next_record();
    assert_eq!(c.eval_no_input(s, &mut ctx), Ok(2.0));
    // The context is still usable afterwards.
    assert_eq!(c.call(down, &[3.0], &mut ctx, &mut none), Ok(3.0));
}

#[test]
fn oversized_programs_are_declined() {
    // The parser refuses statements past 1000 operators or 50 nested parentheses, so
    // the JIT's own limits bound whole programs: exercised here with small limits.
    let mut src = String::from("v0 = $1;\n");
    for i in 1..200 {
        src.push_str(&format!("v{i} = sin(v{}) + v{} * 2;\n", i - 1, i - 1));
    }
    src.push_str(&format!(
        "$1 = {}$1{};\n",
        "sin(".repeat(40),
        ")".repeat(40)
    ));
    src.push_str("$2 = v199;\n");
    let m = module(&src);
    // Within the defaults: compiled.
    assert!(Jit::new().compile(&m, &["$1", "$2"]).is_ok());
    // Too many nodes across the definitions an entry reaches.
    let nodes = Jit::new()
        .with_size_limits(500, 1000)
        .compile(&m, &["$2"])
        .err();
    assert!(matches!(nodes, Some(JitError::TooLarge(_))), "{nodes:?}");
    // Nested too deep.
    let deep = Jit::new()
        .with_size_limits(1_000_000, 30)
        .compile(&m, &["$1"])
        .err();
    assert!(matches!(deep, Some(JitError::TooLarge(_))), "{deep:?}");
    // Each limit alone: the shallow entry passes the nesting limit.
    assert!(
        Jit::new()
            .with_size_limits(1_000_000, 30)
            .compile(&m, &["$2"])
            .is_ok()
    );
}

#[test]
fn one_program_many_threads() {
    fn shareable<T: Send + Sync>() {}
    fn sendable<T: Send>() {}
    shareable::<radc_jit::Compiled>();
    sendable::<radc_jit::Context>();
    let m = module("f(x) = if(x, x*f(x-1), 1); sq(x) = x*x");
    let c = Jit::new().compile(&m, &["f", "sq"]).expect("compiles");
    std::thread::scope(|s| {
        for t in 0..4 {
            let c = &c;
            s.spawn(move || {
                let mut ctx = c.context();
                let f = c.entry("f").expect("f");
                let mut none = radc_lang::cal::eval::NoInput;
                for i in 0..200 {
                    ctx.next_record();
                    let n = f64::from((i + t) % 10);
                    let want: f64 = (1..=((i + t) % 10)).map(f64::from).product();
                    assert_eq!(c.call(f, &[n], &mut ctx, &mut none), Ok(want));
                }
            });
        }
    });
}

/// A new context is in its first record already: `=` values are computed once until
/// `next_record`, as for an interpreter on which `next_record` was called (the
/// interpreter alone, before its first one, keeps nothing).
#[test]
fn a_new_context_is_in_its_first_record() {
    use radc_lang::cal::eval::{Evaluator, NoInput};
    let m = module("a = 1/in(0) + 1; b = a + a; $1 = b + a; $2 = a*a");
    let c = Jit::new().compile(&m, &["$*"]).expect("compiles");
    let all = c.entry("$*").expect("$*");
    let mut ev = Evaluator::new(&m);
    ev.next_record();
    let mut ctx = c.context();
    let bodies: Vec<_> = m.outputs().values().map(|o| &o.body).collect();
    for round in 0..4 {
        if round % 2 == 1 {
            ev.next_record();
            ctx.next_record();
        }
        let mut want = Vec::new();
        for body in &bodies {
            want.push(ev.eval_top(body, &mut NoInput).map(f64::to_bits));
        }
        let mut got = Vec::new();
        c.eval_outputs(all, &mut ctx, &mut NoInput, &mut got)
            .expect("evaluates");
        let got: Vec<_> = got.iter().map(|v| Ok(v.to_bits())).collect();
        assert_eq!(got, want, "round {round}");
        let warned = ctx.take_warnings();
        // `a` is computed (and warns) once per record.
        let expected = if round % 2 == 1 || round == 0 { 1 } else { 0 };
        assert_eq!(warned.len(), expected, "round {round}: {warned:?}");
        assert_eq!(warned, std::mem::take(&mut ev.warnings), "round {round}");
    }
}
