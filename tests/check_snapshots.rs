//! Every broken scene of the corpus pinned to the exact report `radc check` prints for
//! it: code, location, message, labels and hint. A change in wording or spans shows up
//! as a snapshot diff to review (`cargo insta review`, or `INSTA_UPDATE=always`).

use std::path::Path;
use std::process::Command;

fn report(scene: &Path) -> String {
    let dir = scene.parent().expect("scene has a folder");
    let name = scene.file_name().expect("scene has a name");
    let out = Command::new(env!("CARGO_BIN_EXE_radc"))
        .arg("check")
        .arg(name)
        .current_dir(dir)
        // Snapshots must not depend on the machine's Radiance library.
        .env_remove("RAYPATH")
        .env("NO_COLOR", "1")
        .output()
        .expect("radc runs");
    format!(
        "exit: {:?}\n{}{}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

#[test]
fn invalid_scene_reports() {
    insta::glob!("data/scenes/invalid/*.rad", |path| {
        insta::assert_snapshot!(report(path));
    });
}
