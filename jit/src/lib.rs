//! calcomp evaluation and the data Radiance's functions read.

pub mod datafile;
