//! The functions of function and data materials (m_brdf.c `dirbrdf` for `plasfunc`,
//! `metfunc`, `transfunc`, `plasdata`, `metdata`, `transdata`): for each light source
//! sample the material's function is called with the light's direction in the
//! function's frame and its solid angle (`f(ldx, ldy, ldz, omega)`); the data forms first
//! call one function per data dimension the same way for the point to look up, then
//! the main function with the value found in front (`f(value, ldx, ldy, ldz, omega)`).
//! The shading variables m_brdf.c sets with `varset` (`NxP NyP NzP`, the perturbed
//! normal in the function's frame, `RdotP`, and the pattern-modified colour `CrP CgP
//! CbP`) reach the function file through channels after the data's.
//!
//! `BRTDfunc` (m_brdf.c `m_brdf`) has six expressions (the colours of its mirror ray and
//! of its straight-through ray) and up to three functions of the light for its
//! directional part, a `0` for none, a repeated name computed once.

use std::sync::Arc;

use radc_lang::datafile::DataFile;

use super::channels::{Channels, RayView};
use super::data::DATA_CHANNEL;
use super::{Functions, ProgramId, RayInput};
use crate::math::{Color, Vec3};

/// The light direction and solid angle arrive as `$28`..`$31`, a data value as `$32`.
pub const LIGHT_CHANNEL: u32 = DATA_CHANNEL;
pub const VALUE_CHANNEL: u32 = DATA_CHANNEL + 4;
/// `NxP`, `NyP`, `NzP`, `RdotP`, `CrP`, `CgP`, `CbP` from `$33` on.
pub const SHADE_CHANNEL: u32 = DATA_CHANNEL + 5;
pub const SHADING_VARIABLES: [&str; 7] = ["NxP", "NyP", "NzP", "RdotP", "CrP", "CgP", "CbP"];

/// A function or data material's calls, in its program.
#[derive(Clone, Debug)]
pub struct BrdfLookup {
    /// The data form's file; the pattern's expressions are then the coordinate calls.
    pub data: Option<Arc<DataFile>>,
    /// The main function's call.
    pub value: usize,
}

/// What the material works out at its hit before the light loop: the (perturbed,
/// flipped) normal and its cosine with the ray, and its pattern-modified colour.
#[derive(Clone, Copy, Debug)]
pub struct ShadeState {
    pub normal: Vec3,
    pub cos: f64,
    pub color: Color,
}

/// A BRTDfunc's directional functions, red, green, blue: an expression index, `None`
/// for `0`, or the same as an earlier channel.
#[derive(Clone, Debug)]
pub struct BrtdLookup {
    pub directional: [Directional; 3],
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Directional {
    Zero,
    Call(usize),
    SameAs(usize),
}

/// The shading variables and light arguments in the channels after the ray's.
fn extra(
    inverse: &radc_lang::transform::Transform,
    shade: &ShadeState,
    light: Option<(Vec3, f64)>,
) -> [f64; 12] {
    let turn = |v: Vec3| {
        let m = &inverse.matrix;
        let s = inverse.scale;
        [0, 1, 2].map(|j| (v.x * m[0][j] + v.y * m[1][j] + v.z * m[2][j]) / s)
    };
    let (l, omega) = light.map_or(([0.0; 3], 0.0), |(d, o)| (turn(d), o));
    let n = turn(shade.normal);
    let c = shade.color;
    [
        l[0], l[1], l[2], omega, 0.0, n[0], n[1], n[2], shade.cos, c.x, c.y, c.z,
    ]
}

impl BrtdLookup {
    /// The directional part's colour for light from `dir` of solid angle `omega`.
    #[allow(clippy::too_many_arguments)]
    pub fn directional(
        &self,
        functions: &Functions,
        pattern: u32,
        program: ProgramId,
        ray: &RayView,
        inverse: &radc_lang::transform::Transform,
        args: &[f64],
        shade: &ShadeState,
        dir: Vec3,
        omega: f64,
    ) -> Option<Color> {
        let channels = Channels::new(ray, inverse);
        let extra = extra(inverse, shade, Some((dir, omega)));
        let mut input = RayInput {
            channels: &channels,
            args,
            data: &extra,
        };
        let mut c = [0.0; 3];
        for i in 0..3 {
            c[i] = match self.directional[i] {
                Directional::Zero => 0.0,
                Directional::SameAs(j) => c[j],
                Directional::Call(k) => {
                    let mut v = [0.0];
                    functions.eval(pattern, program, &[k], &mut input, &mut v)?;
                    v[0]
                }
            };
        }
        Some(Color::new(c[0], c[1], c[2]))
    }

    /// The mirror ray's (`which` 0) or the straight ray's (1) colour: three of the six
    /// expressions `exprs`.
    #[allow(clippy::too_many_arguments)]
    pub fn coefficient(
        functions: &Functions,
        pattern: u32,
        program: ProgramId,
        exprs: &[usize],
        ray: &RayView,
        inverse: &radc_lang::transform::Transform,
        args: &[f64],
        shade: &ShadeState,
        which: usize,
    ) -> Option<Color> {
        let channels = Channels::new(ray, inverse);
        let extra = extra(inverse, shade, None);
        let mut input = RayInput {
            channels: &channels,
            args,
            data: &extra,
        };
        let mut v = [0.0; 3];
        let three = exprs.get(3 * which..3 * which + 3)?;
        functions.eval(pattern, program, three, &mut input, &mut v)?;
        Some(Color::new(v[0], v[1], v[2]))
    }
}

impl BrdfLookup {
    /// The function's value for light from `dir` (world) of solid angle `omega`;
    /// `None` on a compute error.
    #[allow(clippy::too_many_arguments)]
    pub fn value(
        &self,
        functions: &Functions,
        pattern: u32,
        program: ProgramId,
        coords: &[usize],
        ray: &RayView,
        inverse: &radc_lang::transform::Transform,
        args: &[f64],
        shade: &ShadeState,
        dir: Vec3,
        omega: f64,
    ) -> Option<f64> {
        let channels = Channels::new(ray, inverse);
        let mut extra = extra(inverse, shade, Some((dir, omega)));
        if let Some(d) = &self.data {
            let mut pt = vec![0.0; coords.len()];
            let mut input = RayInput {
                channels: &channels,
                args,
                data: &extra,
            };
            functions.eval(pattern, program, coords, &mut input, &mut pt)?;
            extra[4] = d.eval(&pt);
        }
        let mut input = RayInput {
            channels: &channels,
            args,
            data: &extra,
        };
        let mut v = [0.0];
        functions.eval(pattern, program, &[self.value], &mut input, &mut v)?;
        Some(v[0])
    }
}

impl Functions {
    /// Makes m_brdf.c's shading variables visible to program `p` (once).
    pub fn bind_shading_variables(&mut self, p: ProgramId) {
        let Some(program) = self.programs.get_mut(p.0 as usize) else {
            return;
        };
        for (i, name) in SHADING_VARIABLES.iter().enumerate() {
            let bound = program
                .module
                .lookup(name)
                .and_then(|s| program.module.current_def(s))
                .is_some();
            if !bound {
                program.module.bind_channel(name, SHADE_CHANNEL + i as u32);
            }
        }
    }

    /// Adds the call `name($c1, $c2, ...)` of the channels given to program `p` (C's
    /// `funvalue(name, n, args)`: a function of fewer parameters sees the first ones);
    /// returns its expression's index.
    pub fn add_call(
        &mut self,
        p: ProgramId,
        name: &str,
        channels: &[u32],
    ) -> Result<usize, String> {
        let arity = self.callable_arity(p, name)?;
        if arity > channels.len() {
            return Err(format!(
                "'{name}' takes {arity} arguments; the material passes {}",
                channels.len()
            ));
        }
        let words: Vec<String> = channels[..arity].iter().map(|c| format!("${c}")).collect();
        self.add_expression(p, &format!("{name}({})", words.join(",")))
    }
}
