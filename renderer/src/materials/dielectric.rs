//! `dielectric` and `interface` (dielectric.c): a boundary between media that refracts
//! by Snell's law and reflects by Fresnel's equations (averaged over polarizations);
//! total internal reflection beyond the critical angle. The transmission colours are per
//! unit distance: rays inside absorb along their length.

use crate::integrator::{RayKind, RayState, Tracer};
use crate::math::{Color, FTINY, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Dielectric {
    /// Transmission per unit length inside (the side the normal points away from).
    pub inside: Color,
    /// Refractive index inside relative to outside.
    pub index: f64,
    /// `interface`: transmission per unit length of the outside medium (a plain
    /// dielectric has the scene's medium, `-me`).
    pub outside: Option<Color>,
}

/// Extinction coefficient for a transmission per unit length (dielectric.c's `mylog`).
fn extinction(c: Color) -> Color {
    let k = |x: f64| {
        if x < 1e-40 {
            100.0
        } else if x >= 1.0 {
            0.0
        } else {
            -x.ln()
        }
    };
    Color::new(k(c.x), k(c.y), k(c.z))
}

impl Dielectric {
    pub fn shade(&self, t: &Tracer<'_>, r: &mut RayState) {
        let mut cos1 = r.rod;
        let mut normal = r.normal;
        let flat = r.hit_is_flat(t.scene());
        let mut nratio = self.index;
        let refracted_extinction;
        if cos1 < 0.0 {
            // Leaving: this ray travelled inside.
            cos1 = -cos1;
            normal = -normal;
            r.extinction = extinction(self.inside);
            refracted_extinction = self.outside.map_or(t.options().medium, extinction);
        } else {
            nratio = 1.0 / nratio;
            refracted_extinction = extinction(self.inside);
            if let Some(out) = self.outside {
                r.extinction = extinction(out);
            }
        }
        let d2 = 1.0 - nratio * nratio * (1.0 - cos1 * cos1);
        let reflectance = if d2 < FTINY {
            1.0 // total internal reflection
        } else {
            let cos2 = d2.sqrt();
            let te = (cos1 - nratio * cos2) / (cos1 + nratio * cos2);
            let tm = (1.0 / cos1 - nratio / cos2) / (1.0 / cos1 + nratio / cos2);
            let refl = 0.5 * (te * te + tm * tm);
            // Transmitted radiance grows as the solid angle narrows.
            let trans = (1.0 - refl) * nratio * nratio;
            if let Some(mut child) = t.spawn(r, RayKind::REFRACTED, Some(Color::splat(trans))) {
                child.dir = r.dir * nratio + normal * (nratio * cos1 - cos2);
                normalize(&mut child.dir);
                child.extinction = refracted_extinction;
                t.trace(&mut child);
                r.color += child.color * child.coef;
                if flat || (1.0 - FTINY..=1.0 + FTINY).contains(&nratio) {
                    r.other_length = r.length + child.effective_length();
                }
            }
            refl
        };
        if r.kind.any(RayKind::SHADOW) {
            return;
        }
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(Color::splat(reflectance)))
        else {
            return;
        };
        child.dir = r.dir + normal * (2.0 * cos1);
        normalize(&mut child.dir);
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        r.mirror_length = r.length;
        if flat {
            r.mirror_length += child.effective_length();
        }
    }
}
