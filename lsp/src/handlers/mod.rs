//! One file per request kind. Each handler takes a [`crate::document::Document`] and
//! the request's parameters and returns the response; none of them waits, locks or
//! does IO.

pub mod colors;
pub mod completion;
pub mod definition;
pub mod formatting;
pub mod hover;
pub mod inlay_hints;
pub mod references;
pub mod symbols;
