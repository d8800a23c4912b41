//! `BRTDfunc` (m_brdf.c `m_brdf`): the most general function material. Six expressions
//! give the colours of a mirror ray and of a straight-through ray, the reals a diffuse
//! reflectance for each side and a diffuse transmittance, and up to three functions of
//! the light's direction a directional part toward light sources. Unlike the other
//! function materials its normal is not turned toward the ray: the front and back
//! reflectances differ, and the functions see the side the ray is on.

use std::f64::consts::PI;

use super::ShadingContext;
use super::plastic::perturbed_normal;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, brightness, intensity, normalize};
use crate::procedural::ShadeState;

/// What a BRTDfunc asks its functions for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BrtdPart {
    /// The mirror ray's colour (its first three expressions).
    Mirror,
    /// The straight-through ray's colour (the next three).
    Straight,
    /// The directional part for light from a direction of a solid angle.
    Directional(Vec3, f64),
}

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Brtd {
    pub front_diffuse: Color,
    pub back_diffuse: Color,
    pub transmitted_diffuse: Color,
    /// Whether the red directional function is not `0` (m_brdf: then the light loop
    /// runs even without diffuse parts).
    pub directional: bool,
    /// The pattern that evaluates its expressions (`procedural::PatternKind::Brtd`).
    pub pattern: u32,
    /// The patterns' colour and the texture's perturbation at the hit being shaded.
    #[serde(skip, default = "super::one")]
    pub pattern_color: Color,
    #[serde(skip)]
    pub texture: Vec3,
}

impl Brtd {
    /// Radiance's `istransp` for BRTDfunc: a straight-through expression other than
    /// `0` makes it transparent (set by the scene compiler).
    pub fn shade<C: ShadingContext + ?Sized>(&self, ctx: &C, r: &mut RayState) {
        let mut rdiff = if r.rod > 0.0 {
            self.front_diffuse
        } else {
            self.back_diffuse
        };
        let mut tdiff = self.transmitted_diffuse;
        let mut pert = self.texture;
        let textured = pert.dot(pert) > FTINY * FTINY;
        let (mut normal, mut cos) = if textured {
            perturbed_normal(r, pert)
        } else {
            (r.normal, r.rod)
        };
        if r.rod < 0.0 {
            cos = -cos;
            normal = -normal;
            pert = -pert;
        }
        let mcolor = self.pattern_color;
        rdiff *= mcolor;
        tdiff *= mcolor;
        let reflects = intensity(rdiff) > FTINY;
        let transmits = intensity(tdiff) > FTINY;
        let view = r.view();
        let shade = ShadeState {
            normal,
            cos,
            color: mcolor,
        };
        let shadow_or_ambient = r.kind.any(RayKind::SHADOW) || r.kind.any(RayKind::AMBIENT);
        if let Some(coef) = ctx.brtd(self.pattern, &view, &shade, BrtdPart::Straight)
            && let Some(mut child) = ctx.spawn(r, RayKind::TRANS, Some(coef))
        {
            child.dir = r.dir;
            if textured && !shadow_or_ambient {
                let mut d = r.dir - pert;
                if normalize(&mut d) != 0.0 {
                    child.dir = d;
                }
            }
            ctx.trace(&mut child);
            r.color += child.color * child.coef;
            if (!textured || shadow_or_ambient) && 1.0 > brightness(tdiff) + brightness(rdiff) {
                r.other_length = r.length + child.effective_length();
            }
        }
        if r.kind.any(RayKind::SHADOW) {
            return;
        }
        if let Some(coef) = ctx.brtd(self.pattern, &view, &shade, BrtdPart::Mirror)
            && let Some(mut child) = ctx.spawn(r, RayKind::REFLECTED, Some(coef))
        {
            child.dir = r.dir + normal * (2.0 * cos);
            normalize(&mut child.dir);
            ctx.trace(&mut child);
            let c = child.color * child.coef;
            r.mirror_color = c;
            r.color += c;
            r.mirror_length = r.length;
            if ctx.hit_is_flat(r) && (!textured || r.kind.any(RayKind::AMBIENT)) {
                r.mirror_length += child.effective_length();
            }
        }
        if reflects {
            r.color += ctx.ambient(r, rdiff, normal);
        }
        if transmits {
            r.color += ctx.ambient(r, tdiff, -normal);
        }
        if !(reflects || transmits || self.directional) {
            return;
        }
        let pattern = self.pattern;
        ctx.direct(r, &|dir, omega| {
            let ldot = normal.dot(dir);
            if (-FTINY..=FTINY).contains(&ldot) {
                return Color::ZERO;
            }
            let mut c = if ldot > 0.0 {
                rdiff * (ldot * omega / PI)
            } else {
                tdiff * (-ldot * omega / PI)
            };
            let Some(d) = ctx.brtd(pattern, &view, &shade, BrtdPart::Directional(dir, omega))
            else {
                return c;
            };
            if brightness(d) <= FTINY {
                return c;
            }
            c += d * (ldot.abs() * omega);
            c
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};

    fn brtd() -> Brtd {
        Brtd {
            front_diffuse: Color::splat(0.2),
            back_diffuse: Color::splat(0.1),
            transmitted_diffuse: Color::splat(0.3),
            directional: true,
            pattern: 0,
            pattern_color: Color::ONE,
            texture: Vec3::ZERO,
        }
    }

    /// The straight and mirror rays carry the expressions' colours; the directional
    /// part adds the functions' value times the solid angle and cosine.
    #[test]
    fn rays_and_light_take_the_expressions_and_functions() {
        let ctx = Scripted {
            seen: Color::splat(2.0),
            source: Some((Vec3::Z, 0.01, Color::splat(100.0))),
            brtd_value: Some(Color::splat(0.5)),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        brtd().shade(&ctx, &mut r);
        let traced = ctx.traced.borrow();
        assert_eq!(traced.len(), 2);
        assert!(traced[0].0.any(RayKind::TRANS) && traced[1].0.any(RayKind::REFLECTED));
        // Straight and mirror rays: .5 * 2 each; direct: (.2 / pi + .5) * .01 * 100.
        let want = 2.0 * 0.5 * 2.0 + (0.2 / PI + 0.5) * 0.01 * 100.0;
        assert!(
            (r.color - Color::splat(want)).abs().max_element() < 1e-12,
            "{:?}",
            r.color
        );
    }

    #[test]
    fn the_back_has_its_own_reflectance_and_shadows_see_only_the_straight_ray() {
        let ctx = Scripted {
            source: Some((-Vec3::Z, 0.01, Color::splat(100.0))),
            brtd_value: None,
            ..Scripted::default()
        };
        // From below: the back's diffuse reflectance toward a source below.
        let mut r = hit(Vec3::new(0.0, 0.0, 1.0));
        brtd().shade(&ctx, &mut r);
        assert!(
            (r.color - Color::splat(0.1 * 0.01 / PI * 100.0))
                .abs()
                .max_element()
                < 1e-12
        );
        let ctx = Scripted {
            seen: Color::splat(2.0),
            brtd_value: Some(Color::splat(0.25)),
            ..Scripted::default()
        };
        let mut shadow = hit(Vec3::new(0.0, 0.0, -1.0));
        shadow.kind = RayKind::SHADOW;
        brtd().shade(&ctx, &mut shadow);
        assert_eq!(shadow.color, Color::splat(0.5));
        assert_eq!(ctx.traced.borrow().len(), 1);
    }
}
