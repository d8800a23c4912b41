//! Source positions: byte spans and the line/column view of them that people read.

use std::ops::Range;

/// Which file a span belongs to. The CLI and the database hand these out; `lang`
/// only carries them so a diagnostic can point into a file other than the one being
/// checked (for example a `.cal` file named by a scene).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(pub u32);

/// A half-open byte range `start..end` in one file's text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    pub file: FileId,
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub fn new(file: FileId, range: Range<usize>) -> Self {
        Span {
            file,
            start: clamp_u32(range.start),
            end: clamp_u32(range.end.max(range.start)),
        }
    }

    pub fn range(&self) -> Range<usize> {
        self.start as usize..self.end as usize
    }

    /// The smallest span covering both (same file assumed).
    pub fn to(&self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    pub fn len(&self) -> usize {
        (self.end - self.start) as usize
    }

    pub fn is_empty(&self) -> bool {
        self.start == self.end
    }
}

/// Files over 4 GiB are not supported: spans saturate rather than wrap.
fn clamp_u32(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
}

/// Maps byte offsets to 1-based line and column numbers (columns count characters,
/// as editors and `file:line:col` readers expect).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineIndex {
    line_starts: Vec<usize>,
}

impl LineIndex {
    pub fn new(text: &str) -> Self {
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { line_starts }
    }

    /// Updates the index after an edit: bytes `start..old_end` of the text it was
    /// built from are now bytes `start..new_end` of `text`. The lines before the edit
    /// are kept and those after it shifted, so the cost is one pass over the line
    /// starts, not over the text. The result is exactly `LineIndex::new(text)`.
    pub fn edit(&mut self, text: &str, start: usize, old_end: usize, new_end: usize) {
        let Some(inserted) = text.as_bytes().get(start..new_end) else {
            *self = LineIndex::new(text);
            return;
        };
        // A line starts after each newline: those of the old bytes start in
        // `start + 1..=old_end`.
        let from = self.line_starts.partition_point(|&s| s <= start);
        let to = self
            .line_starts
            .partition_point(|&s| s <= old_end)
            .max(from);
        let delta = new_end as isize - old_end as isize;
        for s in &mut self.line_starts[to..] {
            *s = s.wrapping_add_signed(delta);
        }
        let new = inserted
            .iter()
            .enumerate()
            .filter(|&(_, &b)| b == b'\n')
            .map(|(i, _)| start + i + 1);
        self.line_starts.splice(from..to, new);
    }

    /// 0-based line containing `offset`.
    pub fn line_of(&self, offset: usize) -> usize {
        match self.line_starts.binary_search(&offset) {
            Ok(l) => l,
            Err(l) => l - 1,
        }
    }

    pub fn line_start(&self, line: usize) -> usize {
        self.line_starts.get(line).copied().unwrap_or(0)
    }

    /// 1-based (line, column) of a byte offset; the column counts characters.
    pub fn line_col(&self, text: &str, offset: usize) -> (usize, usize) {
        let offset = offset.min(text.len());
        let line = self.line_of(offset);
        let start = self.line_start(line);
        let col = text
            .get(start..offset)
            .map(|s| s.chars().count())
            .unwrap_or(offset - start);
        (line + 1, col + 1)
    }

    /// 0-based (line, UTF-16 column) as the Language Server Protocol counts them.
    pub fn line_utf16(&self, text: &str, offset: usize) -> (u32, u32) {
        let offset = offset.min(text.len());
        let line = self.line_of(offset);
        let start = self.line_start(line);
        let col: usize = text
            .get(start..offset)
            .map(|s| s.chars().map(char::len_utf16).sum())
            .unwrap_or(offset - start);
        (line as u32, col as u32)
    }

    pub fn line_count(&self) -> usize {
        self.line_starts.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_characters_from_one() {
        let text = "ab\ncé d\n";
        let idx = LineIndex::new(text);
        assert_eq!(idx.line_col(text, 0), (1, 1));
        assert_eq!(idx.line_col(text, 3), (2, 1));
        // 'd' sits after a two-byte 'é': byte 7, character column 4.
        assert_eq!(idx.line_col(text, 7), (2, 4));
        assert_eq!(idx.line_col(text, text.len()), (3, 1));
    }

    #[test]
    fn an_edited_index_is_the_index_of_the_new_text() {
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: usize| {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng % n as u64) as usize
        };
        let pieces = ["", "a", "\n", "\r\n", "ab\ncd", "\n\n", "é\n"];
        let mut text = String::from("one\ntwo\n\nthree");
        let mut index = LineIndex::new(&text);
        for _ in 0..2000 {
            let start = next(text.len() + 1);
            let end = (start + next(6)).min(text.len());
            if !text.is_char_boundary(start) || !text.is_char_boundary(end) {
                continue;
            }
            let new = pieces[next(pieces.len())];
            text.replace_range(start..end, new);
            index.edit(&text, start, end, start + new.len());
            assert_eq!(index, LineIndex::new(&text), "{text:?}");
        }
    }

    #[test]
    fn utf16_columns_for_the_lsp() {
        let text = "😀x";
        let idx = LineIndex::new(text);
        assert_eq!(idx.line_utf16(text, 4), (0, 2));
    }
}

/// Turns file bytes into text without moving any byte offset: invalid UTF-8 bytes
/// become `?`, and invalid bytes and NULs are each reported once at their first
/// occurrence. Radiance reads bytes, so an old Latin-1 comment is no reason to reject
/// a scene; a NUL ends the C string of the word it sits in (see `lexer::unquote`).
pub fn decode(file: FileId, bytes: &[u8]) -> (String, Vec<crate::Diagnostic>) {
    use crate::diagnostic::{self as codes, Diagnostic};
    let mut diags = Vec::new();
    let mut text = String::with_capacity(bytes.len());
    let mut rest = bytes;
    let mut offset = 0;
    let mut first_invalid = None;
    loop {
        match std::str::from_utf8(rest) {
            Ok(s) => {
                text.push_str(s);
                break;
            }
            Err(e) => {
                let good = e.valid_up_to();
                text.push_str(std::str::from_utf8(&rest[..good]).unwrap_or_default());
                let bad = e.error_len().unwrap_or(rest.len() - good);
                first_invalid.get_or_insert(offset + good);
                text.extend(std::iter::repeat_n('?', bad));
                offset += good + bad;
                rest = &rest[good + bad..];
            }
        }
    }
    if let Some(at) = first_invalid {
        diags.push(
            Diagnostic::new(
                codes::W0101,
                Span::new(file, at..at + 1),
                "the file is not valid UTF-8; invalid bytes are read as '?'",
            )
            .with_hint("save the file as UTF-8 (names with non-ASCII bytes may not match)"),
        );
    }
    if let Some(at) = text.find('\0') {
        diags.push(
            Diagnostic::new(codes::W0103, Span::new(file, at..at + 1), "the file contains a NUL byte")
                .with_hint("Radiance stops reading a word at a NUL and skips the rest of it; remove it (is this a binary file?)"),
        );
    }
    (text, diags)
}

/// [`decode`] for bytes the caller owns: a clean file (valid UTF-8, no NUL) becomes
/// the text without being copied, which halves the memory for a big scene.
pub fn decode_owned(file: FileId, bytes: Vec<u8>) -> (String, Vec<crate::Diagnostic>) {
    if bytes.contains(&0) {
        return decode(file, &bytes);
    }
    match String::from_utf8(bytes) {
        Ok(text) => (text, Vec::new()),
        Err(e) => decode(file, e.as_bytes()),
    }
}

#[cfg(test)]
mod decode_tests {
    use super::*;

    #[test]
    fn keeps_byte_offsets() {
        let (text, diags) = decode(FileId(0), b"ab\xff\xfecd\0e");
        assert_eq!(text, "ab??cd\0e");
        let ids: Vec<_> = diags.iter().map(|d| d.code.id).collect();
        assert_eq!(ids, vec!["W0101", "W0103"]);
        assert_eq!(diags[0].span.range(), 2..3);
        assert_eq!(
            decode_owned(FileId(0), b"ab\xff\xfecd\0e".to_vec()),
            (text, diags)
        );
        assert_eq!(
            decode_owned(FileId(0), b"ok".to_vec()),
            ("ok".to_string(), vec![])
        );
    }
}
