//! Patterns (p_func.c, p_data.c): a `brightfunc` scales the colour a material or light
//! is shaded with by one expression's value, a `colorfunc` multiplies it by three; the
//! data and picture patterns find their value(s) in a file first. Radiance keeps that
//! colour (`pcol`) in single precision; so does this.

use radc_lang::transform::Transform;

use super::channels::{Channels, RayView};
use super::data::DataLookup;
use super::picture::PictureLookup;
use super::{Functions, ProgramId, RayInput};
use crate::math::{Color, Vec3};

/// What a pattern computes its value(s) from, with what that takes.
#[derive(Clone, Debug)]
pub enum PatternKind {
    Bright,
    Color,
    /// `texfunc` (t_func.c): three expressions displace the surface normal.
    Texture,
    /// `brightdata`: the pattern's expressions are the data coordinates.
    BrightData(DataLookup),
    /// `colordata`: likewise, three files.
    ColorData(DataLookup),
    /// `texdata` (t_data.c): the data files' values, through its functions, displace
    /// the normal as a texfunc's expressions do.
    TextureData(DataLookup),
    /// `colorpict`: the expressions are the picture coordinates.
    ColorPict(PictureLookup),
}

/// One pattern primitive, ready to evaluate.
#[derive(Clone, Debug)]
pub struct Pattern {
    /// `type 'name'`, for messages.
    pub who: String,
    pub kind: PatternKind,
    pub program: ProgramId,
    /// Its expressions' indices in the program (one, or red, green, blue; for data
    /// and picture patterns, the coordinates).
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
        let (program, coords, args) = (self.program, &self.exprs[..], &self.args[..]);
        let v = match &self.kind {
            PatternKind::Bright | PatternKind::Color | PatternKind::Texture => {
                let mut input = RayInput {
                    channels: &channels,
                    args,
                    data: &[],
                };
                let mut v = [0.0; 3];
                let n = self.exprs.len().min(3);
                functions
                    .eval(index, program, coords, &mut input, &mut v[..n])
                    .map(|()| v)
            }
            PatternKind::BrightData(d) | PatternKind::ColorData(d) | PatternKind::TextureData(d) => {
                d.values(functions, index, program, coords, &channels, args)
            }
            PatternKind::ColorPict(p) => {
                p.values(functions, index, program, coords, &channels, args)
            }
        };
        let Some(v) = v else { return };
        // `scalescolor`/`smultscolor` on a float colour: each product rounded to float
        // (a colour pattern's values are a float COLOR first).
        let f = |c: f64, by: f64| f64::from((c * by) as f32);
        *pcol = match self.kind {
            PatternKind::Bright | PatternKind::BrightData(_) => {
                Color::new(f(pcol.x, v[0]), f(pcol.y, v[0]), f(pcol.z, v[0]))
            }
            PatternKind::Color | PatternKind::ColorData(_) | PatternKind::ColorPict(_) => {
                Color::new(
                    f(pcol.x, f64::from(v[0] as f32)),
                    f(pcol.y, f64::from(v[1] as f32)),
                    f(pcol.z, f64::from(v[2] as f32)),
                )
            }
            PatternKind::Texture | PatternKind::TextureData(_) => {
                // The displacement turns with the texture (`multv3` by `fxp`) and is
                // divided by its scale (`VSUM(pert, pert, disp, 1/sca)`), so only the
                // rotation and mirroring remain.
                let (d, by) = match &self.forward {
                    Some(xf) => (xf.vector(v), 1.0 / xf.scale),
                    None => (v, 1.0),
                };
                *pert += Vec3::new(d[0] * by, d[1] * by, d[2] * by);
                return;
            }
        };
    }
}
