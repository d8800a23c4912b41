//! End-to-end tests of `radc check`: exit codes, report formats, how files combine.

use std::path::Path;
use std::process::{Command, Output};

fn radc(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_radc"))
        .args(args)
        .current_dir(cwd)
        .env_remove("RAYPATH")
        .env("NO_COLOR", "1")
        .output()
        .expect("radc runs")
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).expect("write fixture");
}

fn json_lines(out: &Output) -> Vec<serde_json::Value> {
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("each line is JSON"))
        .collect()
}

const MATERIAL: &str = "void plastic paint 0 0 5 .5 .5 .5 0 0\n";

#[test]
fn clean_scene_exits_zero() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "ok.rad",
        &format!("{MATERIAL}paint sphere ball 0 0 4 0 0 0 1\n"),
    );
    let out = radc(&["check", "ok.rad"], dir.path());
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("0 errors, 0 warnings"));
}

/// The bundled example is clean, and the renderer runs its stripes pattern (no W0307).
#[test]
fn bundled_example_is_clean() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = radc(&["check", "--deny", "warnings", "examples/room.rad"], root);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}

#[test]
fn errors_exit_one_with_json_locations() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.rad",
        &format!("{MATERIAL}\npaint sphere a 0 0 3 0 0 0\nglos sphere b 0 0 4 0 0 0 1\n"),
    );
    let out = radc(&["check", "--format", "json", "bad.rad"], dir.path());
    assert_eq!(out.status.code(), Some(1));
    let diags = json_lines(&out);
    let codes: Vec<&str> = diags.iter().map(|d| d["code"].as_str().unwrap()).collect();
    assert_eq!(codes, vec!["E0202", "E0301"]);
    let undefined = &diags[1];
    assert_eq!(undefined["severity"], "error");
    assert_eq!(undefined["file"], "bad.rad");
    assert_eq!(
        (undefined["line"].as_u64(), undefined["column"].as_u64()),
        (Some(4), Some(1))
    );
    assert_eq!(
        (
            undefined["end_line"].as_u64(),
            undefined["end_column"].as_u64()
        ),
        (Some(4), Some(5))
    );
    assert!(undefined["message"].as_str().unwrap().contains("glos"));
}

#[test]
fn warnings_pass_unless_denied() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "w.rad",
        &format!("{MATERIAL}paint sphere a 0 0 4 0 0 0 -1\n"),
    );
    assert_eq!(radc(&["check", "w.rad"], dir.path()).status.code(), Some(0));
    assert_eq!(
        radc(&["check", "--deny", "warnings", "w.rad"], dir.path())
            .status
            .code(),
        Some(1)
    );
}

#[test]
fn usage_errors_exit_two() {
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(radc(&["check"], dir.path()).status.code(), Some(2));
    assert_eq!(
        radc(&["check", "--bogus", "x.rad"], dir.path())
            .status
            .code(),
        Some(2)
    );
    assert_eq!(
        radc(&["check", "--format", "xml", "x.rad"], dir.path())
            .status
            .code(),
        Some(2)
    );
    assert_eq!(radc(&["frobnicate"], dir.path()).status.code(), Some(2));
}

#[test]
fn files_on_the_command_line_form_one_scene() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "lib.mat",
        &format!("{MATERIAL}void plastic spare 0 0 5 .1 .1 .1 0 0\n"),
    );
    write(dir.path(), "room.rad", "paint sphere ball 0 0 4 0 0 0 1\n");
    let together = radc(
        &["check", "--format", "json", "lib.mat", "room.rad"],
        dir.path(),
    );
    assert_eq!(together.status.code(), Some(0));
    // Unused materials in a .mat library are expected, not warned about.
    assert!(json_lines(&together).is_empty());
    let alone = radc(&["check", "--format", "json", "room.rad"], dir.path());
    assert_eq!(alone.status.code(), Some(1));
}

#[test]
fn directories_check_each_scene_on_its_own() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    write(
        dir.path(),
        "a.rad",
        &format!("{MATERIAL}paint sphere a 0 0 4 0 0 0 1\n"),
    );
    write(
        &dir.path().join("sub"),
        "b.rad",
        "paint sphere b 0 0 4 0 0 0 1\n",
    );
    write(dir.path(), "notes.txt", "not a scene");
    let out = radc(&["check", "--format", "json", "."], dir.path());
    assert_eq!(out.status.code(), Some(1));
    let diags = json_lines(&out);
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert!(diags[0]["file"].as_str().unwrap().ends_with("b.rad"));
}

#[test]
fn unreadable_input_is_a_diagnostic_not_a_crash() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bin.rad"),
        b"void plastic \xff\x00 0 0 5 1 1 1 0 0\n",
    )
    .unwrap();
    let out = radc(
        &["check", "--format", "json", "bin.rad", "missing.rad"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(1));
    let codes: Vec<String> = json_lines(&out)
        .iter()
        .map(|d| d["code"].as_str().unwrap().to_string())
        .collect();
    assert!(codes.contains(&"W0101".to_string()), "{codes:?}");
    assert!(codes.contains(&"W0103".to_string()), "{codes:?}");
    assert!(codes.contains(&"E0305".to_string()), "{codes:?}");
}

#[test]
fn human_report_names_file_line_and_hint() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "t.rad", "void plastc m 0 0 5 .5 .5 .5 0 0\n");
    let out = radc(&["check", "t.rad"], dir.path());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("E0201"), "{text}");
    assert!(text.contains("t.rad:1:6"), "{text}");
    assert!(text.contains("did you mean 'plastic'?"), "{text}");
    assert!(!text.contains('\u{1b}'), "no colour codes when piped");
}

#[test]
fn doc_and_explain_read_the_tables() {
    let dir = tempfile::tempdir().unwrap();
    let plastic = radc(&["doc", "plastic"], dir.path());
    assert_eq!(plastic.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&plastic.stdout).contains("rough"));
    assert_eq!(radc(&["doc", "plastc"], dir.path()).status.code(), Some(2));
    let explain = radc(&["explain", "E0301"], dir.path());
    assert!(String::from_utf8_lossy(&explain.stdout).contains("undefined-modifier"));
    assert_eq!(
        radc(&["explain", "E9999"], dir.path()).status.code(),
        Some(2)
    );
}

#[test]
fn cal_files_are_checked_on_their_own_and_through_scenes() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "good.cal",
        "{ a pattern } stripes = if(sin(Px*10), 1, .5);\n",
    );
    write(dir.path(), "bad.cal", "broken = 1 + * 2;\n");
    assert_eq!(
        radc(&["check", "good.cal"], dir.path()).status.code(),
        Some(0)
    );
    let bad = radc(&["check", "--format", "json", "bad.cal"], dir.path());
    assert_eq!(bad.status.code(), Some(1));
    assert_eq!(json_lines(&bad)[0]["code"], "E0501");

    let scene = |func: &str, file: &str| {
        format!(
            "void brightfunc pat 2 {func} {file} 0 0\npat plastic paint 0 0 5 .5 .5 .5 0 0\n\
             paint sphere ball 0 0 4 0 0 0 1\n"
        )
    };
    write(dir.path(), "ok.rad", &scene("stripes", "good.cal"));
    assert_eq!(
        radc(&["check", "ok.rad"], dir.path()).status.code(),
        Some(0)
    );
    write(dir.path(), "typo.rad", &scene("stripe", "good.cal"));
    let typo = radc(&["check", "--format", "json", "typo.rad"], dir.path());
    let typo = json_lines(&typo);
    let d = typo
        .iter()
        .find(|d| d["code"] != "W0307")
        .expect("an error");
    assert_eq!(
        (d["code"].as_str(), d["hint"].as_str()),
        (Some("E0601"), Some("did you mean 'stripes'?"))
    );
    write(dir.path(), "broken.rad", &scene("broken", "bad.cal"));
    let broken = radc(&["check", "--format", "json", "broken.rad"], dir.path());
    let broken = json_lines(&broken);
    let d = broken
        .iter()
        .find(|d| d["code"] != "W0307")
        .expect("an error");
    assert_eq!(
        (d["code"].as_str(), d["file"].as_str()),
        (Some("E0501"), Some("bad.cal"))
    );
    assert_eq!(d["labels"][0]["file"], "broken.rad");
}

#[test]
fn generator_lines_are_expanded_and_pipelines_work() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "gen.rad",
        &format!(
            "{MATERIAL}!genbox paint box 1 2 3 | xform -rz 30\n!genbox pant box2 1 1 1\n!ls -l\n"
        ),
    );
    let out = radc(&["check", "--format", "json", "gen.rad"], dir.path());
    let diags = json_lines(&out);
    let codes: Vec<&str> = diags.iter().map(|d| d["code"].as_str().unwrap()).collect();
    assert_eq!(codes, vec!["W0303", "E0301"], "{diags:?}");
    // The undefined modifier is reported inside the generator's output, with the
    // command line as the place it came from.
    assert_eq!(diags[1]["file"], "!genbox pant box2 1 1 1");
    assert_eq!(diags[1]["labels"][0]["line"], 3);
}

#[test]
fn failing_xform_lines_warn_on_the_line_and_keep_what_was_expanded() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "part.rad", "glos sphere a 0 0 4 0 0 0 1\n");
    write(
        dir.path(),
        "nest.rad",
        "!xform -t 1 0 0 missing.rad\nglas sphere b 0 0 4 0 0 0 1\n",
    );
    write(
        dir.path(),
        "scene.rad",
        &format!("{MATERIAL}!xform part.rad missing.rad\n!xform -n n nest.rad\n"),
    );
    let out = radc(&["check", "--format", "json", "scene.rad"], dir.path());
    let diags = json_lines(&out);
    let summary: Vec<(&str, &str, u64)> = diags
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap(),
                d["file"].as_str().unwrap(),
                d["line"].as_u64().unwrap(),
            )
        })
        .collect();
    // xform wrote part.rad's sphere before failing on the missing file: the sphere is
    // checked (its modifier is undefined), and the failure is a warning on line 2.
    // nest.rad's own failing command only warns inside xform ("bad status"), so its
    // sphere is read too, and the warning lands on line 3.
    assert!(summary.contains(&("W0306", "scene.rad", 2)), "{summary:?}");
    assert!(summary.contains(&("W0306", "scene.rad", 3)), "{summary:?}");
    let undefined: Vec<&serde_json::Value> =
        diags.iter().filter(|d| d["code"] == "E0301").collect();
    assert_eq!(undefined.len(), 2, "{summary:?}");
    assert_eq!(undefined[0]["file"], "!xform part.rad missing.rad");
    assert_eq!(undefined[0]["labels"][0]["line"], 2);
    assert_eq!(undefined[1]["file"], "!xform -n n nest.rad");
    assert_eq!(undefined[1]["labels"][0]["line"], 3);
    let status = diags
        .iter()
        .find(|d| d["code"] == "W0306" && d["line"] == 3)
        .unwrap();
    assert!(
        status["message"]
            .as_str()
            .unwrap()
            .contains("bad status from \"!xform -t 1 0 0 missing.rad\""),
        "{status}"
    );
    assert!(
        status["hint"]
            .as_str()
            .unwrap()
            .contains("xform: cannot find file \"missing.rad\""),
        "{status}"
    );
}

#[test]
fn include_cycles_through_xform_are_errors_on_the_line() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "a.rad",
        &format!("{MATERIAL}paint sphere s 0 0 4 0 0 0 1\n!xform -t 1 0 0 b.rad\n"),
    );
    write(dir.path(), "b.rad", "!xform -rz 10 a.rad\n");
    write(dir.path(), "self.rad", "!xform -s 2 self.rad\n");
    for (scene, line) in [("a.rad", 3), ("self.rad", 1)] {
        let out = radc(&["check", "--format", "json", scene], dir.path());
        assert_eq!(out.status.code(), Some(1), "{scene}");
        let diags = json_lines(&out);
        let cycle: Vec<_> = diags.iter().filter(|d| d["code"] == "E0307").collect();
        assert_eq!(cycle.len(), 1, "{scene}: {diags:?}");
        assert_eq!(cycle[0]["file"], scene);
        assert_eq!(cycle[0]["line"], line);
    }
}

/// A sky from gensky or gendaylit names skybright.cal or perezlum.cal; with no Radiance
/// installed (no RAYPATH) radc's built-in copies answer, so the scene is clean.
#[test]
fn skies_check_clean_without_radiance_installed() {
    let dir = tempfile::tempdir().unwrap();
    let glow = "skyfunc glow skyglow 0 0 4 1 1 1 0\nskyglow source sky 0 0 4 0 0 1 180\n";
    for (name, command) in [
        ("gensky.rad", "!gensky 3 21 12 -a 40 -o 105 -m 105"),
        (
            "gendaylit.rad",
            "!gendaylit 6 21 12 -a 40 -o 105 -m 105 -W 800 120",
        ),
        ("surf.rad", "!gensurf paint s 's' 't' 's*t' 3 3 -s"),
        ("rev.rad", "!genrev paint r 't' '1+t*t' 4 -s"),
    ] {
        let text = if name.starts_with("gen") {
            format!("{command}\n{glow}")
        } else {
            format!("{MATERIAL}{command}\n")
        };
        write(dir.path(), name, &text);
        let out = radc(&["check", "--deny", "warnings", name], dir.path());
        assert_eq!(
            out.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&out.stdout)
        );
    }
}

/// As in Radiance, a file of a library name found beside the scene wins over radc's
/// built-in text: here a skybright.cal without `skybr`.
#[test]
fn a_library_file_beside_the_scene_replaces_the_built_in_one() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "skybright.cal", "other = 1;\n");
    write(
        dir.path(),
        "sky.rad",
        "void brightfunc skyfunc 2 skybr skybright.cal 0 7 1 1 1 1 0 0 1\n\
         skyfunc glow skyglow 0 0 4 1 1 1 0\nskyglow source sky 0 0 4 0 0 1 180\n",
    );
    let out = radc(&["check", "sky.rad"], dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("E0601"), "{stdout}");
}
