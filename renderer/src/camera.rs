//! Views as rpict takes them (`-vt -vp -vd -vu -vh -vv -vo -va -vs -vl`,
//! `src/common/image.c`): perspective, parallel, and the fisheye and panoramic
//! projections; image coordinates `(x, y)` in `[0, 1]` with `y` up.

use std::f64::consts::PI;

use crate::math::{FTINY, Vec3, normalize};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    /// `-vtv`: sizes are full angles in degrees.
    Perspective,
    /// `-vtl`: sizes are world widths.
    Parallel,
    /// `-vth`: hemispherical fisheye (sine of the angle).
    Hemispherical,
    /// `-vta`: angular fisheye (angle proportional to radius).
    Angular,
    /// `-vtc`: cylindrical panorama.
    Cylindrical,
    /// `-vts`: planispheric (stereographic) fisheye.
    Planispheric,
}

impl Projection {
    pub fn from_letter(c: char) -> Option<Projection> {
        Some(match c {
            'v' => Projection::Perspective,
            'l' => Projection::Parallel,
            'h' => Projection::Hemispherical,
            'a' => Projection::Angular,
            'c' => Projection::Cylindrical,
            's' => Projection::Planispheric,
            _ => return None,
        })
    }

    fn letter(self) -> char {
        match self {
            Projection::Perspective => 'v',
            Projection::Parallel => 'l',
            Projection::Hemispherical => 'h',
            Projection::Angular => 'a',
            Projection::Cylindrical => 'c',
            Projection::Planispheric => 's',
        }
    }
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
    /// `-vo`, `-va`: fore and aft clipping distances (0: none).
    pub fore: f64,
    pub aft: f64,
    /// `-vs`, `-vl`: image shift and lift, in image widths and heights.
    pub shift: f64,
    pub lift: f64,
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
            fore: 0.0,
            aft: 0.0,
            shift: 0.0,
            lift: 0.0,
        }
    }
}

/// A view ready to make rays (`setview`): unit direction, image-plane vectors scaled as
/// the projection needs them, and the squared image sizes.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    view: View,
    dir: Vec3,
    hvec: Vec3,
    vvec: Vec3,
    hn2: f64,
    vn2: f64,
}

/// A primary ray: origin, unit direction and how far it may go (0: unlimited).
pub type ViewRay = (Vec3, Vec3, f64);

impl View {
    /// Checks the view as rpict's `setview` does; the error says what is wrong.
    pub fn camera(&self) -> Result<Camera, &'static str> {
        const HORIZ: &str = "illegal horizontal view size";
        const VERT: &str = "illegal vertical view size";
        if self.fore < -FTINY || self.aft < -FTINY || (self.aft > FTINY && self.aft <= self.fore) {
            return Err("illegal fore/aft clipping plane");
        }
        let mut dir = self.direction;
        if normalize(&mut dir) == 0.0 {
            return Err("zero view direction");
        }
        let mut up = self.up;
        if normalize(&mut up) == 0.0 {
            return Err("zero view up vector");
        }
        let mut h = dir.cross(up);
        if normalize(&mut h) == 0.0 {
            return Err("view up parallel to view direction");
        }
        let v = h.cross(dir);
        let (hz, vt) = (self.horizontal, self.vertical);
        if hz <= FTINY || !hz.is_finite() {
            return Err(HORIZ);
        }
        if vt <= FTINY || !vt.is_finite() {
            return Err(VERT);
        }
        let half = |deg: f64| deg * (PI / 360.0);
        // Sizes (hn, vn) and whether the image vectors are scaled by them.
        let (hn, vn, scale_h, scale_v) = match self.projection {
            Projection::Parallel => (hz, vt, true, true),
            Projection::Perspective => {
                if hz >= 180.0 - FTINY {
                    return Err(HORIZ);
                }
                if vt >= 180.0 - FTINY {
                    return Err(VERT);
                }
                (2.0 * half(hz).tan(), 2.0 * half(vt).tan(), true, true)
            }
            Projection::Cylindrical => {
                if hz > 360.0 + FTINY {
                    return Err(HORIZ);
                }
                if vt >= 180.0 - FTINY {
                    return Err(VERT);
                }
                (hz * (PI / 180.0), 2.0 * half(vt).tan(), false, true)
            }
            Projection::Angular => {
                if hz > 360.0 + FTINY {
                    return Err(HORIZ);
                }
                if vt > 360.0 + FTINY {
                    return Err(VERT);
                }
                (hz * (PI / 180.0), vt * (PI / 180.0), false, false)
            }
            Projection::Hemispherical => {
                if hz > 180.0 + FTINY {
                    return Err(HORIZ);
                }
                if vt > 180.0 + FTINY {
                    return Err(VERT);
                }
                (2.0 * half(hz).sin(), 2.0 * half(vt).sin(), true, true)
            }
            Projection::Planispheric => {
                if hz >= 360.0 - FTINY {
                    return Err(HORIZ);
                }
                if vt >= 360.0 - FTINY {
                    return Err(VERT);
                }
                let s = |deg: f64| 2.0 * half(deg).sin() / (1.0 + half(deg).cos());
                (s(hz), s(vt), false, false)
            }
        };
        Ok(Camera {
            view: self.clone(),
            dir,
            hvec: if scale_h { h * hn } else { h },
            vvec: if scale_v { v * vn } else { v },
            hn2: hn * hn,
            vn2: vn * vn,
        })
    }

    /// The `VIEW=` header value.
    pub fn header(&self) -> String {
        let v = |a: Vec3| format!("{} {} {}", a.x, a.y, a.z);
        format!(
            "-vt{} -vp {} -vd {} -vu {} -vh {} -vv {} -vo {} -va {} -vs {} -vl {}",
            self.projection.letter(),
            v(self.position),
            v(self.direction),
            v(self.up),
            self.horizontal,
            self.vertical,
            self.fore,
            self.aft,
            self.shift,
            self.lift
        )
    }

    /// Applies one view option (`-vtv`, `-vp x y z`, ...) from `args`, as rpict's
    /// `getviewopt` does; returns how many words it used (0: not a view option).
    pub fn option(&mut self, args: &[&str]) -> Result<usize, String> {
        let Some(&opt) = args.first() else {
            return Ok(0);
        };
        let num = |i: usize| -> Result<f64, String> {
            let w = args.get(i).ok_or_else(|| format!("{opt} needs a value"))?;
            w.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{opt}: '{w}' is not a number"))
        };
        let vec = || -> Result<Vec3, String> { Ok(Vec3::new(num(1)?, num(2)?, num(3)?)) };
        Ok(match opt {
            "-vp" => {
                self.position = vec()?;
                4
            }
            "-vd" => {
                self.direction = vec()?;
                4
            }
            "-vu" => {
                self.up = vec()?;
                4
            }
            "-vh" => {
                self.horizontal = num(1)?;
                2
            }
            "-vv" => {
                self.vertical = num(1)?;
                2
            }
            "-vo" => {
                self.fore = num(1)?;
                2
            }
            "-va" => {
                self.aft = num(1)?;
                2
            }
            "-vs" => {
                self.shift = num(1)?;
                2
            }
            "-vl" => {
                self.lift = num(1)?;
                2
            }
            s if s.len() == 4 && s.starts_with("-vt") => {
                let c = s.chars().nth(3).unwrap_or(' ');
                self.projection =
                    Projection::from_letter(c).ok_or_else(|| format!("unknown view type '{s}'"))?;
                1
            }
            _ => 0,
        })
    }
}

impl Camera {
    pub fn projection(&self) -> Projection {
        self.view.projection
    }

    pub fn position(&self) -> Vec3 {
        self.view.position
    }

    pub fn fore(&self) -> f64 {
        self.view.fore
    }

    /// Height over width of the image (`viewaspect`).
    pub fn aspect(&self) -> f64 {
        (self.vn2 / self.hn2).sqrt()
    }

    /// The ray through image point `(x, y)` (`viewray`), or `None` outside a fisheye's
    /// circle.
    pub fn ray(&self, x: f64, y: f64) -> Option<ViewRay> {
        let v = &self.view;
        let (x, y) = (x + v.shift - 0.5, y + v.lift - 0.5);
        let aft = |d: f64| {
            if v.aft > FTINY {
                (v.aft - v.fore) * d
            } else {
                0.0
            }
        };
        let along = |z: f64, x: f64, y: f64| self.dir * z + self.hvec * x + self.vvec * y;
        match v.projection {
            Projection::Parallel => {
                let org = v.position + self.dir * v.fore + self.hvec * x + self.vvec * y;
                Some((org, self.dir, aft(1.0)))
            }
            Projection::Perspective => {
                let mut d = along(1.0, x, y);
                let org = v.position + d * v.fore;
                let len = normalize(&mut d);
                Some((org, d, aft(len)))
            }
            Projection::Hemispherical => {
                let z = 1.0 - x * x * self.hn2 - y * y * self.vn2;
                if z < 0.0 {
                    return None;
                }
                let d = along(z.sqrt(), x, y);
                Some((v.position + d * v.fore, d, aft(1.0)))
            }
            Projection::Cylindrical => {
                let a = x * v.horizontal * (PI / 180.0);
                let mut d = along(a.cos(), a.sin(), y);
                let org = v.position + d * v.fore;
                let len = normalize(&mut d);
                Some((org, d, aft(len)))
            }
            Projection::Angular => {
                let (mut x, mut y) = (x * v.horizontal / 180.0, y * v.vertical / 180.0);
                let r2 = x * x + y * y;
                if r2 > 1.0 {
                    return None;
                }
                let r = r2.sqrt();
                let z = (PI * r).cos();
                let k = if r <= FTINY {
                    PI
                } else {
                    (1.0 - z * z).sqrt() / r
                };
                x *= k;
                y *= k;
                let d = along(z, x, y);
                Some((v.position + d * v.fore, d, aft(1.0)))
            }
            Projection::Planispheric => {
                let (mut x, mut y) = (x * self.hn2.sqrt(), y * self.vn2.sqrt());
                let r2 = x * x + y * y;
                let z = (1.0 - r2) / (1.0 + r2);
                x *= 1.0 + z;
                y *= 1.0 + z;
                let d = along(z, x, y);
                Some((v.position + d * v.fore, d, aft(1.0)))
            }
        }
    }

    /// Where a world point appears in the image (`viewloc`), or `None` unless it is in
    /// front of the view (and its clipping planes) and strictly inside the frame.
    pub fn project(&self, p: Vec3) -> Option<(f64, f64)> {
        let v = &self.view;
        let mut disp = p - v.position;
        let (x, y, depth) = match v.projection {
            Projection::Parallel | Projection::Perspective | Projection::Hemispherical => {
                let depth = match v.projection {
                    Projection::Parallel => disp.dot(self.dir) - v.fore,
                    Projection::Perspective => {
                        let d = disp.dot(self.dir);
                        if v.aft > FTINY && d >= v.aft {
                            return None; // beyond the aft plane
                        }
                        let mut depth = disp.length();
                        let mut inv = if d < -FTINY {
                            depth = -depth;
                            -1.0 / d
                        } else if d <= FTINY {
                            return None;
                        } else {
                            1.0 / d
                        };
                        disp *= inv;
                        if depth < 0.0 {
                            inv = -inv;
                        }
                        depth * (1.0 - v.fore * inv)
                    }
                    _ => {
                        let d = normalize(&mut disp);
                        let depth = if disp.dot(self.dir) < 0.0 { -d } else { d };
                        depth - v.fore
                    }
                };
                let x = disp.dot(self.hvec) / self.hn2 + 0.5 - v.shift;
                let y = disp.dot(self.vvec) / self.vn2 + 0.5 - v.lift;
                (x, y, depth)
            }
            Projection::Cylindrical => {
                let (a, b) = (disp.dot(self.hvec), disp.dot(self.dir));
                let x = 180.0 / PI * a.atan2(b) / v.horizontal + 0.5 - v.shift;
                let r2 = a * a + b * b;
                if r2 <= FTINY * FTINY || (v.aft > FTINY && r2 >= v.aft * v.aft) {
                    return None;
                }
                let inv = 1.0 / r2.sqrt();
                let y = disp.dot(self.vvec) * inv / self.vn2 + 0.5 - v.lift;
                (x, y, disp.length() * (1.0 - v.fore * inv))
            }
            Projection::Angular | Projection::Planispheric => {
                let depth = normalize(&mut disp) - v.fore;
                let (mut x, mut y) = (0.5 - v.shift, 0.5 - v.lift);
                let d = disp.dot(self.dir);
                if d < 1.0 - FTINY {
                    if v.projection == Projection::Angular {
                        if d <= -(1.0 - FTINY) {
                            x += 180.0 / v.horizontal;
                        } else {
                            let k = (180.0 / PI) * d.acos() / (1.0 - d * d).sqrt();
                            x += disp.dot(self.hvec) * k / v.horizontal;
                            y += disp.dot(self.vvec) * k / v.vertical;
                        }
                    } else {
                        if d <= -(1.0 - FTINY) {
                            return None;
                        }
                        x += disp.dot(self.hvec) / ((1.0 + d) * self.hn2.sqrt());
                        y += disp.dot(self.vvec) / ((1.0 + d) * self.vn2.sqrt());
                    }
                }
                (x, y, depth)
            }
        };
        if depth <= 0.0 {
            return None; // behind
        }
        let beyond = !matches!(
            v.projection,
            Projection::Perspective | Projection::Cylindrical
        ) && v.aft > FTINY
            && depth >= v.aft - v.fore;
        (!beyond && x > 0.0 && x < 1.0 && y > 0.0 && y < 1.0).then_some((x, y))
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
        let (o, d, _) = c.ray(0.5, 0.5).unwrap();
        assert_eq!(o, Vec3::ZERO);
        assert!((d - Vec3::Y).length() < 1e-12);
        // The right edge is 22.5 degrees off for a 45 degree view.
        let (_, d, _) = c.ray(1.0, 0.5).unwrap();
        assert!((d.dot(Vec3::Y) - 22.5f64.to_radians().cos()).abs() < 1e-12);
        assert!(d.x > 0.0);
    }

    #[test]
    fn projection_inverts_rays() {
        for t in ['v', 'l', 'h', 'a', 'c', 's'] {
            let view = View {
                projection: Projection::from_letter(t).unwrap(),
                horizontal: if t == 'l' { 4.0 } else { 120.0 },
                vertical: if t == 'l' { 3.0 } else { 90.0 },
                ..View::default()
            };
            let c = view.camera().unwrap();
            let (o, d, _) = c.ray(0.3, 0.6).unwrap();
            let (x, y) = c.project(o + d * 5.0).unwrap();
            assert!(
                (x - 0.3).abs() < 1e-9 && (y - 0.6).abs() < 1e-9,
                "{t}: {x} {y}"
            );
        }
    }

    #[test]
    fn fisheye_corners_are_outside() {
        // A 360 degree angular fisheye fills a circle touching the frame's sides.
        let view = View {
            projection: Projection::Angular,
            horizontal: 360.0,
            vertical: 360.0,
            ..View::default()
        };
        let c = view.camera().unwrap();
        assert!(c.ray(0.0, 0.0).is_none());
        assert!(c.ray(0.5, 0.99).is_some());
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
        let v = View {
            fore: 2.0,
            aft: 1.0,
            ..View::default()
        };
        assert!(v.camera().is_err());
    }
}
