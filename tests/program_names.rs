//! radc under Radiance's program names: `radc links DIR` makes the links, and a
//! pipeline calling `oconv` and `rtrace` by name gets what `radc build` and `radc
//! trace` give.

mod common;

use std::process::Command;

use common::{radc, run};

const SCENE: &str = "void plastic grey 0 0 5 .5 .5 .5 0 0\n\
grey sphere ball 0 0 4 0 0 0 1\n\
void light lamp 0 0 3 100 100 100\n\
lamp sphere bulb 0 0 4 0 -4 5 .5\n";

const RAYS: &[u8] = b"0 -3 0 0 1 0\n0 -3 0.5 0 1 0\n";

#[test]
fn oconv_and_rtrace_by_name_are_radc_build_and_trace() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bin = dir.path().join("bin");
    let out = run(radc(["links".as_ref(), bin.as_os_str()]), b"");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::write(dir.path().join("s.rad"), SCENE).expect("scene");

    let oconv = Command::new(bin.join("oconv"))
        .arg("s.rad")
        .current_dir(dir.path())
        .output()
        .expect("oconv runs");
    assert!(
        oconv.status.success(),
        "{}",
        String::from_utf8_lossy(&oconv.stderr)
    );
    std::fs::write(dir.path().join("s.oct"), &oconv.stdout).expect("octree");

    let mut rtrace = Command::new(bin.join("rtrace"));
    rtrace.args(["-h", "s.oct"]).current_dir(dir.path());
    let by_name = run(rtrace, RAYS);
    let mut trace = radc(["trace", "-h", "s.rad"]);
    trace.current_dir(dir.path());
    let direct = run(trace, RAYS);
    assert!(
        by_name.status.success(),
        "{}",
        String::from_utf8_lossy(&by_name.stderr)
    );
    assert_eq!(by_name.stdout, direct.stdout);
    assert_eq!(String::from_utf8_lossy(&by_name.stdout).lines().count(), 2);

    let version = Command::new(bin.join("rtrace"))
        .arg("-version")
        .output()
        .expect("runs");
    assert!(String::from_utf8_lossy(&version.stdout).starts_with("RADIANCE 6"));
    let rcalc = Command::new(bin.join("rcalc"))
        .args(["-n", "-e", "$1=6*7"])
        .output()
        .expect("rcalc runs");
    assert_eq!(String::from_utf8_lossy(&rcalc.stdout), "42\n");
}

#[test]
fn links_never_overwrite_a_real_program() {
    let dir = tempfile::tempdir().expect("temp dir");
    let real = dir.path().join("rtrace");
    std::fs::write(&real, "#!/bin/sh\necho real rtrace\n").expect("real rtrace");
    let out = run(radc(["links".as_ref(), dir.path().as_os_str()]), b"");
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("exists and is not a link; left alone"));
    assert_eq!(
        std::fs::read_to_string(&real).expect("still there"),
        "#!/bin/sh\necho real rtrace\n"
    );
    // The others were made, and making them again replaces them.
    assert!(dir.path().join("oconv").symlink_metadata().is_ok());
    let again = run(radc(["links".as_ref(), dir.path().as_os_str()]), b"");
    assert!(
        String::from_utf8_lossy(&again.stderr)
            .matches("left alone")
            .count()
            == 1
    );
    // A name radc does not stand in for gets no link.
    assert!(dir.path().join("rcontrib").symlink_metadata().is_err());
}

/// A daylight scene (a `gensky` sky, a pattern) through `oconv` and `rtrace` by name:
/// the scene file keeps the scene as it was read, so rtrace renders it from another
/// folder, after the scene files are gone, without running its commands again (oconv
/// ran `!cat` through `sh`, as Radiance's oconv does).
#[test]
fn a_daylight_scene_through_oconv_renders_as_it_was_built() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bin = dir.path().join("bin");
    assert!(
        run(radc(["links".as_ref(), bin.as_os_str()]), b"")
            .status
            .success()
    );
    let scene = dir.path().join("scene");
    std::fs::create_dir(&scene).expect("scene folder");
    std::fs::write(
        scene.join("sky.rad"),
        "!gensky 3 21 12 -a 40 -o 98 -m 105\n\
         skyfunc glow skyglow 0 0 4 .9 .9 1.15 0\n\
         skyglow source sky 0 0 4 0 0 1 180\n\
         !cat floor.rad\n",
    )
    .expect("sky");
    std::fs::write(
        scene.join("floor.rad"),
        "void brightfunc stripes 2 'if(sin(Px*10),1,.2)' . 0 0\n\
         stripes plastic grey 0 0 5 .5 .5 .5 0 0\n\
         grey polygon ground 0 0 12 -5 -5 0 5 -5 0 5 5 0 -5 5 0\n",
    )
    .expect("floor");
    let rays = b"0.3 0.1 1 0 0 -1\n0.4 0.2 1 0 0 -1\n";
    let mut text = radc(["trace", "-h", "--allow-commands", "sky.rad"]);
    text.current_dir(&scene);
    let expected = run(text, rays);
    assert!(
        expected.status.success(),
        "{}",
        String::from_utf8_lossy(&expected.stderr)
    );

    let oconv = Command::new(bin.join("oconv"))
        .arg("sky.rad")
        .current_dir(&scene)
        .output()
        .expect("oconv runs");
    assert!(
        oconv.status.success(),
        "{}",
        String::from_utf8_lossy(&oconv.stderr)
    );
    let octree = dir.path().join("sky.oct");
    std::fs::write(&octree, &oconv.stdout).expect("octree");
    std::fs::remove_file(scene.join("floor.rad")).expect("gone");
    std::fs::remove_file(scene.join("sky.rad")).expect("gone");

    let mut rtrace = Command::new(bin.join("rtrace"));
    rtrace
        .args(["-h".as_ref(), octree.as_os_str()])
        .current_dir(dir.path());
    let got = run(rtrace, rays);
    assert!(
        got.status.success(),
        "{}",
        String::from_utf8_lossy(&got.stderr)
    );
    assert_eq!(
        String::from_utf8_lossy(&got.stdout),
        String::from_utf8_lossy(&expected.stdout)
    );
    // The stripes are there: the two points see different brightness.
    let values: Vec<f64> = String::from_utf8_lossy(&got.stdout)
        .split_whitespace()
        .map(|w| w.parse().expect("number"))
        .collect();
    assert!(values[0] > 2.0 * values[3], "{values:?}");

    // A damaged scene file is refused, naming it.
    let mut damaged = oconv.stdout.clone();
    let last = damaged.len() - 1;
    damaged[last] ^= 1;
    std::fs::write(&octree, &damaged).expect("damaged");
    let mut rtrace = Command::new(bin.join("rtrace"));
    rtrace.args(["-h".as_ref(), octree.as_os_str()]);
    let refused = run(rtrace, rays);
    assert!(!refused.status.success());
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("sky.oct") && err.contains("corrupt scene file"),
        "{err}"
    );
}
