//! The information header (`src/common/header.c`): lines up to an empty one, each kept
//! byte for byte and in order, so a command that copies a header copies it exactly.

use crate::error::{ErrorKind, PictureError};
use radc_lang::c_number::atof;

/// `getheader` reads with `fgets` into a 2048-byte buffer: a longer line reaches its
/// callback in pieces of at most this many bytes.
const MAX_PIECE: usize = 2046;

/// One header line as `getheader` hands it over: its bytes, with its `\n` when it had
/// one (a piece of an over-long line has none).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HeaderLine(pub Vec<u8>);

impl HeaderLine {
    /// The line without its newline, lossily as text (header lines are ASCII in practice).
    pub fn text(&self) -> String {
        let b = self.0.strip_suffix(b"\n").unwrap_or(&self.0);
        String::from_utf8_lossy(b).into_owned()
    }

    /// The value of `FORMAT=` as `formatval` reads it (blanks around it removed), if
    /// this is a format line with a value.
    pub fn format(&self) -> Option<String> {
        let rest = self.0.strip_prefix(b"FORMAT=")?;
        let v = String::from_utf8_lossy(rest);
        let v = v.trim_matches(|c: char| c.is_ascii_whitespace());
        (!v.is_empty()).then(|| v.to_string())
    }

    /// The text after `prefix` when the line starts with it (`isexpos`, `isaspect`...).
    pub fn value_after(&self, prefix: &str) -> Option<String> {
        let rest = self.0.strip_prefix(prefix.as_bytes())?;
        Some(
            String::from_utf8_lossy(rest)
                .trim_end_matches('\n')
                .to_string(),
        )
    }
}

/// A header: every line in order, including the `#?RADIANCE` line and `FORMAT=` lines.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Header {
    pub lines: Vec<HeaderLine>,
}

impl Header {
    /// A new picture header: `#?RADIANCE`, `lines` (commands, `VAR= value`, each
    /// without its newline) and the `FORMAT=` line last, as Radiance's programs write it.
    pub fn new_picture(lines: &[String], format: &str) -> Header {
        let mut h = Header {
            lines: vec![HeaderLine(b"#?RADIANCE\n".to_vec())],
        };
        for l in lines {
            h.push(l);
        }
        h.push(&format!("FORMAT={format}"));
        h
    }

    /// Appends a line (a newline is added).
    pub fn push(&mut self, line: &str) {
        let mut b = line.as_bytes().to_vec();
        b.push(b'\n');
        self.lines.push(HeaderLine(b));
    }

    /// Reads a header from the start of `data` as `getheader` does: the first byte must
    /// be printable; lines end at `\n`; an empty line (or `\r\n`) ends the header.
    /// Returns the header and the offset of the byte after the empty line.
    pub fn parse(data: &[u8]) -> Result<(Header, usize), PictureError> {
        let (lines, end) = Self::parse_partial(data);
        end.map(|end| (Header { lines }, end))
    }

    /// [`Header::parse`], also giving the lines read before an error: `getinfo` has
    /// printed those by the time it finds the header is bad.
    pub fn parse_partial(data: &[u8]) -> (Vec<HeaderLine>, Result<usize, PictureError>) {
        let bad = |at| Err(PictureError::new(ErrorKind::BadHeader, at));
        let mut lines = Vec::new();
        match data.first() {
            Some(&c) if (0x20..0x7f).contains(&c) => {}
            _ => return (lines, bad(0)),
        }
        let mut pos = 0;
        loop {
            if pos >= data.len() {
                return (lines, bad(pos));
            }
            let rest = &data[pos..];
            let (piece, len) = match memchr(rest) {
                Some(nl) if nl <= MAX_PIECE => (&rest[..=nl], nl + 1),
                _ if rest.len() > MAX_PIECE => (&rest[..MAX_PIECE], MAX_PIECE),
                // The last line has no newline: fgets returns it, then the next read fails.
                _ => (rest, rest.len()),
            };
            if piece == b"\n" || piece == b"\r\n" {
                return (lines, Ok(pos + len));
            }
            lines.push(HeaderLine(piece.to_vec()));
            pos += len;
        }
    }

    /// The header as bytes, every line as read (no ending empty line).
    pub fn to_bytes(&self) -> Vec<u8> {
        self.lines
            .iter()
            .flat_map(|l| l.0.iter().copied())
            .collect()
    }

    /// The last `FORMAT=` value (each format line replaces the one before, as
    /// `checkheader` keeps the last).
    pub fn format(&self) -> Option<String> {
        self.lines.iter().rev().find_map(HeaderLine::format)
    }

    /// The lines that start with `prefix`, the text after it.
    pub fn values<'a>(&'a self, prefix: &'a str) -> impl Iterator<Item = String> + 'a {
        self.lines.iter().filter_map(move |l| l.value_after(prefix))
    }

    /// The product of every `EXPOSURE=` (they are cumulative: pfilt appends one per
    /// adjustment), 1 when there is none.
    pub fn exposure(&self) -> f64 {
        self.values("EXPOSURE=").map(|v| atof(&v)).product()
    }

    /// The product of every `PIXASPECT=` (cumulative, as `headaspect` multiplies them):
    /// the height of a pixel over its width. 1 when there is none.
    pub fn pixel_aspect(&self) -> f64 {
        self.values("PIXASPECT=").map(|v| atof(&v)).product()
    }

    /// The product of every `COLORCORR=` (three factors each), `None` when there is none
    /// or one does not have three numbers.
    pub fn color_correction(&self) -> Option<[f64; 3]> {
        let mut cc = None;
        for v in self.values("COLORCORR=") {
            let n: Vec<f64> = v.split_whitespace().map_while(|w| w.parse().ok()).collect();
            let [r, g, b] = n[..] else { return None };
            let c = cc.get_or_insert([1.0; 3]);
            *c = [c[0] * r, c[1] * g, c[2] * b];
        }
        cc
    }

    /// The eight chromaticities of the last `PRIMARIES=` line.
    pub fn primaries(&self) -> Option<[f64; 8]> {
        let v = self.values("PRIMARIES=").last()?;
        let n: Vec<f64> = v.split_whitespace().map_while(|w| w.parse().ok()).collect();
        n.get(..8)?.try_into().ok()
    }

    /// The text of the last `VIEW=` line (view options; later lines add to earlier ones
    /// in Radiance, so callers that need the whole view read every line).
    pub fn view(&self) -> Option<String> {
        self.values("VIEW=").last().map(|v| v.trim().to_string())
    }

    /// `CAPDATE=` and `SOFTWARE=`, as written.
    pub fn capture_date(&self) -> Option<String> {
        self.values("CAPDATE=").last().map(|v| v.trim().to_string())
    }
    pub fn software(&self) -> Option<String> {
        self.values("SOFTWARE=")
            .last()
            .map(|v| v.trim().to_string())
    }

    /// The lines that record commands: not the magic line and not `VAR=value` lines.
    pub fn commands(&self) -> impl Iterator<Item = String> + '_ {
        self.lines.iter().skip(1).map(HeaderLine::text).filter(|t| {
            let word = t.split_whitespace().next().unwrap_or("");
            !word.is_empty() && !word.contains('=')
        })
    }
}

fn memchr(b: &[u8]) -> Option<usize> {
    b.iter().position(|&c| c == b'\n')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_lines_are_kept_in_order() {
        let data = b"#?RADIANCE\nrpict -x 4\nEXPOSURE=2\nPIXASPECT=0.5\nEXPOSURE=1.5\nCOLORCORR= 1 2 3\nPRIMARIES= .64 .33 .29 .6 .15 .06 .333 .333\nVIEW= -vtv -vp 0 0 0\nFORMAT=32-bit_rle_rgbe  \n\n-Y 1 +X 1\n";
        let (h, end) = Header::parse(data).unwrap();
        assert_eq!(&data[end..end + 2], b"-Y");
        assert_eq!(h.lines.len(), 9);
        assert_eq!(h.to_bytes(), data[..end - 1].to_vec());
        assert_eq!(h.format().as_deref(), Some("32-bit_rle_rgbe"));
        assert_eq!(h.exposure(), 3.0);
        assert_eq!(h.pixel_aspect(), 0.5);
        assert_eq!(h.color_correction(), Some([1.0, 2.0, 3.0]));
        assert_eq!(h.primaries().unwrap()[0], 0.64);
        assert_eq!(h.view().as_deref(), Some("-vtv -vp 0 0 0"));
        assert_eq!(h.commands().collect::<Vec<_>>(), ["rpict -x 4"]);
    }

    #[test]
    fn bad_headers_are_errors() {
        assert!(Header::parse(b"").is_err());
        assert!(Header::parse(b"\x01\x02\n\n").is_err());
        assert!(Header::parse(b"#?RADIANCE\nno end").is_err());
        let (h, end) = Header::parse(b"#?RADIANCE\r\n\r\nrest").unwrap();
        assert_eq!((h.lines.len(), end), (1, 14));
    }

    #[test]
    fn long_lines_come_in_pieces() {
        let mut data = b"#?RADIANCE\n".to_vec();
        data.extend(std::iter::repeat_n(b'a', 3000));
        data.extend_from_slice(b"\n\n");
        let (h, _) = Header::parse(&data).unwrap();
        assert_eq!(h.lines.len(), 3);
        assert_eq!(h.lines[1].0.len(), MAX_PIECE);
    }
}
