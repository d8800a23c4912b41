//! How the CLI expands `!command` lines in scenes: Radiance's generators that radc
//! builds in (genbox, genprism, xform) run in-process; any other command runs through
//! `sh` only when the user passed `--allow-commands`, and is otherwise reported as not
//! expanded. Expanded text becomes a source file of its own so diagnostics inside it
//! can be shown against it.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use radc_generators::{GenError, Host};
use radc_lang::FileId;
use radc_lang::scene::{CommandExpander, Expansion};

/// Words that make a command line more than a program and its arguments.
const SHELL_SYNTAX: &[char] = &['|', '&', ';', '<', '>', '(', ')', '$', '`', '*', '?', '\\'];

/// Files a check reads beyond the scenes named on the command line (command
/// outputs, function files), numbered after the sources already read so diagnostics
/// can point into them. Shared by the command expander and the file lookup.
pub struct PendingSources {
    first_id: u32,
    /// (display name, text, folder) in id order.
    files: RefCell<Vec<(String, String, PathBuf)>>,
}

impl PendingSources {
    pub fn new(first_id: u32) -> Self {
        PendingSources {
            first_id,
            files: RefCell::new(Vec::new()),
        }
    }

    pub fn add(&self, name: String, text: String, dir: PathBuf) -> FileId {
        let mut files = self.files.borrow_mut();
        files.push((name, text, dir));
        FileId(self.first_id + files.len() as u32 - 1)
    }

    /// The folder a pending file's relative names resolve from.
    pub fn dir_of(&self, file: FileId) -> Option<PathBuf> {
        let index = file.0.checked_sub(self.first_id)?;
        self.files.borrow().get(index as usize).map(|e| e.2.clone())
    }

    /// The files, as (display name, text), in id order.
    pub fn into_sources(self) -> Vec<(String, String)> {
        self.files
            .into_inner()
            .into_iter()
            .map(|(name, text, _)| (name, text))
            .collect()
    }
}

pub struct Commands<'a> {
    /// The folder of each scene file, so relative names resolve from the scene.
    scene_dirs: Vec<(FileId, PathBuf)>,
    allow_commands: bool,
    pending: &'a PendingSources,
}

impl<'a> Commands<'a> {
    pub fn new(
        scene_dirs: Vec<(FileId, PathBuf)>,
        pending: &'a PendingSources,
        allow_commands: bool,
    ) -> Self {
        Commands {
            scene_dirs,
            allow_commands,
            pending,
        }
    }

    fn dir_of(&self, file: FileId) -> PathBuf {
        if let Some((_, d)) = self.scene_dirs.iter().find(|(f, _)| *f == file) {
            return d.clone();
        }
        self.pending.dir_of(file).unwrap_or_default()
    }

    /// Runs a command line: a pipeline of built-in generators (`genbox ... | xform
    /// -rz 90`) in-process, each stage reading the previous one's output; anything
    /// else through the shell, if allowed.
    fn run(&self, command: &str, dir: &Path) -> Result<String, Expansion> {
        let Some(stages) = pipeline(command) else {
            return self.shell(command, dir);
        };
        let mut output = String::new();
        for (i, words) in stages.iter().enumerate() {
            let Some((program, rest)) = words.split_first() else {
                return self.shell(command, dir);
            };
            let program = program.rsplit('/').next().unwrap_or(program);
            let mut host = SceneHost {
                dir: dir.to_path_buf(),
                stdin: if i == 0 {
                    String::new()
                } else {
                    std::mem::take(&mut output)
                },
            };
            let result = match program {
                "genbox" => radc_generators::genbox(rest),
                "genprism" => radc_generators::genprism(rest, &mut host),
                "xform" => radc_generators::xform(rest, &mut host),
                _ => return self.shell(command, dir),
            };
            output = result.map_err(|e| failed(program, e))?;
        }
        Ok(output)
    }

    fn shell(&self, command: &str, dir: &Path) -> Result<String, Expansion> {
        if !self.allow_commands {
            return Err(Expansion::NotExpanded {
                reason: "radc builds in genbox, genprism and xform; other commands run only \
                         with --allow-commands"
                    .into(),
            });
        }
        let mut sh = std::process::Command::new("sh");
        sh.arg("-c").arg(command);
        if !dir.as_os_str().is_empty() {
            sh.current_dir(dir);
        }
        match sh.output() {
            Ok(out) if out.status.success() => {
                Ok(String::from_utf8_lossy(&out.stdout).into_owned())
            }
            Ok(out) => Err(Expansion::Failed {
                message: format!("command exited with {}", out.status),
                hint: Some(String::from_utf8_lossy(&out.stderr).trim().to_string())
                    .filter(|s| !s.is_empty()),
            }),
            Err(e) => Err(Expansion::Failed {
                message: format!("cannot run the command: {e}"),
                hint: None,
            }),
        }
    }
}

fn failed(program: &str, e: GenError) -> Expansion {
    match e {
        GenError::Scene(m) if m.contains("nested more than") => Expansion::Cycle {
            message: format!("{program}: {m}"),
        },
        GenError::Transform(d) => Expansion::Failed {
            message: format!("{program}: {}", d.message),
            hint: d.hint,
        },
        other => Expansion::Failed {
            message: format!("{program}: {other}"),
            hint: None,
        },
    }
}

impl CommandExpander for Commands<'_> {
    fn expand(&self, command: &str, from: FileId, _depth: u32) -> Expansion {
        let dir = self.dir_of(from);
        match self.run(command, &dir) {
            Ok(text) => {
                let file = self.pending.add(format!("!{command}"), text.clone(), dir);
                Expansion::Text { file, text }
            }
            Err(e) => e,
        }
    }
}

/// Splits a command line into pipeline stages of plain words; `None` if it uses any
/// shell syntax other than `|`.
fn pipeline(command: &str) -> Option<Vec<Vec<String>>> {
    split_outside_quotes(command, '|')
        .iter()
        .map(|stage| simple_words(stage))
        .collect()
}

/// Splits at `sep` where it is not inside quotes.
fn split_outside_quotes(text: &str, sep: char) -> Vec<String> {
    let mut parts = vec![String::new()];
    let mut quote: Option<char> = None;
    for c in text.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c == sep => {
                parts.push(String::new());
                continue;
            }
            _ => {}
        }
        if let Some(last) = parts.last_mut() {
            last.push(c);
        }
    }
    parts
}

/// Splits a command into words as the shell would for a plain command: whitespace
/// separated, quotes grouping. `None` if it uses any other shell syntax.
fn simple_words(command: &str) -> Option<Vec<String>> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut quote: Option<char> = None;
    for c in command.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => word.push(c),
            None if c == '"' || c == '\'' => {
                quote = Some(c);
                in_word = true;
            }
            None if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            None if SHELL_SYNTAX.contains(&c) => return None,
            None => {
                word.push(c);
                in_word = true;
            }
        }
    }
    if quote.is_some() {
        return None;
    }
    if in_word {
        words.push(word);
    }
    Some(words)
}

/// Files for generators run from a scene: relative to the scene's folder, then RAYPATH.
struct SceneHost {
    dir: PathBuf,
    /// The previous pipeline stage's output.
    stdin: String,
}

impl Host for SceneHost {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        let p = Path::new(path);
        let mut candidates = vec![self.dir.join(p)];
        if let (false, Some(raypath)) = (p.is_absolute(), std::env::var_os("RAYPATH")) {
            candidates.extend(std::env::split_paths(&raypath).map(|d| d.join(p)));
        }
        for c in &candidates {
            if let Ok(bytes) = std::fs::read(c) {
                return Ok(String::from_utf8_lossy(&bytes).into_owned());
            }
        }
        Err(GenError::Host(format!("cannot find file \"{path}\"")))
    }

    fn read_stdin(&mut self) -> Result<String, GenError> {
        Ok(std::mem::take(&mut self.stdin))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_commands_split_and_shell_syntax_does_not() {
        assert_eq!(
            simple_words("genbox 'my mat' box 1 2 3").unwrap(),
            vec!["genbox", "my mat", "box", "1", "2", "3"]
        );
        assert!(simple_words("genbox m b 1 1 1 | xform -rz 90").is_none());
        let stages = pipeline("genbox m 'a|b' 1 1 1 | xform -rz 90").unwrap();
        assert_eq!(stages.len(), 2);
        assert_eq!(stages[0][2], "a|b");
        assert!(pipeline("genbox m b 1 1 1 > out.rad").is_none());
        assert!(simple_words("cat $HOME/x").is_none());
    }
}
