//! The renderer's pure functions against rtrace: tests/data/renderer-math/*.golden hold
//! rtrace's values of `noise3 noise3x noise3y noise3z fnoise3 erf erfc` in full double
//! precision (tests/oracle/regen_renderer_math.py splits each into three channels that
//! survive rtrace's single-precision colour exactly), and radc must give the same
//! doubles: 0 ulps. The `*-cache` goldens replay noise3.c's one-point cache.

use radc_lang::cal::renderer_math::{self, Noise3Cache};
use std::path::PathBuf;

const FUNCTIONS: [&str; 7] = [
    "noise3", "noise3x", "noise3y", "noise3z", "fnoise3", "erf", "erfc",
];

fn golden(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data/renderer-math")
        .join(format!("{name}.golden"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Distance in units in the last place, across zero and with NaN equal to NaN.
fn ulps(a: f64, b: f64) -> u64 {
    if a.is_nan() && b.is_nan() {
        return 0;
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    let key = |x: f64| {
        let bits = x.to_bits() as i64;
        if bits < 0 { i64::MIN - bits } else { bits }
    };
    key(a).abs_diff(key(b))
}

/// A golden's lines as (arguments, rtrace's value).
fn cases(name: &str) -> Vec<(Vec<f64>, f64)> {
    let text = golden(name);
    let lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty());
    lines
        .map(|line| {
            let (args, value) = line.split_once(" = ").expect("golden line `args = value`");
            let args = args
                .split(' ')
                .map(|a| a.parse().expect("argument"))
                .collect();
            (args, value.parse().expect("value"))
        })
        .collect()
}

/// Compares `eval` with one golden; returns the worst difference in ulps and notes
/// each differing point in `failures`.
fn compare(name: &str, mut eval: impl FnMut(&[f64]) -> f64, failures: &mut Vec<String>) -> u64 {
    let cases = cases(name);
    let mut worst = 0;
    for (args, expected) in &cases {
        let got = eval(args);
        let d = ulps(got, *expected);
        worst = worst.max(d);
        if d != 0 && failures.len() < 20 {
            failures.push(format!(
                "{name}{args:?}: radc {got:e}, rtrace {expected:e} ({d} ulps)"
            ));
        }
    }
    eprintln!(
        "{name}: {} points, max difference {worst} ulps",
        cases.len()
    );
    worst
}

#[test]
fn every_function_matches_rtrace_to_the_last_bit() {
    let mut failures = Vec::new();
    for name in FUNCTIONS {
        assert!(cases(name).len() > 500, "{name}: too few golden points");
        compare(
            name,
            |args| renderer_math::call(name, args).expect("a renderer function"),
            &mut failures,
        );
    }
    assert!(
        failures.is_empty(),
        "differs from rtrace:\n{}",
        failures.join("\n")
    );
}

/// noise3.c keeps one cached point per process; with NaN coordinates (which its
/// fast-math comparisons call equal to anything) what a call returns depends on the
/// previous call. The goldens are one rtrace process's rays in order, one call each.
#[test]
fn the_noise_cache_matches_rtrace_through_a_sequence_with_nans() {
    let mut failures = Vec::new();
    for (axis, name) in ["noise3x", "noise3y", "noise3z", "noise3"]
        .into_iter()
        .enumerate()
    {
        let mut cache = Noise3Cache::default();
        compare(
            &format!("{name}-cache"),
            |a| {
                let p = [a[0], a[1], a[2]];
                if axis < 3 {
                    cache.partial(p, axis)
                } else {
                    cache.noise3(p)
                }
            },
            &mut failures,
        );
    }
    assert!(
        failures.is_empty(),
        "differs from rtrace:\n{}",
        failures.join("\n")
    );
}

mod fuzz {
    use super::renderer_math::{self, Noise3Cache};
    use proptest::prelude::*;

    /// Finite doubles of every magnitude, with extra weight on the lattice scale.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            -300.0..300.0f64,
            (-30i32..30).prop_map(f64::from),
            any::<f64>().prop_filter("finite", |x| x.is_finite()),
        ]
    }

    proptest! {
        /// Within C's `int` range Perlin noise is bounded and its differences finite;
        /// beyond it Radiance's offsets grow without bound (the goldens pin values up
        /// to 1e157), so only "no panic" is asked there.
        #[test]
        fn noise_never_panics_and_is_finite_on_the_int_range(
            x in coordinate(), y in coordinate(), z in coordinate()
        ) {
            for name in ["noise3", "noise3x", "noise3y", "noise3z"] {
                let v = renderer_math::call(name, &[x, y, z]).expect("a renderer function");
                if [x, y, z].iter().all(|c| c.abs() < 2e9) {
                    prop_assert!(v.is_finite(), "{name}({x}, {y}, {z}) = {v}");
                    if name == "noise3" {
                        prop_assert!(v.abs() <= 1.1, "{name}({x}, {y}, {z}) = {v}");
                    }
                }
            }
            let mut cache = Noise3Cache::default();
            prop_assert_eq!(cache.noise3([x, y, z]).to_bits(), renderer_math::noise3(x, y, z).to_bits());
        }

        #[test]
        fn fractal_noise_and_erf_are_finite_for_every_finite_input(
            x in coordinate(), y in coordinate(), z in coordinate()
        ) {
            let f = renderer_math::fnoise3(x, y, z);
            prop_assert!(f.is_finite() && f.abs() < 2.0, "fnoise3({x}, {y}, {z}) = {f}");
            let (e, c) = (renderer_math::erf(x), renderer_math::erfc(x));
            prop_assert!((-1.0..=1.0).contains(&e), "erf({x}) = {e}");
            prop_assert!((0.0..=2.0).contains(&c), "erfc({x}) = {c}");
        }

        #[test]
        fn no_input_panics(args in proptest::collection::vec(any::<f64>(), 0..5), name in "[a-z0-9]{0,8}") {
            let _ = renderer_math::call(&name, &args);
            for f in ["noise3", "noise3x", "noise3y", "noise3z", "fnoise3", "erf", "erfc"] {
                let _ = renderer_math::call(f, &args);
            }
        }
    }
}
