//! The resolution line (`src/common/resolu.c`, `resolu.h`): how the stored scanlines
//! lie in the picture. The picture's own frame has its origin at the lower left, x to
//! the right and y up; the line says whether scanlines run along x or y (`YMAJOR`: the
//! Y word comes first) and whether each coordinate decreases along the file.

use radc_lang::c_number::atoi;

/// Bit flags of `resolu.h`: `XDECR`, `YDECR`, `YMAJOR`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Orientation(pub u8);

impl Orientation {
    pub const XDECR: u8 = 1;
    pub const YDECR: u8 = 2;
    pub const YMAJOR: u8 = 4;
    /// `-Y N +X M`: scanlines left to right, top scanline first (English reading order).
    pub const STANDARD: Orientation = Orientation(Self::YMAJOR | Self::YDECR);

    pub fn x_decreasing(self) -> bool {
        self.0 & Self::XDECR != 0
    }
    pub fn y_decreasing(self) -> bool {
        self.0 & Self::YDECR != 0
    }
    pub fn y_major(self) -> bool {
        self.0 & Self::YMAJOR != 0
    }
}

/// A picture's resolution: `x` by `y` pixels in its own frame, stored as `orientation`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Resolution {
    pub orientation: Orientation,
    pub x: u32,
    pub y: u32,
}

/// `fgetsresolu` reads the line with `fgets` into a 32-byte buffer: at most 31 bytes.
pub const LINE_MAX: usize = 31;

impl Resolution {
    /// A standard (`-Y y +X x`) resolution.
    pub fn standard(x: u32, y: u32) -> Resolution {
        Resolution {
            orientation: Orientation::STANDARD,
            x,
            y,
        }
    }

    /// Parses the line at the start of `data` as `fgetsresolu` does, returning the
    /// resolution and how many bytes the line took (up to its newline, or 31 bytes).
    /// As `str2resolu`: the last `X` and `Y` in the line give the order and the signs
    /// before them; the numbers after them must be positive.
    pub fn parse(data: &[u8]) -> Option<(Resolution, usize)> {
        let take = data.len().min(LINE_MAX);
        let len = match data[..take].iter().position(|&b| b == b'\n') {
            Some(nl) => nl + 1,
            None => take,
        };
        if len == 0 {
            return None;
        }
        // fgets stops at a NUL too, as far as str2resolu can see.
        let line = &data[..len];
        let seen = line.iter().position(|&b| b == 0).unwrap_or(len);
        let line = &line[..seen];
        let xi = line.iter().rposition(|&b| b == b'X')?;
        let yi = line.iter().rposition(|&b| b == b'Y')?;
        let mut o = 0;
        if xi > yi {
            o |= Orientation::YMAJOR;
        }
        if xi > 0 && line[xi - 1] == b'-' {
            o |= Orientation::XDECR;
        }
        if yi > 0 && line[yi - 1] == b'-' {
            o |= Orientation::YDECR;
        }
        let x = i64::from(atoi(&line[xi + 1..]));
        let y = i64::from(atoi(&line[yi + 1..]));
        if x <= 0 || y <= 0 {
            return None;
        }
        Some((
            Resolution {
                orientation: Orientation(o),
                x: x as u32,
                y: y as u32,
            },
            len,
        ))
    }

    /// The line as `resolu2str` writes it (`%8d` numbers), with its newline.
    pub fn line(&self) -> String {
        let sign = |dec: bool| if dec { '-' } else { '+' };
        let o = self.orientation;
        if o.y_major() {
            format!(
                "{}Y {:8} {}X {:8}\n",
                sign(o.y_decreasing()),
                self.y,
                sign(o.x_decreasing()),
                self.x
            )
        } else {
            format!(
                "{}X {:8} {}Y {:8}\n",
                sign(o.x_decreasing()),
                self.x,
                sign(o.y_decreasing()),
                self.y
            )
        }
    }

    /// Pixels per scanline (`scanlen`).
    pub fn scan_length(&self) -> u32 {
        if self.orientation.y_major() {
            self.x
        } else {
            self.y
        }
    }

    /// Scanlines (`numscans`).
    pub fn scan_count(&self) -> u32 {
        if self.orientation.y_major() {
            self.y
        } else {
            self.x
        }
    }

    /// Where pixel `p` of scanline `s` (file order) lies in the picture's frame: column
    /// `x` from the left and row `y` from the bottom (`pix2loc` before its scaling).
    pub fn frame_position(&self, s: u32, p: u32) -> (u32, u32) {
        let o = self.orientation;
        let (mut x, mut y) = if o.y_major() { (p, s) } else { (s, p) };
        if o.x_decreasing() {
            x = self.x - 1 - x;
        }
        if o.y_decreasing() {
            y = self.y - 1 - y;
        }
        (x, y)
    }

    /// The inverse of [`Resolution::frame_position`]: scanline and position of the
    /// pixel at column `x`, row `y` from the bottom.
    pub fn file_position(&self, x: u32, y: u32) -> (u32, u32) {
        let o = self.orientation;
        let x = if o.x_decreasing() { self.x - 1 - x } else { x };
        let y = if o.y_decreasing() { self.y - 1 - y } else { y };
        if o.y_major() { (y, x) } else { (x, y) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_eight_orientations_parse_and_print() {
        for line in [
            "-Y 3 +X 5\n",
            "-Y 3 -X 5\n",
            "+Y 3 +X 5\n",
            "+Y 3 -X 5\n",
            "+X 5 +Y 3\n",
            "-X 5 +Y 3\n",
            "+X 5 -Y 3\n",
            "-X 5 -Y 3\n",
        ] {
            let (r, n) = Resolution::parse(line.as_bytes()).unwrap();
            assert_eq!((r.x, r.y, n), (5, 3, line.len()), "{line}");
            let printed = r.line();
            let (back, _) = Resolution::parse(printed.as_bytes()).unwrap();
            assert_eq!(back, r);
            let words: Vec<&str> = printed.split_whitespace().collect();
            assert_eq!(words.join(" "), line.trim());
        }
        assert_eq!(
            Resolution::standard(5, 3).line(),
            "-Y        3 +X        5\n"
        );
    }

    #[test]
    fn frame_positions_invert() {
        for o in 0..8 {
            let r = Resolution {
                orientation: Orientation(o),
                x: 4,
                y: 3,
            };
            for s in 0..r.scan_count() {
                for p in 0..r.scan_length() {
                    let (x, y) = r.frame_position(s, p);
                    assert!(x < 4 && y < 3);
                    assert_eq!(r.file_position(x, y), (s, p));
                }
            }
        }
    }

    #[test]
    fn bad_lines_are_refused() {
        for bad in [
            "",
            "\n",
            "-Y 0 +X 5\n",
            "-Y 3 +Z 5\n",
            "-Y -3 +X 5\n",
            "hello\n",
        ] {
            assert!(Resolution::parse(bad.as_bytes()).is_none(), "{bad:?}");
        }
        // Only 31 bytes are looked at.
        let long = format!("-Y 3 {}+X 5\n", " ".repeat(40));
        assert!(Resolution::parse(long.as_bytes()).is_none());
    }
}
