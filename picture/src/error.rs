//! The one error type of picture reading: what went wrong and at which byte, in words a
//! user can act on. Commands add the file name.

use std::fmt;

/// What is wrong with a picture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ErrorKind {
    /// The first byte is not printable, or the file ends before the empty line that ends
    /// the header (`getheader` fails the same way).
    BadHeader,
    /// The header names a format other than a Radiance picture's (`FORMAT=`).
    WrongFormat(String),
    /// No resolution line after the header, or one `str2resolu` refuses.
    BadResolution,
    /// The resolution asks for more pixels than the reader was allowed to hold.
    TooLarge { width: u32, height: u32 },
    /// The pixels end early (or a run overruns its scanline): `scanline` counts from 0
    /// in file order.
    Truncated { scanline: u32 },
    /// A new-style scanline whose length field is not the picture's scanline length.
    ScanlineLength { scanline: u32, found: u32 },
}

/// A picture that cannot be read, with the byte offset where the problem was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PictureError {
    pub kind: ErrorKind,
    pub offset: usize,
}

impl PictureError {
    pub fn new(kind: ErrorKind, offset: usize) -> Self {
        PictureError { kind, offset }
    }
}

impl fmt::Display for PictureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let at = self.offset;
        match &self.kind {
            ErrorKind::BadHeader => write!(
                f,
                "bad header: not a Radiance file, or the header has no ending empty line (byte {at})"
            ),
            ErrorKind::WrongFormat(found) => write!(
                f,
                "wrong format: the header says FORMAT={found}, not a Radiance picture (32-bit_rle_rgbe or 32-bit_rle_xyze)"
            ),
            ErrorKind::BadResolution => write!(
                f,
                "bad resolution line at byte {at}: expected one like '-Y 512 +X 768'"
            ),
            ErrorKind::TooLarge { width, height } => {
                write!(f, "a {width} by {height} picture is too large to read")
            }
            ErrorKind::Truncated { scanline } => write!(
                f,
                "truncated picture: scanline {scanline} ends early at byte {at}"
            ),
            ErrorKind::ScanlineLength { scanline, found } => write!(
                f,
                "bad scanline {scanline} at byte {at}: it says it is {found} pixels long"
            ),
        }
    }
}

impl std::error::Error for PictureError {}
