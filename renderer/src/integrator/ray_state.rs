//! A ray being evaluated, and what it hit.

use super::RayKind;
use crate::lights::SourceTarget;
use crate::math::{Color, FHUGE, Vec3, brightness};
use crate::ray::ObjectId;
use crate::scene::Scene;

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    None,
    Object(ObjectId),
    Distant(u32),
}

/// A ray being evaluated: Radiance's `RAY` without the parts radc does not model.
#[derive(Clone, Debug)]
pub struct RayState {
    pub org: Vec3,
    pub dir: Vec3,
    pub kind: RayKind,
    pub weight: f64,
    pub level: u32,
    /// Rays in the chain down from the primary, of every kind (transmitted rays keep
    /// `level`).
    pub depth: u32,
    /// Coefficient applied by the parent.
    pub coef: Color,
    /// Source this (shadow) ray is aimed at.
    pub source: Option<usize>,
    pub hit: Target,
    /// Distance to the hit (`FHUGE` when nothing was hit).
    pub length: f64,
    pub point: Vec3,
    /// Surface normal, flipped to face the ray by two-sided materials.
    pub normal: Vec3,
    pub rod: f64,
    pub flips: u32,
    pub color: Color,
    /// The part of `color` from a mirror reflection, and the distance it appears at.
    pub mirror_color: Color,
    pub mirror_length: f64,
    /// The distance of everything else (through transparent surfaces).
    pub other_length: f64,
    /// Extinction coefficient of the medium the ray travels in (inside a dielectric).
    pub extinction: Color,
    /// Distance travelled from the eye to this ray's origin.
    pub path_length: f64,
    /// Farthest distance the ray may hit at (0: unlimited; rtrace's `-ld`, the aft
    /// clipping plane). Rays passed through a surface keep what is left of it.
    pub max_distance: f64,
    /// Modifiers whose surfaces this ray passes through (inside `antimatter`), and the
    /// set its transmitted continuations get (`clipset`, `newcset`).
    pub clipset: Vec<i64>,
    pub new_clipset: Option<Vec<i64>>,
    /// For each transmitted link up the ray tree: the modifier of the surface passed
    /// and whether it was entered from the front (antimatter's penetration count).
    pub passages: Vec<(i64, bool)>,
    /// Seed of this ray's random choices ([`crate::random`]).
    pub seed: u64,
    /// Ambient rays among this ray's ancestors (and itself): Radiance's ambient
    /// recursion depth, compared with `-ab`.
    pub ambient_depth: u32,
    /// The perturbation of the normal (`pert`): the surface's own at the hit (a
    /// smoothed mesh's interpolated normal less the triangle's, o_mesh.c), to which
    /// the textures add theirs when shading; flipped with the surface.
    pub pert: Vec3,
    /// The surface's (u,v) (`Lu`, `Lv`: a mesh's interpolated texture coordinates).
    pub uv: [f64; 2],
    /// A hit on a mesh triangle shaded with the mesh file's own material: its index
    /// in the mesh object's `triangle_materials`. Radiance then shades a stand-in face
    /// (`getmeshpseudo`): flat, named `M-Tri`, modified by that material.
    pub triangle: Option<u16>,
}

impl RayState {
    pub fn primary(org: Vec3, dir: Vec3) -> RayState {
        RayState {
            org,
            dir,
            kind: RayKind::PRIMARY,
            weight: 1.0,
            level: 0,
            depth: 0,
            coef: Color::ONE,
            source: None,
            hit: Target::None,
            length: FHUGE,
            point: org,
            normal: -dir,
            rod: 1.0,
            flips: 0,
            color: Color::ZERO,
            mirror_color: Color::ZERO,
            mirror_length: FHUGE,
            other_length: FHUGE,
            extinction: Color::ZERO,
            path_length: 0.0,
            max_distance: 0.0,
            clipset: Vec::new(),
            new_clipset: None,
            passages: Vec::new(),
            seed: 0,
            ambient_depth: 0,
            pert: Vec3::ZERO,
            uv: [0.0, 0.0],
            triangle: None,
        }
    }

    /// Radiance's `flipsurface`: look at the back as if it were the front.
    pub fn flip(&mut self) {
        self.rod = -self.rod;
        self.normal = -self.normal;
        self.pert = -self.pert;
        self.flips += 1;
    }

    /// `raynormal`: the normal with the perturbation added, turned back to the ray's
    /// side of the surface when the perturbation crossed it (rtrace's `-on`).
    pub fn perturbed_normal(&self) -> Vec3 {
        if self.pert == Vec3::ZERO {
            return self.normal;
        }
        let mut n = self.normal + self.pert;
        if crate::math::normalize(&mut n) == 0.0 {
            return self.normal;
        }
        let newdot = -n.dot(self.dir);
        if (newdot > 0.0) != (self.rod > 0.0) {
            n += self.dir * (2.0 * newdot);
        }
        n
    }

    /// `raydistance`: where the ray's value appears to come from.
    pub fn effective_length(&self) -> f64 {
        if brightness(self.mirror_color) > 0.5 * brightness(self.color) {
            self.mirror_length
        } else {
            self.other_length
        }
    }

    /// For a shadow ray: whether what it hit is not the source it was aimed at (`None`
    /// when it is not aimed at a source).
    pub fn aimed_at_other_source(&self, scene: &Scene) -> Option<bool> {
        let s = scene.sources.get(self.source?)?;
        let on_target = match (s.target, self.hit) {
            (SourceTarget::Object(a), Target::Object(b)) => a == b.0,
            (SourceTarget::Distant(a), Target::Distant(b)) => a == b,
            _ => false,
        };
        Some(!on_target)
    }

    pub fn hit_is_flat(&self, scene: &Scene) -> bool {
        match self.hit {
            Target::Object(o) => {
                self.triangle.is_some() || scene.hit_info(o.0).is_some_and(|o| o.flat)
            }
            _ => false,
        }
    }

    /// The unperturbed normal as it was before any flips (`-oN`).
    pub fn surface_normal(&self) -> Vec3 {
        if self.flips % 2 == 1 {
            -self.normal
        } else {
            self.normal
        }
    }
}

impl RayState {
    /// What the scene's functions see of the ray at its hit.
    pub fn view(&self) -> crate::procedural::RayView {
        crate::procedural::RayView {
            dir: self.dir,
            normal: self.normal,
            point: self.point,
            total_distance: self.path_length + self.length,
            length: self.length,
            rod: self.rod,
            uv: self.uv,
        }
    }
}
