//! vwrays' rays: the view ray through each pixel of a picture, in the picture's file
//! order, or through pixel positions given one by one (`vwrays -i`), each as an origin
//! and a direction (its length the distance to the aft clipping plane, when there is
//! one). A pipeline sends them to `rtrace -x X -y Y -ffc` to render a picture, or to
//! compute values over a view; the same camera as `radc render` makes them.

use radc_picture::Resolution;

use crate::camera::Camera;
use crate::math::{FTINY, Vec3};
use crate::trace::RayEncoding;
use radc_lang::c_number::format_e;

/// A ray as vwrays writes it; all zero where the view has no ray (outside a
/// fisheye's circle), which rtrace answers with zero.
pub type OutputRay = [f64; 6];

/// One ray as vwrays writes it: `%.5e` words on a line (`-fa`), or six floats or
/// doubles (`-ff`, `-fd`). RGBE is not a ray encoding: an `InvalidInput` error.
pub fn write_ray(
    out: &mut impl std::io::Write,
    encoding: RayEncoding,
    ray: &OutputRay,
) -> std::io::Result<()> {
    match encoding {
        RayEncoding::Ascii => {
            let words: Vec<String> = ray.iter().map(|v| format_e(*v, 5)).collect();
            writeln!(out, "{}", words.join(" "))
        }
        RayEncoding::Float => ray
            .iter()
            .try_for_each(|v| out.write_all(&(*v as f32).to_ne_bytes())),
        RayEncoding::Double => ray.iter().try_for_each(|v| out.write_all(&v.to_ne_bytes())),
        RayEncoding::Color => Err(std::io::Error::from(std::io::ErrorKind::InvalidInput)),
    }
}

/// How the rays of a view are made.
pub struct ViewRays<'a> {
    pub camera: &'a Camera,
    pub resolution: Resolution,
    /// `-pj`: each sample moves by up to this fraction of a pixel, at random.
    pub jitter: f64,
    /// `-c`: samples per pixel.
    pub repeat: u32,
}

impl ViewRays<'_> {
    /// The ray through image location `(x, y)` (0..1 from the lower left).
    pub fn at(&self, x: f64, y: f64) -> OutputRay {
        match self.camera.ray(x, y) {
            Some((org, dir, max)) => {
                let dir = if max > FTINY { dir * max } else { dir };
                [org.x, org.y, org.z, dir.x, dir.y, dir.z]
            }
            None => [0.0; 6],
        }
    }

    /// The `repeat` rays of pixel `(px, py)` of the frame (column from the left, row
    /// from the bottom, fractional for `-i`); `index` seeds the jitter, so the rays
    /// are the same on every run.
    pub fn pixel(&self, px: f64, py: f64, index: u64, out: &mut Vec<OutputRay>) {
        let (w, h) = (f64::from(self.resolution.x), f64::from(self.resolution.y));
        let (x, y) = ((px + 0.5) / w, (py + 0.5) / h);
        for sample in 0..u64::from(self.repeat.max(1)) {
            let (mut jx, mut jy) = (x, y);
            if self.jitter > FTINY {
                let seed = crate::random::primary_seed(index);
                jx += self.jitter * (0.5 - crate::random::uniform(seed, 2 * sample)) / w;
                jy += self.jitter * (0.5 - crate::random::uniform(seed, 2 * sample + 1)) / h;
            }
            out.push(self.at(jx, jy));
        }
    }

    /// Every pixel's rays, scanline by scanline in the picture's file order.
    pub fn scanline(&self, s: u32, out: &mut Vec<OutputRay>) {
        let r = self.resolution;
        for p in 0..r.scan_length() {
            let (x, y) = r.frame_position(s, p);
            let index = u64::from(s) * u64::from(r.scan_length()) + u64::from(p);
            self.pixel(f64::from(x), f64::from(y), index, out);
        }
    }
}

/// The direction of an output ray, for tests.
pub fn direction(ray: &OutputRay) -> Vec3 {
    Vec3::new(ray[3], ray[4], ray[5])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::View;

    #[test]
    fn the_centre_pixel_looks_along_the_view_and_the_top_row_comes_first() {
        let view = View::default();
        let camera = view.camera().expect("a valid view");
        let rays = ViewRays {
            camera: &camera,
            resolution: Resolution::standard(3, 3),
            jitter: 0.0,
            repeat: 1,
        };
        let mut out = Vec::new();
        rays.scanline(1, &mut out);
        let centre = direction(&out[1]);
        assert!(
            (centre - view.direction.normalize()).length() < 1e-12,
            "{centre:?}"
        );
        out.clear();
        rays.scanline(0, &mut out);
        // Radiance's standard view looks along +y with +z up: the first scanline is
        // the top one.
        assert!(direction(&out[1]).z > 0.0);
    }

    #[test]
    fn jittered_samples_stay_within_their_pixel_and_repeat_exactly() {
        let view = View::default();
        let camera = view.camera().expect("a valid view");
        let rays = ViewRays {
            camera: &camera,
            resolution: Resolution::standard(4, 4),
            jitter: 1.0,
            repeat: 8,
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        rays.pixel(2.0, 1.0, 9, &mut a);
        rays.pixel(2.0, 1.0, 9, &mut b);
        assert_eq!(a, b);
        assert_eq!(a.len(), 8);
        let centre = direction(&rays.at(2.5 / 4.0, 1.5 / 4.0)).normalize();
        let corner = direction(&rays.at(2.0 / 4.0, 1.0 / 4.0)).normalize();
        let half_pixel = centre.angle_between(corner);
        for ray in &a {
            assert!(direction(ray).normalize().angle_between(centre) <= half_pixel * 1.0001);
        }
        assert!(a.windows(2).any(|w| w[0] != w[1]), "samples differ");
    }
}
