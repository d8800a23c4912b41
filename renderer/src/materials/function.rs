//! Function and data materials (m_brdf.c `m_brdf2`): `plasfunc`, `metfunc`,
//! `transfunc` and their data forms `plasdata`, `metdata`, `transdata`. The diffuse
//! part is plastic's, metal's or trans's (the colour times one minus the specular and
//! transmitted parts); the specular part is the material's function of the light's
//! direction, so it applies to light sources only: there is no mirror ray and no
//! sampled highlight, and indirect light is diffuse. The specular part is coloured by
//! the material for metfunc (reflection) and transfunc (transmission). They are always
//! opaque to shadow rays. Surfaces are two-sided as plastic's are.

use std::f64::consts::PI;

use super::ShadingContext;
use super::plastic::perturbed_normal;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3};
use crate::procedural::ShadeState;

/// Which of the three it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum FunctionKind {
    Plastic,
    Metal,
    Trans,
}

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FunctionMaterial {
    pub kind: FunctionKind,
    /// The material's colour, times the patterns' at the hit being shaded.
    pub color: Color,
    pub spec: f64,
    /// `transfunc`: the transmitted fraction of what is not reflected specularly, and
    /// the specular fraction of that (zero for the others).
    pub transmission: f64,
    pub transmitted_specular: f64,
    /// The pattern that evaluates its function (`procedural::PatternKind::Brdf`).
    pub pattern: u32,
    /// The normal's perturbation at the hit being shaded (see `Plastic::texture`).
    #[serde(skip)]
    pub texture: Vec3,
}

impl FunctionMaterial {
    pub fn shade<C: ShadingContext + ?Sized>(&self, ctx: &C, r: &mut RayState) {
        if r.kind.any(RayKind::SHADOW) {
            return; // always a shadow
        }
        let mut pert = self.texture;
        if r.rod < 0.0 {
            if !ctx.options().backface_visible {
                return ctx.transmit(r);
            }
            r.flip();
            pert = -pert;
        }
        let spec = self.spec;
        let (trans, tspec) = match self.kind {
            FunctionKind::Trans => {
                let trans = self.transmission * (1.0 - spec);
                (trans, trans * self.transmitted_specular)
            }
            _ => (0.0, 0.0),
        };
        let rdiff = self.color * (1.0 - trans - spec);
        let tdiff = self.color * (trans - tspec);
        let (normal, cos) = perturbed_normal(r, pert);
        if trans < 1.0 - FTINY {
            r.color += ctx.ambient(r, self.color * (1.0 - trans), normal);
        }
        if trans > FTINY {
            r.color += ctx.ambient(r, self.color * trans, -normal);
        }
        let view = r.view();
        let shade = ShadeState {
            normal,
            cos,
            color: self.color,
        };
        let kind = self.kind;
        let color = self.color;
        let pattern = self.pattern;
        ctx.direct(r, &|dir, omega| {
            let ldot = normal.dot(dir);
            if (-FTINY..=FTINY).contains(&ldot) {
                return Color::ZERO; // too close to grazing
            }
            if if ldot < 0.0 {
                trans <= FTINY
            } else {
                trans >= 1.0 - FTINY
            } {
                return Color::ZERO; // wrong side
            }
            let mut c = if ldot > 0.0 {
                rdiff * (ldot * omega / PI)
            } else {
                tdiff * (-ldot * omega / PI)
            };
            if (ldot > 0.0 && spec <= FTINY) || (ldot < 0.0 && tspec <= FTINY) {
                return c; // diffuse only
            }
            let Some(v) = ctx.brdf(pattern, &view, &shade, dir, omega) else {
                return c;
            };
            if v <= FTINY {
                return c;
            }
            let mut s = Color::splat(v);
            if ldot > 0.0 {
                if kind == FunctionKind::Metal {
                    s *= color;
                }
                c += s * (ldot * omega * spec);
            } else {
                if kind == FunctionKind::Trans {
                    s *= color;
                }
                c += s * (-ldot * omega * tspec);
            }
            c
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};

    fn material(kind: FunctionKind) -> FunctionMaterial {
        FunctionMaterial {
            kind,
            color: Color::new(0.5, 0.4, 0.3),
            spec: 0.2,
            transmission: 0.5,
            transmitted_specular: 0.5,
            pattern: 0,
            texture: Vec3::ZERO,
        }
    }

    /// A source straight above, 0.01 sr of radiance 100: diffuse plus the function's
    /// value times the specularity.
    #[test]
    fn the_function_gives_the_specular_part_toward_sources() {
        let source = Some((Vec3::Z, 0.01, Color::splat(100.0)));
        let ctx = Scripted {
            source,
            brdf_value: Some(2.0),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        material(FunctionKind::Plastic).shade(&ctx, &mut r);
        let diffuse = Color::new(0.5, 0.4, 0.3) * (0.8 * 0.01 / PI) * 100.0;
        let specular = Color::splat(2.0 * 0.01 * 0.2 * 100.0);
        assert!((r.color - (diffuse + specular)).abs().max_element() < 1e-12);
        let calls = ctx.brdf_calls.borrow();
        assert_eq!(calls.len(), 1);
        assert_eq!(
            (calls[0].0, calls[0].1, calls[0].2),
            (Vec3::Z, Vec3::Z, 0.01)
        );
    }

    #[test]
    fn metal_colours_the_specular_part_and_no_value_leaves_the_diffuse() {
        let source = Some((Vec3::Z, 0.01, Color::splat(100.0)));
        let ctx = Scripted {
            source,
            brdf_value: Some(1.0),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        material(FunctionKind::Metal).shade(&ctx, &mut r);
        let c = Color::new(0.5, 0.4, 0.3);
        let want = c * (0.8 * 0.01 / PI) * 100.0 + c * (0.01 * 0.2 * 100.0);
        assert!((r.color - want).abs().max_element() < 1e-12);
        let ctx = Scripted {
            source,
            brdf_value: None,
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        material(FunctionKind::Metal).shade(&ctx, &mut r);
        assert!(
            (r.color - c * (0.8 * 0.01 / PI) * 100.0)
                .abs()
                .max_element()
                < 1e-12
        );
    }

    #[test]
    fn trans_lights_from_behind_and_shadows_see_nothing() {
        // A source below the surface: the transmitted parts.
        let source = Some((-Vec3::Z, 0.01, Color::splat(100.0)));
        let ctx = Scripted {
            source,
            brdf_value: Some(1.0),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        material(FunctionKind::Trans).shade(&ctx, &mut r);
        let c = Color::new(0.5, 0.4, 0.3);
        let (trans, tspec) = (0.5 * 0.8, 0.5 * 0.8 * 0.5);
        let want = c * ((trans - tspec) * 0.01 / PI * 100.0) + c * (0.01 * tspec * 100.0);
        assert!((r.color - want).abs().max_element() < 1e-12);
        let mut shadow = hit(Vec3::new(0.0, 0.0, -1.0));
        shadow.kind = RayKind::SHADOW;
        material(FunctionKind::Trans).shade(&ctx, &mut shadow);
        assert_eq!(shadow.color, Color::ZERO);
    }
}
