//! `radc build` and the compiled scene files it writes: every trace case gives the same
//! output from the `.rsc` as from the `.rad` files; damaged, foreign and mismatched
//! files are refused with a message naming the file and the problem; and the render
//! front end's own checks (PNG output, `-e`, bad sizes and views).

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

fn radc(args: &[&str], input: &[u8]) -> Output {
    common::run(common::radc(args), input)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn trace_data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/trace")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

fn build(scenes: &[PathBuf], out: &Path) {
    let mut args = vec!["build", "-o", s(out)];
    args.extend(scenes.iter().map(|p| s(p)));
    let o = radc(&args, b"");
    assert!(o.status.success(), "radc build failed: {}", stderr(&o));
}

const LAMP: &str = "void light bright 0 0 3 10 10 10\n\
                    bright sphere lamp 0 0 4 0 0 5 0.5\n\
                    void plastic grey 0 0 5 .5 .5 .5 0 0\n\
                    grey sphere ball 0 0 4 0 0 0 1\n\
                    grey polygon floor 0 0 12 -5 -5 -1 5 -5 -1 5 5 -1 -5 5 -1\n";

fn lamp_scene(dir: &Path) -> PathBuf {
    let p = dir.join("lamp.rad");
    std::fs::write(&p, LAMP).expect("write scene");
    p
}

/// The whole trace corpus (every surface and material radc renders), through a
/// compiled scene: byte-identical output, names included.
#[test]
fn compiled_scenes_trace_exactly_like_their_text() {
    let cases: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(trace_data().join("cases.json")).expect("cases.json"),
    )
    .expect("valid JSON");
    let dir = tempfile::tempdir().expect("temp dir");
    let mut checked = 0;
    let mut bundled = 0;
    for case in cases.as_array().expect("a list") {
        let id = case["id"].as_str().expect("id");
        let options: Vec<&str> = case["options"]
            .as_array()
            .expect("options")
            .iter()
            .map(|o| o.as_str().expect("option"))
            .collect();
        let scenes: Vec<PathBuf> = case["scenes"]
            .as_array()
            .expect("scenes")
            .iter()
            .map(|p| trace_data().join("scenes").join(p.as_str().expect("scene")))
            .collect();
        let rays = std::fs::read(trace_data().join(format!("{id}.rays"))).expect("rays");
        let rsc = dir.path().join(format!("{id}.rsc"));
        // Patterns and textures are compiled at render time, and meshes' geometry is
        // read from their files: such scenes are stored as read (a scene bundle), the
        // others compiled.
        let with_functions = [
            "patterns-",
            "textures-",
            "daylight-",
            "data_patterns-",
            "texture_data-",
            "mixtures-",
            "functions-",
            "brtd-",
            "aniso_functions-",
            "aniso_patterns-",
            "mirror_patterns-",
            "glass_patterns-",
            "trans_textures-",
            "dielectric_patterns-",
            "ashik-",
            "meshes-",
        ]
        .iter()
        .any(|p| id.starts_with(p));
        build(&scenes, &rsc);
        let head = std::fs::read(&rsc).expect("scene file");
        assert_eq!(head.starts_with(b"RADCSRC\x1a"), with_functions, "{id}");
        bundled += usize::from(with_functions);
        let mut from_text = vec!["trace", "-h"];
        from_text.extend(&options);
        let mut from_rsc = from_text.clone();
        from_text.extend(scenes.iter().map(|p| s(p)));
        from_rsc.push(s(&rsc));
        let (a, b) = (radc(&from_text, &rays), radc(&from_rsc, &rays));
        assert!(
            a.status.success() && b.status.success(),
            "{id}: {}",
            stderr(&b)
        );
        assert_eq!(
            String::from_utf8_lossy(&a.stdout),
            String::from_utf8_lossy(&b.stdout),
            "{id}: output from the .rsc differs"
        );
        checked += 1;
    }
    assert!(checked > 40, "only {checked} cases");
    assert!(bundled > 5, "only {bundled} scenes with functions");
}

#[test]
fn render_from_a_compiled_scene_is_the_same_picture() {
    let dir = tempfile::tempdir().expect("temp dir");
    let rad = lamp_scene(dir.path());
    let rsc = dir.path().join("lamp.rsc");
    build(std::slice::from_ref(&rad), &rsc);
    let view = [
        "render", "-vp", "0", "-6", "1", "-vd", "0", "1", "0", "-x", "24", "-y", "24",
    ];
    let picture = |scene: &Path| {
        let mut args = view.to_vec();
        args.push(s(scene));
        let o = radc(&args, b"");
        assert!(o.status.success(), "{}", stderr(&o));
        // The pixels: everything from the resolution line on (the header names the
        // command); the line as rpict writes it, numbers in `%8d`.
        let line = b"-Y       24 +X       24\n";
        let at = o
            .stdout
            .windows(line.len())
            .position(|w| w == line)
            .expect("resolution line");
        o.stdout[at..].to_vec()
    };
    assert_eq!(picture(&rad), picture(&rsc));
}

/// Each kind of bad `.rsc`: an error naming the file and the problem, exit status 1,
/// never a panic.
#[test]
fn bad_compiled_scenes_are_refused_clearly() {
    let dir = tempfile::tempdir().expect("temp dir");
    let rsc = dir.path().join("good.rsc");
    build(&[lamp_scene(dir.path())], &rsc);
    let good = std::fs::read(&rsc).expect("read");
    let mut corrupt = good.clone();
    let last = corrupt.len() - 3;
    corrupt[last] ^= 0x55;
    let mut version = good.clone();
    version[8] ^= 0x7f;
    let octree = b"#?RADIANCE\noconv lamp.rad\nFORMAT=Radiance_octree\n\n\x03\x00\x01\x02".to_vec();
    let random: Vec<u8> = (0u32..5000)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    let cases: [(&str, Vec<u8>, &str); 6] = [
        ("corrupt.rsc", corrupt, "checksum"),
        (
            "truncated.rsc",
            good[..good.len() / 2].to_vec(),
            "truncated",
        ),
        ("version.rsc", version, "format"),
        ("random.rsc", random, "not a radc compiled scene"),
        ("empty.rsc", Vec::new(), "empty"),
        ("scene.oct", octree, "octree"),
    ];
    for (name, bytes, says) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).expect("write");
        for command in ["trace", "render"] {
            let o = radc(&[command, s(&path)], b"0 0 3 0 0 -1\n");
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(1), "{command} {name}: {err}");
            assert!(
                err.contains(name),
                "{command} {name}: names the file: {err}"
            );
            assert!(err.contains(says), "{command} {name}: says '{says}': {err}");
            assert!(!err.contains("panicked"), "{command} {name}: {err}");
            assert!(o.stdout.is_empty(), "{command} {name}: no output");
        }
    }
    // A compiled scene is the whole scene.
    let o = radc(&["trace", s(&rsc), s(&dir.path().join("lamp.rad"))], b"");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("only scene argument"), "{}", stderr(&o));
}

#[test]
fn build_refuses_scenes_with_errors_and_accepts_oconv_options() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bad = dir.path().join("bad.rad");
    std::fs::write(
        &bad,
        "void plastic red 0 0 2 1 0\nred sphere s 0 0 4 0 0 0 1\n",
    )
    .expect("write");
    let out = dir.path().join("bad.rsc");
    let o = radc(&["build", "-o", s(&out), s(&bad)], b"");
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bad.rad:1"),
        "diagnostics shown: {}",
        stderr(&o)
    );
    assert!(!out.exists(), "no file written for a scene with errors");

    let rad = lamp_scene(dir.path());
    let out = dir.path().join("lamp.rsc");
    let o = radc(
        &[
            "build", "-f", "-w", "-n", "6", "-r", "1024", "-b", "-9", "-9", "-9", "18", "-o",
        ],
        b"",
    );
    assert_eq!(
        o.status.code(),
        Some(2),
        "-o without a file is a usage error"
    );
    let o = radc(
        &[
            "build",
            "-f",
            "-w",
            "-n",
            "6",
            "-r",
            "1024",
            "-b",
            "-9",
            "-9",
            "-9",
            "18",
            "-o",
            s(&out),
            s(&rad),
        ],
        b"",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::read(&out)
            .expect("written")
            .starts_with(b"RADCSCN")
    );
    let o = radc(&["build", "-i", "old.oct", "-o", s(&out), s(&rad)], b"");
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("-i"), "{}", stderr(&o));
}

#[test]
fn render_writes_png_and_picture_together() {
    let dir = tempfile::tempdir().expect("temp dir");
    let rad = lamp_scene(dir.path());
    let (png, hdr) = (dir.path().join("x.png"), dir.path().join("x.hdr"));
    let o = radc(
        &[
            "render",
            "-vp",
            "0",
            "-6",
            "1",
            "-vd",
            "0",
            "1",
            "0",
            "-x",
            "40",
            "-y",
            "30",
            "-o",
            s(&png),
            "-o",
            s(&hdr),
            s(&rad),
        ],
        b"",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.is_empty(), "with -o nothing goes to stdout");
    assert!(
        stderr(&o).is_empty(),
        "no progress bar when stderr is not a terminal"
    );
    let bytes = std::fs::read(&png).expect("png written");
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
    // IHDR: width and height, big-endian, after the signature and the chunk header.
    assert_eq!(
        &bytes[16..24],
        &[0, 0, 0, 30, 0, 0, 0, 30],
        "30 by 30 (square view)"
    );
    assert!(std::fs::read(&hdr).expect("hdr").starts_with(b"#?RADIANCE"));
}

#[test]
fn render_error_file_takes_the_messages() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bad = dir.path().join("bad.rad");
    std::fs::write(
        &bad,
        "void plastic red 0 0 2 1 0\nred sphere s 0 0 4 0 0 0 1\n",
    )
    .expect("write");
    let log = dir.path().join("errors.txt");
    let o = radc(&["render", "-e", s(&log), s(&bad)], b"");
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).is_empty(), "stderr stays quiet: {}", stderr(&o));
    let text = std::fs::read_to_string(&log).expect("error file");
    assert!(
        text.contains("bad.rad:1") && text.contains("nothing rendered"),
        "{text}"
    );
}

#[test]
fn render_refuses_bad_sizes_and_views() {
    let dir = tempfile::tempdir().expect("temp dir");
    let rad = lamp_scene(dir.path());
    let r = s(&rad);
    for args in [
        vec!["-x", "0"],
        vec!["-y", "0"],
        vec!["-x", "-5"],
        vec!["-vp", "nan", "0", "0"],
        vec!["-vd", "0", "inf", "0"],
        vec!["-vh", "NaN"],
        vec!["-pa", "nan"],
        vec!["-vd", "0", "0", "0"],
    ] {
        let mut all = vec!["render"];
        all.extend(&args);
        all.push(r);
        let o = radc(&all, b"");
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            !err.contains("panicked") && o.stdout.is_empty(),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn render_warns_about_a_view_inside_geometry() {
    let dir = tempfile::tempdir().expect("temp dir");
    let rad = lamp_scene(dir.path());
    // The view point is the centre of the opaque ball.
    let o = radc(
        &[
            "render",
            "-vp",
            "0",
            "0",
            "0",
            "-x",
            "16",
            "-y",
            "16",
            s(&rad),
        ],
        b"",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("inside geometry") && err.contains("'ball'"),
        "{err}"
    );
    assert!(err.contains("the picture is black"), "{err}");
    // Outside it: no warning.
    let o = radc(
        &[
            "render",
            "-vp",
            "0",
            "-6",
            "1",
            "-x",
            "16",
            "-y",
            "16",
            s(&rad),
        ],
        b"",
    );
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
}

/// A built scene names its mesh files (the bundle holds no copy: it stays small) and
/// refuses one that changed since.
#[test]
fn built_scenes_refer_to_mesh_files_and_refuse_changed_ones() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scenes = trace_data().join("scenes");
    let mesh = dir.path().join("ball.rtm");
    std::fs::copy(scenes.join("ball.rtm"), &mesh).expect("copy");
    let rad = dir.path().join("m.rad");
    std::fs::write(
        &rad,
        format!("{LAMP}void plastic grey 0 0 5 .5 .5 .5 0 0\ngrey mesh ball 1 ball.rtm 0 0\n"),
    )
    .expect("write");
    let rsc = dir.path().join("m.rsc");
    build(&[rad], &rsc);
    let size = std::fs::metadata(&rsc).expect("built").len();
    let mesh_size = std::fs::metadata(&mesh).expect("mesh").len();
    assert!(
        size < mesh_size / 4,
        "{size} bytes for a {mesh_size}-byte mesh"
    );
    let ray = b"0 0 3 0 0 -1\n";
    let o = radc(&["trace", "-h", s(&rsc)], ray);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(o.stdout, b"0.000000e+00\t0.000000e+00\t0.000000e+00\t\n");
    let mut bytes = std::fs::read(&mesh).expect("mesh");
    bytes.push(b'\n');
    std::fs::write(&mesh, bytes).expect("change it");
    let o = radc(&["trace", "-h", s(&rsc)], ray);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("mesh file 'ball.rtm' changed since the scene was built"),
        "{}",
        stderr(&o)
    );
}
