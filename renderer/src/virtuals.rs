//! Virtual light sources (virtuals.c, m_mirror.c's `mir_proj`): the image of each light
//! source in each plane `mirror` it faces, so that light reflected by mirrors reaches
//! surfaces in the direct calculation (`-dr`). A shadow ray aimed at a virtual source
//! hits the mirror and is relayed toward the source it images.
//!
//! Radiance pretests each virtual source's visibility with a few rays (`-dp`) to skip
//! shadow tests when the relay path is clear; radc always follows the path, which
//! gives the same values. Images of images (`-dr 2` and up, two mirrors facing each
//! other) and images of spotlights are not made yet.

use crate::lights::{Source, SourceShape, SourceTarget};
use crate::materials::Material;
use crate::materials::light::Spot;
use crate::math::{FTINY, Vec3, normalize, perpendicular};
use crate::scene::Scene;
use crate::shapes::Shape;

/// A plane mirror: its plane and the disk that holds it (`getplaneq`, `getmaxdisk`).
struct MirrorPlane {
    object: u32,
    normal: Vec3,
    offset: f64,
    center: Vec3,
    radius2: f64,
}

impl MirrorPlane {
    fn of(object: u32, shape: &Shape) -> Option<MirrorPlane> {
        match shape {
            Shape::Polygon(p) => {
                let c = p.centroid();
                // The vertex mean moved into the plane.
                let center = c + p.normal * (p.offset - c.dot(p.normal));
                let radius2 = p
                    .vertices
                    .iter()
                    .map(|v| v.distance_squared(center))
                    .fold(0.0, f64::max);
                Some(MirrorPlane {
                    object,
                    normal: p.normal,
                    offset: p.offset,
                    center,
                    radius2,
                })
            }
            Shape::Ring(r) => Some(MirrorPlane {
                object,
                normal: r.normal,
                offset: r.normal.dot(r.center),
                center: r.center,
                radius2: r.r1 * r.r1,
            }),
            _ => None,
        }
    }

    fn point(&self, p: Vec3) -> Vec3 {
        p - self.normal * (2.0 * (self.normal.dot(p) - self.offset))
    }

    fn vector(&self, v: Vec3) -> Vec3 {
        v - self.normal * (2.0 * self.normal.dot(v))
    }
}

/// Radiance's sampling vectors of a source (`ss[SU]`, `ss[SV]`, `ss[SW]`), the factor
/// that makes them reach its extremes, and whether it is flat (two vectors only).
fn extent_vectors(shape: &SourceShape) -> ([Vec3; 3], f64, bool) {
    match shape {
        SourceShape::Sphere { radius, .. } => {
            let k = 0.7236 * radius;
            ([Vec3::X * k, Vec3::Y * k, Vec3::Z * k], 1.0 / 0.7236, false)
        }
        SourceShape::Flat {
            u,
            v,
            normal,
            circular,
            ..
        } => (
            [*u, *v, *normal],
            if *circular {
                std::f64::consts::FRAC_2_SQRT_PI
            } else {
                1.0
            },
            true,
        ),
        SourceShape::Cylinder {
            half_axis, radius, ..
        } => {
            let mut axis = *half_axis;
            normalize(&mut axis);
            let w = perpendicular(axis).unwrap_or(Vec3::X) * (0.8559 * radius);
            ([*half_axis, w.cross(axis), w], 1.0, false)
        }
        SourceShape::Distant {
            direction,
            solid_angle,
        } => {
            let u = perpendicular(*direction).unwrap_or(Vec3::X) * (0.5 * solid_angle.sqrt());
            (
                [u, direction.cross(u), *direction],
                std::f64::consts::FRAC_2_SQRT_PI,
                false,
            )
        }
    }
}

fn location(shape: &SourceShape) -> Vec3 {
    match shape {
        SourceShape::Sphere { center, .. }
        | SourceShape::Flat { center, .. }
        | SourceShape::Cylinder { center, .. } => *center,
        SourceShape::Distant { direction, .. } => *direction,
    }
}

/// Whether the source lies (at least partly) in front of the mirror (`mir_proj`).
fn in_front(m: &MirrorPlane, shape: &SourceShape) -> bool {
    let distant = matches!(shape, SourceShape::Distant { .. });
    let offs = if distant { 0.0 } else { m.offset };
    let (ss, corr, flat) = extent_vectors(shape);
    let mut extreme = location(shape);
    for v in ss.iter().take(if flat { 2 } else { 3 }).rev() {
        if m.normal.dot(*v) > offs {
            extreme += *v * corr;
        } else {
            extreme -= *v * corr;
        }
    }
    extreme.dot(m.normal) > offs + FTINY
}

fn reflect_shape(m: &MirrorPlane, shape: &SourceShape) -> SourceShape {
    match shape {
        SourceShape::Sphere { center, radius } => SourceShape::Sphere {
            center: m.point(*center),
            radius: *radius,
        },
        SourceShape::Flat {
            center,
            normal,
            area,
            u,
            v,
            circular,
            radius,
        } => {
            let mut n = m.vector(*normal);
            normalize(&mut n);
            SourceShape::Flat {
                center: m.point(*center),
                normal: n,
                area: *area,
                u: m.vector(*u),
                v: m.vector(*v),
                circular: *circular,
                radius: *radius,
            }
        }
        SourceShape::Cylinder {
            center,
            half_axis,
            radius,
        } => SourceShape::Cylinder {
            center: m.point(*center),
            half_axis: m.vector(*half_axis),
            radius: *radius,
        },
        SourceShape::Distant {
            direction,
            solid_angle,
        } => {
            let mut d = m.vector(*direction);
            normalize(&mut d);
            SourceShape::Distant {
                direction: d,
                solid_angle: *solid_angle,
            }
        }
    }
}

/// The virtual source of `source` (number `index`) in mirror `m` (`makevsrc`), if the
/// mirror can relay it.
fn image(m: &MirrorPlane, source: &Source, index: usize) -> Option<Source> {
    if source.target == SourceTarget::Object(m.object)
        || source.parent.is_some()
        || source.spot.is_some()
    {
        return None;
    }
    if m.radius2 <= FTINY || !in_front(m, &source.shape) {
        return None;
    }
    let shape = reflect_shape(m, &source.shape);
    let (mut spot, mut beam) = (None, None);
    if let SourceShape::Distant { .. } = shape {
        beam = Some((m.center, std::f64::consts::PI * m.radius2));
    } else {
        let mut aim = m.center - location(&shape);
        let d = normalize(&mut aim);
        if d == 0.0 {
            return None;
        }
        if source.proximity.is_some_and(|p| d > p) {
            return None;
        }
        let (_, srad) = source.shape.center_radius();
        let k = (m.radius2.sqrt() + srad) / d;
        if k < 1.0 - FTINY {
            spot = Some(Spot {
                size: 2.0 * std::f64::consts::PI * (1.0 - (1.0 - k * k).sqrt()),
                aim,
                focus: 0.0,
            });
        }
        if let (Some(s), SourceShape::Flat { normal, .. }) = (&spot, &shape)
            && !s.faces(*normal)
        {
            return None;
        }
    }
    Some(Source {
        shape,
        proximity: source.proximity,
        spot,
        target: SourceTarget::Object(m.object),
        parent: Some(index),
        beam,
    })
}

impl Scene {
    /// Adds the images of the light sources in the scene's plane mirrors (rtrace's
    /// `-dr`: 0 adds none; radc makes first images only, whatever the count).
    pub fn add_virtual_sources(&mut self, relays: u32) {
        if relays == 0 {
            return;
        }
        let mirrors: Vec<MirrorPlane> = self
            .objects
            .iter()
            .enumerate()
            .filter(|(_, o)| {
                matches!(
                    o.material.and_then(|m| self.material(m)),
                    Some(Material::Mirror(_))
                )
            })
            .filter_map(|(i, o)| MirrorPlane::of(i as u32, &o.shape))
            .collect();
        let real = self.sources.len();
        for index in (0..real).rev() {
            for m in &mirrors {
                if let Some(v) = image(m, &self.sources[index], index) {
                    self.sources.push(v);
                }
            }
        }
    }
}
