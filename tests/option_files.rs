//! rtrace's and rpict's ways of being asked for options: `@file` option files (nested,
//! and `$VAR`), `-version` in the form pipelines' version checks read, and `-defaults`
//! listing the settings in force in Radiance's layout.

mod common;

use common::{radc, run};

const SCENE: &str = "void plastic grey 0 0 5 .5 .5 .5 0 0\ngrey sphere ball 0 0 4 0 0 0 1\n";

fn stdout_of(dir: &std::path::Path, args: &[&str]) -> (bool, String, String) {
    let mut cmd = radc(args);
    cmd.current_dir(dir).env("RADC_TEST_OPTS", "-ab 3");
    let out = run(cmd, b"0 0 3 0 0 -1\n");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn option_files_nest_and_environment_variables_expand() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("outer.opt"), "-ad 16\n@inner.opt -ds .1").expect("outer");
    std::fs::write(dir.path().join("inner.opt"), "  -lr   4\t-st .3\n").expect("inner");
    for command in ["trace", "render"] {
        let (ok, out, err) = stdout_of(
            dir.path(),
            &[command, "@outer.opt", "$RADC_TEST_OPTS", "-defaults"],
        );
        assert!(ok, "{err}");
        for expected in [
            "-ab 3        \t\t\t# ambient bounces\n",
            "-ad 16       \t\t\t# ambient divisions\n",
            "-ds 0.100000\t\t\t# direct sampling\n",
            "-lr 4        \t\t\t# limit reflection\n",
            "-st 0.300000\t\t\t# specular threshold\n",
        ] {
            assert!(out.contains(expected), "{command}: {expected:?} in\n{out}");
        }
    }
}

#[test]
fn a_missing_or_self_naming_option_file_is_an_error_naming_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("s.rad"), SCENE).expect("scene");
    std::fs::write(dir.path().join("loop.opt"), "-ab 1 @loop.opt").expect("loop");
    let (ok, _, err) = stdout_of(dir.path(), &["trace", "@missing.opt", "s.rad"]);
    assert!(!ok);
    assert!(err.contains("cannot expand '@missing.opt'"), "{err}");
    let (ok, _, err) = stdout_of(dir.path(), &["trace", "@loop.opt", "s.rad"]);
    assert!(!ok);
    assert!(err.contains("cannot expand '@loop.opt'"), "{err}");
    let (ok, _, err) = stdout_of(dir.path(), &["trace", "$RADC_NO_SUCH_VARIABLE", "s.rad"]);
    assert!(!ok);
    assert!(err.contains("no such environment variable"), "{err}");
}

#[test]
fn version_reads_as_radiance_6_to_version_checks() {
    let dir = tempfile::tempdir().expect("temp dir");
    for command in ["trace", "render"] {
        let (ok, out, _) = stdout_of(dir.path(), &[command, "-version"]);
        assert!(ok);
        // frads and honeybee-radiance read the second word and want a major version >= 5.
        let second = out.split_whitespace().nth(1).expect("two words");
        assert!(out.starts_with("RADIANCE "), "{out}");
        assert!(second.starts_with('6'), "{out}");
    }
}

#[test]
fn defaults_say_where_radc_computes_otherwise_than_radiance() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (ok, out, _) = stdout_of(dir.path(), &["trace", "-defaults"]);
    assert!(ok);
    assert!(
        out.contains("-aa 0.000000\t\t\t# ambient accuracy (radc has no irradiance cache yet)\n")
    );
    assert!(out.contains("-dt 0.000000\t\t\t# direct threshold (radc tests every shadow)\n"));
    let (ok, out, _) = stdout_of(
        dir.path(),
        &["render", "-vp", "1", "2", "3", "-x", "64", "-defaults"],
    );
    assert!(ok);
    assert!(
        out.starts_with("-vtv\t\t\t\t# view type perspective\n"),
        "{out}"
    );
    assert!(
        out.contains("-vp 1.000000 2.000000 3.000000\t# view point\n"),
        "{out}"
    );
    assert!(out.contains("-x  64       \t\t\t# x resolution\n"), "{out}");
    // rpict's own defaults, not rtrace's.
    assert!(
        out.contains("-lr 7        \t\t\t# limit reflection\n"),
        "{out}"
    );
}
