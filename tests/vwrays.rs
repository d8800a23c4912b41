//! `radc vwrays` against Radiance's vwrays, byte for byte, on the cases of
//! `tests/oracle/regen_vwrays_goldens.py` (every view type, clipping, shift and lift,
//! `-d`, the three output formats, `-c`, a picture's view, `-i` pixel positions), and
//! its refusals.

mod common;

use std::path::{Path, PathBuf};

use common::{radc, run};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/vwrays")
}

#[test]
fn vwrays_matches_radiance_byte_for_byte() {
    let cases: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(data().join("cases.json")).expect("cases.json"),
    )
    .expect("valid JSON");
    let cases = cases.as_array().expect("a list");
    assert!(cases.len() >= 15);
    for case in cases {
        let id = case["id"].as_str().expect("id");
        let mut args = vec!["vwrays".to_string()];
        args.extend(
            case["args"]
                .as_array()
                .expect("args")
                .iter()
                .map(|a| a.as_str().expect("arg").to_string()),
        );
        let mut cmd = radc(&args);
        cmd.current_dir(data());
        let out = run(cmd, case["stdin"].as_str().expect("stdin").as_bytes());
        assert!(
            out.status.success(),
            "{id}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let golden = std::fs::read(data().join(format!("{id}.out"))).expect("golden");
        assert!(!golden.is_empty(), "{id}: empty golden");
        assert!(out.stdout == golden, "{id}: differs from vwrays");
    }
}

#[test]
fn jittered_rays_repeat_and_what_is_not_implemented_is_refused() {
    let jittered = || {
        let out = run(
            radc(["vwrays", "-pj", "1", "-c", "3", "-x", "4", "-y", "4"]),
            b"",
        );
        assert!(out.status.success());
        out.stdout
    };
    let (a, b) = (jittered(), jittered());
    assert_eq!(a, b, "the same rays on every run");
    assert_eq!(String::from_utf8_lossy(&a).lines().count(), 48);
    let plain = run(radc(["vwrays", "-c", "3", "-x", "4", "-y", "4"]), b"").stdout;
    assert_ne!(a, plain, "jitter moves the rays");

    let refused = run(radc(["vwrays", "-pd", ".1", "-x", "4", "-y", "4"]), b"");
    assert_eq!(refused.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&refused.stderr)
            .contains("-pd (depth of field) is not implemented")
    );
    let mut zbuf = radc(["vwrays", "view.hdr", "view.zbf"]);
    zbuf.current_dir(data());
    let refused = run(zbuf, b"");
    assert_eq!(refused.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("depth buffers"));
    let bad = run(
        radc(["vwrays", "-i", "-x", "4", "-y", "4"]),
        b"1 2\nthree 4\n",
    );
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("expected px py on input"));
    assert_eq!(String::from_utf8_lossy(&bad.stdout).lines().count(), 1);
    let usage = run(radc(["vwrays", "-q"]), b"");
    assert_eq!(usage.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&usage.stderr).starts_with("Usage: vwrays"));
}
