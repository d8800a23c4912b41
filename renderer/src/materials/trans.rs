//! `trans`: the normal.c model with part of the light passing through, diffusely and
//! specularly (`trans` and `tspec` of the arguments).

use super::plastic::Plastic;
use crate::math::{Color, Vec3};

pub fn trans(color: Color, spec: f64, rough: f64, trans: f64, tspec: f64) -> Plastic {
    Plastic {
        color,
        spec,
        rough,
        metal: false,
        transmission: Some((trans, tspec)),
        texture: Vec3::ZERO,
    }
}
