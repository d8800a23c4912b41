//! `plastic` (and, through [`super::metal`] and [`super::trans`], `metal` and `trans`):
//! Radiance's "normal" material (normal.c). A diffuse part coloured by the material plus
//! Ward's isotropic Gaussian highlight (Siggraph '92), uncoloured for plastic; `trans`
//! adds diffuse and specular transmission. Surfaces are two-sided: a ray hitting the
//! back sees the front's reflection with the normal flipped. Smooth surfaces
//! (`rough^2 <= FTINY`) trace a mirror (and a straight-through) ray instead of a
//! highlight and, above a specularity of 0.018, follow a Fresnel estimate.

use crate::integrator::{RayKind, RayState, Tracer};
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

/// Fresnel estimate at cosine `ci` (normal.c's `FRESNE`).
fn fresnel(ci: f64) -> f64 {
    (-5.85 * ci).exp() - 0.00202943064
}
/// Smallest specularity that gets the Fresnel estimate.
const FRESNEL_THRESHOLD: f64 = 0.017999;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Normal {
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
    pdot: f64,
    alpha2: f64,
    rdiff: f64,
    rspec: f64,
    trans: f64,
    tdiff: f64,
    tspec: f64,
    pure: bool,
    has_highlight: bool,
    /// Rough specular transmission (sampled only above `-st`, else folded into the
    /// diffuse transmission).
    has_rough_transmission: bool,
    flat: bool,
    ray_dir: Vec3,
}

impl Normal {
    /// Transparent types win no ties against opaque ones (`istransp`).
    pub fn is_transparent(&self) -> bool {
        self.transmission.is_some()
    }

    pub fn shade(&self, t: &Tracer<'_>, r: &mut RayState) {
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
        if s.tspec > FTINY && s.pure {
            self.straight_ray(t, r, &s);
        }
        if shadow {
            return;
        }
        if s.rspec > FTINY && s.pure {
            self.mirror_ray(t, r, &s);
        }
        if s.pure && s.rdiff <= FTINY && s.tdiff <= FTINY {
            return;
        }
        let threshold = t.options().specular_threshold + FTINY;
        if s.has_highlight && s.rspec > threshold {
            self.specular_sample(t, r, &s);
        }
        if s.has_rough_transmission && s.tspec > threshold && t.options().samples_randomly() {
            self.transmitted_sample(t, r, &s);
        }
        if s.rdiff > FTINY {
            let mut amb = s.color * s.rdiff;
            if s.has_highlight && s.rspec <= threshold {
                amb += s.specular;
            }
            let indirect = t.ambient(r, amb, s.normal);
            r.color += indirect;
        }
        if s.tdiff > FTINY {
            // Ambient from the other side; a rough transmission below the threshold
            // counts as diffuse.
            let below = s.has_rough_transmission && s.tspec <= threshold;
            let k = if below { s.trans } else { s.tdiff };
            // From the other side: the hemisphere behind the surface.
            let indirect = t.ambient(r, s.color * k, -s.normal);
            r.color += indirect;
        }
        t.direct(r, &|dir, omega| s.source_coefficient(dir, omega));
    }

    fn setup(&self, t: &Tracer<'_>, r: &RayState, flipped: bool) -> Shading {
        let alpha2 = self.rough * self.rough;
        let pure = alpha2 <= FTINY;
        // `flipsurface` turns the perturbation with the normal.
        let pert = if flipped { -self.texture } else { self.texture };
        let (normal, pdot) = perturbed_normal(r, pert);
        let pdot = pdot.max(0.001);
        let mut rspec = self.spec;
        let mut fest = 0.0;
        if pure && rspec >= FRESNEL_THRESHOLD {
            fest = fresnel(pdot);
            rspec += fest * (1.0 - rspec);
        }
        let (trans, tspec) = match self.transmission {
            Some((tr, ts)) => {
                let trans = tr * (1.0 - rspec);
                (trans, trans * ts)
            }
            None => (0.0, 0.0),
        };
        let specular = if self.metal {
            super::metal::specular_color(self.color, self.spec, rspec, fest)
        } else {
            Color::splat(rspec)
        };
        Shading {
            color: self.color,
            specular,
            normal,
            pdot,
            alpha2,
            rdiff: 1.0 - trans - rspec,
            rspec,
            trans,
            tdiff: trans - tspec,
            tspec,
            pure,
            has_highlight: rspec > FTINY && !pure,
            has_rough_transmission: tspec > FTINY && !pure,
            // normal.c: a textured surface is not treated as flat.
            flat: pert.dot(pert) <= FTINY * FTINY && r.hit_is_flat(t.scene()),
            ray_dir: r.dir,
        }
    }

    /// A smooth transmitting surface passes light straight through, tinted.
    fn straight_ray(&self, t: &Tracer<'_>, r: &mut RayState, s: &Shading) {
        let coef = s.color * s.tspec;
        let Some(mut child) = t.spawn(r, RayKind::TRANS, Some(coef)) else {
            return;
        };
        child.dir = r.dir;
        t.trace(&mut child);
        r.color += child.color * child.coef;
        if s.tspec >= 1.0 - FTINY {
            r.mirror_color = child.mirror_color * child.coef;
            r.mirror_length = r.length + child.mirror_length;
            r.other_length = r.length + child.other_length;
        } else if s.tspec > s.tdiff + s.rdiff {
            r.other_length = r.length + child.effective_length();
        }
    }

    /// A smooth surface's mirror reflection (normal.c's reflected ray).
    fn mirror_ray(&self, t: &Tracer<'_>, r: &mut RayState, s: &Shading) {
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(s.specular)) else {
            return;
        };
        child.dir = r.dir + s.normal * (2.0 * s.pdot);
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
    fn specular_sample(&self, t: &Tracer<'_>, r: &mut RayState, s: &Shading) {
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
    fn transmitted_sample(&self, t: &Tracer<'_>, r: &mut RayState, s: &Shading) {
        let Some(u) = perpendicular(s.normal) else {
            return;
        };
        let v = s.normal.cross(u);
        let Some(mut child) = t.spawn(r, RayKind::SPECULAR, Some(s.color * s.tspec)) else {
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
            child.dir = s.ray_dir + (u * phi.cos() + v * phi.sin()) * d;
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
            self.trans <= FTINY
        } else {
            self.trans >= 1.0 - FTINY
        };
        if wrong_side {
            return out;
        }
        let (mut lrdiff, mut ltdiff) = (self.rdiff, self.tdiff);
        if self.pure && self.rspec >= FRESNEL_THRESHOLD && (lrdiff > FTINY || ltdiff > FTINY) {
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
            let g = ((2.0 * self.ray_dir.dot(ldir) - 2.0) / a2).exp() / (PI * a2);
            if g > FTINY {
                out += self.color * (g * self.tspec * omega * (-ldot / self.pdot).sqrt());
            }
        }
        out
    }
}
