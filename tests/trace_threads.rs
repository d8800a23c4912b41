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

/// Rays over the whole scene in no spatial order (a fixed pseudo-random sequence).
fn scattered_rays(n: usize) -> String {
    let mut rays = String::new();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..n {
        let (x, y) = (8.0 * next() - 4.0, 8.0 * next() - 4.0);
        let (dx, dy) = (next() - 0.5, next() - 0.5);
        rays.push_str(&format!("{x:.6} {y:.6} 2.5 {dx:.8} {dy:.8} -1\n"));
    }
    rays
}

#[test]
fn tracing_a_batch_in_space_order_changes_no_output() {
    // A batch is traced sorted along a curve through the scene; with -x 1 every ray
    // is flushed on its own, so each is its own batch and goes as given.
    // Scenes bigger than a core's cache are the ones sorted: 16,000 balls (about
    // 2 MB of nodes and spheres) under the lamp.
    let mut scene = SCENE.to_string();
    for k in 0..16_000 {
        let (x, y) = (
            (k % 128) as f64 * 0.0625 - 4.0,
            (k / 128) as f64 * 0.0625 - 4.0,
        );
        scene.push_str(&format!("grey sphere b{k} 0 0 4 {x} {y} -0.9 0.02\n"));
    }
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("scene.rad"), scene).expect("write scene");
    let rays = scattered_rays(1500);
    for options in [
        &["-ov"][..],
        &["-ab", "1", "-ad", "16", "-ovdplLn"],
        &["-ffd", "-ovn"],
    ] {
        let mut one_by_one = options.to_vec();
        one_by_one.extend(["-x", "1"]);
        let sorted = trace(dir.path(), options, rays.as_bytes());
        assert!(!sorted.is_empty());
        assert_eq!(
            sorted,
            trace(dir.path(), &one_by_one, rays.as_bytes()),
            "{options:?}"
        );
    }
}

/// A reader of `radc trace`'s lines on another thread, as a program that waits for
/// each answer would be.
struct Session {
    child: std::process::Child,
    stdin: std::process::ChildStdin,
    lines: std::sync::mpsc::Receiver<String>,
}

impl Session {
    fn start(dir: &std::path::Path, options: &[&str]) -> Session {
        use std::io::BufRead;
        let mut cmd = common::radc(["trace", "-h"]);
        cmd.args(options).arg(dir.join("scene.rad"));
        let mut child = cmd
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .spawn()
            .expect("radc runs");
        let stdin = child.stdin.take().expect("stdin");
        let stdout = child.stdout.take().expect("stdout");
        let (send, lines) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in std::io::BufReader::new(stdout)
                .lines()
                .map_while(Result::ok)
            {
                if send.send(line).is_err() {
                    break;
                }
            }
        });
        Session {
            child,
            stdin,
            lines,
        }
    }

    fn send(&mut self, ray: &str) {
        use std::io::Write;
        self.stdin.write_all(ray.as_bytes()).expect("write a ray");
        self.stdin.flush().expect("flush");
    }

    fn line(&self, wait: std::time::Duration) -> Option<String> {
        self.lines.recv_timeout(wait).ok()
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[test]
fn x_flushes_every_x_rays_to_a_program_waiting_for_them() {
    use std::time::Duration;
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("scene.rad"), SCENE).expect("write scene");
    let long = Duration::from_secs(30);
    // -x 1: each answer as soon as its ray is read.
    let mut s = Session::start(dir.path(), &["-x", "1", "-ov"]);
    for _ in 0..3 {
        s.send("0 0 2.5 0 0 -1\n");
        let line = s.line(long).expect("an answer to each ray");
        assert_eq!(line.split_whitespace().count(), 3, "{line}");
    }
    // -x 3 -y 0: answers three at a time.
    let mut s = Session::start(dir.path(), &["-x", "3", "-y", "0", "-ov"]);
    s.send("0 0 2.5 0 0 -1\n0 0 2.5 0.1 0 -1\n");
    assert_eq!(
        s.line(Duration::from_millis(500)),
        None,
        "flushed before the third ray"
    );
    s.send("0 0 2.5 0 0.1 -1\n");
    for _ in 0..3 {
        assert!(s.line(long).is_some(), "three answers after the third ray");
    }
    // Without -x: answers wait for a flush request (a zero direction) or the end.
    let mut s = Session::start(dir.path(), &["-ov"]);
    s.send("0 0 2.5 0 0 -1\n");
    assert_eq!(
        s.line(Duration::from_millis(500)),
        None,
        "flushed without a request"
    );
    s.send("0 0 0 0 0 0\n");
    assert!(s.line(long).is_some(), "the answer after a flush request");
    assert!(s.line(long).is_some(), "the flush request's empty record");
}
