//! `metal`: the normal.c model with the highlight tinted by the material colour.

use super::plastic::Plastic;
use crate::math::{Color, Vec3};

/// A metal: `spec` of the reflection is specular, coloured by `color`.
pub fn metal(color: Color, spec: f64, rough: f64) -> Plastic {
    Plastic {
        color,
        spec,
        rough,
        metal: true,
        transmission: None,
        texture: Vec3::ZERO,
    }
}

/// The specular colour of a metal (normal.c): the material colour times the specular
/// fraction, blended toward white by the Fresnel estimate `fresnel` for smooth metals.
pub fn specular_color(color: Color, spec: f64, specular_reflection: f64, fresnel: f64) -> Color {
    if fresnel > crate::math::FTINY {
        Color::splat(fresnel) + color * (spec * (1.0 - fresnel))
    } else {
        color * specular_reflection
    }
}
