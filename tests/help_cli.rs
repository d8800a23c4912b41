//! `--help` on every command: exit 0, a usage line and the options one line each;
//! `radc help COMMAND` says the same.

mod common;

use common::{radc, run};

fn commands() -> Vec<String> {
    let out = run(radc(["help"]), b"");
    assert!(out.status.success());
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .skip_while(|l| !l.starts_with("commands:"))
        .skip(1)
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect()
}

#[test]
fn every_command_answers_help_with_its_options() {
    let commands = commands();
    assert!(commands.len() > 25, "{commands:?}");
    for c in &commands {
        let out = run(radc([c.as_str(), "--help"]), b"");
        assert_eq!(out.status.code(), Some(0), "{c} --help");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("usage: radc"), "{c}: {text}");
        assert!(text.lines().count() >= 4, "{c}: too short\n{text}");
        let again = run(radc(["help", c.as_str()]), b"");
        assert_eq!(again.stdout, out.stdout, "radc help {c}");
    }
    let out = run(radc(["help", "nosuch"]), b"");
    assert_eq!(out.status.code(), Some(2));
}
