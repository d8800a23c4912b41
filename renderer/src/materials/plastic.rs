//! `plastic` (and, through [`super::metal`] and [`super::trans`], `metal` and `trans`):
//! Radiance's "normal" material (normal.c). A diffuse part coloured by the material plus
//! Ward's isotropic Gaussian highlight (Siggraph '92), uncoloured for plastic; `trans`
//! adds diffuse and specular transmission. Surfaces are two-sided: a ray hitting the
//! back sees the front's reflection with the normal flipped. Smooth surfaces
//! (`rough^2 <= FTINY`) trace a mirror (and a straight-through) ray instead of a
//! highlight and, above a specularity of 0.018, follow a Fresnel estimate.

use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, normalize, perpendicular};
use crate::random::uniform;
use std::f64::consts::PI;

/// raytrace.c's `raynormal`: the surface normal plus a texture's perturbation, turned
/// back to the ray's side of the surface if the perturbation crossed it, and its
/// cosine with the ray.
pub fn perturbed_normal(r: &RayState, pert: Vec3) -> (Vec3, f64) {
    if pert.dot(pert) <= FTINY * FTINY {
        return (r.normal, r.rod);
    }
    let mut norm = r.normal + pert;
    if normalize(&mut norm) == 0.0 {
        return (r.normal, r.rod);
    }
    let mut newdot = -norm.dot(r.dir);
    if (newdot > 0.0) != (r.rod > 0.0) {
        norm += r.dir * (2.0 * newdot);
        newdot = -newdot;
    }
    (norm, newdot)
}

/// normal.c's `prdir`: the ray's direction less a texture's perturbation (normalized)
/// when that still leaves the surface behind it, for rays other than shadow and ambient
/// ones; else the ray's own direction.
fn transmitted_dir(r: &RayState, pert: Vec3) -> Vec3 {
    if pert.dot(pert) <= FTINY * FTINY || r.kind.any(RayKind::SHADOW | RayKind::AMBIENT) {
        return r.dir;
    }
    let mut d = r.dir - pert;
    if d.dot(r.normal) < -FTINY {
        normalize(&mut d);
        d
    } else {
        r.dir
    }
}

/// Fresnel estimate at cosine `ci` (normal.c's `FRESNE`).
fn fresnel(ci: f64) -> f64 {
    (-5.85 * ci).exp() - 0.00202943064
}
/// Smallest specularity that gets the Fresnel estimate.
const FRESNEL_THRESHOLD: f64 = 0.017999;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Plastic {
    pub color: Color,
    pub spec: f64,
    pub rough: f64,
    pub metal: bool,
    /// `trans` only: the transmitted fraction of what is not reflected specularly, and
    /// the specular fraction of that.
    pub transmission: Option<(f64, f64)>,
    /// The normal's perturbation at the hit being shaded (`r->pert`), which textures
    /// set on a per-hit copy of the material (`Tracer::shade_patterned`); zero in the
    /// scene's own materials.
    #[serde(skip)]
    pub texture: Vec3,
}

/// What a hit on a normal material works out once, for the ambient, specular and
/// every source's direct term.
pub struct Shading {
    color: Color,
    specular: Color,
    normal: Vec3,
    cos_incidence: f64,
    alpha2: f64,
    diffuse_reflection: f64,
    specular_reflection: f64,
    transmission: f64,
    diffuse_transmission: f64,
    specular_transmission: f64,
    pure: bool,
    has_highlight: bool,
    /// Rough specular transmission (sampled only above `-st`, else folded into the
    /// diffuse transmission).
    has_rough_transmission: bool,
    flat: bool,
    ray_dir: Vec3,
    /// Where the transmitted ray goes (`prdir`): the ray's direction, bent by a texture
    /// except for shadow and ambient rays.
    transmitted_dir: Vec3,
}

impl Plastic {
    /// Transparent types win no ties against opaque ones (`istransp`).
    pub fn is_transparent(&self) -> bool {
        self.transmission.is_some()
    }

    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        let shadow = r.kind.any(RayKind::SHADOW);
        if shadow && self.transmission.is_none() {
            return; // opaque to shadow rays
        }
        let mut flipped = false;
        if r.rod < 0.0 {
            if !t.options().backface_visible {
                t.transmit(r);
                return;
            }
            r.flip();
            flipped = true;
        }
        let s = self.setup(t, r, flipped);
        if s.specular_transmission > FTINY && s.pure {
            self.straight_ray(t, r, &s);
        }
        if shadow {
            return;
        }
        if s.specular_reflection > FTINY && s.pure {
            self.mirror_ray(t, r, &s);
        }
        if s.pure && s.diffuse_reflection <= FTINY && s.diffuse_transmission <= FTINY {
            return;
        }
        let threshold = t.options().specular_threshold + FTINY;
        if s.has_highlight && s.specular_reflection > threshold {
            self.specular_sample(t, r, &s);
        }
        if s.has_rough_transmission
            && s.specular_transmission > threshold
            && t.options().samples_randomly()
        {
            self.transmitted_sample(t, r, &s);
        }
        if s.diffuse_reflection > FTINY {
            let mut amb = s.color * s.diffuse_reflection;
            if s.has_highlight && s.specular_reflection <= threshold {
                amb += s.specular;
            }
            let indirect = t.ambient(r, amb, s.normal);
            r.color += indirect;
        }
        if s.diffuse_transmission > FTINY {
            // Ambient from the other side; a rough transmission below the threshold
            // counts as diffuse.
            let below = s.has_rough_transmission && s.specular_transmission <= threshold;
            let k = if below {
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

    fn setup(&self, t: &impl ShadingContext, r: &RayState, flipped: bool) -> Shading {
        let alpha2 = self.rough * self.rough;
        let pure = alpha2 <= FTINY;
        // `flipsurface` turns the perturbation with the normal.
        let pert = if flipped { -self.texture } else { self.texture };
        let (normal, cos_incidence) = perturbed_normal(r, pert);
        let cos_incidence = cos_incidence.max(0.001);
        let mut specular_reflection = self.spec;
        let mut fresnel_estimate = 0.0;
        if pure && specular_reflection >= FRESNEL_THRESHOLD {
            fresnel_estimate = fresnel(cos_incidence);
            specular_reflection += fresnel_estimate * (1.0 - specular_reflection);
        }
        let (transmission, specular_transmission) = match self.transmission {
            Some((tr, ts)) => {
                let transmission = tr * (1.0 - specular_reflection);
                (transmission, transmission * ts)
            }
            None => (0.0, 0.0),
        };
        let specular = if self.metal {
            super::metal::specular_color(
                self.color,
                self.spec,
                specular_reflection,
                fresnel_estimate,
            )
        } else {
            Color::splat(specular_reflection)
        };
        Shading {
            color: self.color,
            specular,
            normal,
            cos_incidence,
            alpha2,
            diffuse_reflection: 1.0 - transmission - specular_reflection,
            specular_reflection,
            transmission,
            diffuse_transmission: transmission - specular_transmission,
            specular_transmission,
            pure,
            has_highlight: specular_reflection > FTINY && !pure,
            has_rough_transmission: specular_transmission > FTINY && !pure,
            // normal.c: a textured surface is not treated as flat.
            flat: pert.dot(pert) <= FTINY * FTINY && t.hit_is_flat(r),
            ray_dir: r.dir,
            transmitted_dir: transmitted_dir(r, pert),
        }
    }

    /// A smooth transmitting surface passes light straight through, tinted.
    fn straight_ray(&self, t: &impl ShadingContext, r: &mut RayState, s: &Shading) {
        let coef = s.color * s.specular_transmission;
        let Some(mut child) = t.spawn(r, RayKind::TRANS, Some(coef)) else {
            return;
        };
        child.dir = s.transmitted_dir;
        t.trace(&mut child);
        r.color += child.color * child.coef;
        if s.specular_transmission >= 1.0 - FTINY {
            r.mirror_color = child.mirror_color * child.coef;
            r.mirror_length = r.length + child.mirror_length;
            r.other_length = r.length + child.other_length;
        } else if s.specular_transmission > s.diffuse_transmission + s.diffuse_reflection {
            r.other_length = r.length + child.effective_length();
        }
    }

    /// A smooth surface's mirror reflection (normal.c's reflected ray).
    fn mirror_ray(&self, t: &impl ShadingContext, r: &mut RayState, s: &Shading) {
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(s.specular)) else {
            return;
        };
        child.dir = r.dir + s.normal * (2.0 * s.cos_incidence);
        // A texture may tip the reflection under the surface: normal.c reflects off
        // the unperturbed normal then.
        if s.normal != r.normal && child.dir.dot(r.normal) <= FTINY {
            child.dir = r.dir + r.normal * (2.0 * r.rod);
        }
        normalize(&mut child.dir);
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        // rtrace 6.0 (measured) reports the surface's own distance for a reflection
        // off a normal material, flat or not; `mirror` adds the reflected distance.
        r.mirror_length = r.length;
    }

    /// A rough highlight above the `-st` threshold is sampled by one ray (normal.c's
    /// `gaussamp`): a half-vector drawn from the Gaussian, at a random azimuth. When
    /// radc samples at random (`-ab > 0` or `-dj > 0`) the draw is random, as in
    /// Radiance; otherwise radc takes the median of the Gaussian at a fixed azimuth so
    /// results are repeatable (they differ from rtrace's random sample).
    fn specular_sample(&self, t: &impl ShadingContext, r: &mut RayState, s: &Shading) {
        let Some(u) = perpendicular(s.normal) else {
            return;
        };
        let v = s.normal.cross(u);
        let Some(mut child) = t.spawn(r, RayKind::SPECULAR, Some(s.specular)) else {
            return;
        };
        let random = t.options().samples_randomly();
        // Directions below the surface are drawn again (up to Radiance's 10 tries).
        for attempt in 0..if random { 10 } else { 1 } {
            let (phi, q) = if random {
                (
                    2.0 * PI * uniform(child.seed, 2 * attempt),
                    uniform(child.seed, 2 * attempt + 1),
                )
            } else {
                (0.0, 0.5)
            };
            let d = if q <= FTINY {
                1.0
            } else {
                (s.alpha2 * -q.ln()).sqrt()
            };
            let h = s.normal + (u * phi.cos() + v * phi.sin()) * d;
            let k = -2.0 * h.dot(r.dir) / (1.0 + d * d);
            child.dir = r.dir + h * k;
            if child.dir.dot(r.normal) > FTINY {
                normalize(&mut child.dir);
                t.trace(&mut child);
                r.color += child.color * child.coef;
                return;
            }
        }
    }

    /// Rough specular transmission above `-st` (normal.c's transmitted `gaussamp`),
    /// sampled only when radc samples at random: a direction scattered about the
    /// straight-through one by the Gaussian, on the far side of the surface.
    fn transmitted_sample(&self, t: &impl ShadingContext, r: &mut RayState, s: &Shading) {
        let Some(u) = perpendicular(s.normal) else {
            return;
        };
        let v = s.normal.cross(u);
        let Some(mut child) = t.spawn(
            r,
            RayKind::SPECULAR,
            Some(s.color * s.specular_transmission),
        ) else {
            return;
        };
        for attempt in 0..10 {
            let phi = 2.0 * PI * uniform(child.seed, 2 * attempt);
            let q = uniform(child.seed, 2 * attempt + 1);
            let d = if q <= FTINY {
                1.0
            } else {
                (s.alpha2 * -q.ln()).sqrt()
            };
            child.dir = s.transmitted_dir + (u * phi.cos() + v * phi.sin()) * d;
            normalize(&mut child.dir);
            if child.dir.dot(r.normal) < -FTINY {
                t.trace(&mut child);
                r.color += child.color * child.coef;
                return;
            }
        }
    }
}

impl Shading {
    /// The coefficient turning a source's radiance into reflected (or transmitted)
    /// radiance, for a source sample in direction `ldir` of solid angle `omega`
    /// (normal.c's `dirnorm`).
    #[inline]
    pub fn source_coefficient(&self, ldir: Vec3, omega: f64) -> Color {
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
        let (mut lrdiff, mut ltdiff) = (self.diffuse_reflection, self.diffuse_transmission);
        if self.pure
            && self.specular_reflection >= FRESNEL_THRESHOLD
            && (lrdiff > FTINY || ltdiff > FTINY)
        {
            let k = 1.0 - fresnel(ldot.abs());
            lrdiff *= k;
            ltdiff *= k;
        }
        if ldot > FTINY && lrdiff > FTINY {
            out += self.color * (ldot * omega * lrdiff / PI);
        }
        if ldot < -FTINY && ltdiff > FTINY {
            out += self.color * (-ldot * omega * ltdiff / PI);
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
        if ldot < -FTINY && self.has_rough_transmission {
            let a2 = self.alpha2 + omega / PI;
            let g = ((2.0 * self.transmitted_dir.dot(ldir) - 2.0) / a2).exp() / (PI * a2);
            if g > FTINY {
                out += self.color
                    * (g * self.specular_transmission
                        * omega
                        * (-ldot / self.cos_incidence).sqrt());
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Options;
    use crate::materials::context::scripted::{Scripted, hit};

    fn plastic(grey: f64, spec: f64, rough: f64) -> Plastic {
        Plastic {
            color: Color::splat(grey),
            spec,
            rough,
            metal: false,
            transmission: None,
            texture: Vec3::ZERO,
        }
    }

    #[test]
    fn a_diffuse_surface_reflects_a_source_by_lamberts_law() {
        let mut t = Scripted::default();
        let (omega, radiance) = (0.01, 100.0);
        let ldir = Vec3::new(0.0, 0.6, 0.8);
        t.source = Some((ldir, omega, Color::splat(radiance)));
        let mut r = hit(Vec3::new(0.3, 0.0, -1.0));
        plastic(0.5, 0.0, 0.0).shade(&t, &mut r);
        let expected = 0.5 * 0.8 * omega * radiance / PI;
        assert!(
            (r.color.x - expected).abs() < 1e-12,
            "{} vs {expected}",
            r.color.x
        );
        assert!(t.traced.borrow().is_empty(), "no specular ray for spec 0");
    }

    #[test]
    fn ambient_light_is_the_diffuse_part_of_the_material_and_faces_the_ray() {
        let t = Scripted {
            ambient_value: Color::splat(2.0),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        plastic(0.4, 0.0, 0.1).shade(&t, &mut r);
        assert!((r.color.x - 0.8).abs() < 1e-12);
        // A ray seeing the back: shaded as the front, normal flipped toward it.
        let mut back = hit(Vec3::new(0.0, 0.0, 1.0));
        plastic(0.4, 0.0, 0.1).shade(&t, &mut back);
        let normals = t.ambient_normals.borrow();
        assert_eq!(normals[0], Vec3::Z);
        assert_eq!(normals[1], -Vec3::Z);
    }

    #[test]
    fn an_opaque_plastic_stops_shadow_rays_and_without_backfaces_passes_rays_on() {
        let t = Scripted {
            source: Some((Vec3::Z, 0.1, Color::ONE)),
            ..Scripted::default()
        };
        let mut shadow = hit(Vec3::new(0.0, 0.0, -1.0));
        shadow.kind = RayKind::SHADOW;
        plastic(0.5, 0.0, 0.0).shade(&t, &mut shadow);
        assert_eq!(shadow.color, Color::ZERO);
        assert!(t.traced.borrow().is_empty());
        let t = Scripted {
            options: Options {
                backface_visible: false,
                ..Options::default()
            },
            seen: Color::splat(3.0),
            ..Scripted::default()
        };
        let mut back = hit(Vec3::new(0.0, 0.0, 1.0));
        plastic(0.5, 0.0, 0.0).shade(&t, &mut back);
        assert_eq!(*t.transmitted.borrow(), 1);
        assert_eq!(back.color, Color::splat(3.0));
    }

    #[test]
    fn a_smooth_plastic_traces_the_mirror_ray_with_the_fresnel_estimate() {
        let t = Scripted {
            seen: Color::splat(10.0),
            ..Scripted::default()
        };
        let dir = Vec3::new(1.0, 0.0, -1.0).normalize();
        let mut r = hit(dir);
        plastic(0.5, 0.05, 0.0).shade(&t, &mut r);
        let traced = t.traced.borrow();
        assert_eq!(traced.len(), 1);
        let (kind, d, coef) = traced[0];
        assert!(kind.any(RayKind::REFLECTED));
        assert!((d - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-12);
        let k = 0.05 + fresnel(dir.z.abs()) * 0.95;
        assert!((coef.x - k).abs() < 1e-12);
        assert!((r.mirror_color.x - 10.0 * k).abs() < 1e-9);
    }

    #[test]
    fn a_metal_tints_its_highlight_and_a_smooth_trans_passes_light_straight_through() {
        let t = Scripted::default();
        let red = Color::new(0.8, 0.2, 0.1);
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        crate::materials::metal::metal(red, 0.9, 0.0).shade(&t, &mut r);
        let (_, _, coef) = t.traced.borrow()[0];
        assert!(coef.x > coef.y && coef.y > coef.z, "{coef:?}");

        let t = Scripted::default();
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        crate::materials::trans::trans(Color::ONE, 0.0, 0.0, 0.5, 1.0).shade(&t, &mut r);
        let traced = t.traced.borrow();
        let (kind, d, coef) = traced[0];
        assert!(kind.any(RayKind::TRANS));
        assert_eq!(d, Vec3::new(0.0, 0.0, -1.0));
        assert!((coef.x - 0.5).abs() < 1e-12);
    }
}
