//! `ashik2` (ashikhmin.c): the Ashikhmin-Shirley anisotropic model, a diffuse part with
//! Schlick's Fresnel loss and a specular lobe of powers `u` and `v` along an orientation
//! (three expressions, as plastic2's). Its highlight toward light sources is exact; its
//! sampled specular ray (above `-st`) is random in Radiance and not traced here (see the
//! crate's list of what is not reproduced).

use std::f64::consts::PI;

use super::ShadingContext;
use super::plastic::perturbed_normal;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, brightness, intensity, normalize, perpendicular};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ashikhmin {
    /// Diffuse colour, times the patterns' at the hit being shaded.
    pub color: Color,
    pub specular: Color,
    pub u_power: f64,
    pub v_power: f64,
    /// The orientation when its expressions are numbers and there is no transform.
    pub orientation: Vec3,
    pub orientation_pattern: Option<u32>,
    #[serde(skip)]
    pub texture: Vec3,
}

/// Schlick's approximation of the Fresnel term's variation.
fn schlick(cos: f64) -> f64 {
    (1.0 - cos).powi(5)
}

impl Ashikhmin {
    pub fn shade<C: ShadingContext + ?Sized>(&self, ctx: &C, r: &mut RayState) {
        if r.kind.any(RayKind::SHADOW) {
            return;
        }
        let mut pert = self.texture;
        if r.rod < 0.0 {
            if !ctx.options().backface_visible {
                return ctx.transmit(r);
            }
            r.flip();
            pert = -pert;
        }
        let (normal, pdot) = perturbed_normal(r, pert);
        let pdot = pdot.max(0.001);
        let mut scolor = self.specular;
        let reflects = intensity(scolor) > FTINY;
        let below_threshold =
            reflects && ctx.options().specular_threshold >= brightness(scolor) - FTINY;
        if reflects {
            let f = schlick(pdot);
            scolor += (Color::ONE - scolor) * f;
        }
        let orientation = match self.orientation_pattern {
            Some(p) => ctx.orientation(p, &r.view()).unwrap_or(Vec3::ZERO),
            None => self.orientation,
        };
        let (mut up, mut vp) = (self.u_power, self.v_power);
        let mut v = normal.cross(orientation);
        let u = if normalize(&mut v) == 0.0 {
            let u = perpendicular(normal).unwrap_or(Vec3::X);
            v = normal.cross(u);
            let p = 2.0 / (1.0 / (up + 1e-5) + 1.0 / (vp + 1e-5));
            (up, vp) = (p, p);
            u
        } else {
            v.cross(normal)
        };
        if intensity(self.color) > FTINY {
            let mut amb = self.color;
            if below_threshold {
                amb += scolor;
            }
            r.color += ctx.ambient(r, amb, normal);
        }
        let (color, dir) = (self.color, r.dir);
        ctx.direct(r, &|ldir, omega| {
            let ldot = normal.dot(ldir);
            if ldot <= FTINY {
                return Color::ZERO;
            }
            let mut c = color * (ldot * omega * (1.0 / PI) * (1.0 - schlick(ldot)));
            if !reflects {
                return c;
            }
            let mut h = ldir - dir;
            normalize(&mut h);
            let (du, dv) = (u.dot(h), v.dot(h));
            let (e1, e2) = (du * du * up, dv * dv * vp);
            let nh = normal.dot(h);
            let mut d = nh.powf((e1 + e2) / (1.0 - nh * nh));
            d *= ((up + 1.0) * (vp + 1.0)).sqrt();
            d /= 8.0 * PI * ldir.dot(h) * ldot.max(pdot);
            if d > FTINY {
                c += scolor * (d * ldot * omega);
            }
            c
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};

    fn ashik() -> Ashikhmin {
        Ashikhmin {
            color: Color::splat(0.5),
            specular: Color::ZERO,
            u_power: 10.0,
            v_power: 100.0,
            orientation: Vec3::X,
            orientation_pattern: None,
            texture: Vec3::ZERO,
        }
    }

    #[test]
    fn diffuse_loses_schlicks_fresnel_term() {
        let ctx = Scripted {
            source: Some((Vec3::new(0.0, 0.6, 0.8), 0.01, Color::splat(100.0))),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        ashik().shade(&ctx, &mut r);
        let want = 0.5 * 0.8 * 0.01 / PI * (1.0 - 0.2f64.powi(5)) * 100.0;
        assert!((r.color.x - want).abs() < 1e-12, "{:?}", r.color);
    }

    #[test]
    fn the_highlight_peaks_in_the_mirror_direction() {
        let m = Ashikhmin {
            specular: Color::splat(0.1),
            ..ashik()
        };
        let value = |l: Vec3| {
            let ctx = Scripted {
                source: Some((l, 0.001, Color::splat(1.0))),
                ..Scripted::default()
            };
            let mut r = hit(Vec3::new(0.0, 0.6, -0.8));
            m.shade(&ctx, &mut r);
            r.color.x
        };
        assert!(value(Vec3::new(0.0, 0.6, 0.8)) > value(Vec3::new(0.3, 0.5, 0.81)));
    }
}
