//! Virtual light sources (virtuals.c, m_mirror.c's `mir_proj`): the image of each light
//! source in each plane `mirror` it faces, so that light reflected by mirrors reaches
//! surfaces in the direct calculation (`-dr`). A shadow ray aimed at a virtual source
//! hits the mirror and is relayed toward the source it images.
//!
//! Images of images are made up to `-dr` mirrors deep, their apertures narrowed to the
//! cone (or, for distant sources, the beam) common to each mirror on the way. Radiance
//! pretests each image's visibility with a few rays (`-dp`) to skip shadow tests when
//! the relay path is clear; radc always follows the path, which gives the same values.

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

/// Radiance's sampling vectors of a real source (`ss[SU]`, `ss[SV]`, `ss[SW]`).
pub(crate) fn radiance_axes(shape: &SourceShape) -> [Vec3; 3] {
    match shape {
        SourceShape::Sphere { radius, .. } => {
            let k = 0.7236 * radius;
            [Vec3::X * k, Vec3::Y * k, Vec3::Z * k]
        }
        SourceShape::Flat { u, v, normal, .. } => [*u, *v, *normal],
        SourceShape::Cylinder {
            half_axis, radius, ..
        } => {
            let mut axis = *half_axis;
            normalize(&mut axis);
            let w = perpendicular(axis).unwrap_or(Vec3::X) * (0.8559 * radius);
            [*half_axis, w.cross(axis), w]
        }
        SourceShape::Distant {
            direction,
            solid_angle,
        } => {
            let u = perpendicular(*direction).unwrap_or(Vec3::X) * (0.5 * solid_angle.sqrt());
            [u, direction.cross(u), *direction]
        }
    }
}

/// The factor that makes a source's sampling vectors reach its extremes, and whether
/// it is flat (two vectors only).
fn extent_factor(shape: &SourceShape) -> (f64, bool) {
    match shape {
        SourceShape::Sphere { .. } => (1.0 / 0.7236, false),
        SourceShape::Flat { circular, .. } => (
            if *circular {
                std::f64::consts::FRAC_2_SQRT_PI
            } else {
                1.0
            },
            true,
        ),
        SourceShape::Cylinder { .. } => (1.0, false),
        SourceShape::Distant { .. } => (std::f64::consts::FRAC_2_SQRT_PI, false),
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
fn in_front(m: &MirrorPlane, shape: &SourceShape, ss: &[Vec3; 3]) -> bool {
    let distant = matches!(shape, SourceShape::Distant { .. });
    let offs = if distant { 0.0 } else { m.offset };
    let (corr, flat) = extent_factor(shape);
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
            parallelogram,
            convex_outline,
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
                parallelogram: *parallelogram,
                convex_outline: convex_outline.iter().map(|p| m.point(*p)).collect(),
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

/// The part of mirror `m` that can relay source `s`, as centre and squared radius
/// (`getdisk`): its whole disk, unless `s` is itself an image and `m` lies on the far
/// side of the mirror that made it.
fn relay_disk(m: &MirrorPlane, s: &Source, mirrors: &[MirrorPlane]) -> f64 {
    let Some(rm) = mirrors
        .iter()
        .find(|r| SourceTarget::Object(r.object) == s.target)
    else {
        return m.radius2;
    };
    if s.parent.is_none() {
        return m.radius2;
    }
    let mut rd = rm.normal.dot(location(&s.shape));
    if !matches!(s.shape, SourceShape::Distant { .. }) {
        rd -= rm.offset;
    }
    let d = rm.normal.dot(m.center) - rm.offset;
    if (d > 0.0) != (rd > 0.0) {
        return m.radius2;
    }
    if d * d >= m.radius2 {
        return 0.0;
    }
    let cos = rm.normal.dot(m.normal);
    if d * d >= m.radius2 * (1.0 - cos * cos) {
        return 0.0;
    }
    m.radius2
}

/// Radiance's `intercircle`: the circle where two circles (centres, squared radii)
/// overlap, as centre and squared radius (0 for none).
fn intercircle(c1: Vec3, c2: Vec3, r1s: f64, r2s: f64) -> (Vec3, f64) {
    let disp = c2 - c1;
    let d2 = disp.length_squared();
    if r1s < r2s {
        if r2s >= r1s + d2 {
            return (c1, r1s);
        }
    } else if r1s >= r2s + d2 {
        return (c2, r2s);
    }
    let a2 = 0.25 * (2.0 * (r1s + r2s) - d2 - (r2s - r1s) * (r2s - r1s) / d2);
    if a2 <= 0.0 || !a2.is_finite() {
        return (c1, 0.0);
    }
    let l = ((r1s - a2) / d2).sqrt();
    (c1 + disp * l, a2)
}

/// The cone common to two cones from the same point (`commonspot`), into `a`.
fn common_spot(a: &mut Spot, b: &Spot) -> bool {
    use std::f64::consts::PI;
    let cos1 = 1.0 - a.size / (2.0 * PI);
    let cos2 = 1.0 - b.size / (2.0 * PI);
    if b.size >= 2.0 * PI - FTINY {
        return a.aim.dot(b.aim)
            >= cos1 * cos2 - ((1.0 - cos1 * cos1) * (1.0 - cos2 * cos2)).sqrt();
    }
    let (mut cent, rad2) = intercircle(
        a.aim,
        b.aim,
        1.0 / (cos1 * cos1) - 1.0,
        1.0 / (cos2 * cos2) - 1.0,
    );
    if rad2 <= FTINY || normalize(&mut cent) == 0.0 {
        return false;
    }
    a.aim = cent;
    a.size = 2.0 * PI * (1.0 - 1.0 / (1.0 + rad2).sqrt());
    true
}

/// The beam common to two beams along `dir` (`commonbeam`): (centre, area) each.
fn common_beam(a: &mut (Vec3, f64), b: (Vec3, f64), dir: Vec3) -> bool {
    use std::f64::consts::PI;
    let c1 = a.0 - dir * a.0.dot(dir);
    let c2 = b.0 - dir * b.0.dot(dir);
    let (cent, rad2) = intercircle(c1, c2, a.1 / PI, b.1 / PI);
    if rad2 <= FTINY {
        return false;
    }
    *a = (cent, PI * rad2);
    true
}

/// The image of source number `index` in mirror `m` (`makevsrc`), if the mirror can
/// relay it.
fn image(
    m: &MirrorPlane,
    sources: &[Source],
    index: usize,
    mirrors: &[MirrorPlane],
) -> Option<Source> {
    use std::f64::consts::PI;
    let source = sources.get(index)?;
    if source.target == SourceTarget::Object(m.object) {
        return None; // a mirror cannot image itself
    }
    if !in_front(m, &source.shape, &source.axes) {
        return None;
    }
    let radius2 = relay_disk(m, source, mirrors);
    if radius2 <= FTINY {
        return None;
    }
    let shape = reflect_shape(m, &source.shape);
    let (mut spot, mut beam) = (None, None);
    if let SourceShape::Distant { direction, .. } = shape {
        if source.proximity.is_some() {
            return None;
        }
        let mut ours = (m.center, PI * radius2);
        if let Some((c, area)) = source.beam {
            let (_, srad) = source.shape.center_radius();
            let theirs_center = m.point(c);
            let d = (area / PI).sqrt() + ours.0.distance(theirs_center) * srad;
            if !common_beam(&mut ours, (theirs_center, PI * d * d), direction) {
                return None;
            }
        }
        beam = Some(ours);
    } else {
        let mut aim = m.center - location(&shape);
        let d = normalize(&mut aim);
        if d == 0.0 || source.proximity.is_some_and(|p| d > p) {
            return None;
        }
        let (_, srad) = source.shape.center_radius();
        let k = (radius2.sqrt() + srad) / d;
        let mut ours = (k < 1.0 - FTINY).then(|| Spot {
            size: 2.0 * PI * (1.0 - (1.0 - k * k).sqrt()),
            aim,
            focus: 0.0,
        });
        if let Some(theirs) = &source.spot {
            let mut theirs = *theirs;
            theirs.aim = m.vector(theirs.aim);
            normalize(&mut theirs.aim);
            match ours.as_mut() {
                Some(o) => {
                    o.focus = theirs.focus;
                    if !common_spot(o, &theirs) {
                        return None;
                    }
                }
                None => ours = Some(theirs),
            }
        }
        if let (Some(s), SourceShape::Flat { normal, .. }) = (&ours, &shape)
            && !s.faces(*normal)
        {
            return None;
        }
        spot = ours;
    }
    Some(Source {
        axes: source.axes.map(|a| m.vector(a)),
        shape,
        proximity: source.proximity,
        spot,
        target: SourceTarget::Object(m.object),
        parent: Some(index),
        beam,
    })
}

impl Scene {
    /// Adds the images of the light sources in the scene's plane mirrors, and images of
    /// those up to `relays` mirrors deep (rtrace's `-dr`; 0 adds none).
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
        if mirrors.is_empty() {
            return;
        }
        for index in (0..self.sources.len()).rev() {
            add_images(&mut self.sources, index, relays, &mirrors);
        }
    }
}

/// `addvirtuals`: images of source `index` in every mirror, and of those in turn.
fn add_images(sources: &mut Vec<Source>, index: usize, relays: u32, mirrors: &[MirrorPlane]) {
    if relays == 0 {
        return;
    }
    for m in mirrors {
        if let Some(v) = image(m, sources, index, mirrors) {
            sources.push(v);
            let new = sources.len() - 1;
            add_images(sources, new, relays - 1, mirrors);
        }
    }
}
