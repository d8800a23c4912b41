//! Light sources for the direct calculation (`src/rt/srcsupp.c`, `srcsamp.c`): where a
//! source is, its size, and the deterministic samples (`-dj 0`) a point sends shadow
//! rays to. Flat sources are split into up to 64 partitions, finer for nearer points and
//! for smaller `-ds`, exactly as Radiance splits them, so sample directions and solid
//! angles agree with rtrace. radc's `-dx+` ([`Source::exact_samples`]) instead gives
//! each partition its exact solid angle (`crate::solid_angle`), more accurate than
//! rtrace and so no longer equal to it.

use crate::materials::light::Spot;
use crate::math::Vec3;
use crate::scene::Object;
use crate::shapes::{PackedSphere, Shape};

mod exact;
mod partition;
mod shape;

use partition::sphere_sample;

/// Radiance's `MAXSPART`: partitions per source, and the unit of partition coordinates.
const MAXSPART: i32 = 64;

/// Where a source is.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum SourceShape {
    /// A sphere: sampled at its centre, solid angle `pi r^2 / d^2`.
    Sphere { center: Vec3, radius: f64 },
    /// A polygon or disk: `u`, `v` are half-extent vectors spanning it from `center`.
    Flat {
        center: Vec3,
        normal: Vec3,
        area: f64,
        u: Vec3,
        v: Vec3,
        /// A disk: samples are pulled in toward the rim's circle.
        circular: bool,
        /// A parallelogram (`u`, `v` span exactly the polygon), so that the partitions
        /// tile the source and `-dx+` can take each one's exact solid angle.
        parallelogram: bool,
        /// The vertices of a convex polygon that is not a parallelogram (empty
        /// otherwise): `-dx+` splits it into triangles.
        convex_outline: Vec<Vec3>,
        /// Distance from the centre to the farthest point (`srad`).
        radius: f64,
    },
    /// A cylinder: `half_axis` spans half its length from `center`; sampled along the
    /// axis, seen with its projected area `2 r l`.
    Cylinder {
        center: Vec3,
        half_axis: Vec3,
        radius: f64,
    },
    /// A distant `source`: a unit direction and its solid angle.
    Distant { direction: Vec3, solid_angle: f64 },
}

/// One direct source.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Source {
    pub shape: SourceShape,
    /// `glow` sources only light points within this distance.
    pub proximity: Option<f64>,
    /// `spotlight` sources only light points inside their cone.
    pub spot: Option<Spot>,
    /// The surface this source is: local object index or distant-source index (for a
    /// virtual source, the mirror).
    pub target: SourceTarget,
    /// A virtual source: the image of source `parent` in the mirror `target`.
    pub parent: Option<usize>,
    /// A distant virtual source only lights points whose shadow rays pass within the
    /// mirror's disk: its centre and area (Radiance's distant `spotout`).
    pub beam: Option<(Vec3, f64)>,
    /// Radiance's sampling vectors (`ss`), carried through mirror images.
    pub axes: [Vec3; 3],
}

/// A source as most scenes' lamps are: a sphere that is its own surface (no virtual
/// image), lighting every point the same way (no `glow` distance, spotlight cone or
/// mirror beam). Its one sample is the centre ([`Lamp::sample`]), and its surface is a
/// sphere whose test direct lighting calls without looking anything up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lamp {
    pub center: Vec3,
    pub radius: f64,
    /// The object the source is.
    pub target: u32,
    pub sphere: PackedSphere,
}

impl Lamp {
    /// `source` as a lamp, when it is one, its surface a sphere among `objects`.
    pub fn of(source: &Source, objects: &[Object]) -> Option<Lamp> {
        let (SourceShape::Sphere { center, radius }, SourceTarget::Object(target)) =
            (&source.shape, source.target)
        else {
            return None;
        };
        if source.parent.is_some()
            || source.proximity.is_some()
            || source.spot.is_some()
            || source.beam.is_some()
        {
            return None;
        }
        let Shape::Sphere(s) = &objects.get(target as usize)?.shape else {
            return None;
        };
        Some(Lamp {
            center: *center,
            radius: *radius,
            target,
            sphere: PackedSphere::of(s),
        })
    }

    /// What [`Source::jittered_samples`] gives without jitter or `-dx+` from `org`: the
    /// centre, or nothing at the centre itself.
    #[inline(always)]
    pub fn sample(&self, org: Vec3) -> Option<SourceSample> {
        sphere_sample(self.center, self.radius, org, [0.0; 3], [1.0; 3])
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum SourceTarget {
    Object(u32),
    Distant(u32),
}

/// A shadow-ray direction, the solid angle it stands for, and the distance to the
/// sample point (`FHUGE` for distant sources).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SourceSample {
    pub dir: Vec3,
    pub omega: f64,
    pub dist: f64,
}

impl Source {}

/// The solid angle of a cone of half-angle cosine `cos`, `2 pi (1 - cos)`, as the
/// reference build (pyradiance's Radiance, compiled with `-ffast-math`) evaluates it
/// in srcsupp.c and source.c: distributed, `2 pi - 2 pi cos`. The difference is one
/// rounding, and it decides the horizon: a 180-degree `source` (every sky) then
/// covers rays exactly along its boundary, as rtrace shows it there, where the
/// factored form leaves a black line at the horizon of a level view.
pub fn cap_solid_angle(cos: f64) -> f64 {
    let two_pi = 2.0 * std::f64::consts::PI;
    two_pi - two_pi * cos
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::perpendicular;
    use crate::solid_angle::DiskFrame;

    fn square_source(side: f64) -> Source {
        let h = side / 2.0;
        let verts = [
            Vec3::new(-h, -h, 0.0),
            Vec3::new(-h, h, 0.0),
            Vec3::new(h, h, 0.0),
            Vec3::new(h, -h, 0.0),
        ];
        Source {
            shape: SourceShape::polygon(&verts, -Vec3::Z, side * side),
            proximity: None,
            spot: None,
            target: SourceTarget::Object(0),
            parent: None,
            beam: None,
            axes: [Vec3::ZERO; 3],
        }
    }

    #[test]
    fn far_point_gets_one_sample_with_full_solid_angle() {
        let s = square_source(1.0);
        let mut out = Vec::new();
        s.samples(Vec3::new(0.0, 0.0, -100.0), 1.0, 0.2, &mut out);
        assert_eq!(out.len(), 1);
        assert!((out[0].omega - 1.0 / 10000.0).abs() < 1e-12);
    }

    #[test]
    fn near_point_gets_partitions_covering_the_source() {
        let s = square_source(1.0);
        let mut out = Vec::new();
        s.samples(Vec3::new(0.0, 0.0, -1.0), 1.0, 0.2, &mut out);
        assert!(out.len() > 1 && out.len() <= 64);
        // Projected solid angles approximate the exact value for a unit square at 1.
        let total: f64 = out.iter().map(|s| s.omega).sum();
        assert!(total > 0.7 && total < 1.0, "{total}");
    }

    fn sphere_source(center: Vec3, radius: f64) -> Source {
        Source {
            shape: SourceShape::sphere(center, radius),
            ..square_source(1.0)
        }
    }

    /// Sums of `dir * omega`, i.e. of the samples' `V`.
    fn vector_sum(samples: &[SourceSample]) -> Vec3 {
        samples.iter().map(|s| s.dir * s.omega).sum()
    }

    #[test]
    fn exact_sphere_pieces_add_up_to_the_cap() {
        let s = sphere_source(Vec3::new(0.3, -0.2, 2.0), 0.8);
        let org = Vec3::new(0.1, 0.1, 0.0);
        let mut out = Vec::new();
        s.jittered_samples(org, 1.0, 0.05, None, true, &mut out);
        assert!(out.len() > 8 && out.len() <= 64, "{}", out.len());
        let to = Vec3::new(0.2, -0.3, 2.0);
        let sin2 = 0.64 / to.length_squared();
        let want = to.normalize() * (std::f64::consts::PI * sin2);
        assert!(
            (vector_sum(&out) - want).length() < 1e-12,
            "{}",
            vector_sum(&out)
        );
        for x in &out {
            // Every shadow ray meets the sphere.
            let c = Vec3::new(0.3, -0.2, 2.0) - org;
            let along = x.dir.dot(c);
            assert!(c.length_squared() - along * along < 0.64);
        }
    }

    #[test]
    fn exact_square_pieces_add_up_to_lamberts_formula() {
        let s = square_source(1.0);
        let org = Vec3::new(0.2, 0.1, -0.7);
        let mut out = Vec::new();
        s.jittered_samples(org, 1.0, 0.2, None, true, &mut out);
        assert!(out.len() > 1);
        let corners = [(-0.5, -0.5), (-0.5, 0.5), (0.5, 0.5), (0.5, -0.5)]
            .map(|(x, y)| Vec3::new(x, y, 0.0) - org);
        let whole = crate::solid_angle::polygon(&corners, Vec3::Z);
        assert!((vector_sum(&out) - whole).length() < 1e-12 * whole.length());
    }

    #[test]
    fn exact_disk_pieces_add_up_and_meet_the_disk() {
        let (center, normal) = (
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.2, 0.1, -1.0).normalize(),
        );
        let s = Source {
            shape: SourceShape::disk(center, normal, 0.6),
            ..square_source(1.0)
        };
        let org = Vec3::new(0.3, -0.1, 0.0);
        let mut out = Vec::new();
        s.jittered_samples(org, 1.0, 0.05, None, true, &mut out);
        assert!(out.len() > 8 && out.len() <= 64, "{}", out.len());
        let e1 = perpendicular(normal).expect("a perpendicular");
        let frame = DiskFrame {
            center: center - org,
            e1,
            e2: normal.cross(e1),
            radius: 0.6,
        };
        let whole = frame.whole();
        assert!((vector_sum(&out) - whole).length() < 1e-8 * whole.length());
        for x in &out {
            let p = org + x.dir * x.dist;
            assert!((p - center).dot(normal).abs() < 1e-9 && p.distance(center) <= 0.6 + 1e-9);
        }
    }

    #[test]
    fn exact_triangle_pieces_add_up_to_lamberts_formula() {
        let verts = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(0.2, 0.9, 1.0),
        ];
        let area = 0.5 * (verts[1] - verts[0]).cross(verts[2] - verts[0]).length();
        let s = Source {
            shape: SourceShape::polygon(&verts, -Vec3::Z, area),
            ..square_source(1.0)
        };
        let org = Vec3::new(0.3, 0.2, 0.2);
        let mut out = Vec::new();
        s.jittered_samples(org, 1.0, 0.05, None, true, &mut out);
        assert!(out.len() > 8 && out.len() <= 64, "{}", out.len());
        let whole = crate::solid_angle::polygon(&verts.map(|v| v - org), Vec3::Z);
        assert!((vector_sum(&out) - whole).length() < 1e-12 * whole.length());
        // A concave polygon keeps Radiance's samples.
        let l_shape = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(2.0, 0.0, 1.0),
            Vec3::new(2.0, 1.0, 1.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, 2.0, 1.0),
            Vec3::new(0.0, 2.0, 1.0),
        ];
        match SourceShape::polygon(&l_shape, -Vec3::Z, 3.0) {
            SourceShape::Flat { convex_outline, .. } => assert!(convex_outline.is_empty()),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn behind_a_flat_source_nothing() {
        let s = square_source(1.0);
        let mut out = Vec::new();
        s.samples(Vec3::new(0.0, 0.0, 1.0), 1.0, 0.2, &mut out);
        assert!(out.is_empty());
    }
}
