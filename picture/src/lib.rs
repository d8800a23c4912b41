//! Radiance pictures, read and written byte for byte as Radiance's own library does
//! (`src/common/header.c resolu.c color.c`): an information header kept line by line,
//! a resolution line in any of its eight orientations, and RGBE or XYZE scanlines that
//! are flat, old-style run-length encoded or new-style (per byte plane) encoded.
//!
//! This crate is the one home of pictures in radc: the renderer writes through it, the
//! engines of the picture programs (`tools`: getinfo, pvalue, pflip, protate, ra_*)
//! are here, with `radc`'s commands thin shells over them, and `colorpict` patterns sample through [`ColorPicture`]. It never prints and
//! never panics on file data: every problem is a [`PictureError`] with the byte offset.

pub mod color;
pub mod error;
pub mod header;
pub mod png_out;
pub mod resolution;
pub mod sample;
pub mod scanline;
pub mod tonemap;
pub mod tools;

mod picture;

pub use color::{Colr, decode, encode};
pub use error::{ErrorKind, PictureError};
pub use header::{Header, HeaderLine};
pub use picture::{DEFAULT_MAX_PIXELS, Format, Picture, write_rgb};
pub use resolution::{Orientation, Resolution};
pub use sample::ColorPicture;
