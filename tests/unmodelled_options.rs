//! Never silently wrong, for options: an rtrace or rpict option whose value changes
//! what Radiance computes but which radc does not model yet is reported by name (a
//! warning where radc's result is a sound answer to the question, e.g. the irradiance
//! cache's options, where radc computes every value as `-aa 0`; an error where the
//! picture would be a different one, e.g. motion blur), and the same options at the
//! values radc does compute pass quietly.

mod common;

use common::{radc, run};

const SCENE: &str = "void plastic grey 0 0 5 .5 .5 .5 0 0\n\
grey sphere ball 0 0 4 0 0 0 1\n\
void light lamp 0 0 3 100 100 100\n\
lamp sphere bulb 0 0 4 0 0 5 .5\n";

fn scene() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("s.rad"), SCENE).expect("scene");
    dir
}

fn trace(dir: &tempfile::TempDir, options: &[&str]) -> (bool, String, String) {
    let mut cmd = radc(["trace", "-h"]);
    cmd.args(options).arg("s.rad").current_dir(dir.path());
    let out = run(cmd, b"0 0 3 0 0 -1\n");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn irradiance_cache_options_warn_by_name_when_indirect_light_is_computed() {
    let dir = scene();
    let (ok, stdout, stderr) = trace(
        &dir,
        &[
            "-ab", "1", "-ad", "16", "-aa", ".1", "-ar", "64", "-af", "x.amb",
        ],
    );
    assert!(ok, "{stderr}");
    assert_eq!(
        stdout.lines().count(),
        1,
        "the ray is still traced: {stdout}"
    );
    assert!(
        stderr.contains("warning: -aa 0.1: radc has no irradiance cache"),
        "{stderr}"
    );
    assert!(
        stderr.contains("-ar 64: irradiance cache options"),
        "{stderr}"
    );
    assert!(stderr.contains("-af x.amb: no ambient file"), "{stderr}");
    assert!(!dir.path().join("x.amb").exists());
}

#[test]
fn options_at_the_values_radc_computes_pass_quietly() {
    let dir = scene();
    // Without -ab the cache is never used; -aa 0 is radc's own computation.
    for options in [
        &["-aa", ".1", "-ar", "64"][..],
        &["-ab", "1", "-ad", "16", "-aa", "0"][..],
        &["-dt", "0", "-dc", ".5", "-ss", "1", "-u-", "-dp", "512"][..],
    ] {
        let (ok, _, stderr) = trace(&dir, options);
        assert!(ok && stderr.is_empty(), "{options:?}: {stderr}");
    }
}

#[test]
fn shadow_testing_specular_sampling_and_uncorrelated_sampling_warn() {
    let dir = scene();
    let (ok, _, stderr) = trace(&dir, &["-dt", ".05", "-ss", "4", "-u+"]);
    assert!(ok, "{stderr}");
    for expected in ["-dt 0.05: radc tests every shadow", "-ss 4:", "-u+:"] {
        assert!(stderr.contains(expected), "{expected}: {stderr}");
    }
    // -w silences warnings, as in rtrace.
    let (_, _, quiet) = trace(&dir, &["-w", "-dt", ".05"]);
    assert!(quiet.is_empty(), "{quiet}");
}

#[test]
fn rpict_refuses_motion_blur_and_depth_of_field_and_warns_of_jitter() {
    let dir = scene();
    let render = |options: &[&str]| {
        let mut cmd = radc([
            "render", "-x", "4", "-y", "4", "-vp", "0", "-3", "0", "-vd", "0", "1", "0",
        ]);
        cmd.args(options)
            .args(["-o", "p.hdr", "s.rad"])
            .current_dir(dir.path());
        run(cmd, b"")
    };
    for (option, what) in [("-pm", "motion blur"), ("-pd", "depth of field")] {
        let out = render(&[option, ".5"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success());
        assert!(
            stderr.contains(&format!("{option}: {what} is not implemented")),
            "{stderr}"
        );
        assert!(render(&[option, "0"]).status.success());
    }
    let out = render(&["-pj", ".67"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("-pj 0.67: radc traces one ray through each pixel's centre"),
        "{stderr}"
    );
}
