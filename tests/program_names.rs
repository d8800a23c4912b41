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
