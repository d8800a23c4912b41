//! `!` command lines: the command is expanded through the caller's
//! [`CommandExpander`] (`lang` never spawns) and its output lowered where the
//! command stands, as Radiance reads it; diagnostics inside the output point back
//! at the command line. oconv only warns about a command that fails.

use super::Lowering;
use crate::diagnostic::{self as codes, Diagnostic};
use crate::scene::command::{Expansion, MAX_DEPTH};
use crate::scene::syntax::Command;
use crate::source::FileId;

impl Lowering<'_> {
    /// Expands a `!` line and lowers its output in place, as Radiance reads a
    /// command's output where the command stands. Diagnostics inside the output get a
    /// label pointing back at the command line.
    pub(super) fn command(&mut self, c: &Command, warn_unused: bool, depth: u32) {
        if depth >= MAX_DEPTH {
            self.diags.push(
                Diagnostic::new(
                    codes::E0307,
                    c.span,
                    format!("commands nest more than {MAX_DEPTH} deep"),
                )
                .with_hint("a file probably includes itself through '!xform'"),
            );
            return;
        }
        match self.commands.expand(&c.text, c.span.file, depth + 1) {
            Expansion::Text { file, text } => self.output(c, file, &text, warn_unused, depth),
            Expansion::Partial {
                file,
                text,
                message,
                hint,
            } => {
                self.output(c, file, &text, warn_unused, depth);
                let mut d = Diagnostic::new(codes::W0306, c.span, message);
                if let Some(h) = hint {
                    d = d.with_hint(h);
                }
                self.diags.push(d);
            }
            Expansion::NotExpanded { reason } => self.diags.push(
                Diagnostic::new(
                    codes::W0303,
                    c.span,
                    "this '!' command was not run, so what it makes is not checked",
                )
                .with_hint(reason),
            ),
            Expansion::Cycle { message } => {
                self.diags
                    .push(Diagnostic::new(codes::E0307, c.span, message).with_hint(
                        "a scene cannot include itself; remove the '!' line that reads this file",
                    ))
            }
            Expansion::Failed { message, hint } => {
                // oconv only warns about a failing command ("bad status") and goes on.
                let mut d = Diagnostic::new(codes::W0306, c.span, message);
                if let Some(h) = hint {
                    d = d.with_hint(h);
                }
                self.diags.push(d);
            }
        }
    }

    /// Lowers a command's output where the command stands.
    fn output(&mut self, c: &Command, file: FileId, text: &str, warn_unused: bool, depth: u32) {
        let (syntax, mut diags) = crate::scene::parse(file, text);
        let first = self.diags.len();
        self.diags.append(&mut diags);
        self.items(&syntax.items, warn_unused, depth + 1);
        for d in &mut self.diags[first..] {
            if d.span.file == file {
                d.labels.push(crate::diagnostic::Label {
                    span: c.span,
                    message: "in the output of this command".into(),
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::command::CommandExpander;
    use crate::scene::ir::Scene;
    use crate::scene::lower::tests::PAINT;
    use crate::scene::lower::{AssumeFilesExist, LowerInput, lower_with};

    /// Expands `!gen NAME` into a sphere named NAME using the material `paint`, and
    /// `!loop` into itself.
    struct FakeGenerators;

    impl CommandExpander for FakeGenerators {
        fn expand(&self, command: &str, _: FileId, depth: u32) -> Expansion {
            let file = FileId(depth);
            match command.split_whitespace().collect::<Vec<_>>().as_slice() {
                ["gen", name] => Expansion::Text {
                    file,
                    text: format!("paint sphere {name} 0 0 4 0 0 0 1\n"),
                },
                ["genbad"] => Expansion::Text {
                    file,
                    text: "undefined sphere x 0 0 4 0 0 0 1\n".into(),
                },
                ["loop"] => Expansion::Text {
                    file,
                    text: "!loop\n".into(),
                },
                ["fail"] => Expansion::Failed {
                    message: "it failed".into(),
                    hint: None,
                },
                ["halfway", name] => Expansion::Partial {
                    file,
                    text: format!("paint sphere {name} 0 0 4 0 0 0 1\nundefined sphere y\n"),
                    message: "it failed halfway".into(),
                    hint: Some("the program's own message".into()),
                },
                _ => Expansion::NotExpanded {
                    reason: "not a generator".into(),
                },
            }
        }
    }

    fn check_with_commands(text: &str) -> (Scene, Vec<Diagnostic>) {
        let (syntax, mut diags) = crate::scene::parse(FileId(0), text);
        let input = LowerInput {
            file: FileId(0),
            syntax: &syntax,
            warn_unused: true,
        };
        let (scene, more) = lower_with(&[input], &AssumeFilesExist, &FakeGenerators);
        diags.extend(more);
        (scene, diags)
    }

    #[test]
    fn commands_expand_in_place_and_errors_point_back() {
        let (scene, diags) = check_with_commands(&format!("{PAINT}!gen ball\n!ls -l\n!genbad\n"));
        assert!(scene.prims.iter().any(|p| p.name == "ball"));
        let codes: Vec<_> = diags.iter().map(|d| d.code.id).collect();
        assert_eq!(codes, vec!["W0303", "E0301"]);
        assert_eq!(diags[1].labels[0].message, "in the output of this command");
        let (_, diags) = check_with_commands("!loop\n");
        assert_eq!(
            diags.iter().map(|d| d.code.id).collect::<Vec<_>>(),
            vec!["E0307"]
        );
    }

    #[test]
    fn output_before_a_failure_is_lowered_and_the_failure_warns_on_the_command() {
        let text = format!("{PAINT}\n!halfway half\n");
        let (scene, diags) = check_with_commands(&text);
        assert!(scene.prims.iter().any(|p| p.name == "half"));
        let failure = diags
            .iter()
            .find(|d| d.code.id == "W0306")
            .expect("a command-failed warning");
        assert_eq!(failure.span.file, FileId(0));
        let at = failure.span.start as usize..failure.span.end as usize;
        assert_eq!(&text[at], "!halfway half");
        assert_eq!(failure.hint.as_deref(), Some("the program's own message"));
        // The truncated primitive is reported in the output, pointing back at the line.
        let truncated = diags
            .iter()
            .find(|d| d.span.file != FileId(0))
            .expect("a diagnostic inside the output");
        assert_eq!(truncated.labels[0].span, failure.span);
    }
}
