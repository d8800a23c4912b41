//! `plastic2`, `metal2` and `trans2` (aniso.c): the normal.c model with an elliptical
//! Gaussian highlight, rougher along one surface direction than across it. The
//! direction comes from three expressions (`getacoords`), evaluated per hit through
//! the scene's functions when they are more than numbers, and turned by the material's
//! transform.

use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, normalize, perpendicular};
use std::f64::consts::PI;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Anisotropic {
    pub color: Color,
    pub spec: f64,
    pub u_rough: f64,
    pub v_rough: f64,
    /// The direction of `u_rough` before projection onto the surface, when its
    /// expressions are numbers and there is no transform.
    pub orientation: Vec3,
    /// Otherwise the pattern that evaluates them (`procedural::PatternKind::Orientation`).
    pub orientation_pattern: Option<u32>,
    pub metal: bool,
    /// `trans2`: transmitted fraction and its specular part.
    pub transmission: Option<(f64, f64)>,
    /// The normal's perturbation at the hit being shaded (see `Plastic::texture`).
    #[serde(skip)]
    pub texture: Vec3,
}

struct Shading {
    color: Color,
    specular: Color,
    normal: Vec3,
    cos_incidence: f64,
    u: Vec3,
    v: Vec3,
    u_alpha: f64,
    v_alpha: f64,
    diffuse_reflection: f64,
    transmission: f64,
    diffuse_transmission: f64,
    specular_transmission: f64,
    reflects: bool,
    transmits: bool,
    flat: bool,
    ray_dir: Vec3,
}

impl Anisotropic {
    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        if r.kind.any(RayKind::SHADOW) {
            return; // opaque to shadow rays, even trans2
        }
        // `flipsurface` turns the perturbation with the normal.
        let mut pert = self.texture;
        if r.rod < 0.0 {
            if !t.options().backface_visible {
                return t.transmit(r);
            }
            r.flip();
            pert = -pert;
        }
        let orientation = match self.orientation_pattern {
            // A compute error gives a zero vector (then the frame is made up).
            Some(p) => t.orientation(p, &r.view()).unwrap_or(Vec3::ZERO),
            None => self.orientation,
        };
        let s = self.setup(t, r, orientation, pert);
        let threshold = t.options().specular_threshold + FTINY;
        // Highlights above -st are sampled at random by Radiance; radc does not sample
        // them (its result then lacks that part).
        if s.diffuse_reflection > FTINY {
            let mut amb = s.color * s.diffuse_reflection;
            if s.reflects && self.spec <= threshold {
                amb += s.specular;
            }
            let indirect = t.ambient(r, amb, s.normal);
            r.color += indirect;
        }
        if s.diffuse_transmission > FTINY {
            let k = if s.transmits && s.specular_transmission <= threshold {
                s.transmission
            } else {
                s.diffuse_transmission
            };
            // From the other side: the hemisphere behind the surface.
            let indirect = t.ambient(r, s.color * k, -s.normal);
            r.color += indirect;
        }
        t.direct(r, &|dir, omega| s.source_coefficient(dir, omega));
    }

    fn setup(
        &self,
        t: &impl ShadingContext,
        r: &RayState,
        orientation: Vec3,
        pert: Vec3,
    ) -> Shading {
        let specular_reflection = self.spec;
        let reflects = specular_reflection > FTINY;
        let specular = if self.metal {
            self.color * specular_reflection
        } else {
            Color::splat(specular_reflection)
        };
        let (transmission, specular_transmission) = match self.transmission {
            Some((tr, ts)) => {
                let transmission = tr * (1.0 - specular_reflection);
                (transmission, transmission * ts)
            }
            None => (0.0, 0.0),
        };
        let (normal, cos) = super::plastic::perturbed_normal(r, pert);
        let textured = pert.dot(pert) > FTINY * FTINY;
        let (mut u_alpha, mut v_alpha) = (self.u_rough, self.v_rough);
        // The frame: v across the projected orientation, u along it (`getacoords`).
        let mut v = normal.cross(orientation);
        let u = if normalize(&mut v) == 0.0 {
            let u = perpendicular(normal).unwrap_or(Vec3::X);
            v = normal.cross(u);
            let a = (0.5 * (u_alpha * u_alpha + v_alpha * v_alpha)).sqrt();
            (u_alpha, v_alpha) = (a, a);
            u
        } else {
            v.cross(normal)
        };
        Shading {
            color: self.color,
            specular,
            normal,
            cos_incidence: cos.max(0.001),
            u,
            v,
            u_alpha,
            v_alpha,
            diffuse_reflection: 1.0 - transmission - specular_reflection,
            transmission,
            diffuse_transmission: transmission - specular_transmission,
            specular_transmission,
            reflects,
            transmits: specular_transmission > FTINY,
            flat: !textured && t.hit_is_flat(r),
            ray_dir: r.dir,
        }
    }
}

impl Shading {
    /// aniso.c's `diraniso`.
    fn source_coefficient(&self, ldir: Vec3, omega: f64) -> Color {
        let ldot = self.normal.dot(ldir);
        let mut out = Color::ZERO;
        let wrong_side = if ldot < 0.0 {
            self.transmission <= FTINY
        } else {
            self.transmission >= 1.0 - FTINY
        };
        if wrong_side {
            return out;
        }
        if ldot > FTINY && self.diffuse_reflection > FTINY {
            out += self.color * (ldot * omega * self.diffuse_reflection / PI);
        }
        if ldot < -FTINY && self.diffuse_transmission > FTINY {
            out += self.color * (-ldot * omega * self.diffuse_transmission / PI);
        }
        if ldot > FTINY && self.reflects {
            let extra = if self.flat { omega * (0.25 / PI) } else { 0.0 };
            let au2 = extra + self.u_alpha * self.u_alpha;
            let av2 = extra + self.v_alpha * self.v_alpha;
            let h = ldir - self.ray_dir;
            let du = self.u.dot(h).powi(2) / au2;
            let dv = self.v.dot(h).powi(2) / av2;
            let hn = self.normal.dot(h).powi(2);
            let g =
                (-(du + dv) / hn).exp() * h.length_squared() / (PI * hn * hn * (au2 * av2).sqrt());
            if g > FTINY {
                out += self.specular * (g * ldot * omega);
            }
        }
        if ldot < -FTINY && self.transmits {
            let au2 = omega / PI + self.u_alpha * self.u_alpha;
            let av2 = omega / PI + self.v_alpha * self.v_alpha;
            let h = ldir - self.ray_dir;
            let mut d = h.length_squared();
            if d > FTINY * FTINY {
                let hn = h.dot(self.normal);
                d = 1.0 - hn * hn / d;
            }
            let mut g = if d > FTINY * FTINY {
                let du = h.dot(self.u).powi(2) / au2;
                let dv = h.dot(self.v).powi(2) / av2;
                (-(du + dv) / d).exp()
            } else {
                1.0
            };
            g *= (1.0 / PI) * (-ldot / (self.cos_incidence * au2 * av2)).sqrt();
            if g > FTINY {
                out += self.color * (g * self.specular_transmission * omega);
            }
        }
        out
    }
}
