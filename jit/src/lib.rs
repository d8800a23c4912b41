//! calcomp evaluation and the data Radiance's functions read.

/// Data files are parsed in `lang` (the checker validates them); evaluation lives here.
pub use radc_lang::datafile;
