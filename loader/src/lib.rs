//! Scenes from disk, for the command line and the language server: the files named,
//! read in order as one scene; auxiliary files along the search path
//! ([`scene_files`]); `!` lines expanded ([`commands`]: radc's built-in generators
//! in-process, any other command through `sh` only when the caller allows it); compiled
//! scenes (`radc build`); and pictures and octrees told apart from scene text
//! ([`kind`]). `lang` does no IO: this crate is where scene text meets the disk.

pub mod bundle;
pub mod commands;
pub mod generator_host;
pub mod kind;
pub mod load;
pub mod pending;
pub mod read;
pub mod scene_files;
pub mod sources;

pub use bundle::SceneBundle;
pub use kind::{Kind, file_kind, picture_description};
pub use load::{LoadError, LoadOptions, SceneLoad, load_scene};
pub use read::{read_bundle, read_scene, read_scene_bundled, read_source};
pub use sources::{SourceText, Sources};
