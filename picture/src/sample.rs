//! A picture as a `colorpict` pattern sees it (`src/common/data.c`: `getpict`,
//! `data_interp`; `src/rt/p_data.c`: `p_pdata`).
//!
//! The picture becomes a two-dimensional array in its own frame, origin at the lower
//! left. Its smaller dimension spans 1 and the other the ratio of the two (ray.1: a
//! 500x338 picture covers (0,0) to (1.48,1)), the dimensions measured with the pixel
//! aspect ratio (`PIXASPECT=`, height over width of a pixel, cumulative). Pixels are
//! grid points, the first at 0 and the last at the far edge, interpolated linearly;
//! beyond the grid values extrapolate for one division and then taper to zero as
//! `data_interp` does. Only RGBE pictures may be used (`headaspect` refuses others).

use crate::color::{Colr, exponent_scale};
use crate::error::{ErrorKind, PictureError};
use crate::picture::{Format, Picture};

/// Radiance's `FTINY`.
const FTINY: f64 = 1e-6;

/// A picture loaded for `colorpict`: rows from the bottom up.
#[derive(Debug, Clone)]
pub struct ColorPicture {
    width: usize,
    height: usize,
    /// The extent of u (across) and v (up): one of them is 1.
    extent: (f64, f64),
    /// Row `y` (from the bottom), column `x` at `y * width + x`.
    pixels: Vec<Colr>,
}

impl ColorPicture {
    /// The pattern's view of `picture`; an XYZE picture or a pixel aspect ratio at or
    /// below `FTINY` is refused, as `getpict` reports "bad picture file".
    pub fn new(picture: &Picture) -> Result<ColorPicture, PictureError> {
        // headaspect: any format line other than RGBE's makes the picture unusable.
        if let Some(f) = picture
            .format_name
            .as_deref()
            .filter(|f| *f != Format::RGBE)
        {
            let f = f.to_string();
            return Err(PictureError::new(ErrorKind::WrongFormat(f), 0));
        }
        let aspect = picture.header.pixel_aspect();
        if aspect.is_nan() || aspect <= FTINY {
            return Err(PictureError::new(ErrorKind::BadHeader, 0));
        }
        let (w, h) = (picture.width() as usize, picture.height() as usize);
        let (xr, yr) = (w as f64, h as f64);
        let extent = if xr <= yr * aspect {
            (1.0, aspect * yr / xr)
        } else {
            (xr / yr / aspect, 1.0)
        };
        let mut pixels = vec![[0; 4]; w * h];
        for y in 0..h {
            for x in 0..w {
                // get() counts rows from the top.
                pixels[y * w + x] = picture.get(x as u32, (h - 1 - y) as u32).unwrap_or([0; 4]);
            }
        }
        Ok(ColorPicture {
            width: w,
            height: h,
            extent,
            pixels,
        })
    }

    /// The rectangle the picture covers: (0, 0) to this.
    pub fn extent(&self) -> (f64, f64) {
        self.extent
    }

    /// The colour at (u, v) in the picture's frame (u across from the left, v up from
    /// the bottom, as `colorpict`'s two coordinate expressions give them), interpolated
    /// in double precision from the RGBE values as `datavalue` does for each channel.
    pub fn value(&self, u: f64, v: f64) -> [f64; 3] {
        let (ry, rx) = (
            Axis::at(v, self.extent.1, self.height),
            Axis::at(u, self.extent.0, self.width),
        );
        std::array::from_fn(|c| {
            let row = |coef: f64, y: isize| {
                if (-FTINY..=FTINY).contains(&coef) {
                    return 0.0;
                }
                let (c0, c1) = (rx.c0 * coef, rx.c1 * coef);
                let y0 = self.channel(rx.i, y, c) * c0;
                let y1 = self.channel(rx.i + 1, y, c) * c1;
                y0 + y1
            };
            row(ry.c0, ry.i) + row(ry.c1, ry.i + 1)
        })
    }

    /// The same value, with u and v given as fractions of the extent ([0, 1) across
    /// the picture in each direction).
    pub fn value_fraction(&self, fu: f64, fv: f64) -> [f64; 3] {
        self.value(fu * self.extent.0, fv * self.extent.1)
    }

    /// Channel `c` of the pixel at column `x`, row `y`, as `colrval` decodes it. Index
    /// -1 only occurs with a zero coefficient (a one-pixel dimension): any value serves.
    fn channel(&self, x: isize, y: isize, c: usize) -> f64 {
        let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) else {
            return 0.0;
        };
        let Some(p) = self.pixels.get(y * self.width + x) else {
            return 0.0;
        };
        f64::from((f32::from(p[c]) + 0.5) * exponent_scale(p[3]))
    }
}

/// One dimension's grid index and interpolation coefficients (`data_interp`).
struct Axis {
    i: isize,
    c0: f64,
    c1: f64,
}

impl Axis {
    fn at(pt: f64, size: f64, n: usize) -> Axis {
        let x = pt / size * (n as f64 - 1.0);
        // C's conversion truncates toward zero; NaN and huge values are clamped below.
        let mut i = if x.is_nan() {
            0
        } else {
            x.clamp(-1e15, 1e15) as isize
        };
        let top = n as isize - 2;
        if i < 0 {
            i = 0;
        } else if i > top {
            i = top;
        }
        let fi = i as f64;
        // Extrapolate one division, then taper harmonically to zero.
        let (c0, c1) = if x > fi + 2.0 {
            let c0 = 1.0 / (fi - 1.0 - x);
            (c0, -2.0 * c0)
        } else if x < fi - 1.0 {
            let c1 = 1.0 / (x - fi);
            (-2.0 * c1, c1)
        } else {
            (fi + 1.0 - x, x - fi)
        };
        Axis { i, c0, c1 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::header::Header;

    fn picture(w: u32, h: u32, aspect: Option<&str>) -> Picture {
        let lines: Vec<String> = aspect
            .map(|a| format!("PIXASPECT={a}"))
            .into_iter()
            .collect();
        let px = (0..w * h)
            .map(|i| crate::color::encode(f64::from(i % w) + 1.0, f64::from(i / w) + 1.0, 1.0))
            .collect();
        Picture::new(Header::new_picture(&lines, Format::RGBE), w, h, px)
    }

    #[test]
    fn extent_follows_the_manual_and_the_pixel_aspect() {
        let p = ColorPicture::new(&picture(500, 338, None)).unwrap();
        let (u, v) = p.extent();
        assert!((u - 500.0 / 338.0).abs() < 1e-12 && v == 1.0);
        let p = ColorPicture::new(&picture(338, 500, None)).unwrap();
        assert_eq!(p.extent().0, 1.0);
        // Pixels twice as tall as wide: 4 x 3 pixels is 4 wide, 6 tall.
        let p = ColorPicture::new(&picture(4, 3, Some("2"))).unwrap();
        assert_eq!(p.extent(), (1.0, 1.5));
    }

    #[test]
    fn corners_are_pixels_and_between_is_linear() {
        // 3 wide, 2 tall: u in [0, 1.5], v in [0, 1]; red counts columns from 1, green
        // counts rows from the top.
        let p = ColorPicture::new(&picture(3, 2, None)).unwrap();
        let near = |a: f64, b: f64| (a - b).abs() < 0.02 * b.abs().max(1.0);
        let lower_left = p.value(0.0, 0.0);
        assert!(
            near(lower_left[0], 1.0) && near(lower_left[1], 2.0),
            "{lower_left:?}"
        );
        let upper_right = p.value(1.5, 1.0);
        assert!(near(upper_right[0], 3.0) && near(upper_right[1], 1.0));
        let mid = p.value(0.375, 0.5);
        assert!(near(mid[0], 1.5) && near(mid[1], 1.5), "{mid:?}");
        let f = p.value_fraction(0.5, 0.5);
        assert!(near(f[0], 2.0), "{f:?}");
        // Far outside the picture values taper towards zero.
        assert!(p.value(100.0, 0.5)[0].abs() < 1.0);
    }

    #[test]
    fn one_pixel_pictures_are_constant_and_xyz_is_refused() {
        let p = ColorPicture::new(&picture(1, 1, None)).unwrap();
        let v = p.value(0.3, 0.7);
        assert!((v[0] - 1.0).abs() < 0.01, "{v:?}");
        let mut xyz = picture(2, 2, None);
        xyz.format_name = Some(Format::XYZE.into());
        assert!(ColorPicture::new(&xyz).is_err());
        assert!(ColorPicture::new(&picture(2, 2, Some("0"))).is_err());
    }
}
