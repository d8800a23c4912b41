//! How a scene read from disk expands `!command` lines in scenes: Radiance's generators that radc
//! builds in (genbox, gendaylit, genprism, genrev, gensky, gensurf, genworm, xform) run in-process; any other command runs through
//! `sh` only when the user passed `--allow-commands`, and is otherwise reported as not
//! expanded. Expanded text becomes a source file of its own so diagnostics inside it
//! can be shown against it.

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};

use radc_generators::expansion::expansion;
use radc_lang::FileId;
use radc_lang::scene::{CommandExpander, Expansion};
use radc_lang::search_path::{Policy, SearchPath};

use crate::bundle::{RecordedExpansion, RecordedOutcome};
use crate::generator_host::GeneratorHost;
use crate::pending::PendingSources;

pub struct Commands<'a> {
    /// The folder of each scene file, so relative names resolve from the scene.
    scene_dirs: Vec<(FileId, PathBuf)>,
    allow_commands: bool,
    pending: &'a PendingSources,
    /// Every expansion made, for a scene bundle (`crate::bundle`).
    recorded: RefCell<Vec<RecordedExpansion>>,
    /// Reading a bundle: the expansions recorded when it was built, answered in order
    /// instead of running anything.
    replay: Option<(Vec<RecordedExpansion>, Cell<usize>)>,
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
            recorded: RefCell::new(Vec::new()),
            replay: None,
        }
    }

    /// Commands that answer from `recorded` (a bundle's), running nothing.
    pub fn replaying(
        scene_dirs: Vec<(FileId, PathBuf)>,
        pending: &'a PendingSources,
        recorded: Vec<RecordedExpansion>,
    ) -> Self {
        Commands {
            replay: Some((recorded, Cell::new(0))),
            ..Commands::new(scene_dirs, pending, false)
        }
    }

    /// The expansions made so far, in order.
    pub fn into_recorded(self) -> Vec<RecordedExpansion> {
        self.recorded.into_inner()
    }

    /// The next recorded expansion, if it is of `command` in `dir`.
    fn replayed(&self, command: &str, dir: &Path) -> Option<Expansion> {
        let (recorded, next) = self.replay.as_ref()?;
        // In reading order, the same commands as when it was built (the folders differ:
        // a bundle's are absolute).
        let found = recorded.get(next.get()).filter(|r| r.command == command);
        let Some(r) = found else {
            return Some(Expansion::NotExpanded {
                reason: "the scene file holds no output for this command (rebuild it)".into(),
            });
        };
        next.set(next.get() + 1);
        let register = |text: &str| {
            self.pending
                .add(format!("!{command}"), text.to_string(), dir.to_path_buf())
        };
        Some(match &r.outcome {
            RecordedOutcome::Text(text) => Expansion::Text {
                file: register(text),
                text: text.clone(),
            },
            RecordedOutcome::Partial {
                text,
                message,
                hint,
            } => Expansion::Partial {
                file: register(text),
                text: text.clone(),
                message: message.clone(),
                hint: hint.clone(),
            },
            RecordedOutcome::Failed { message, hint } => Expansion::Failed {
                message: message.clone(),
                hint: hint.clone(),
            },
        })
    }

    fn record(&self, command: &str, dir: &Path, expansion: &Expansion) {
        let outcome = match expansion {
            Expansion::Text { text, .. } => RecordedOutcome::Text(text.clone()),
            Expansion::Partial {
                text,
                message,
                hint,
                ..
            } => RecordedOutcome::Partial {
                text: text.clone(),
                message: message.clone(),
                hint: hint.clone(),
            },
            Expansion::Failed { message, hint } => RecordedOutcome::Failed {
                message: message.clone(),
                hint: hint.clone(),
            },
            // A scene with these is refused: nothing to keep.
            Expansion::NotExpanded { .. } | Expansion::Cycle { .. } => return,
        };
        self.recorded.borrow_mut().push(RecordedExpansion {
            command: command.to_string(),
            dir: dir.display().to_string(),
            outcome,
        });
    }

    fn dir_of(&self, file: FileId) -> PathBuf {
        if let Some((_, d)) = self.scene_dirs.iter().find(|(f, _)| *f == file) {
            return d.clone();
        }
        self.pending.dir_of(file).unwrap_or_default()
    }

    /// Runs a command line: a built-in generator, or a pipeline of them (`genbox ... |
    /// xform -rz 90`), in-process; anything else through the shell, if allowed.
    fn run(&self, command: &str, dir: &Path) -> Expansion {
        let search = SearchPath::new(Policy::SceneRaypath, std::env::var_os("RAYPATH").as_deref());
        let mut host = GeneratorHost::new(dir.to_path_buf(), &search);
        let register = |text: &str| {
            self.pending
                .add(format!("!{command}"), text.to_string(), dir.to_path_buf())
        };
        match radc_generators::command::run_builtin(command, &mut host) {
            Some(result) => expansion(result, &host.warnings, register),
            None => match self.shell(command, dir) {
                Ok(text) => Expansion::Text {
                    file: register(&text),
                    text,
                },
                Err(e) => e,
            },
        }
    }

    fn shell(&self, command: &str, dir: &Path) -> Result<String, Expansion> {
        if !self.allow_commands {
            return Err(Expansion::NotExpanded {
                reason: "radc builds in genbox, gendaylit, genprism, genrev, gensky, gensurf, genworm and \
                         xform; other commands run only with --allow-commands"
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

impl CommandExpander for Commands<'_> {
    fn expand(&self, command: &str, from: FileId, _depth: u32) -> Expansion {
        let dir = self.dir_of(from);
        if let Some(replayed) = self.replayed(command, &dir) {
            return replayed;
        }
        let expansion = self.run(command, &dir);
        self.record(command, &dir, &expansion);
        expansion
    }
}
