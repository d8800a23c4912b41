//! Views as rpict takes them (`-vt -vp -vd -vu -vh -vv`, `src/common/image.c`):
//! perspective and parallel projections, image coordinates `(x, y)` in `[0, 1]` with
//! `y` up.

use crate::math::{FTINY, Vec3, normalize};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    /// `-vtv`: sizes are full angles in degrees.
    Perspective,
    /// `-vtl`: sizes are world widths.
    Parallel,
}

/// A view as given on the command line.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    pub projection: Projection,
    pub position: Vec3,
    pub direction: Vec3,
    pub up: Vec3,
    pub horizontal: f64,
    pub vertical: f64,
}

impl Default for View {
    /// rpict's default view.
    fn default() -> View {
        View {
            projection: Projection::Perspective,
            position: Vec3::ZERO,
            direction: Vec3::Y,
            up: Vec3::Z,
            horizontal: 45.0,
            vertical: 45.0,
        }
    }
}

/// A view ready to make rays: unit direction and image-plane vectors spanning the
/// picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    view: View,
    dir: Vec3,
    hvec: Vec3,
    vvec: Vec3,
}

impl View {
    /// Checks the view as rpict's `setview` does; the error says what is wrong.
    pub fn camera(&self) -> Result<Camera, &'static str> {
        let mut dir = self.direction;
        if normalize(&mut dir) == 0.0 {
            return Err("zero view direction");
        }
        let mut up = self.up;
        if normalize(&mut up) == 0.0 {
            return Err("zero view up vector");
        }
        let mut hvec = dir.cross(up);
        if normalize(&mut hvec) == 0.0 {
            return Err("view up parallel to view direction");
        }
        let vvec = hvec.cross(dir);
        if self.horizontal <= FTINY {
            return Err("illegal horizontal view size");
        }
        if self.vertical <= FTINY {
            return Err("illegal vertical view size");
        }
        let (hn, vn) = match self.projection {
            Projection::Parallel => (self.horizontal, self.vertical),
            Projection::Perspective => {
                if self.horizontal >= 180.0 - FTINY {
                    return Err("illegal horizontal view size");
                }
                if self.vertical >= 180.0 - FTINY {
                    return Err("illegal vertical view size");
                }
                let half = |deg: f64| 2.0 * (deg * (std::f64::consts::PI / 360.0)).tan();
                (half(self.horizontal), half(self.vertical))
            }
        };
        Ok(Camera {
            view: self.clone(),
            dir,
            hvec: hvec * hn,
            vvec: vvec * vn,
        })
    }

    /// The `VIEW=` header value.
    pub fn header(&self) -> String {
        let t = match self.projection {
            Projection::Perspective => 'v',
            Projection::Parallel => 'l',
        };
        let v = |a: Vec3| format!("{} {} {}", a.x, a.y, a.z);
        format!(
            "-vt{t} -vp {} -vd {} -vu {} -vh {} -vv {} -vo 0 -va 0 -vs 0 -vl 0",
            v(self.position),
            v(self.direction),
            v(self.up),
            self.horizontal,
            self.vertical
        )
    }
}

impl Camera {
    /// Height over width of the image plane (`viewaspect`).
    pub fn aspect(&self) -> f64 {
        self.vvec.length() / self.hvec.length()
    }

    /// The ray through image point `(x, y)` (`viewray`): origin and unit direction.
    pub fn ray(&self, x: f64, y: f64) -> (Vec3, Vec3) {
        let (x, y) = (x - 0.5, y - 0.5);
        match self.view.projection {
            Projection::Perspective => {
                let mut d = self.dir + self.hvec * x + self.vvec * y;
                normalize(&mut d);
                (self.view.position, d)
            }
            Projection::Parallel => (self.view.position + self.hvec * x + self.vvec * y, self.dir),
        }
    }

    /// Fits `x` by `y` pixels to the view with square pixels, shrinking one of them as
    /// rpict does (`normaspect` with `-pa 1`).
    pub fn fit_resolution(&self, x: u32, y: u32, pixel_aspect: f64) -> (u32, u32) {
        let va = self.aspect();
        let (xf, yf) = (f64::from(x), f64::from(y));
        if pixel_aspect <= FTINY {
            (x, y)
        } else if va * xf > pixel_aspect * yf {
            (((yf / va * pixel_aspect) + 0.5) as u32, y)
        } else {
            (x, ((xf * va / pixel_aspect) + 0.5) as u32)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_is_the_view_direction() {
        let c = View::default().camera().unwrap();
        let (o, d) = c.ray(0.5, 0.5);
        assert_eq!(o, Vec3::ZERO);
        assert!((d - Vec3::Y).length() < 1e-12);
        // The right edge is 22.5 degrees off for a 45 degree view.
        let (_, d) = c.ray(1.0, 0.5);
        assert!((d.dot(Vec3::Y) - 22.5f64.to_radians().cos()).abs() < 1e-12);
        assert!(d.x > 0.0);
    }

    #[test]
    fn resolution_follows_aspect() {
        let v = View {
            vertical: 2.0 * (0.5f64.atan()).to_degrees(),
            horizontal: 90.0,
            ..View::default()
        };
        let c = v.camera().unwrap();
        assert_eq!(c.fit_resolution(512, 512, 1.0), (512, 256));
    }

    #[test]
    fn bad_views_are_refused() {
        let v = View {
            up: Vec3::Y,
            ..View::default()
        };
        assert!(v.camera().is_err());
    }
}
