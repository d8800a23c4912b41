//! A whole picture in memory: its header, its resolution and its pixels as stored.

use std::io::{self, Write};

use crate::color::{self, Colr};
use crate::error::{ErrorKind, PictureError};
use crate::header::Header;
use crate::resolution::Resolution;
use crate::scanline::{self, ScanlineError};

/// What the pixels hold (`FORMAT=`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `32-bit_rle_rgbe`, also assumed when the header names no format (as Radiance's
    /// readers assume it).
    Rgbe,
    /// `32-bit_rle_xyze`: CIE XYZ.
    Xyze,
}

impl Format {
    pub const RGBE: &'static str = "32-bit_rle_rgbe";
    pub const XYZE: &'static str = "32-bit_rle_xyze";

    pub fn name(self) -> &'static str {
        match self {
            Format::Rgbe => Self::RGBE,
            Format::Xyze => Self::XYZE,
        }
    }
}

/// Pictures larger than this many pixels are refused by [`Picture::read`] (1 GiB of
/// RGBE): a damaged resolution line must not make the reader allocate without bound.
pub const DEFAULT_MAX_PIXELS: u64 = 1 << 28;

/// A Radiance picture: the header as read (every line, in order), the resolution and
/// the pixels in file order (scanline after scanline), exactly as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    pub header: Header,
    pub resolution: Resolution,
    /// `FORMAT=` as the header gives it (`None`: no format line).
    pub format_name: Option<String>,
    pub pixels: Vec<Colr>,
}

impl Picture {
    /// Reads a picture, accepting any header a Radiance picture reader accepts (format
    /// `32-bit_rle_???e` or none), any orientation and all three scanline encodings.
    pub fn read(data: &[u8]) -> Result<Picture, PictureError> {
        Self::read_with_limit(data, DEFAULT_MAX_PIXELS)
    }

    /// [`Picture::read`] refusing pictures of more than `max_pixels` pixels.
    pub fn read_with_limit(data: &[u8], max_pixels: u64) -> Result<Picture, PictureError> {
        Self::read_prefix(data, max_pixels).map(|(p, _)| p)
    }

    /// Reads the picture at the start of `data`, which may go on (a stream of pictures,
    /// as `ra_rgbe` reads): the picture and the number of bytes it took.
    pub fn read_prefix(data: &[u8], max_pixels: u64) -> Result<(Picture, usize), PictureError> {
        let (header, mut pos) = Header::parse(data)?;
        let format_name = header.format();
        if let Some(f) = &format_name
            && !is_picture_format(f)
        {
            return Err(PictureError::new(ErrorKind::WrongFormat(f.clone()), 0));
        }
        let (resolution, used) = Resolution::parse(&data[pos..])
            .ok_or(PictureError::new(ErrorKind::BadResolution, pos))?;
        pos += used;
        let (len, scans) = (resolution.scan_length(), resolution.scan_count());
        if u64::from(len) * u64::from(scans) > max_pixels {
            return Err(PictureError::new(
                ErrorKind::TooLarge {
                    width: resolution.x,
                    height: resolution.y,
                },
                pos - used,
            ));
        }
        // Grown scanline by scanline: a short file never allocates the whole picture.
        let mut pixels = Vec::new();
        for s in 0..scans {
            scanline::read(data, &mut pos, len as usize, &mut pixels).map_err(|e| match e {
                ScanlineError::Truncated(at) => {
                    PictureError::new(ErrorKind::Truncated { scanline: s }, at)
                }
                ScanlineError::Length { found, at } => {
                    PictureError::new(ErrorKind::ScanlineLength { scanline: s, found }, at)
                }
            })?;
        }
        Ok((
            Picture {
                header,
                resolution,
                format_name,
                pixels,
            },
            pos,
        ))
    }

    /// A new picture in standard orientation from pixels given top row first.
    pub fn new(header: Header, width: u32, height: u32, pixels: Vec<Colr>) -> Picture {
        let format_name = header.format();
        Picture {
            header,
            resolution: Resolution::standard(width, height),
            format_name,
            pixels,
        }
    }

    /// True for the formats a picture may have (`32-bit_rle_???e`, `PICFMT`).
    pub fn is_format(format: &str) -> bool {
        is_picture_format(format)
    }

    /// RGBE or XYZE (RGBE when the header names none; any other `???e` counts as RGBE).
    pub fn format(&self) -> Format {
        match self.format_name.as_deref() {
            Some(Format::XYZE) => Format::Xyze,
            _ => Format::Rgbe,
        }
    }

    /// Width and height in the picture's own frame.
    pub fn width(&self) -> u32 {
        self.resolution.x
    }
    pub fn height(&self) -> u32 {
        self.resolution.y
    }

    /// The pixel at column `x` from the left and row `y` from the top, whatever the
    /// file's orientation; `None` outside the picture.
    pub fn get(&self, x: u32, y: u32) -> Option<Colr> {
        let r = &self.resolution;
        if x >= r.x || y >= r.y {
            return None;
        }
        let (s, p) = r.file_position(x, r.y - 1 - y);
        let i = s as usize * r.scan_length() as usize + p as usize;
        self.pixels.get(i).copied()
    }

    /// Scanline `s` in file order.
    pub fn scanline(&self, s: u32) -> &[Colr] {
        let len = self.resolution.scan_length() as usize;
        let start = (s as usize * len).min(self.pixels.len());
        &self.pixels[start..(start + len).min(self.pixels.len())]
    }

    /// The pixels top row first, left to right (the order of `-Y N +X M`).
    pub fn standard_pixels(&self) -> Vec<Colr> {
        let (w, h) = (self.width(), self.height());
        let mut out = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            for x in 0..w {
                out.push(self.get(x, y).unwrap_or([0; 4]));
            }
        }
        out
    }

    /// Writes the picture as Radiance does: the header lines, an empty line, the
    /// resolution line and every scanline as `fwritecolrs` encodes it.
    pub fn write(&self, out: &mut impl Write) -> io::Result<()> {
        out.write_all(&self.header.to_bytes())?;
        out.write_all(b"\n")?;
        out.write_all(self.resolution.line().as_bytes())?;
        self.write_pixels(out)
    }

    /// Only the scanlines.
    pub fn write_pixels(&self, out: &mut impl Write) -> io::Result<()> {
        let mut buf = Vec::new();
        for s in 0..self.resolution.scan_count() {
            buf.clear();
            scanline::write(self.scanline(s), &mut buf);
            out.write_all(&buf)?;
        }
        Ok(())
    }
}

/// `globmatch("32-bit_rle_???e", f)`, the test `checkheader` makes for pictures.
fn is_picture_format(f: &str) -> bool {
    let b = f.as_bytes();
    b.len() == 15 && b.starts_with(b"32-bit_rle_") && b[14] == b'e'
}

/// Writes a new RGBE picture in standard orientation: `#?RADIANCE`, `header` lines, the
/// format line, the resolution, then `width` by `height` colours given top row first,
/// each encoded by [`color::encode`] (rpict's output, from `f64` colours).
pub fn write_rgb(
    out: &mut impl Write,
    header: &[String],
    width: u32,
    height: u32,
    pixels: &[[f64; 3]],
) -> io::Result<()> {
    let header = Header::new_picture(header, Format::RGBE);
    out.write_all(&header.to_bytes())?;
    out.write_all(b"\n")?;
    out.write_all(Resolution::standard(width, height).line().as_bytes())?;
    let mut scan = Vec::with_capacity(width as usize);
    let mut buf = Vec::new();
    for row in pixels.chunks(width.max(1) as usize).take(height as usize) {
        scan.clear();
        scan.extend(row.iter().map(|c| color::encode(c[0], c[1], c[2])));
        buf.clear();
        scanline::write(&scan, &mut buf);
        out.write_all(&buf)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::resolution::Orientation;

    fn sample(w: u32, h: u32) -> Vec<[f64; 3]> {
        (0..w * h)
            .map(|i| {
                let x = f64::from(i % w);
                if x < 10.0 {
                    [0.5; 3]
                } else {
                    [x / 300.0, 0.1, (x % 7.0) / 7.0]
                }
            })
            .collect()
    }

    #[test]
    fn written_pictures_read_back() {
        for w in [1, 16, 17, 300] {
            let px = sample(w, 3);
            let mut out = Vec::new();
            write_rgb(&mut out, &["SOFTWARE= test".into()], w, 3, &px).unwrap();
            let p = Picture::read(&out).unwrap();
            assert_eq!((p.width(), p.height(), p.format()), (w, 3, Format::Rgbe));
            let want: Vec<Colr> = px.iter().map(|c| color::encode(c[0], c[1], c[2])).collect();
            assert_eq!(p.pixels, want);
            let mut again = Vec::new();
            p.write(&mut again).unwrap();
            assert_eq!(again, out, "width {w}: byte for byte");
        }
    }

    #[test]
    fn orientation_does_not_change_what_get_sees() {
        let (w, h) = (3u32, 2u32);
        let std: Vec<Colr> = (0..w * h).map(|i| [i as u8 + 1, 0, 0, 130]).collect();
        let base = Picture::new(Header::new_picture(&[], Format::RGBE), w, h, std.clone());
        for o in 0..8 {
            let res = Resolution {
                orientation: Orientation(o),
                x: w,
                y: h,
            };
            // Store the same image in orientation o.
            let mut pixels = vec![[0; 4]; (w * h) as usize];
            for s in 0..res.scan_count() {
                for p in 0..res.scan_length() {
                    let (x, y) = res.frame_position(s, p);
                    pixels[(s * res.scan_length() + p) as usize] = base.get(x, h - 1 - y).unwrap();
                }
            }
            let pic = Picture {
                resolution: res,
                pixels,
                ..base.clone()
            };
            assert_eq!(pic.standard_pixels(), std, "orientation {o}");
            let mut bytes = Vec::new();
            pic.write(&mut bytes).unwrap();
            assert_eq!(Picture::read(&bytes).unwrap(), pic);
        }
    }

    #[test]
    fn bad_pictures_are_errors_with_offsets() {
        let mut good = Vec::new();
        write_rgb(&mut good, &[], 20, 2, &sample(20, 2)).unwrap();
        let kind = |d: &[u8]| Picture::read(d).map(|_| ()).map_err(|e| e.kind);
        assert_eq!(kind(b"\x00\x01"), Err(ErrorKind::BadHeader));
        assert_eq!(
            kind(b"#?RADIANCE\nFORMAT=ascii\n\n-Y 1 +X 1\n"),
            Err(ErrorKind::WrongFormat("ascii".into()))
        );
        assert_eq!(
            kind(b"#?RADIANCE\n\n-Y 0 +X 1\n"),
            Err(ErrorKind::BadResolution)
        );
        assert_eq!(
            kind(b"#?RADIANCE\n\n-Y 100000 +X 100000\n"),
            Err(ErrorKind::TooLarge {
                width: 100000,
                height: 100000
            })
        );
        let cut = &good[..good.len() - 5];
        let e = Picture::read(cut).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Truncated { scanline: 1 });
        assert!(e.to_string().contains("truncated"), "{e}");
        // No format line: taken as RGBE.
        assert!(Picture::read(b"#?RADIANCE\n\n-Y 1 +X 1\n\x80\x80\x80\x81").is_ok());
    }
}
