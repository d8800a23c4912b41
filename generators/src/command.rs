//! `!` command lines that name a generator radc has built in.
//!
//! Scenes often hold lines like `!genbox wood shelf 1 .3 .02` or `!xform -rz 90 a.rad`.
//! Radiance hands them to the shell; radc runs the built-in generator instead, with no
//! process and no shell. A line with shell syntax (pipes, redirection, variables,
//! globs) or another program is not a built-in: the caller decides what to do.

use crate::{Failure, GenError, Host};

/// The programs radc runs itself.
pub const BUILTINS: &[&str] = &[
    "genbox",
    "gendaylit",
    "genprism",
    "genrev",
    "gensky",
    "gensurf",
    "genworm",
    "xform",
];

/// The output of `command` (the text after `!`) if it is a plain invocation of a
/// built-in generator, or a pipeline of them (`genbox m b 1 1 1 | xform -rz 90`, each
/// stage reading the previous one's output as standard input); `None` if it is not.
/// Files it names are read through `host`. A failing stage ends the pipeline with what
/// it wrote before failing.
pub fn run_builtin(command: &str, host: &mut dyn Host) -> Option<Result<String, Failure>> {
    run_builtin_at(command, host, 0)
}

/// The program a command line runs (its first word, without a folder), for messages.
pub fn program_of(command: &str) -> &str {
    program_name(command.split_whitespace().next().unwrap_or("command"))
}

/// [`run_builtin`] from inside xform, `depth` nested commands deep.
pub(crate) fn run_builtin_at(
    command: &str,
    host: &mut dyn Host,
    depth: usize,
) -> Option<Result<String, Failure>> {
    let stages = split_pipeline(command)
        .iter()
        .map(|stage| simple_words(stage))
        .collect::<Option<Vec<_>>>()?;
    let is_builtin = |words: &Vec<String>| {
        words
            .first()
            .is_some_and(|p| BUILTINS.contains(&program_name(p)))
    };
    if stages.len() > 1 && !stages.iter().all(is_builtin) {
        return None;
    }
    let mut piped: Option<String> = None;
    for words in &stages {
        let Some(program) = words.first() else {
            return Some(Ok(String::new()));
        };
        let args = &words[1..];
        let mut stage_host = Piped {
            host: &mut *host,
            stdin: piped.take(),
        };
        let name = program_name(program);
        let whole = |r: Result<String, GenError>| r.map_err(|e| Failure::new(name, e));
        let result = match name {
            "genbox" => whole(crate::genbox(args)),
            "gendaylit" => crate::gendaylit(args, &mut stage_host),
            "genprism" => whole(crate::genprism(args, &mut stage_host)),
            "genrev" => crate::genrev(args, &mut stage_host),
            "gensky" => whole(crate::gensky(args, &mut stage_host)),
            "gensurf" => crate::gensurf(args, &mut stage_host),
            "genworm" => crate::genworm(args, &mut stage_host),
            "xform" => crate::xform::nested(args, &mut stage_host, depth),
            _ => return None,
        };
        match result {
            Ok(text) => piped = Some(text),
            Err(f) => return Some(Err(f)),
        }
    }
    Some(Ok(piped.unwrap_or_default()))
}

/// A program name without its folder (`/usr/local/bin/genbox` runs genbox).
fn program_name(word: &str) -> &str {
    word.rsplit('/').next().unwrap_or(word)
}

/// A pipeline stage's view of the host: standard input is the previous stage's output.
struct Piped<'h> {
    host: &'h mut dyn Host,
    stdin: Option<String>,
}

impl Host for Piped<'_> {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        self.host.read_file(path)
    }

    fn read_stdin(&mut self) -> Result<String, GenError> {
        match self.stdin.take() {
            Some(text) => Ok(text),
            None => self.host.read_stdin(),
        }
    }

    fn run_command(&mut self, command: &str, dir: &str) -> Result<String, Failure> {
        self.host.run_command(command, dir)
    }

    fn warn(&mut self, line: &str) {
        self.host.warn(line);
    }
}

/// Splits at `|` outside quotes.
fn split_pipeline(command: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let mut quote = None;
    let mut start = 0;
    for (i, c) in command.char_indices() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (None, '"' | '\'') => quote = Some(c),
            (None, '|') => {
                parts.push(&command[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&command[start..]);
    parts
}

/// Splits a command into words if it is a plain command line (quotes allowed, no
/// pipes, redirections, substitutions or variables): only those can be built-ins.
pub fn simple_words(command: &str) -> Option<Vec<String>> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quote = None;
    let mut chars = command.chars();
    while let Some(c) = chars.next() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '"' | '\'') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, '\\') => {
                let next = chars.next()?;
                if next != '\n' {
                    word.get_or_insert_with(String::new).push(next);
                }
            }
            (None, c) if c.is_whitespace() => words.extend(word.take()),
            (None, '|' | '&' | ';' | '<' | '>' | '`' | '$' | '(' | ')' | '*' | '?' | '[') => {
                return None;
            }
            (None, c) => word.get_or_insert_with(String::new).push(c),
        }
    }
    if quote.is_some() {
        return None;
    }
    words.extend(word);
    Some(words)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::NoHost;

    #[test]
    fn runs_only_plain_generator_lines() {
        let out = run_builtin("genbox m b 1 1 1", &mut NoHost);
        assert!(matches!(out, Some(Ok(text)) if text.starts_with("# genbox m b 1 1 1\n")));
        let out = run_builtin("/usr/local/bin/gensky -ang 45 0", &mut NoHost);
        assert!(matches!(out, Some(Ok(text)) if text.contains("skybright.cal")));
        let out = run_builtin("gendaylit -ang 45 0 -W 600 100", &mut NoHost);
        assert!(matches!(out, Some(Ok(text)) if text.contains("2 skybright perezlum.cal")));
        assert!(matches!(
            run_builtin("gendaylit 6 21 12 -i -5 -W 600 100", &mut NoHost),
            Some(Err(f)) if f.partial.starts_with("# gendaylit 6 21 12")
        ));
        assert!(run_builtin("cat scene.rad", &mut NoHost).is_none());
        assert!(run_builtin("genbox m b 1 1 1 | sort", &mut NoHost).is_none());
        assert!(run_builtin("genbox m b 1 1 1 > out.rad", &mut NoHost).is_none());
        assert!(run_builtin("genbox m b $W 1 1", &mut NoHost).is_none());
        assert!(matches!(
            run_builtin("genbox m b 0 1 1", &mut NoHost),
            Some(Err(_))
        ));
        assert!(matches!(
            run_builtin("xform -rz 9 missing.rad", &mut NoHost),
            Some(Err(_))
        ));
    }

    #[test]
    fn pipelines_of_generators_feed_each_other() {
        let out = run_builtin("genbox m b 1 1 1 | xform -n 'x|y' -rz 90", &mut NoHost);
        let Some(Ok(text)) = out else {
            panic!("pipeline did not run: {out:?}");
        };
        assert!(
            text.starts_with("# xform -n x|y -rz 90\n# genbox m b 1 1 1\n"),
            "{text}"
        );
    }

    #[test]
    fn quotes_group_words() {
        assert_eq!(
            simple_words("genbox 'my mat' \"a b\" 1\\ 2").unwrap_or_default(),
            ["genbox", "my mat", "a b", "1 2"]
        );
        assert_eq!(simple_words("genbox 'open"), None);
    }
}
