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
use super::pattern::{Pattern, PatternKind};
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

impl Pattern {
    /// The channels and inputs a material's functions read at a hit: the ray's in the
    /// pattern's frame, the light (if any) and the shading variables after them.
    fn material_input(
        &self,
        ray: &RayView,
        shade: &ShadeState,
        light: Option<(Vec3, f64)>,
    ) -> (Channels, [f64; 12]) {
        (
            Channels::new(ray, &self.inverse),
            extra(&self.inverse, shade, light),
        )
    }

    /// A function or data material's function for light from `dir` (world) of solid
    /// angle `omega`; `None` on a compute error, or when this is no such pattern.
    pub fn brdf(
        &self,
        functions: &Functions,
        index: u32,
        ray: &RayView,
        shade: &ShadeState,
        dir: Vec3,
        omega: f64,
    ) -> Option<f64> {
        let PatternKind::Brdf(b) = &self.kind else {
            return None;
        };
        let (channels, mut extra) = self.material_input(ray, shade, Some((dir, omega)));
        if let Some(d) = &b.data {
            let mut pt = vec![0.0; self.exprs.len()];
            let mut input = RayInput {
                channels: &channels,
                args: &self.args,
                data: &extra,
            };
            functions.eval(index, self.program, &self.exprs, &mut input, &mut pt)?;
            extra[4] = d.eval(&pt);
        }
        let mut input = RayInput {
            channels: &channels,
            args: &self.args,
            data: &extra,
        };
        let mut v = [0.0];
        functions.eval(index, self.program, &[b.value], &mut input, &mut v)?;
        Some(v[0])
    }

    /// A BRTDfunc's directional colour for light from `dir` of solid angle `omega`.
    pub fn brtd_directional(
        &self,
        functions: &Functions,
        index: u32,
        ray: &RayView,
        shade: &ShadeState,
        dir: Vec3,
        omega: f64,
    ) -> Option<Color> {
        let PatternKind::Brtd(b) = &self.kind else {
            return None;
        };
        let (channels, extra) = self.material_input(ray, shade, Some((dir, omega)));
        let mut input = RayInput {
            channels: &channels,
            args: &self.args,
            data: &extra,
        };
        let mut c = [0.0; 3];
        for i in 0..3 {
            c[i] = match b.directional[i] {
                Directional::Zero => 0.0,
                Directional::SameAs(j) => c[j],
                Directional::Call(k) => {
                    let mut v = [0.0];
                    functions.eval(index, self.program, &[k], &mut input, &mut v)?;
                    v[0]
                }
            };
        }
        Some(Color::new(c[0], c[1], c[2]))
    }

    /// A BRTDfunc's mirror (`which` 0) or straight-through (1) colour: three of its six
    /// expressions.
    pub fn brtd_coefficient(
        &self,
        functions: &Functions,
        index: u32,
        ray: &RayView,
        shade: &ShadeState,
        which: usize,
    ) -> Option<Color> {
        if !matches!(self.kind, PatternKind::Brtd(_)) {
            return None;
        }
        let (channels, extra) = self.material_input(ray, shade, None);
        let mut input = RayInput {
            channels: &channels,
            args: &self.args,
            data: &extra,
        };
        let mut v = [0.0; 3];
        let three = self.exprs.get(3 * which..3 * which + 3)?;
        functions.eval(index, self.program, three, &mut input, &mut v)?;
        Some(Color::new(v[0], v[1], v[2]))
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
