//! `plastic` (and, through [`super::metal`], `metal`): Radiance's "normal" material
//! (normal.c). A diffuse part coloured by the material plus Ward's isotropic Gaussian
//! highlight (Siggraph '92), uncoloured for plastic. Surfaces are two-sided: a ray
//! hitting the back sees the front's reflection with the normal flipped. Smooth
//! surfaces (`rough^2 <= FTINY`) trace a mirror ray instead of a highlight and, above a
//! specularity of 0.018, follow a Fresnel estimate.

use crate::integrator::{RayKind, RayState, Tracer};
use crate::math::{Color, FTINY, Vec3, normalize, perpendicular};
use std::f64::consts::PI;

/// Fresnel estimate at cosine `ci` (normal.c's `FRESNE`).
fn fresnel(ci: f64) -> f64 {
    (-5.85 * ci).exp() - 0.00202943064
}
/// Smallest specularity that gets the Fresnel estimate.
const FRESNEL_THRESHOLD: f64 = 0.017999;

#[derive(Clone, Debug, PartialEq)]
pub struct Normal {
    pub color: Color,
    pub spec: f64,
    pub rough: f64,
    pub metal: bool,
}

/// What a hit on a normal material works out once, for the ambient, specular and
/// every source's direct term.
pub struct Shading {
    color: Color,
    specular: Color,
    normal: Vec3,
    alpha2: f64,
    rdiff: f64,
    rspec: f64,
    pure: bool,
    has_highlight: bool,
    flat: bool,
    ray_dir: Vec3,
}

impl Normal {
    pub fn shade(&self, t: &Tracer<'_>, r: &mut RayState) {
        if r.kind.any(RayKind::SHADOW) {
            return; // opaque to shadow rays
        }
        if r.rod < 0.0 {
            if !t.options().backface_visible {
                t.transmit(r);
                return;
            }
            r.flip();
        }
        let s = self.setup(t, r);
        if s.rspec > FTINY && s.pure {
            self.mirror_ray(t, r, &s);
        }
        if s.pure && s.rdiff <= FTINY {
            return;
        }
        if s.has_highlight && s.rspec > t.options().specular_threshold + FTINY {
            self.specular_sample(t, r, &s);
        }
        if s.rdiff > FTINY {
            let mut amb = s.color * s.rdiff;
            if s.has_highlight && s.rspec <= t.options().specular_threshold + FTINY {
                amb += s.specular;
            }
            r.color += amb * t.options().ambient;
        }
        t.direct(r, &|dir, omega| s.source_coefficient(dir, omega));
    }

    fn setup(&self, t: &Tracer<'_>, r: &RayState) -> Shading {
        let alpha2 = self.rough * self.rough;
        let pure = alpha2 <= FTINY;
        let pdot = r.rod.max(0.001);
        let mut rspec = self.spec;
        let mut fest = 0.0;
        if pure && rspec >= FRESNEL_THRESHOLD {
            fest = fresnel(pdot);
            rspec += fest * (1.0 - rspec);
        }
        let specular = if self.metal {
            super::metal::specular_color(self.color, self.spec, rspec, fest)
        } else {
            Color::splat(rspec)
        };
        Shading {
            color: self.color,
            specular,
            normal: r.normal,
            alpha2,
            rdiff: 1.0 - rspec,
            rspec,
            pure,
            has_highlight: rspec > FTINY && !pure,
            flat: r.hit_is_flat(t.scene()),
            ray_dir: r.dir,
        }
    }

    /// A smooth surface's mirror reflection (normal.c's reflected ray).
    fn mirror_ray(&self, t: &Tracer<'_>, r: &mut RayState, s: &Shading) {
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(s.specular)) else {
            return;
        };
        child.dir = r.dir + s.normal * (2.0 * r.rod.max(0.001));
        normalize(&mut child.dir);
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        r.mirror_length = r.length;
        if s.flat {
            r.mirror_length += child.effective_length();
        }
    }

    /// A rough highlight above the `-st` threshold is sampled by one ray. Radiance
    /// draws it at random; radc takes the median of the Gaussian at a fixed azimuth so
    /// results are repeatable (they differ from rtrace's random sample).
    fn specular_sample(&self, t: &Tracer<'_>, r: &mut RayState, s: &Shading) {
        let Some(u) = perpendicular(s.normal) else {
            return;
        };
        let Some(mut child) = t.spawn(r, RayKind::SPECULAR, Some(s.specular)) else {
            return;
        };
        let d = (s.alpha2 * -(0.5f64).ln()).sqrt();
        let h = s.normal + u * d;
        let k = -2.0 * h.dot(r.dir) / (1.0 + d * d);
        child.dir = r.dir + h * k;
        if child.dir.dot(r.normal) <= FTINY {
            return;
        }
        normalize(&mut child.dir);
        t.trace(&mut child);
        r.color += child.color * child.coef;
    }
}

impl Shading {
    /// The coefficient turning a source's radiance into reflected radiance, for a source
    /// sample in direction `ldir` of solid angle `omega` (normal.c's `dirnorm`).
    pub fn source_coefficient(&self, ldir: Vec3, omega: f64) -> Color {
        let ldot = self.normal.dot(ldir);
        let mut out = Color::ZERO;
        if ldot < 0.0 {
            return out; // no transmission
        }
        let mut lrdiff = self.rdiff;
        if self.pure && self.rspec >= FRESNEL_THRESHOLD && lrdiff > FTINY {
            lrdiff *= 1.0 - fresnel(ldot.abs());
        }
        if ldot > FTINY && lrdiff > FTINY {
            out += self.color * (ldot * omega * lrdiff / PI);
        }
        if ldot > FTINY && self.has_highlight {
            let mut a2 = self.alpha2;
            if self.flat {
                a2 += omega * (0.25 / PI);
            }
            let h = ldir - self.ray_dir;
            let d2 = h.dot(self.normal).powi(2);
            let d3 = h.length_squared();
            let d4 = (d3 - d2) / d2;
            let g = (-d4 / a2).exp() * d3 / (PI * d2 * d2 * a2);
            if g > FTINY {
                out += self.specular * (g * ldot * omega);
            }
        }
        out
    }
}
