//! Materials: what a ray sees where it hits. Each file reproduces one of Radiance's
//! shading routines; `Material` is the closed set the renderer models so far.

pub mod light;
pub mod metal;
pub mod mirror;
pub mod plastic;

use crate::math::Color;

/// Index into [`crate::scene::Scene::materials`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialId(pub u32);

#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// `plastic` and `metal`: Radiance's "normal" materials (normal.c).
    Normal(plastic::Normal),
    Mirror(mirror::Mirror),
    /// `light`, `glow`, `illum`.
    Emitter(light::Emitter),
}

/// A material named in another's string argument (illum and mirror alternates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Alternate {
    /// No alternate given.
    None,
    /// `void`: rays pass through.
    Void,
    Material(MaterialId),
}

impl Material {
    pub fn color(&self) -> Color {
        match self {
            Material::Normal(n) => n.color,
            Material::Mirror(m) => m.color,
            Material::Emitter(e) => e.color,
        }
    }
}
