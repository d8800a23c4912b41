//! `dielectric` and `interface` (dielectric.c): a boundary between media that refracts
//! by Snell's law and reflects by Fresnel's equations (averaged over polarizations);
//! total internal reflection beyond the critical angle. The transmission colours are per
//! unit distance: rays inside absorb along their length.

use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Dielectric {
    /// Transmission per unit length inside (the side the normal points away from).
    pub inside: Color,
    /// Refractive index inside relative to outside.
    pub index: f64,
    /// `interface`: transmission per unit length of the outside medium (a plain
    /// dielectric has the scene's medium, `-me`).
    pub outside: Option<Color>,
    /// The patterns' colour at the hit being shaded, which multiplies the transmissions,
    /// and the texture's perturbation (see `Plastic::texture`).
    #[serde(skip, default = "super::one")]
    pub pattern_color: Color,
    #[serde(skip)]
    pub texture: Vec3,
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
    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        // dielectric.c's `hastexture`: 1 with a texture, its sign turned for rays
        // leaving, so the accidental-reflection tests look from the ray's side.
        let mut textured: f64 = if self.texture.dot(self.texture) > FTINY * FTINY {
            1.0
        } else {
            0.0
        };
        let (mut normal, mut cos1) = if textured != 0.0 {
            super::plastic::perturbed_normal(r, self.texture)
        } else {
            (r.normal, r.rod)
        };
        let flat = t.hit_is_flat(r) && (textured == 0.0 || r.kind.any(RayKind::AMBIENT));
        let mut nratio = self.index;
        let (inside, outside) = (
            self.inside * self.pattern_color,
            self.outside.map(|o| o * self.pattern_color),
        );
        let refracted_extinction;
        if cos1 < 0.0 {
            // Leaving: this ray travelled inside.
            textured = -textured;
            cos1 = -cos1;
            normal = -normal;
            r.extinction = extinction(inside);
            refracted_extinction = outside.map_or(t.options().medium, extinction);
        } else {
            nratio = 1.0 / nratio;
            refracted_extinction = extinction(inside);
            if let Some(out) = outside {
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
                let d1 = nratio * cos1 - cos2;
                child.dir = r.dir * nratio + normal * d1;
                // A texture may turn the refraction back out: then it is ignored.
                if textured != 0.0 && child.dir.dot(r.normal) * textured >= -FTINY {
                    child.dir = r.dir * nratio + r.normal * (d1 * textured);
                }
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
        // ... and the reflection under the surface: then off the unperturbed normal.
        if textured != 0.0 && child.dir.dot(r.normal) * textured <= FTINY {
            child.dir = r.dir + r.normal * (2.0 * r.rod);
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};
    use crate::math::Vec3;

    fn water() -> Dielectric {
        Dielectric {
            inside: Color::ONE,
            index: 1.33,
            outside: None,
            pattern_color: Color::ONE,
            texture: Vec3::ZERO,
        }
    }

    #[test]
    fn a_ray_entering_refracts_by_snells_law() {
        let t = Scripted::default();
        let dir = Vec3::new(0.5, 0.0, -1.0).normalize();
        let mut r = hit(dir);
        water().shade(&t, &mut r);
        let traced = t.traced.borrow();
        let (kind, refracted, _) = traced[0];
        assert!(kind.any(RayKind::REFRACTED));
        let sin_in = dir.x;
        assert!((refracted.x - sin_in / 1.33).abs() < 1e-12, "{refracted:?}");
        let (_, _, reflected) = traced[1];
        assert!(reflected.x > 0.0 && reflected.x < 0.1);
    }

    #[test]
    fn beyond_the_critical_angle_all_light_is_reflected() {
        let t = Scripted::default();
        // Leaving the water (hitting the back) at 60 degrees, past asin(1/1.33).
        let dir = Vec3::new(60f64.to_radians().sin(), 0.0, 60f64.to_radians().cos());
        let mut r = hit(dir);
        water().shade(&t, &mut r);
        let traced = t.traced.borrow();
        assert_eq!(traced.len(), 1, "no refracted ray");
        let (kind, d, coef) = traced[0];
        assert!(kind.any(RayKind::REFLECTED));
        assert_eq!(coef, Color::ONE);
        assert!(d.z < 0.0, "reflected back inside: {d:?}");
    }
}
