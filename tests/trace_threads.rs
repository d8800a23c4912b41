//! `radc trace` writes the same bytes for any thread count: rays are evaluated and
//! formatted in parallel chunks but written in input order, and each ray's random
//! choices derive from its place in the input.

mod common;

const SCENE: &str = "\
void light glow 0 0 3 10 10 10
glow sphere lamp 0 0 4 0 0 3 0.5
void plastic grey 0 0 5 0.5 0.5 0.5 0 0
grey sphere ball 0 0 4 0 0 0 1
grey polygon floor 0 0 12 -5 -5 -1 5 -5 -1 5 5 -1 -5 5 -1
";

fn trace(dir: &std::path::Path, options: &[&str], rays: &[u8]) -> Vec<u8> {
    let mut cmd = common::radc(["trace", "-h"]);
    cmd.args(options).arg(dir.join("scene.rad"));
    let out = common::run(cmd, rays);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

#[test]
fn output_is_the_same_for_any_thread_count() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("scene.rad"), SCENE).expect("write scene");
    // 1,500 rays (several chunks) from above towards the ball and the floor, a
    // zero-direction flush request in the middle, and a line that is not one ray.
    let mut rays = String::new();
    for k in 0..1500 {
        let (x, y) = ((k % 37) as f64 * 0.21 - 3.8, (k % 41) as f64 * 0.19 - 3.8);
        rays.push_str(&format!(
            "{x:.6} {y:.6} 2.5 {:.8} {:.8} -1\n",
            x * -0.1,
            y * -0.1
        ));
        if k == 700 {
            rays.push_str("1 2 3 0 0 0\n");
        }
        if k == 900 {
            rays.push_str("0 0 2.5\n0.1 0.1 -1 0 0 2.5 0 0 -1\n");
        }
    }
    for options in [
        &["-ov"][..],
        &["-ab", "1", "-ad", "16", "-ovdlL"],
        &["-ffd", "-ov"],
    ] {
        let mut outputs = Vec::new();
        for n in ["1", "2", "3"] {
            let mut o = options.to_vec();
            o.extend(["-n", n]);
            outputs.push(trace(dir.path(), &o, rays.as_bytes()));
        }
        assert!(!outputs[0].is_empty());
        assert_eq!(outputs[0], outputs[1], "{options:?}: -n 1 vs -n 2");
        assert_eq!(outputs[0], outputs[2], "{options:?}: -n 1 vs -n 3");
    }
}
