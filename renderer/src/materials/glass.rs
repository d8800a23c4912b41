//! `glass` (glass.c): a thin pane, both surfaces at once. Transmission and reflection
//! follow the Fresnel equations for each polarization with the infinite series of
//! reflections between the two faces summed in closed form; the colour is the
//! transmission at normal incidence, attenuated along the longer path at an angle.

use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Glass {
    pub transmission: Color,
    pub index: f64,
    /// The patterns' colour at the hit being shaded, which tints the transmitted ray
    /// only, and the texture's perturbation (see `Plastic::texture`).
    #[serde(skip, default = "super::one")]
    pub pattern_color: Color,
    #[serde(skip)]
    pub texture: Vec3,
}

impl Glass {
    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        if !t.options().backface_visible && r.rod <= 0.0 {
            return t.transmit(r);
        }
        let n = self.index;
        let mut color = self.transmission;
        let transmits = color.max_element() > 1e-15;
        if transmits {
            color = color.max(Color::splat(1e-15));
        } else if r.kind.any(RayKind::SHADOW) {
            return;
        }
        let mut pert = self.texture;
        if r.rod < 0.0 {
            r.flip();
            pert = -pert;
        }
        let textured = pert.dot(pert) > FTINY * FTINY;
        let (normal, cos_incidence) = if textured {
            super::plastic::perturbed_normal(r, pert)
        } else {
            (r.normal, r.rod)
        };
        let cos2 = ((1.0 - 1.0 / (n * n)) + cos_incidence * cos_incidence / (n * n)).sqrt();
        if transmits {
            color = Color::new(
                color.x.powf(1.0 / cos2),
                color.y.powf(1.0 / cos2),
                color.z.powf(1.0 / cos2),
            );
        }
        // Fresnel reflectances for the two polarizations.
        let r1e = ((cos_incidence - n * cos2) / (cos_incidence + n * cos2)).powi(2);
        let r1m = ((1.0 / cos_incidence - n / cos2) / (1.0 / cos_incidence + n / cos2)).powi(2);
        if transmits {
            let through = |d: f64| {
                0.5 * (1.0 - r1e).powi(2) * d / (1.0 - r1e * r1e * d * d)
                    + 0.5 * (1.0 - r1m).powi(2) * d / (1.0 - r1m * r1m * d * d)
            };
            let coef = Color::new(through(color.x), through(color.y), through(color.z))
                * self.pattern_color;
            if let Some(mut child) = t.spawn(r, RayKind::TRANS, Some(coef)) {
                child.dir = r.dir;
                let shadow_or_ambient = r.kind.any(RayKind::SHADOW | RayKind::AMBIENT);
                if textured && !shadow_or_ambient {
                    let mut d = r.dir + pert * (2.0 * (1.0 - n));
                    if normalize(&mut d) != 0.0 {
                        child.dir = d;
                    }
                }
                t.trace(&mut child);
                r.color += child.color * child.coef;
                if !textured || shadow_or_ambient {
                    r.other_length = r.length + child.effective_length();
                }
            }
        }
        if r.kind.any(RayKind::SHADOW) {
            return;
        }
        let back = |d: f64| {
            let d = d * d;
            0.5 * r1e * (1.0 + (1.0 - 2.0 * r1e) * d) / (1.0 - r1e * r1e * d)
                + 0.5 * r1m * (1.0 + (1.0 - 2.0 * r1m) * d) / (1.0 - r1m * r1m * d)
        };
        let coef = Color::new(back(color.x), back(color.y), back(color.z));
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(coef)) else {
            return;
        };
        child.dir = r.dir + normal * (2.0 * cos_incidence);
        normalize(&mut child.dir);
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        r.mirror_length = r.length;
        if t.hit_is_flat(r) && (!textured || r.kind.any(RayKind::AMBIENT)) {
            r.mirror_length += child.effective_length();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};
    use crate::math::Vec3;

    #[test]
    fn clear_glass_at_normal_incidence_splits_light_as_the_fresnel_series_sums() {
        let t = Scripted::default();
        let glass = Glass {
            transmission: Color::ONE,
            index: 1.52,
            pattern_color: Color::ONE,
            texture: Vec3::ZERO,
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        glass.shade(&t, &mut r);
        let traced = t.traced.borrow();
        assert_eq!(traced.len(), 2);
        let f: f64 = ((1.0 - 1.52) / (1.0 + 1.52_f64)).powi(2);
        let (through, reflected) = (traced[0].2.x, traced[1].2.x);
        assert!((through - (1.0 - f) / (1.0 + f)).abs() < 1e-12, "{through}");
        assert!(
            (reflected - 2.0 * f / (1.0 + f)).abs() < 1e-12,
            "{reflected}"
        );
        assert!(
            (through + reflected - 1.0).abs() < 1e-12,
            "no loss in clear glass"
        );
    }
}
