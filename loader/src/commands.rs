//! How a scene read from disk expands `!command` lines in scenes: Radiance's generators that radc
//! builds in (genbox, gendaylit, genprism, genrev, gensky, gensurf, genworm, xform) run in-process; any other command runs through
//! `sh` only when the user passed `--allow-commands`, and is otherwise reported as not
//! expanded. Expanded text becomes a source file of its own so diagnostics inside it
//! can be shown against it.

use std::path::{Path, PathBuf};

use radc_generators::expansion::expansion;
use radc_lang::FileId;
use radc_lang::scene::{CommandExpander, Expansion};
use radc_lang::search_path::{Policy, SearchPath};

use crate::generator_host::GeneratorHost;
use crate::pending::PendingSources;

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
        self.run(command, &self.dir_of(from))
    }
}
