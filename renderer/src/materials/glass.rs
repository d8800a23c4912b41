//! `glass` (glass.c): a thin pane, both surfaces at once. Transmission and reflection
//! follow the Fresnel equations for each polarization with the infinite series of
//! reflections between the two faces summed in closed form; the colour is the
//! transmission at normal incidence, attenuated along the longer path at an angle.

use crate::integrator::{RayKind, RayState, Tracer};
use crate::math::{Color, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Glass {
    pub transmission: Color,
    pub index: f64,
}

impl Glass {
    pub fn shade(&self, t: &Tracer<'_>, r: &mut RayState) {
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
        if r.rod < 0.0 {
            r.flip();
        }
        let pdot = r.rod;
        let cos2 = ((1.0 - 1.0 / (n * n)) + pdot * pdot / (n * n)).sqrt();
        if transmits {
            color = Color::new(
                color.x.powf(1.0 / cos2),
                color.y.powf(1.0 / cos2),
                color.z.powf(1.0 / cos2),
            );
        }
        // Fresnel reflectances for the two polarizations.
        let r1e = ((pdot - n * cos2) / (pdot + n * cos2)).powi(2);
        let r1m = ((1.0 / pdot - n / cos2) / (1.0 / pdot + n / cos2)).powi(2);
        if transmits {
            let through = |d: f64| {
                0.5 * (1.0 - r1e).powi(2) * d / (1.0 - r1e * r1e * d * d)
                    + 0.5 * (1.0 - r1m).powi(2) * d / (1.0 - r1m * r1m * d * d)
            };
            let coef = Color::new(through(color.x), through(color.y), through(color.z));
            if let Some(mut child) = t.spawn(r, RayKind::TRANS, Some(coef)) {
                child.dir = r.dir;
                t.trace(&mut child);
                r.color += child.color * child.coef;
                r.other_length = r.length + child.effective_length();
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
        child.dir = r.dir + r.normal * (2.0 * pdot);
        normalize(&mut child.dir);
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        r.mirror_length = r.length;
        if r.hit_is_flat(t.scene()) {
            r.mirror_length += child.effective_length();
        }
    }
}
