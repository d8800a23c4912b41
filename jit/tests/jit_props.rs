//! Property test: random well-formed calcomp programs and inputs give the same
//! results under the JIT as under the reference interpreter, to the bit (any NaN
//! equals any NaN), with the same warnings and errors, folded or not.

use proptest::prelude::*;
use radc_jit::interp::{Interpreter, Outputs, Record};
use radc_jit::{Error, JitProgram, RecordEngine};
use radc_lang::FileId;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::{Env, Module};

fn literal() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("0".to_string()),
        Just("1".to_string()),
        Just("2".to_string()),
        Just("0.5".to_string()),
        Just("3".to_string()),
        Just("1e308".to_string()),
        Just("1e-300".to_string()),
        (0.0f64..100.0).prop_map(|v| format!("{v:e}")),
    ]
}

/// An expression over `names` (variables, parameters, input columns) that may call
/// the user functions in `calls` (name, arity).
fn expr(
    names: &'static [&'static str],
    calls: &'static [(&'static str, usize)],
) -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        3 => literal(),
        2 => proptest::sample::select(names).prop_map(str::to_string),
    ];
    leaf.prop_recursive(5, 48, 4, move |inner| {
        let unary = proptest::sample::select(vec![
            "sin", "cos", "tan", "sqrt", "exp", "log", "log10", "floor", "ceil", "atan", "asin",
            "acos", "rand",
        ]);
        let op = proptest::sample::select(vec!["+", "-", "*", "/", "^"]);
        let mut choices: Vec<BoxedStrategy<String>> = vec![
            (inner.clone(), op, inner.clone())
                .prop_map(|(a, op, b)| format!("({a}){op}({b})"))
                .boxed(),
            inner.clone().prop_map(|a| format!("-({a})")).boxed(),
            (unary, inner.clone())
                .prop_map(|(f, a)| format!("{f}({a})"))
                .boxed(),
            (inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(c, a, b)| format!("if({c},{a},{b})"))
                .boxed(),
            (
                inner.clone(),
                proptest::collection::vec(inner.clone(), 1..4),
            )
                .prop_map(|(n, v)| format!("select({n},{})", v.join(",")))
                .boxed(),
            (
                proptest::sample::select(vec!["max", "min"]),
                proptest::collection::vec(inner.clone(), 1..4),
            )
                .prop_map(|(f, v)| format!("{f}({})", v.join(",")))
                .boxed(),
            (inner.clone(), inner.clone())
                .prop_map(|(a, b)| format!("atan2({a},{b})"))
                .boxed(),
        ];
        for &(name, arity) in calls {
            choices.push(
                proptest::collection::vec(inner.clone(), arity..=arity)
                    .prop_map(move |v| format!("{name}({})", v.join(",")))
                    .boxed(),
            );
        }
        proptest::strategy::Union::new(choices)
    })
}

const G_NAMES: &[&str] = &["x", "$1"];
const F_NAMES: &[&str] = &["x", "y", "$2"];
// Self-references (`a` in `a`, `c` in `c`) and the cycle through `a` and `b` see the
// previous value.
const B_NAMES: &[&str] = &["$1", "$2", "$3", "recno", "a"];
const C_NAMES: &[&str] = &["PI", "c"];
const A_NAMES: &[&str] = &["$1", "$2", "b", "c", "a"];
const OUT_NAMES: &[&str] = &["$1", "$2", "$3", "a", "b", "c"];
const G_CALLS: &[(&str, usize)] = &[];
const F_CALLS: &[(&str, usize)] = &[("g", 1)];
const TOP_CALLS: &[(&str, usize)] = &[("f", 2), ("g", 1)];

fn program() -> impl Strategy<Value = String> {
    (
        expr(G_NAMES, G_CALLS),
        expr(F_NAMES, F_CALLS),
        expr(B_NAMES, G_CALLS),
        expr(C_NAMES, G_CALLS),
        expr(A_NAMES, TOP_CALLS),
        proptest::collection::vec(expr(OUT_NAMES, TOP_CALLS), 1..4),
        proptest::sample::select(vec!["g", "sqrt", "sin", "f"]),
    )
        .prop_map(|(g, f, b, c, a, outs, passed)| {
            let mut p = format!("g(x)={g}; f(x,y)={f}; h(p,x)=p(x,x); b={b}; c:{c}; a={a};\n");
            for (i, o) in outs.iter().enumerate() {
                p.push_str(&format!("${}={o};\n", i + 1));
            }
            p.push_str(&format!("$9=h({passed},$1);\n"));
            p
        })
}

fn input_value() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("0".to_string()),
        Just("-0".to_string()),
        Just("1".to_string()),
        Just("-1".to_string()),
        Just("2.5".to_string()),
        Just("1e300".to_string()),
        Just("nan".to_string()),
        // Overflows: C's atof sets ERANGE, which a library call around it reports.
        Just("1e999".to_string()),
        Just("12abc".to_string()),
        (-1000.0f64..1000.0).prop_map(|v| v.to_string()),
    ]
}

fn rows() -> impl Strategy<Value = Vec<String>> {
    proptest::collection::vec(
        proptest::collection::vec(input_value(), 3).prop_map(|v| v.join("\t")),
        1..4,
    )
}

type Run = Vec<String>;

fn drive(engine: &mut dyn RecordEngine, rows: &[String]) -> Run {
    let mut out = Vec::new();
    for row in rows {
        let mut rec = Record::new(row, '\t');
        let r = engine.record(&mut rec);
        let warnings: Vec<String> = engine
            .take_warnings()
            .iter()
            .map(|w| w.to_string())
            .collect();
        let partial = engine.take_partial();
        let failed = r.is_err();
        out.push(format!(
            "{} | {warnings:?} | {}",
            show(&r),
            values(&partial)
        ));
        if failed {
            break;
        }
    }
    out
}

fn values(o: &Outputs) -> String {
    o.iter()
        .map(|(c, v)| {
            if v.is_nan() {
                format!("{c}:{}nan", if v.is_sign_negative() { "-" } else { "+" })
            } else {
                format!("{c}:{:016x}", v.to_bits())
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

fn show(r: &Result<Option<Outputs>, Error>) -> String {
    match r {
        Ok(Some(o)) => values(o),
        Ok(None) => "filtered".into(),
        Err(e) => format!("error {e}"),
    }
}

fn compare(src: &str, rows: &[String], nonfinite: bool) -> Result<(), TestCaseError> {
    let policy = if nonfinite {
        MathErrors::NonFinite
    } else {
        MathErrors::ErrnoOnly
    };
    for fold in [true, false] {
        let mut m = Module::new(&Env::rcalc());
        m.set_folding(fold);
        let diags = m.add_source(FileId(0), src);
        prop_assume!(diags.iter().all(|d| !d.is_error()));
        if m.lookup("recno").is_some() {
            m.set_variable("recno", 0.0);
        }
        if fold {
            m.optimize();
        }
        let mut interp =
            Interpreter::new(&m, policy).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let expected = drive(&mut interp, rows);
        let mut jit =
            JitProgram::new(&m, policy).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let got = drive(&mut jit, rows);
        prop_assert_eq!(
            got,
            expected,
            "program {} (fold {}, {:?})",
            src,
            fold,
            policy
        );
    }
    Ok(())
}

// Leaves that repeat library calls on the same values, so that one column, branch
// or function computes what another uses (the JIT reuses library results across
// branches and output columns, and input columns within a call): `sin(a)` inside
// `a` and `b` sees `a`'s previous value, elsewhere its value.
const S_G_NAMES: &[&str] = &["x", "sin(x)", "x^(1/3)", "sin($1)", "cos($2)", "$1"];
const S_B_NAMES: &[&str] = &["$1", "sin($1)", "($1)^(1/3)", "sin(a)", "a", "exp(-($2))"];
const S_A_NAMES: &[&str] = &[
    "$1",
    "$2",
    "sin($1)",
    "cos($2)",
    "sin(a)",
    "a^0.5",
    "b",
    "sin(b)",
    "atan2($1,$2)",
];
const S_OUT_NAMES: &[&str] = &[
    "$1",
    "$2",
    "$3",
    "a",
    "b",
    "sin($1)",
    "cos($2)",
    "($1)^(1/3)",
    "($2)^(1/3)",
    "sqrt($3)",
    "log($3)",
    "atan2($1,$2)",
    "exp(-($2))",
    "sin(a)",
    "sin(b)",
    "b^(1/3)",
    "rand($1)",
    "tan($3)",
];
const S_CALLS: &[(&str, usize)] = &[("g", 1)];

fn shared_program() -> impl Strategy<Value = String> {
    (
        expr(S_G_NAMES, G_CALLS),
        expr(S_B_NAMES, S_CALLS),
        expr(S_A_NAMES, S_CALLS),
        proptest::collection::vec(expr(S_OUT_NAMES, S_CALLS), 2..6),
    )
        .prop_map(|(g, b, a, outs)| {
            let mut p = format!("g(x)={g}; b={b}; a={a};\n");
            for (i, o) in outs.iter().enumerate() {
                p.push_str(&format!("${}={o};\n", i + 1));
            }
            p
        })
}

/// 256 cases unless `PROPTEST_CASES` asks for more (or fewer).
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256);
    ProptestConfig {
        cases,
        // Programs the parser rejects are skipped: about one in five.
        max_global_rejects: cases.max(1024),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn jit_matches_interpreter(src in program(), rows in rows(), nonfinite in any::<bool>()) {
        compare(&src, &rows, nonfinite)?;
    }

    #[test]
    fn shared_library_results_match(
        src in shared_program(),
        rows in rows(),
        nonfinite in any::<bool>(),
    ) {
        compare(&src, &rows, nonfinite)?;
    }
}
