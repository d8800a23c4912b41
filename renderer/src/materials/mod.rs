//! Materials: what a ray sees where it hits. Each file reproduces one of Radiance's
//! shading routines; `Material` is the closed set the renderer models so far.

pub mod anisotropic;
pub mod antimatter;
pub mod ashikhmin;
pub mod brtd;
pub mod context;
pub mod dielectric;
pub mod function;
pub mod glass;
pub mod light;
pub mod metal;
pub mod mirror;
pub mod mist;
pub mod mixture;
pub mod plastic;
pub mod trans;

pub use context::ShadingContext;

use crate::math::Color;

/// The colour patterns leave a material with when none applies (serde's default for
/// the per-hit pattern colours, which scene files never store).
pub(crate) fn one() -> Color {
    Color::ONE
}

/// Index into [`crate::scene::Scene::materials`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct MaterialId(pub u32);

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Material {
    /// `plastic` and `metal`: Radiance's "normal" materials (normal.c).
    Plastic(plastic::Plastic),
    Mirror(mirror::Mirror),
    Glass(glass::Glass),
    /// `dielectric` and `interface`.
    Dielectric(dielectric::Dielectric),
    Antimatter(antimatter::Antimatter),
    /// `plastic2`, `metal2`, `trans2`.
    Anisotropic(anisotropic::Anisotropic),
    Mist(mist::Mist),
    /// `light`, `glow`, `illum`.
    Emitter(light::Emitter),
    /// `plasfunc`, `metfunc`, `transfunc`, `plasdata`, `metdata`, `transdata`.
    Function(function::FunctionMaterial),
    /// `ashik2`.
    Ashikhmin(ashikhmin::Ashikhmin),
    /// `BRTDfunc`; transparent (for ties) when a straight-through expression is not `0`.
    Brtd(brtd::Brtd, bool),
    /// `mixfunc`, `mixdata`, `mixpict` between materials.
    Mixture(mixture::Mixture),
}

/// A material named in another's string argument (illum and mirror alternates).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Alternate {
    /// No alternate given.
    None,
    /// `void`: rays pass through.
    Void,
    Material(MaterialId),
}

impl Material {
    /// Radiance's `istransp`: transmitting types lose ties to opaque ones.
    pub fn is_transparent(&self) -> bool {
        match self {
            Material::Plastic(n) => n.is_transparent(),
            Material::Glass(_) | Material::Dielectric(_) | Material::Mist(_) => true,
            Material::Anisotropic(a) => a.transmission.is_some(),
            Material::Brtd(_, transparent) => *transparent,
            _ => false,
        }
    }

    /// The material this one hands some rays to (a mirror's or an illum's string
    /// argument): shading follows it without tracing a new ray.
    pub fn alternate(&self) -> Option<MaterialId> {
        match self {
            Material::Mirror(mirror::Mirror {
                alternate: Alternate::Material(m),
                ..
            })
            | Material::Emitter(light::Emitter {
                kind:
                    light::EmitterKind::Illum {
                        alternate: Alternate::Material(m),
                    },
                ..
            }) => Some(*m),
            _ => None,
        }
    }

    pub fn color(&self) -> Color {
        match self {
            Material::Plastic(n) => n.color,
            Material::Mirror(m) => m.color,
            Material::Glass(g) => g.transmission,
            Material::Dielectric(d) => d.inside,
            Material::Antimatter(_) => Color::ZERO,
            Material::Anisotropic(a) => a.color,
            Material::Mist(m) => m.extinction,
            Material::Emitter(e) => e.color,
            Material::Mixture(_) => Color::ZERO,
            Material::Function(f) => f.color,
            Material::Brtd(b, _) => b.front_diffuse,
            Material::Ashikhmin(a) => a.color,
        }
    }
}
