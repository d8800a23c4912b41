//! How a scene front end (`radc check`, the language server) takes a built-in
//! command's result: as the text it made, a failure, or both. Radiance reads what a
//! generator wrote before failing (the generators write as they go) and only warns
//! about the bad status, so output before a failure is kept as [`Expansion::Partial`].

use crate::{Failure, GenError};
use radc_lang::FileId;
use radc_lang::scene::Expansion;

/// The expansion of a built-in command that gave `result`, having printed `warnings`
/// (the lines a [`crate::Host`] got through `warn`). `register` makes the output a
/// source file of its own, so diagnostics can point into it.
pub fn expansion(
    result: Result<String, Failure>,
    warnings: &[String],
    register: impl FnOnce(&str) -> FileId,
) -> Expansion {
    let (text, message, hint) = match result {
        Ok(text) => match nested_failure(warnings) {
            None => {
                let file = register(&text);
                return Expansion::Text { file, text };
            }
            Some(status) => (text, status.to_string(), Some(warnings.join("\n"))),
        },
        Err(f) => {
            let Failure {
                program,
                partial,
                error,
            } = f;
            let (message, hint) = match error {
                GenError::Nesting(m) => {
                    return Expansion::Cycle {
                        message: format!("{program}: {m}"),
                    };
                }
                GenError::Transform { diagnostic: d, .. } => {
                    (format!("{program}: {}", d.message), d.hint)
                }
                other => (format!("{program}: {other}"), None),
            };
            let hint = match (hint, warnings.is_empty()) {
                (h, true) => h,
                (None, false) => Some(warnings.join("\n")),
                (Some(h), false) => Some(format!("{h}\n{}", warnings.join("\n"))),
            };
            if partial.is_empty() {
                return Expansion::Failed { message, hint };
            }
            (partial, message, hint)
        }
    };
    let file = register(&text);
    Expansion::Partial {
        file,
        text,
        message,
        hint,
    }
}

/// A command that xform ran from a file it read failed: xform warned "bad status"
/// and went on, and the check goes on too, with that warning as its diagnostic.
fn nested_failure(warnings: &[String]) -> Option<&str> {
    warnings
        .iter()
        .find(|w| w.contains("warning - bad status from"))
        .map(String::as_str)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn register(_: &str) -> FileId {
        FileId(7)
    }

    #[test]
    fn output_before_a_failure_is_kept() {
        let f = Failure {
            program: "xform".into(),
            partial: "# xform\n".into(),
            error: GenError::Host("cannot find file \"a.rad\"".into()),
        };
        match expansion(Err(f), &[], register) {
            Expansion::Partial {
                file,
                text,
                message,
                hint,
            } => {
                assert_eq!((file, text.as_str()), (FileId(7), "# xform\n"));
                assert_eq!(message, "xform: cannot find file \"a.rad\"");
                assert_eq!(hint, None);
            }
            _ => panic!("not the expected expansion"),
        }
    }

    #[test]
    fn a_failure_before_any_output_reads_nothing() {
        let f = Failure::new("genbox", GenError::Usage("genbox m n x y z".into()));
        let warnings = vec!["xform: (a.rad): warning - empty file".to_string()];
        match expansion(Err(f), &warnings, register) {
            Expansion::Failed { message, hint } => {
                assert_eq!(message, "genbox: usage: genbox m n x y z");
                assert_eq!(
                    hint.as_deref(),
                    Some("xform: (a.rad): warning - empty file")
                );
            }
            _ => panic!("not the expected expansion"),
        }
    }

    #[test]
    fn a_nested_bad_status_is_a_warning_on_the_output() {
        let warnings = vec![
            "Usage: genbox m n x y z".to_string(),
            "xform: (s.rad): warning - bad status from \"!genbox m b 1\"".to_string(),
        ];
        match expansion(Ok("text".into()), &warnings, register) {
            Expansion::Partial {
                text,
                message,
                hint,
                ..
            } => {
                assert_eq!(text, "text");
                assert_eq!(message, warnings[1]);
                assert_eq!(hint, Some(warnings.join("\n")));
            }
            _ => panic!("not the expected expansion"),
        }
        // Warnings alone (an empty file) are not a failure.
        let empty = vec!["xform: (e.rad): warning - empty file".to_string()];
        assert!(matches!(
            expansion(Ok(String::new()), &empty, register),
            Expansion::Text { .. }
        ));
    }

    #[test]
    fn nesting_too_deep_is_a_cycle() {
        let f = Failure::new(
            "xform",
            GenError::Nesting("commands nested more than 32 deep".into()),
        );
        assert!(matches!(
            expansion(Err(f), &[], register),
            Expansion::Cycle { .. }
        ));
    }
}
