//! Patterns (p_func.c, p_data.c): a `brightfunc` scales the colour a material or light
//! is shaded with by one expression's value, a `colorfunc` multiplies it by three; the
//! data and picture patterns find their value(s) in a file first. Radiance keeps that
//! colour (`pcol`) in single precision; so does this. A mixture (mx_func.c, mx_data.c:
//! `mixfunc`, `mixdata`, `mixpict`) computes a coefficient the same ways; between
//! patterns and textures it is applied here (raytrace.c `raymixture`: each side's chain
//! on its own copy of `pcol` and `pert`, then the two blended), between materials the
//! tracer shades both and blends the results.

use radc_lang::transform::Transform;

use super::brdf::{BrdfLookup, BrtdLookup};
use super::channels::{Channels, RayView};
use super::data::DataLookup;
use super::picture::PictureLookup;
use super::{Functions, ProgramId, RayInput};
use crate::math::{Color, FTINY, Vec3};

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
    /// A mixture: its coefficient from `source`; between patterns, the chains of the
    /// two sides (nearest first; empty for `void`); between materials both are empty
    /// and the tracer shades the sides.
    Mixture {
        source: MixSource,
        fore: Vec<u32>,
        back: Vec<u32>,
    },
    /// A function or data material's function (its expressions are a data form's
    /// coordinate calls), evaluated per light sample by the material.
    Brdf(BrdfLookup),
    /// An anisotropic material's orientation: three expressions, turned by the
    /// transform (aniso.c `getacoords`: `multv3` by `fxp`, no scale division).
    Orientation,
    /// A BRTDfunc's six coefficient expressions (the pattern's) and directional
    /// functions, evaluated by the material.
    Brtd(BrtdLookup),
}

/// Where a mixture's coefficient comes from.
#[derive(Clone, Debug)]
pub enum MixSource {
    /// `mixfunc`: one expression.
    Function,
    /// `mixdata`: a data file's value through a function of one argument.
    Data(DataLookup),
    /// `mixpict`: a picture's three channels through a function of them.
    Picture(PictureLookup),
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
    /// The pattern's value(s) for the ray (one, or three), `None` on a compute error.
    fn values(&self, functions: &Functions, index: u32, channels: &Channels) -> Option<[f64; 3]> {
        let (program, coords, args) = (self.program, &self.exprs[..], &self.args[..]);
        match &self.kind {
            PatternKind::Bright
            | PatternKind::Color
            | PatternKind::Texture
            | PatternKind::Orientation
            | PatternKind::Mixture {
                source: MixSource::Function,
                ..
            } => {
                let mut input = RayInput {
                    channels,
                    args,
                    data: &[],
                };
                let mut v = [0.0; 3];
                let n = self.exprs.len().min(3);
                functions
                    .eval(index, program, coords, &mut input, &mut v[..n])
                    .map(|()| v)
            }
            PatternKind::BrightData(d)
            | PatternKind::ColorData(d)
            | PatternKind::TextureData(d)
            | PatternKind::Mixture {
                source: MixSource::Data(d),
                ..
            } => d.values(functions, index, program, coords, channels, args),
            PatternKind::ColorPict(p)
            | PatternKind::Mixture {
                source: MixSource::Picture(p),
                ..
            } => p.values(functions, index, program, coords, channels, args),
            PatternKind::Brdf(_) | PatternKind::Brtd(_) => None,
        }
    }

    /// The three values of an orientation pattern for the ray, turned by its transform.
    pub fn vector(&self, functions: &Functions, index: u32, ray: &RayView) -> Option<[f64; 3]> {
        let channels = Channels::new(ray, &self.inverse);
        let v = self.values(functions, index, &channels)?;
        Some(match &self.forward {
            Some(xf) => xf.vector(v),
            None => v,
        })
    }

    /// A mixture's coefficient for the ray, before bounding (`None`: a compute error,
    /// after which mx_func.c leaves the ray to the mixture's own modifier).
    pub fn coefficient(&self, functions: &Functions, index: u32, ray: &RayView) -> Option<f64> {
        let channels = Channels::new(ray, &self.inverse);
        self.values(functions, index, &channels).map(|v| v[0])
    }

    /// Multiplies `pcol` by this pattern's value for the ray, as `p_bfunc`/`p_cfunc`
    /// do, adds a texture's displacement to `pert` (`t_func`), or blends what the two
    /// sides of a mixture make of them; leaves both unchanged where the evaluation
    /// raised an error.
    pub fn apply(
        &self,
        functions: &Functions,
        index: u32,
        ray: &RayView,
        pcol: &mut Color,
        pert: &mut Vec3,
    ) {
        let channels = Channels::new(ray, &self.inverse);
        let v = self.values(functions, index, &channels);
        let Some(v) = v else { return };
        // `scalescolor`/`smultscolor` on a float colour: each product rounded to float
        // (a colour pattern's values are a float COLOR first).
        let f = |c: f64, by: f64| f64::from((c * by) as f32);
        *pcol = match &self.kind {
            PatternKind::Bright | PatternKind::BrightData(_) => {
                // `scalescolor` makes its factor single precision first.
                let b = f64::from(v[0] as f32);
                Color::new(f(pcol.x, b), f(pcol.y, b), f(pcol.z, b))
            }
            PatternKind::Color | PatternKind::ColorData(_) | PatternKind::ColorPict(_) => {
                Color::new(
                    f(pcol.x, f64::from(v[0] as f32)),
                    f(pcol.y, f64::from(v[1] as f32)),
                    f(pcol.z, f64::from(v[2] as f32)),
                )
            }
            PatternKind::Mixture { fore, back, .. } => {
                let coef = bounded(v[0]);
                let side = |chain: &[u32], used: bool| {
                    let (mut c, mut p) = (*pcol, *pert);
                    if used {
                        for &i in chain {
                            if let Some(pattern) = functions.patterns.get(i as usize) {
                                pattern.apply(functions, i, ray, &mut c, &mut p);
                            }
                        }
                    }
                    (c, p)
                };
                let (fc, fp) = side(fore, coef > FTINY);
                let (bc, bp) = side(back, coef < 1.0 - FTINY);
                *pert = fp * coef + bp * (1.0 - coef);
                // scalescolor on each side (its factor made single precision), then
                // saddscolor: floats throughout.
                let (cf, cb) = (f64::from(coef as f32), f64::from((1.0 - coef) as f32));
                let mix = |a: f64, b: f64| f64::from((f(a, cf) as f32) + (f(b, cb) as f32));
                Color::new(mix(fc.x, bc.x), mix(fc.y, bc.y), mix(fc.z, bc.z))
            }
            PatternKind::Brdf(_) | PatternKind::Brtd(_) | PatternKind::Orientation => return,
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

/// raymixture's bounds on a coefficient: above 1 is 1, below 0 is 0 (a NaN stays).
pub fn bounded(coef: f64) -> f64 {
    coef.clamp(0.0, 1.0)
}
