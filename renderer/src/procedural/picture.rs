//! Picture patterns (p_data.c `p_pdata`): two coordinate expressions give a point in
//! the picture's frame (`radc_picture::ColorPicture`, already checked against
//! rtrace), the three interpolated channels go through the named functions, and the
//! result multiplies `pcol`.

use std::sync::Arc;

use radc_picture::sample::ColorPicture;

use super::channels::Channels;
use super::data::apply_functions;
use super::{Functions, ProgramId, RayInput};

/// A `colorpict` pattern's picture and its function expressions.
#[derive(Clone, Debug)]
pub struct PictureLookup {
    pub picture: Arc<ColorPicture>,
    pub functions: Vec<usize>,
}

impl PictureLookup {
    /// The pattern's three values for the ray; `None` on a compute error. `coords`
    /// are its two expressions: across, then up (p_pdata stores them in the other
    /// order because the picture is kept row-major).
    pub fn values(
        &self,
        functions: &Functions,
        pattern: u32,
        program: ProgramId,
        coords: &[usize],
        channels: &Channels,
        args: &[f64],
    ) -> Option<[f64; 3]> {
        let mut pt = [0.0; 2];
        let mut input = RayInput {
            channels,
            args,
            data: &[],
        };
        functions.eval(pattern, program, coords, &mut input, &mut pt)?;
        let data = self.picture.value(pt[0], pt[1]);
        apply_functions(
            functions,
            pattern,
            program,
            &self.functions,
            data,
            channels,
            args,
        )
    }
}
