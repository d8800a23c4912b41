//! Mixtures of materials (raytrace.c `raymixture`, reached from mx_func.c and
//! mx_data.c): `mixfunc`, `mixdata` or `mixpict` whose sides are materials. The ray is
//! shaded twice, once with each side, on copies whose weight and coefficient are scaled
//! by the bounded coefficient and its complement; a side that is `void` (or only
//! patterns) lets its copy through when the other side shades. The results are blended
//! by the coefficient, and the mirror and other lengths come from the side that
//! contributes more. Mixtures between patterns are applied with the patterns
//! (`procedural::pattern`).

use super::MaterialId;
use super::context::ShadingContext;
use crate::integrator::RayState;
use crate::math::{FTINY, brightness};
use crate::procedural::bounded;

/// A mixture of two materials; `pattern` computes its coefficient.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Mixture {
    pub pattern: u32,
    pub fore: Option<MaterialId>,
    pub back: Option<MaterialId>,
}

impl Mixture {
    pub fn shade<C: ShadingContext + ?Sized>(&self, ctx: &C, r: &mut RayState) {
        // A compute error: mx_func returns 0, and the mixture's own modifier (void)
        // shades nothing, so the ray passes.
        let Some(coef) = ctx.mixture_coefficient(self.pattern, r) else {
            return ctx.transmit(r);
        };
        let coef = bounded(coef);
        let side = |material: Option<MaterialId>, share: f64, used: bool| {
            let mut s = r.clone();
            let mut shaded = false;
            if used {
                s.weight *= share;
                s.coef *= share;
                if material.is_some() {
                    ctx.shade(&mut s, material);
                    shaded = true;
                }
            }
            (s, shaded)
        };
        let (mut fore, fore_shaded) = side(self.fore, coef, coef > FTINY);
        let (mut back, back_shaded) = side(self.back, 1.0 - coef, coef < 1.0 - FTINY);
        if fore_shaded != back_shaded {
            if back_shaded && coef > FTINY {
                ctx.transmit(&mut fore);
            } else if fore_shaded && coef < 1.0 - FTINY {
                ctx.transmit(&mut back);
            }
        }
        if !fore_shaded && !back_shaded {
            return ctx.transmit(r);
        }
        r.color = fore.color * coef + back.color * (1.0 - coef);
        let (fore_mirror, back_mirror) =
            (fore.mirror_color * coef, back.mirror_color * (1.0 - coef));
        r.mirror_color = fore_mirror + back_mirror;
        let (mf, mb) = (brightness(fore_mirror), brightness(back_mirror));
        r.mirror_length = if mf > mb {
            fore.mirror_length
        } else {
            back.mirror_length
        };
        let fore_rest = brightness(fore.color * coef) - mf;
        let back_rest = brightness(back.color * (1.0 - coef)) - mb;
        r.other_length = if fore_rest > back_rest {
            fore.other_length
        } else {
            back.other_length
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};
    use crate::math::{Color, Vec3};

    fn mix(fore: Option<u32>, back: Option<u32>) -> Mixture {
        Mixture {
            pattern: 0,
            fore: fore.map(MaterialId),
            back: back.map(MaterialId),
        }
    }

    #[test]
    fn both_sides_shade_with_scaled_weights_and_blend() {
        let ctx = Scripted {
            coefficient: Some(0.25),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        mix(Some(0), Some(1)).shade(&ctx, &mut r);
        // Material k shades k + 1: .25 * 1 + .75 * 2.
        assert_eq!(r.color, Color::splat(1.75));
        let shaded = ctx.shaded.borrow();
        assert_eq!(shaded.len(), 2);
        assert_eq!((shaded[0].0, shaded[0].1), (MaterialId(0), 0.25));
        assert_eq!((shaded[1].0, shaded[1].1), (MaterialId(1), 0.75));
        assert_eq!(shaded[1].2, Color::splat(0.75));
        // The back side contributes more: its lengths.
        assert_eq!(r.other_length, 2.0);
        assert_eq!(*ctx.transmitted.borrow(), 0);
    }

    #[test]
    fn coefficients_are_bounded_and_a_side_at_zero_is_not_shaded() {
        let ctx = Scripted {
            coefficient: Some(1.7),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        mix(Some(0), Some(1)).shade(&ctx, &mut r);
        assert_eq!(r.color, Color::splat(1.0));
        assert_eq!(ctx.shaded.borrow().len(), 1);
    }

    #[test]
    fn a_void_side_lets_its_share_through() {
        let ctx = Scripted {
            coefficient: Some(0.5),
            seen: Color::splat(4.0),
            ..Scripted::default()
        };
        let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
        mix(Some(2), None).shade(&ctx, &mut r);
        // .5 * 3 (material 2) + .5 * 4 (what the passed ray sees).
        assert_eq!(r.color, Color::splat(3.5));
        assert_eq!(*ctx.transmitted.borrow(), 1);
    }

    #[test]
    fn no_material_on_either_side_or_a_compute_error_passes_the_ray() {
        for coefficient in [Some(0.5), None] {
            let ctx = Scripted {
                coefficient,
                seen: Color::splat(4.0),
                ..Scripted::default()
            };
            let mut r = hit(Vec3::new(0.0, 0.0, -1.0));
            mix(None, None).shade(&ctx, &mut r);
            assert_eq!(r.color, Color::splat(4.0));
            assert_eq!(*ctx.transmitted.borrow(), 1);
        }
    }
}
