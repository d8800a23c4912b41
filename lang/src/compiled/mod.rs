//! Radiance's compiled binary files, read from bytes (no IO, like the rest of `lang`):
//! mesh files (`mesh_file`, obj2mesh's `.rtm`), with the portable numbers they are
//! written in (`portio`) and the binary scene section of their materials
//! (`objects`), which becomes scene text for the scene front end.

pub mod mesh_file;
pub mod objects;
pub mod portio;

pub use mesh_file::MeshFile;
pub use portio::BinaryError;
