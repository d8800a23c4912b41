//! The ray as calcomp sees it: func.c's `chanvalue`, channels `$1`..`$27` behind
//! rayinit's names (`Dx = $1`, ..., `Lu = $26`, `Lv = $27`), in the function's own
//! coordinates: the hit mapped through the inverse of the primitive's transform.

use radc_lang::transform::Transform;

use crate::math::Vec3;

/// How many channels there are.
pub const COUNT: usize = 27;

/// The 27 channel values of one ray at one primitive.
pub struct Channels([f64; COUNT]);

/// What the channels are computed from.
pub struct RayView {
    pub dir: Vec3,
    /// The surface normal as intersected (before a material flips it).
    pub normal: Vec3,
    pub point: Vec3,
    /// Distance from the eye along the ray tree (`raydist(r, PRIMARY)`).
    pub total_distance: f64,
    /// This ray's own length (the shadow distance of `Ts`).
    pub length: f64,
    pub rod: f64,
    pub uv: [f64; 2],
}

impl Channels {
    /// `xf` is the inverse of the primitive's transform, scale made positive, as
    /// func.c's `getfunc` keeps it (`bxp`).
    pub fn new(r: &RayView, xf: &Transform) -> Channels {
        let m = &xf.matrix;
        let scale = xf.scale;
        let mut c = [0.0; COUNT];
        let d = [r.dir.x, r.dir.y, r.dir.z];
        let n = [r.normal.x, r.normal.y, r.normal.z];
        let p = [r.point.x, r.point.y, r.point.z];
        for j in 0..3 {
            c[j] = (d[0] * m[0][j] + d[1] * m[1][j] + d[2] * m[2][j]) / scale;
            c[3 + j] = (n[0] * m[0][j] + n[1] * m[1][j] + n[2] * m[2][j]) / scale;
            c[6 + j] = p[0] * m[0][j] + p[1] * m[1][j] + p[2] * m[2][j] + m[3][j];
        }
        c[9] = r.total_distance * scale;
        c[10] = r.rod.clamp(-1.0, 1.0);
        c[11] = scale;
        for j in 0..3 {
            c[12 + j] = m[3][j];
            c[15 + j] = m[0][j] / scale;
            c[18 + j] = m[1][j] / scale;
            c[21 + j] = m[2][j] / scale;
        }
        c[24] = r.length * scale;
        c[25] = r.uv[0];
        c[26] = r.uv[1];
        Channels(c)
    }

    /// Channel `n` (1-based), as `$n` reads it.
    pub fn get(&self, n: u32) -> Option<f64> {
        (n as usize)
            .checked_sub(1)
            .and_then(|i| self.0.get(i))
            .copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view() -> RayView {
        RayView {
            dir: Vec3::new(0.0, 0.6, -0.8),
            normal: Vec3::Z,
            point: Vec3::new(1.0, 2.0, 3.0),
            total_distance: 5.0,
            length: 2.0,
            rod: 0.8,
            uv: [0.0, 0.0],
        }
    }

    #[test]
    fn identity_gives_the_ray_itself() {
        let c = Channels::new(&view(), &Transform::IDENTITY);
        let got: Vec<f64> = (1..=12).map(|n| c.get(n).unwrap_or(f64::NAN)).collect();
        assert_eq!(
            got,
            [0.0, 0.6, -0.8, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 5.0, 0.8, 1.0]
        );
        assert_eq!(c.get(0), None);
        assert_eq!(c.get(28), None);
    }

    #[test]
    fn points_move_into_the_function_frame() {
        // A pattern translated by (1, 0, 0) sees the hit at x - 1, scaled by 2 at x / 2.
        let words = |w: &[&str]| {
            let spanned: Vec<(&str, radc_lang::Span)> =
                w.iter().map(|s| (*s, radc_lang::Span::default())).collect();
            Transform::parse_inverse(&spanned).expect("valid")
        };
        let c = Channels::new(&view(), &words(&["-t", "1", "0", "0"]));
        assert_eq!(c.get(7), Some(0.0));
        let c = Channels::new(&view(), &words(&["-s", "2"]));
        assert_eq!(
            (c.get(7), c.get(12), c.get(10)),
            (Some(0.5), Some(0.5), Some(2.5))
        );
    }
}
