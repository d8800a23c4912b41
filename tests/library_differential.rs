//! Differential test of radc's built-in function files (`lang/src/library/`) against
//! Radiance's files of the same names.
//!
//! `tests/oracle/regen_library_goldens.py` evaluated every name each file defines with
//! the real rcalc and Radiance's own file, at a few hundred points, and recorded the
//! values bit for bit in `tests/data/library/cases.json`. Here the same definitions
//! and inputs go through `radc calc` (JIT and `--interp`) with RAYPATH pointing at an
//! empty folder, so the only `rayinit.cal`, `skybright.cal`, ... radc can find are
//! its built-in ones. The renderer's names (ray, `arg`, noise) are bound by the same
//! `-e` definitions on both sides.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

/// Largest relative difference accepted. The built-in texts evaluate the same
/// arithmetic in the same order as Radiance's, so the values are expected to be equal
/// to the bit; the margin only absorbs a libm difference in the last place.
const RELATIVE_TOLERANCE: f64 = 1e-13;

struct Group {
    file: String,
    before: Vec<String>,
    bindings: String,
    input: String,
    cases: Vec<(String, String, Vec<f64>)>,
}

fn groups() -> Vec<Group> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/library/cases.json");
    let text = std::fs::read_to_string(&path).expect("library goldens");
    let json: serde_json::Value = serde_json::from_str(&text).expect("goldens are JSON");
    let strings = |v: &serde_json::Value| -> Vec<String> {
        v.as_array()
            .expect("a list")
            .iter()
            .map(|s| s.as_str().expect("a string").to_string())
            .collect()
    };
    json["groups"]
        .as_array()
        .expect("groups")
        .iter()
        .map(|g| Group {
            file: g["file"].as_str().expect("file").to_string(),
            before: strings(&g["before"]),
            bindings: g["bindings"].as_str().expect("bindings").to_string(),
            input: g["input"].as_str().expect("input").to_string(),
            cases: g["cases"]
                .as_array()
                .expect("cases")
                .iter()
                .map(|c| {
                    let values = strings(&c["expected"])
                        .iter()
                        .map(|h| from_hex(h))
                        .collect();
                    (
                        c["name"].as_str().expect("name").to_string(),
                        c["expr"].as_str().expect("expr").to_string(),
                        values,
                    )
                })
                .collect(),
        })
        .collect()
}

/// A little-endian f64 as rcalc `-od` wrote it, in hex.
fn from_hex(h: &str) -> f64 {
    let bytes: Vec<u8> = (0..8)
        .map(|i| u8::from_str_radix(&h[2 * i..2 * i + 2], 16).expect("hex"))
        .collect();
    f64::from_le_bytes(bytes.try_into().expect("8 bytes"))
}

/// Every case of a group at once: output `$k` is case k's expression.
fn run_radc(group: &Group, interp: bool, raypath: &Path) -> Vec<f64> {
    let mut args: Vec<String> = Vec::new();
    if interp {
        args.push("--interp".into());
    }
    for f in group.before.iter().chain(std::iter::once(&group.file)) {
        args.extend(["-f".into(), f.clone()]);
    }
    let outputs: Vec<String> = group
        .cases
        .iter()
        .enumerate()
        .map(|(k, (_, expr, _))| format!("${}={expr}", k + 1))
        .collect();
    args.extend(["-e".into(), group.bindings.clone()]);
    args.extend(["-e".into(), outputs.join(";"), "-od".into()]);
    let mut child = Command::new(env!("CARGO_BIN_EXE_radc"))
        .arg("calc")
        .args(&args)
        .current_dir(raypath)
        .env("RAYPATH", raypath)
        .env("LC_ALL", "C")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("radc runs");
    let mut stdin = child.stdin.take().expect("stdin");
    let input = group.input.clone();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("radc finishes");
    writer.join().expect("writer").expect("input written");
    assert!(
        out.status.success(),
        "radc calc failed on {}: {}",
        group.file,
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect()
}

fn relative_difference(got: f64, want: f64) -> f64 {
    if got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()) {
        return 0.0;
    }
    let scale = got.abs().max(want.abs());
    if scale == 0.0 || !scale.is_finite() {
        return f64::INFINITY;
    }
    (got - want).abs() / scale
}

#[test]
fn builtin_library_files_agree_with_radiance() {
    let empty = tempfile::tempdir().expect("a temporary folder");
    let mut failures = Vec::new();
    let mut compared = 0usize;
    for group in groups() {
        for interp in [false, true] {
            let got = run_radc(&group, interp, empty.path());
            let n = group.cases.len();
            let records = group.cases[0].2.len();
            assert_eq!(got.len(), n * records, "{}: output count", group.file);
            let mut worst = (0.0f64, 0usize);
            for (k, (name, _, want)) in group.cases.iter().enumerate() {
                for (r, w) in want.iter().enumerate() {
                    let g = got[r * n + k];
                    let d = relative_difference(g, *w);
                    compared += 1;
                    if d > worst.0 {
                        worst = (d, k);
                    }
                    if d > RELATIVE_TOLERANCE {
                        failures.push(format!(
                            "{} {name} record {r}{}: radc {g:e}, Radiance {w:e}",
                            group.file,
                            if interp { " (--interp)" } else { "" }
                        ));
                    }
                }
            }
            eprintln!(
                "{}{}: {n} names x {records} points, largest relative difference {:e} ({})",
                group.file,
                if interp { " --interp" } else { "" },
                worst.0,
                group.cases[worst.1].0
            );
        }
    }
    assert!(compared > 20_000, "only {compared} values compared");
    assert!(
        failures.is_empty(),
        "{} values differ:\n{}",
        failures.len(),
        failures
            .iter()
            .take(40)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The goldens name every definition of each built-in file (helpers private to
/// rayinit.cal aside), so a name added to a file without a golden fails here.
#[test]
fn goldens_cover_every_name_of_every_file() {
    use radc_lang::cal::{Env, Host, Module};
    let groups = groups();
    for name in radc_lang::library::names() {
        let group = groups
            .iter()
            .find(|g| g.file == name)
            .unwrap_or_else(|| panic!("no goldens for {name}"));
        let mut m = Module::new(&Env {
            host: Host::Bare,
            fold: true,
            complete: false,
        });
        m.add_source(
            radc_lang::FileId(0),
            radc_lang::library::builtin(name).unwrap(),
        );
        for d in m.defs() {
            let defined = &m.symbol(d.sym).name;
            if defined.contains('`') {
                continue;
            }
            assert!(
                group.cases.iter().any(|(n, _, _)| n == defined),
                "{name}: '{defined}' has no golden"
            );
        }
    }
}
