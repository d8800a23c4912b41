//! What a file named as a scene is, from its first bytes: scene text, a compiled scene
//! or a scene bundle (`radc build`), a Radiance octree (oconv) or a Radiance picture, so each is loaded or
//! refused by name instead of read as text.

use std::io::Read;
use std::path::Path;

use radc_renderer::scene_file;

/// What a scene argument is, from its first bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Compiled,
    /// A scene's texts as `radc build` stored them ([`crate::bundle`]).
    Bundle,
    Octree,
    Picture,
    Text,
}

/// What a file is when it is a Radiance picture: "a Radiance picture (W by H, FORMAT)",
/// read from its header and resolution line (in its first 4 KiB); `None` otherwise.
pub fn picture_description(path: &Path) -> Option<String> {
    let mut head = [0u8; 4096];
    let n = std::fs::File::open(path)
        .and_then(|mut f| read_up_to(&mut f, &mut head))
        .ok()?;
    describe_picture(&head[..n])
}

fn describe_picture(head: &[u8]) -> Option<String> {
    // Radiance's pictures start with the magic line; a scene that opens with comments
    // and an empty line must not be taken for a header.
    if !head.starts_with(b"#?") {
        return None;
    }
    let (header, end) = radc_picture::Header::parse(head).ok()?;
    let format = header.format();
    if format
        .as_deref()
        .is_some_and(|f| !radc_picture::Picture::is_format(f))
    {
        return None;
    }
    let (res, _) = radc_picture::Resolution::parse(&head[end..])?;
    let format = format.unwrap_or_else(|| radc_picture::Format::RGBE.into());
    Some(format!(
        "a Radiance picture ({} by {} pixels, {format})",
        res.x, res.y
    ))
}

pub fn file_kind(path: &Path) -> Kind {
    let mut head = [0u8; 4096];
    let n = std::fs::File::open(path)
        .and_then(|mut f| read_up_to(&mut f, &mut head))
        .unwrap_or(0);
    let head = &head[..n];
    let text = String::from_utf8_lossy(head);
    if crate::bundle::looks_bundled(head) {
        Kind::Bundle
    } else if scene_file::looks_compiled(head) || path.extension().is_some_and(|e| e == "rsc") {
        Kind::Compiled
    } else if text.starts_with("#?RADIANCE") && text.contains("FORMAT=Radiance_octree") {
        Kind::Octree
    } else if describe_picture(head).is_some() {
        Kind::Picture
    } else {
        Kind::Text
    }
}

fn read_up_to(f: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match f.read(&mut buf[n..])? {
            0 => break,
            k => n += k,
        }
    }
    Ok(n)
}
