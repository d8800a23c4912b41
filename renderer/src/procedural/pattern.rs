//! Patterns (p_func.c): a `brightfunc` scales the colour a material or light is shaded
//! with by one expression's value, a `colorfunc` multiplies it by three. Radiance keeps
//! that colour (`pcol`) in single precision; so does this.

use radc_lang::transform::Transform;

use super::channels::{Channels, RayView};
use super::{Functions, ProgramId, RayInput};
use crate::math::{Color, Vec3};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatternKind {
    Bright,
    Color,
    /// `texfunc` (t_func.c): three expressions displace the surface normal.
    Texture,
}

/// One pattern primitive, ready to evaluate.
#[derive(Clone, Debug)]
pub struct Pattern {
    /// `type 'name'`, for messages.
    pub who: String,
    pub kind: PatternKind,
    pub program: ProgramId,
    /// Its expressions' indices in the program (one, or red, green, blue).
    pub exprs: Vec<usize>,
    /// Its real arguments (`arg(n)`, `A1`...).
    pub args: Vec<f64>,
    /// The inverse of its transform, scale made positive (func.c's `bxp`).
    pub inverse: Transform,
    /// Its transform (`fxp`), for a texture's displacement; `None` for none.
    pub forward: Option<Transform>,
}

impl Pattern {
    /// Multiplies `pcol` by this pattern's value for the ray, as `p_bfunc`/`p_cfunc`
    /// do, or adds a texture's displacement to `pert` (`t_func`); leaves both
    /// unchanged where the evaluation raised an error.
    pub fn apply(
        &self,
        functions: &Functions,
        index: u32,
        ray: &RayView,
        pcol: &mut Color,
        pert: &mut Vec3,
    ) {
        let channels = Channels::new(ray, &self.inverse);
        let mut input = RayInput {
            channels: &channels,
            args: &self.args,
        };
        let mut v = [0.0; 3];
        let n = self.exprs.len().min(3);
        if functions
            .eval(index, self.program, &self.exprs, &mut input, &mut v[..n])
            .is_none()
        {
            return;
        }
        // `scalescolor`/`smultscolor` on a float colour: each product rounded to float.
        let f = |c: f64, by: f64| f64::from((c * by) as f32);
        *pcol = match self.kind {
            PatternKind::Bright => Color::new(f(pcol.x, v[0]), f(pcol.y, v[0]), f(pcol.z, v[0])),
            PatternKind::Color => Color::new(
                f(pcol.x, f64::from(v[0] as f32)),
                f(pcol.y, f64::from(v[1] as f32)),
                f(pcol.z, f64::from(v[2] as f32)),
            ),
            PatternKind::Texture => {
                // The displacement turns (and scales) with the texture (`multv3` by
                // `fxp`).
                let d = match &self.forward {
                    Some(xf) => xf.vector(v),
                    None => v,
                };
                *pert += Vec3::new(d[0], d[1], d[2]);
                return;
            }
        };
    }
}
