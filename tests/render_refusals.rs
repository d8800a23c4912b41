//! Never silently wrong: every primitive type is either rendered and compared with
//! Radiance's output (it appears in a scene of the rtrace goldens,
//! `tests/data/trace/scenes/`, which `trace_differential.rs` compares), or a scene
//! using it is refused by `radc trace` and `radc render`, naming it, and `radc check`
//! warns of it (W0307). The test walks the schema, so a type added to it without
//! either fails here.
//!
//! Modifiers the renderer does not model are also refused wherever they sit in a
//! modifier chain: on a surface, a material, a light, an alias (its own modifier or
//! one inherited), an alternate, a distant source, an antimatter's face.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::{radc, run};
use radc_lang::scene::syntax::Item;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// Types used by the scenes whose rtrace output is a golden.
fn types_in_trace_goldens() -> BTreeSet<String> {
    let mut types = BTreeSet::new();
    let dir = data().join("trace/scenes");
    for entry in std::fs::read_dir(&dir).expect("trace scenes") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|x| x != "rad") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("scene text");
        let (file, _) = radc_lang::scene::parse(radc_lang::FileId(0), &text);
        for item in file.items {
            match item {
                Item::Primitive(p) => {
                    types.insert(p.kind.text.clone());
                }
                Item::Alias(_) => {
                    types.insert("alias".to_string());
                }
                _ => {}
            }
        }
    }
    types
}

/// Files the refusal scenes name: a function file, a data file, a picture, a font,
/// an octree and a BSDF, just valid enough for `radc check` to accept them.
fn write_auxiliary_files(dir: &Path) {
    std::fs::write(
        dir.join("f.cal"),
        "v = .5;\nf(x) = x;\nr(a, b, c) = .5;\ng(a, b) = .5;\n",
    )
    .expect("f.cal");
    std::fs::write(dir.join("d.dat"), "1\n0 1 2\n.5 .5\n").expect("d.dat");
    let mut pic = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n".to_vec();
    pic.extend_from_slice(&[128, 128, 128, 129]);
    std::fs::write(dir.join("p.hdr"), pic).expect("p.hdr");
    std::fs::write(dir.join("t.fnt"), "65 4 0 0 255 0 255 255 0 255\n").expect("t.fnt");
    std::fs::write(dir.join("o.oct"), "#?RADIANCE\nFORMAT=Radiance_octree\n\n").expect("o.oct");
    std::fs::write(dir.join("b.xml"), "<WindowElement></WindowElement>\n").expect("b.xml");
}

/// One scene per type the renderer refuses: the type reachable from a surface.
const LIGHT: &str = "void light lamp 0 0 3 10 10 10\nlamp sphere bulb 0 0 4 0 0 3 .1\n";

fn refusal_scene(type_name: &str) -> Option<String> {
    let pattern_on_material = |def: &str| format!("{def}\nx plastic m 0 0 5 .5 .5 .5 0 0\n");
    let material = |def: &str| format!("{def}\n");
    let body = match type_name {
        "instance" => "void instance x 1 o.oct 0 0\n".to_string(),
        "brighttext" => {
            pattern_on_material("void brighttext x 3 t.fnt . A 0 11 0 0 0 1 0 0 0 1 0 1 0")
        }
        "colortext" => {
            pattern_on_material("void colortext x 3 t.fnt . A 0 15 0 0 0 1 0 0 0 1 0 1 1 1 0 0 0")
        }
        "spectrum" => pattern_on_material("void spectrum x 0 0 5 400 700 1 1 1"),
        "specfile" => pattern_on_material("void specfile x 1 d.dat 0 0"),
        "specfunc" => pattern_on_material("void specfunc x 2 f f.cal 0 2 400 700"),
        "specdata" => pattern_on_material("void specdata x 4 f d.dat f.cal Px 0 0"),
        "specpict" => pattern_on_material("void specpict x 5 f p.hdr f.cal Px Py 0 0"),
        "mixtext" => "void plastic a 0 0 5 1 1 1 0 0\nvoid plastic b 0 0 5 0 0 0 0 0\n\
                      void mixtext x 5 a b t.fnt . A 0 9 0 0 0 1 0 0 0 1 0\n\
                      x plastic m 0 0 5 .5 .5 .5 0 0\n"
            .to_string(),
        "WGMDfunc" => material(
            "void WGMDfunc m 13 void 0 .1 .1 void 0 .1 .1 void 1 0 0 f.cal 0 9 .5 .5 .5 .5 .5 .5 .5 .5 .5",
        ),
        "BSDF" => material("void BSDF m 6 0 b.xml 0 0 1 f.cal 0 0"),
        "aBSDF" => material("void aBSDF m 5 b.xml 0 0 1 f.cal 0 0"),
        "prism1" => material("void prism1 m 5 v v v v f.cal 0 0"),
        "prism2" => material("void prism2 m 9 v v v v v v v v f.cal 0 0"),
        _ => return None,
    };
    let surface = if type_name == "instance" {
        String::new()
    } else {
        "m polygon floor 0 0 12 -5 -5 0 5 -5 0 5 5 0 -5 5 0\n".to_string()
    };
    Some(format!("{LIGHT}{body}{surface}"))
}

struct Verdicts {
    check: String,
    check_status: Option<i32>,
    trace: String,
    trace_status: Option<i32>,
    render: String,
    render_status: Option<i32>,
}

fn judge(dir: &Path, scene: &str) -> Verdicts {
    let path = dir.join("scene.rad");
    std::fs::write(&path, scene).expect("scene");
    let text = |o: &std::process::Output| {
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )
    };
    let mut check = radc(["check", "scene.rad"]);
    check.current_dir(dir).env_remove("RAYPATH");
    let check = run(check, b"");
    let mut trace = radc(["trace", "-h", "scene.rad"]);
    trace.current_dir(dir).env_remove("RAYPATH");
    let trace = run(trace, b"0 0 1 0 0 -1\n");
    let mut render = radc([
        "render",
        "-x",
        "4",
        "-y",
        "4",
        "-vp",
        "0",
        "0",
        "2",
        "-vd",
        "0",
        "0",
        "-1",
        "-vu",
        "0",
        "1",
        "0",
        "scene.rad",
    ]);
    render.current_dir(dir).env_remove("RAYPATH");
    let render = run(render, b"");
    Verdicts {
        check: text(&check),
        check_status: check.status.code(),
        trace: text(&trace),
        trace_status: trace.status.code(),
        render: text(&render),
        render_status: render.status.code(),
    }
}

/// The refusal names `who` (`type 'name'`), and check warns of it with W0307 and no
/// errors, so the only reason for the refusal is what the renderer does not model.
fn assert_refused(v: &Verdicts, who: &str, context: &str) {
    assert_eq!(
        v.check_status,
        Some(0),
        "{context}: radc check should accept it\n{}",
        v.check
    );
    assert!(
        v.check.contains("W0307") && v.check.contains(who) && v.check.contains("0 errors"),
        "{context}: radc check should warn W0307 about {who}\n{}",
        v.check
    );
    for (command, status, out) in [
        ("trace", v.trace_status, &v.trace),
        ("render", v.render_status, &v.render),
    ] {
        assert_eq!(
            status,
            Some(1),
            "{context}: radc {command} must refuse\n{out}"
        );
        assert!(
            out.contains(&format!("cannot render {who}")),
            "{context}: radc {command} must name {who}\n{out}"
        );
    }
}

#[test]
fn every_type_is_rendered_against_radiance_or_refused() {
    let rendered = types_in_trace_goldens();
    let dir = tempfile::tempdir().expect("tempdir");
    write_auxiliary_files(dir.path());
    let mut unaccounted = Vec::new();
    for t in radc_lang::schema::PRIMITIVE_TYPES {
        if rendered.contains(t.name) {
            assert!(
                refusal_scene(t.name).is_none(),
                "{}: rendered in the goldens and listed as refused",
                t.name
            );
            continue;
        }
        let Some(scene) = refusal_scene(t.name) else {
            unaccounted.push(t.name);
            continue;
        };
        let v = judge(dir.path(), &scene);
        // Materials are named `m` in their scenes, everything else `x`.
        let name = if t.category == radc_lang::schema::Category::Material {
            "m"
        } else {
            "x"
        };
        assert_refused(&v, &format!("{} '{name}'", t.name), t.name);
    }
    assert!(
        unaccounted.is_empty(),
        "types neither rendered in tests/data/trace/scenes nor refused here: {unaccounted:?}"
    );
}

/// A pattern radc does not run yet, wherever Radiance would apply it; the refusal
/// shows the chain.
#[test]
fn unmodelled_modifiers_are_refused_wherever_they_sit() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_auxiliary_files(dir.path());
    let floor = |m: &str| format!("{m} polygon floor 0 0 12 -5 -5 0 5 -5 0 5 5 0 -5 5 0\n");
    // specdata: a pattern the renderer does not run yet.
    let pattern = "void specdata p 4 f d.dat f.cal Px 0 0\n";
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "on a material",
            format!("{pattern}p plastic m 0 0 5 .5 .5 .5 0 0\n{}", floor("m")),
            "(used by plastic 'm', used by polygon 'floor')",
        ),
        (
            "on a surface",
            format!("{pattern}{}", floor("p")),
            "(used by polygon 'floor')",
        ),
        (
            "on a light",
            format!(
                "{pattern}p light l 0 0 3 1 1 1\nvoid plastic w 0 0 5 .5 .5 .5 0 0\n{}\
                 l sphere s 0 0 4 0 0 3 .5\n",
                floor("w")
            ),
            "(used by light 'l', used by sphere 's')",
        ),
        (
            "on a glow of a distant source",
            format!(
                "{pattern}p glow sky 0 0 4 1 1 1 0\nvoid plastic w 0 0 5 .5 .5 .5 0 0\n{}\
                 sky source dome 0 0 4 0 0 1 180\n",
                floor("w")
            ),
            "(used by glow 'sky', used by source 'dome')",
        ),
        (
            "as an alias's own modifier",
            format!(
                "{pattern}void plastic m0 0 0 5 .5 .5 .5 0 0\np alias m m0\n{}",
                floor("m")
            ),
            "(used by alias 'm', used by polygon 'floor')",
        ),
        (
            "inherited through an alias",
            format!(
                "{pattern}p plastic m0 0 0 5 .5 .5 .5 0 0\ninherit alias m m0\n{}",
                floor("m")
            ),
            "(used by alias 'm', used by polygon 'floor')",
        ),
        (
            "on an illum's alternate",
            format!(
                "{pattern}p plastic alt 0 0 5 .5 .5 .5 0 0\nvoid illum m 1 alt 0 3 1 1 1\n{}",
                floor("m")
            ),
            "(used by plastic 'alt', used by illum 'm', used by polygon 'floor')",
        ),
        (
            "on a mirror's alternate",
            format!(
                "{pattern}p plastic alt 0 0 5 .5 .5 .5 0 0\nvoid mirror m 1 alt 0 3 .9 .9 .9\n{}",
                floor("m")
            ),
            "(used by plastic 'alt', used by mirror 'm', used by polygon 'floor')",
        ),
        (
            "modifying a pattern on a material",
            format!(
                "{pattern}p specdata q 4 f d.dat f.cal Px 0 0\nq plastic m 0 0 5 .5 .5 .5 0 0\n{}",
                floor("m")
            ),
            "(used by plastic 'm', used by polygon 'floor')",
        ),
    ];
    for (context, scene, chain) in cases {
        let v = judge(dir.path(), &format!("{LIGHT}{scene}"));
        let who = if context.starts_with("modifying a pattern") {
            "specdata 'q'"
        } else {
            "specdata 'p'"
        };
        assert_refused(&v, who, context);
        assert!(
            v.trace.contains(chain),
            "{context}: the chain {chain:?} is shown\n{}",
            v.trace
        );
    }
}

/// Mixtures radc renders (and compares with rtrace in `mixtures.rad`) except where
/// Radiance itself stops with "inappropriate modifier" or radc does not follow yet:
/// a mixture of materials modifying a material, a mixture of materials with a modifier
/// of its own, and patterns placed before a mixture of materials.
#[test]
fn mixtures_of_materials_are_refused_where_they_cannot_shade() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_auxiliary_files(dir.path());
    let sides = "void plastic a 0 0 5 1 1 1 0 0\nvoid plastic b 0 0 5 0 0 0 0 0\n";
    let floor = |m: &str| format!("{m} polygon floor 0 0 12 -5 -5 0 5 -5 0 5 5 0 -5 5 0\n");
    let cases = [
        (
            format!(
                "{sides}void mixfunc x 4 a b v f.cal 0 0\nx plastic m 0 0 5 .5 .5 .5 0 0\n{}",
                floor("m")
            ),
            "mixfunc 'x'",
        ),
        (
            format!(
                "{sides}void brightfunc p 2 v f.cal 0 0\np mixfunc x 4 a b v f.cal 0 0\n{}",
                floor("x")
            ),
            "mixfunc 'x'",
        ),
        (
            format!(
                "{sides}void mixfunc x 4 a b v f.cal 0 0\nx brightfunc p 2 v f.cal 0 0\n{}",
                floor("p")
            ),
            "mixfunc 'x'",
        ),
    ];
    for (scene, who) in cases {
        let v = judge(dir.path(), &scene);
        assert_refused(&v, who, &scene);
    }
}
