//! Light sources for the direct calculation (`src/rt/srcsupp.c`, `srcsamp.c`): where a
//! source is, its size, and the deterministic samples (`-dj 0`) a point sends shadow
//! rays to. Flat sources are split into up to 64 partitions, finer for nearer points and
//! for smaller `-ds`, exactly as Radiance splits them, so sample directions and solid
//! angles agree with rtrace. radc's `-dx+` ([`Source::exact_samples`]) instead gives
//! each partition its exact solid angle (`crate::solid_angle`), more accurate than
//! rtrace and so no longer equal to it.

use crate::materials::light::Spot;
use crate::math::{FHUGE, FTINY, Vec3, normalize, perpendicular};
use crate::scene::Object;
use crate::shapes::{PackedSphere, Shape};
use crate::solid_angle::DiskFrame;

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

impl SourceShape {
    pub fn sphere(center: Vec3, radius: f64) -> SourceShape {
        SourceShape::Sphere { center, radius }
    }

    /// A polygon source as `fsetsrc` sets it up: centred on the vertex mean, with exact
    /// half-extents for parallelograms and triangles, otherwise a square of equal area.
    pub fn polygon(vertices: &[Vec3], normal: Vec3, area: f64) -> SourceShape {
        let n = vertices.len() as f64;
        let center = vertices.iter().copied().sum::<Vec3>() / n;
        let (u, v) = match vertices {
            [a, b, _, d] => (0.5 * (*b - *a), 0.5 * (*d - *a)),
            [_, _, _] => {
                // Aim U along the edge nearest the centre, scaled to that distance.
                let edges = [(2usize, 0usize), (0, 1), (1, 2)];
                let (mut near0, mut dmin) = (2usize, dist2_line(center, vertices[2], vertices[0]));
                for &(i, j) in &edges[1..] {
                    let d = dist2_line(center, vertices[i], vertices[j]);
                    if d < dmin {
                        near0 = i;
                        dmin = d;
                    }
                }
                let i = (near0 + 1) % 3;
                let mut u = vertices[i] - vertices[near0];
                normalize(&mut u);
                let u = u * dmin.sqrt();
                (u, normal.cross(u))
            }
            _ => square_extents(normal, area),
        };
        SourceShape::Flat {
            center,
            normal,
            area,
            u,
            v,
            circular: false,
            parallelogram: is_parallelogram(vertices),
            convex_outline: if !is_parallelogram(vertices) && is_convex(vertices, normal) {
                vertices.to_vec()
            } else {
                Vec::new()
            },
            radius: vertices
                .iter()
                .map(|p| p.distance(center))
                .fold(0.0, f64::max),
        }
    }

    pub fn cylinder(p0: Vec3, p1: Vec3, radius: f64) -> SourceShape {
        SourceShape::Cylinder {
            center: 0.5 * (p0 + p1),
            half_axis: 0.5 * (p1 - p0),
            radius,
        }
    }

    pub fn disk(center: Vec3, normal: Vec3, radius: f64) -> SourceShape {
        let area = std::f64::consts::PI * radius * radius;
        let (u, v) = square_extents(normal, area);
        SourceShape::Flat {
            center,
            normal,
            area,
            u,
            v,
            circular: true,
            parallelogram: false,
            convex_outline: Vec::new(),
            radius,
        }
    }

    /// A distant source of full angle `angle_deg` degrees toward `direction`. Its solid
    /// angle is `cap_solid_angle`'s, the form rtrace computes it in.
    pub fn distant(mut direction: Vec3, angle_deg: f64) -> Option<SourceShape> {
        if normalize(&mut direction) == 0.0 {
            return None;
        }
        let theta = (std::f64::consts::PI / 180.0 / 2.0) * angle_deg;
        if theta <= FTINY {
            return None;
        }
        Some(SourceShape::Distant {
            direction,
            solid_angle: cap_solid_angle(theta.cos()),
        })
    }

    /// The centre and bounding radius (for `glow` proximity).
    pub(crate) fn center_radius(&self) -> (Vec3, f64) {
        match self {
            SourceShape::Sphere { center, radius } => (*center, *radius),
            SourceShape::Flat { center, radius, .. } => (*center, *radius),
            SourceShape::Distant {
                direction,
                solid_angle,
            } => (*direction, (solid_angle / std::f64::consts::PI).sqrt()),
            SourceShape::Cylinder {
                center, half_axis, ..
            } => (*center, half_axis.length()),
        }
    }
}

/// Whether four vertices form a parallelogram (opposite corners share a midpoint, to
/// rounding).
fn is_parallelogram(vertices: &[Vec3]) -> bool {
    let [a, b, c, d] = vertices else {
        return false;
    };
    let size = (*c - *a).length().max((*d - *b).length());
    ((*a + *c) - (*b + *d)).length() <= 1e-9 * size
}

/// Whether a planar polygon is convex: every corner turns the same way about
/// `normal` (none turning the other way, to rounding).
fn is_convex(vertices: &[Vec3], normal: Vec3) -> bool {
    let n = vertices.len();
    if n < 3 {
        return false;
    }
    let (mut pos, mut neg) = (false, false);
    let size = vertices
        .iter()
        .map(|v| v.distance(vertices[0]))
        .fold(0.0, f64::max);
    for i in 0..n {
        let (a, b, c) = (vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]);
        let turn = (b - a).cross(c - b).dot(normal);
        if turn > 1e-12 * size * size {
            pos = true;
        } else if turn < -1e-12 * size * size {
            neg = true;
        }
    }
    pos != neg
}

/// Half-extents of a square of `area` in the plane of `normal` (`setflatss`, without
/// randomized orientation).
fn square_extents(normal: Vec3, area: f64) -> (Vec3, Vec3) {
    let u = perpendicular(normal).unwrap_or(Vec3::X) * (0.5 * area.sqrt());
    (u, normal.cross(u))
}

/// Squared distance from `p` to the line through `a` and `b`.
fn dist2_line(p: Vec3, a: Vec3, b: Vec3) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let w = p - a;
    if len2 == 0.0 {
        return w.length_squared();
    }
    let along = w.dot(d);
    w.length_squared() - along * along / len2
}

/// A leaf partition: centre and size per axis in partition units (`MAXSPART` is the
/// whole source).
#[derive(Clone, Copy, Debug)]
struct Part {
    cent: [i32; 3],
    size: [i32; 3],
}

/// The whole source as one partition.
const WHOLE: Part = Part {
    cent: [0; 3],
    size: [MAXSPART; 3],
};

/// The sample for a flat region's vector solid angle `vs` (relative to `org`): its
/// direction and length, and the distance to the source's plane that way; `None` when
/// the region is seen edge-on.
fn plane_sample(vs: Vec3, org: Vec3, center: Vec3, normal: Vec3) -> Option<SourceSample> {
    let mut dir = vs;
    let omega = normalize(&mut dir);
    let cos = -dir.dot(normal);
    if omega <= 0.0 || cos <= 0.0 {
        return None;
    }
    Some(SourceSample {
        dir,
        omega,
        dist: (org - center).dot(normal) / cos,
    })
}

/// The halves of a cell spanning `radial` (a radius or polar angle range) and `phi`:
/// across the radial range at `mid()` when `across_radial`, else across the angle at
/// its middle. Disk and cap cells differ only in where their radial middle lies.
fn halve(
    radial: (f64, f64),
    phi: (f64, f64),
    across_radial: bool,
    mid: impl FnOnce() -> f64,
) -> [((f64, f64), (f64, f64)); 2] {
    if across_radial {
        let m = mid();
        [((radial.0, m), phi), ((m, radial.1), phi)]
    } else {
        let m = 0.5 * (phi.0 + phi.1);
        [(radial, (phi.0, m)), (radial, (m, phi.1))]
    }
}

/// An annular sector of a disk source: `rho` in fractions of the radius, `phi` in
/// radians from the frame's `e1` toward `e2`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct DiskCell {
    rho: (f64, f64),
    phi: (f64, f64),
}

impl DiskCell {
    const WHOLE: DiskCell = DiskCell {
        rho: (0.0, 1.0),
        phi: (0.0, 2.0 * std::f64::consts::PI),
    };

    fn is_whole(&self) -> bool {
        *self == DiskCell::WHOLE
    }

    /// Area as a fraction of the disk's.
    fn area_fraction(&self) -> f64 {
        let (r0, r1) = self.rho;
        (r1 * r1 - r0 * r0) * (self.phi.1 - self.phi.0) / (2.0 * std::f64::consts::PI)
    }

    /// The centroid, as (fraction of the radius, angle).
    fn centroid(&self) -> (f64, f64) {
        let (r0, r1) = self.rho;
        let half = 0.5 * (self.phi.1 - self.phi.0);
        let rc =
            2.0 / 3.0 * (r1 * r1 * r1 - r0 * r0 * r0) / (r1 * r1 - r0 * r0) * half.sin() / half;
        (rc, self.phi.0 + half)
    }

    /// The two halves of equal area: across the radius or across the angle, whichever
    /// side is longer.
    fn split(&self) -> [DiskCell; 2] {
        let (r0, r1) = self.rho;
        let across_radius = r1 - r0 >= 0.5 * (r0 + r1) * (self.phi.1 - self.phi.0);
        halve(self.rho, self.phi, across_radius, || {
            (0.5 * (r0 * r0 + r1 * r1)).sqrt()
        })
        .map(|(rho, phi)| DiskCell { rho, phi })
    }

    /// A sample moved from the cell's middle (in `rho^2` and angle, so uniformly by
    /// area) by `o`, fractions of its extent, standing for `cos / d^2` times its area
    /// there (`area` the disk's).
    fn jittered(
        &self,
        frame: &DiskFrame,
        normal: Vec3,
        area: f64,
        o: [f64; 2],
    ) -> Option<SourceSample> {
        let (r0, r1) = self.rho;
        let rho2 = 0.5 * (r0 * r0 + r1 * r1) + o[0] * (r1 * r1 - r0 * r0);
        let phi = 0.5 * (self.phi.0 + self.phi.1) + o[1] * (self.phi.1 - self.phi.0);
        let mut dir = frame.point(rho2.max(0.0).sqrt(), phi);
        let dist = normalize(&mut dir);
        let cos = -normal.dot(dir);
        (dist > 0.0 && cos > 0.0).then(|| SourceSample {
            dir,
            omega: cos * area * self.area_fraction() / (dist * dist),
            dist,
        })
    }

    /// The sample for this cell: toward its vector solid angle `V` when that direction
    /// meets the cell (a sector need not be convex), else toward its centroid with the
    /// part of `V` along that direction.
    fn sample(&self, frame: &DiskFrame, org: Vec3, normal: Vec3) -> Option<SourceSample> {
        let vs = frame.sector(self.rho, self.phi);
        let s = plane_sample(vs, org, org + frame.center, normal)?;
        let q = s.dir * s.dist - frame.center;
        let rho = q.length() / frame.radius;
        let tau = 2.0 * std::f64::consts::PI;
        let phi = (q.dot(frame.e2).atan2(q.dot(frame.e1)) - self.phi.0).rem_euclid(tau);
        let tol = 1e-9;
        if rho >= self.rho.0 - tol
            && rho <= self.rho.1 + tol
            && phi <= self.phi.1 - self.phi.0 + tol
        {
            return Some(s);
        }
        let (rc, pc) = self.centroid();
        let mut dir = frame.point(rc, pc);
        let dist = normalize(&mut dir);
        let omega = vs.dot(dir);
        (omega > 0.0 && dist > 0.0).then_some(SourceSample { dir, omega, dist })
    }
}

/// The cone of directions in which a sphere is seen: its axis (toward the centre), two
/// axes across it, and its half-angle.
struct Cap {
    axis: Vec3,
    e1: Vec3,
    e2: Vec3,
    alpha: f64,
}

/// A piece of a [`Cap`]: angles from the axis and around it (from `e1` toward `e2`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct CapCell {
    theta: (f64, f64),
    phi: (f64, f64),
}

impl Cap {
    fn whole(&self) -> CapCell {
        CapCell {
            theta: (0.0, self.alpha),
            phi: (0.0, 2.0 * std::f64::consts::PI),
        }
    }

    /// `V` of a piece, in closed form: with `w = cos t axis + sin t (cos p e1 + sin p
    /// e2)` and `dw = sin t dt dp`, the axial part is `(sin^2 t1 - sin^2 t0) / 2 dp`
    /// and the parts across are `S (sin p1 - sin p0)` along `e1`, `S (cos p0 - cos p1)`
    /// along `e2`, with `S = [t / 2 - sin 2t / 4]` from `t0` to `t1`.
    fn vector(&self, c: &CapCell) -> Vec3 {
        let (t0, t1) = c.theta;
        let (p0, p1) = c.phi;
        let (s0, s1) = (t0.sin(), t1.sin());
        let along = 0.5 * (s1 * s1 - s0 * s0) * (p1 - p0);
        let across = 0.5 * (t1 - t0) - 0.25 * ((2.0 * t1).sin() - (2.0 * t0).sin());
        self.axis * along
            + self.e1 * (across * (p1.sin() - p0.sin()))
            + self.e2 * (across * (p0.cos() - p1.cos()))
    }
}

impl Cap {
    /// The direction moved from the piece's middle (in `cos t` and angle, so uniformly
    /// by solid angle) by `o`, fractions of its extent.
    fn direction(&self, c: &CapCell, o: [f64; 2]) -> Vec3 {
        let (c0, c1) = (c.theta.0.cos(), c.theta.1.cos());
        let cos_t = 0.5 * (c0 + c1) + o[0] * (c0 - c1);
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        let phi = 0.5 * (c.phi.0 + c.phi.1) + o[1] * (c.phi.1 - c.phi.0);
        let (s, k) = phi.sin_cos();
        self.axis * cos_t + (self.e1 * k + self.e2 * s) * sin_t
    }
}

impl CapCell {
    /// Solid angle.
    fn omega(&self) -> f64 {
        (self.theta.0.cos() - self.theta.1.cos()) * (self.phi.1 - self.phi.0)
    }

    /// The two halves of equal solid angle, across the longer side.
    fn split(&self) -> [CapCell; 2] {
        let (t0, t1) = self.theta;
        let across_theta = t1 - t0 >= (0.5 * (t0 + t1)).sin() * (self.phi.1 - self.phi.0);
        halve(self.theta, self.phi, across_theta, || {
            (0.5 * (t0.cos() + t1.cos())).acos()
        })
        .map(|(theta, phi)| CapCell { theta, phi })
    }
}

/// A sphere's pieces for `-dx+`: the rule of [`disk_cells`] for the sphere's outline
/// (a disk of its radius facing the point, at the distance `d` of its centre), each
/// piece's half-width that of a square of its share of that disk's area.
fn cap_cells(cap: &Cap, d: f64, radius: f64, weight: f64, ds: f64) -> Vec<CapCell> {
    let k = 2.0 * weight / ds;
    let whole = cap.whole();
    let (area, omega) = (std::f64::consts::PI * radius * radius, whole.omega());
    let mut out = Vec::new();
    let mut stack = vec![(whole, MAXSPART)];
    while let Some((cell, mp)) = stack.pop() {
        let half2 = 0.25 * area * cell.omega() / omega;
        if mp < 2 || d * d >= k * k * half2 {
            out.push(cell);
            continue;
        }
        let [a, b] = cell.split();
        stack.push((b, mp / 2));
        stack.push((a, mp / 2));
    }
    out
}

/// A disk source's partitions for `-dx+`: Radiance's rule for flat sources
/// (`flt_partit`: halve while the point is nearer than `2 * weight / ds` half-widths,
/// at most 64 pieces) applied to annular sectors of equal area, each piece's
/// half-width taken as that of a square of its area (so the whole disk splits first
/// exactly when Radiance splits its square of equal area).
fn disk_cells(frame: &DiskFrame, weight: f64, ds: f64) -> Vec<DiskCell> {
    let k = 2.0 * weight / ds;
    let area = std::f64::consts::PI * frame.radius * frame.radius;
    let mut out = Vec::new();
    let mut stack = vec![(DiskCell::WHOLE, MAXSPART)];
    while let Some((cell, mp)) = stack.pop() {
        let (rc, pc) = cell.centroid();
        let d2 = frame.point(rc, pc).length_squared();
        let half2 = 0.25 * area * cell.area_fraction();
        if mp < 2 || d2 >= k * k * half2 {
            out.push(cell);
            continue;
        }
        let [a, b] = cell.split();
        stack.push((b, mp / 2));
        stack.push((a, mp / 2));
    }
    out
}

impl Source {
    /// Whether a point is too far from a `glow` source to be lit by it.
    #[inline]
    fn skipped_from(&self, org: Vec3) -> bool {
        let Some(prox) = self.proximity else {
            return false;
        };
        if matches!(self.shape, SourceShape::Distant { .. }) {
            return false;
        }
        let (c, r) = self.shape.center_radius();
        org.distance_squared(c) > (prox + r) * (prox + r)
    }

    /// The shadow-ray samples from `org` for a ray of weight `weight`, with `-ds`
    /// `size_ratio`, appended to `out`.
    pub fn samples(&self, org: Vec3, weight: f64, size_ratio: f64, out: &mut Vec<SourceSample>) {
        self.jittered_samples(org, weight, size_ratio, None, false, out);
    }

    /// [`Source::samples`] with `-dj`: `jitter` is the fraction of each partition a
    /// sample may move by from its centre (Radiance's `dstrsrc`) and the seed of the
    /// moves; `None` keeps the centres. With `exact` (`-dx+`), convex polygons, disks,
    /// spheres and distant sources are sampled with each partition's exact solid angle
    /// ([`Source::exact_samples`]).
    #[inline]
    pub fn jittered_samples(
        &self,
        org: Vec3,
        weight: f64,
        size_ratio: f64,
        jitter: Option<(f64, u64)>,
        exact: bool,
        out: &mut Vec<SourceSample>,
    ) {
        if self.skipped_from(org) {
            return;
        }
        let start = out.len();
        match (&self.shape, jitter) {
            (&SourceShape::Sphere { center, radius }, None) if !exact => {
                // Radiance's one sample of a sphere, its centre: `partition_samples`'
                // `sample` of `WHOLE` without offsets (centre 0 / MAXSPART, size
                // MAXSPART / MAXSPART on each axis), with nothing of it to look up.
                if let Some(s) = sphere_sample(center, radius, org, [0.0; 3], [1.0; 3]) {
                    out.push(s);
                }
            }
            _ => {
                if !(exact && self.exact_samples(org, weight, size_ratio, jitter, out)) {
                    self.partition_samples(org, weight, size_ratio, jitter, out);
                }
            }
        }
        if self.proximity.is_none() && self.beam.is_none() && self.spot.is_none() {
            return; // `accepted` keeps every sample as it is
        }
        let mut kept = start;
        for i in start..out.len() {
            if let Some(s) = self.accepted(org, out[i]) {
                out[kept] = s;
                kept += 1;
            }
        }
        out.truncate(kept);
    }

    /// Radiance's samples: each partition's centre (moved by the jitter), standing for
    /// the partition's area times `cos / d^2` there.
    fn partition_samples(
        &self,
        org: Vec3,
        weight: f64,
        size_ratio: f64,
        jitter: Option<(f64, u64)>,
        out: &mut Vec<SourceSample>,
    ) {
        // The k-th partition's jitter offsets.
        let offset = |k: usize| {
            jitter.map(|(j, seed)| {
                let seed = crate::random::derive(seed, k as u64);
                [0u64, 1, 2].map(|a| j * (1.0 - 2.0 * crate::random::uniform(seed, a)))
            })
        };
        let parts = match &self.shape {
            SourceShape::Flat {
                center,
                normal,
                u,
                v,
                ..
            } if size_ratio > FTINY => {
                if (org - *center).dot(*normal) <= 0.0 {
                    return; // behind a flat source
                }
                flat_parts(org, *center, *u, *v, weight, size_ratio)
            }
            SourceShape::Cylinder {
                center,
                half_axis,
                radius,
            } if size_ratio > FTINY => {
                match cylinder_parts(org, *center, *half_axis, *radius, weight, size_ratio) {
                    Some(parts) => parts,
                    None => return, // inside the cylinder's extent
                }
            }
            _ => {
                // One partition, the whole source: no list to build.
                if let Some(s) = self.sample(org, WHOLE, 1, offset(0)) {
                    out.push(s);
                }
                return;
            }
        };
        let np = parts.len();
        for (k, p) in parts.into_iter().enumerate() {
            if let Some(s) = self.sample(org, p, np, offset(k)) {
                out.push(s);
            }
        }
    }

    /// The sample as the source's limits leave it: `None` beyond a `glow`'s reach,
    /// outside a distant virtual source's beam or a spotlight's cone; a spotlight's
    /// solid angle as seen from its focus.
    fn accepted(&self, org: Vec3, mut s: SourceSample) -> Option<SourceSample> {
        let local = !matches!(self.shape, SourceShape::Distant { .. });
        if let Some(prox) = self.proximity
            && s.dist > prox
            && local
        {
            return None;
        }
        if let Some((center, area)) = self.beam
            && !local
        {
            let to = center - org;
            let along = s.dir.dot(to);
            if std::f64::consts::PI * (to.length_squared() - along * along) > area {
                return None;
            }
        }
        if let Some(spot) = &self.spot
            && local
        {
            if spot.excludes(s.dir) {
                return None;
            }
            // The solid angle as seen from the spot's virtual focus (srcray).
            let d = s.dist + spot.focus;
            s.omega *= s.dist * s.dist / (d * d);
        }
        Some(s)
    }

    /// `-dx+`: samples that stand for each partition's exact vector solid angle `V`
    /// (see [`crate::solid_angle`]): direction `V / |V|`, solid angle `|V|`, so that a
    /// Lambertian surface receives exactly a fully visible partition's irradiance,
    /// where Radiance's centre samples are off by the order of `(size / distance)^2`.
    /// Parallelograms keep Radiance's partitions (`flat_parts`); disks are split into
    /// annular sectors by the same rule ([`disk_cells`]); a sphere's cone of directions
    /// is split into pieces of its cap the same way ([`cap_cells`]; Radiance samples a
    /// sphere at its centre only, which is exact when all of it is seen above the
    /// horizon, but neither resolves shadows across it nor a sphere the horizon cuts);
    /// other convex polygons are split into triangles ([`Source::exact_convex`]); a
    /// distant source is one cap. False for the shapes without an exact treatment
    /// (cylinders, concave polygons), which keep Radiance's samples.
    ///
    /// With `jitter` (`-dj`) each piece's sample moves by up to that fraction of the
    /// piece, uniformly by area on a disk (standing for `cos / d^2` times the piece's
    /// area there) and by solid angle on a sphere's cap (standing for the piece's solid
    /// angle), and triangles' likewise by area ([`Source::exact_convex`]): at `-dj 1`
    /// all are unbiased, shadows and horizon included, where Radiance's jittered disk
    /// samples fill a square of equal area pulled in toward the rim and its sphere
    /// samples a cube inside the sphere. Parallelograms and distant sources keep
    /// Radiance's jittered samples (unbiased already).
    fn exact_samples(
        &self,
        org: Vec3,
        weight: f64,
        size_ratio: f64,
        jitter: Option<(f64, u64)>,
        out: &mut Vec<SourceSample>,
    ) -> bool {
        // The k-th piece's offsets, each within +-j/2 of the piece's extent.
        let offsets = |k: usize| {
            jitter.map(|(j, seed)| {
                let seed = crate::random::derive(seed, k as u64);
                [0u64, 1].map(|a| j * (crate::random::uniform(seed, a) - 0.5))
            })
        };
        match &self.shape {
            SourceShape::Flat { circular: true, .. } => {
                self.exact_disk(org, weight, size_ratio, &offsets, out)
            }
            SourceShape::Flat { convex_outline, .. } if !convex_outline.is_empty() => {
                self.exact_convex(org, weight, size_ratio, jitter, out)
            }
            SourceShape::Flat { .. } | SourceShape::Distant { .. } if jitter.is_some() => false,
            SourceShape::Flat {
                center,
                normal,
                u,
                v,
                parallelogram: true,
                ..
            } => {
                if (org - *center).dot(*normal) <= 0.0 {
                    return true; // behind a flat source
                }
                let parts = if size_ratio > FTINY {
                    flat_parts(org, *center, *u, *v, weight, size_ratio)
                } else {
                    vec![WHOLE]
                };
                let m = f64::from(MAXSPART);
                for p in parts {
                    let lo = |i: usize| f64::from(p.cent[i] - p.size[i]) / m;
                    let hi = |i: usize| f64::from(p.cent[i] + p.size[i]) / m;
                    let at = |x: f64, y: f64| *center + *u * x + *v * y - org;
                    let corners = [
                        at(lo(0), lo(1)),
                        at(hi(0), lo(1)),
                        at(hi(0), hi(1)),
                        at(lo(0), hi(1)),
                    ];
                    let vs = crate::solid_angle::polygon(&corners, -*normal);
                    // A parallelogram is convex: V / |V| points into it.
                    if let Some(s) = plane_sample(vs, org, *center, *normal) {
                        out.push(s);
                    }
                }
                true
            }
            SourceShape::Sphere { center, radius } => {
                let to = *center - org;
                let d2 = to.length_squared();
                if d2 <= radius * radius * (1.0 + 1e-9) {
                    return false; // inside: Radiance's sample
                }
                let d = d2.sqrt();
                let k = 2.0 * weight / size_ratio;
                let whole_half2 = 0.25 * std::f64::consts::PI * radius * radius;
                let unsplit = size_ratio <= FTINY || d2 >= k * k * whole_half2;
                if unsplit && jitter.is_none() {
                    // One piece: V = pi sin^2(alpha) toward the centre, Radiance's sample.
                    out.push(SourceSample {
                        dir: to / d,
                        omega: std::f64::consts::PI * radius * radius / d2,
                        dist: d,
                    });
                    return true;
                }
                let Some(e1) = perpendicular(to / d) else {
                    return false;
                };
                let cap = Cap {
                    axis: to / d,
                    e1,
                    e2: (to / d).cross(e1),
                    alpha: (*radius / d).asin(),
                };
                let cells = if unsplit {
                    vec![cap.whole()]
                } else {
                    cap_cells(&cap, d, *radius, weight, size_ratio)
                };
                for (k, cell) in cells.into_iter().enumerate() {
                    if let Some(o) = offsets(k) {
                        out.push(SourceSample {
                            dir: cap.direction(&cell, o),
                            omega: cell.omega(),
                            dist: d,
                        });
                        continue;
                    }
                    let mut dir = cap.vector(&cell);
                    let omega = normalize(&mut dir);
                    // V / |V| lies in the cone, so its shadow ray meets the sphere;
                    // the distance is the centre's, as Radiance's (glow, spotlights).
                    if omega > 0.0 {
                        out.push(SourceSample {
                            dir,
                            omega,
                            dist: d,
                        });
                    }
                }
                true
            }
            SourceShape::Distant {
                direction,
                solid_angle,
            } => {
                // A cap of half-angle t: |V| = pi sin^2 t, Omega = 2 pi (1 - cos t).
                let cos_t = 1.0 - solid_angle / (2.0 * std::f64::consts::PI);
                out.push(SourceSample {
                    dir: *direction,
                    omega: std::f64::consts::PI * (1.0 - cos_t * cos_t).max(0.0),
                    dist: FHUGE,
                });
                true
            }
            _ => false,
        }
    }

    /// [`Source::exact_samples`] for a convex polygon other than a parallelogram: the
    /// whole polygon while the point is far enough (Radiance's rule, the half-width
    /// that of a square of equal area), else its fan of triangles from the first
    /// vertex, each halved across its longest edge by the same rule (at most about 64
    /// pieces). Jittered, every piece is a triangle and its sample moves uniformly by
    /// area (toward the centroid for `-dj` below 1), standing for `cos / d^2` times
    /// its area.
    fn exact_convex(
        &self,
        org: Vec3,
        weight: f64,
        size_ratio: f64,
        jitter: Option<(f64, u64)>,
        out: &mut Vec<SourceSample>,
    ) -> bool {
        let SourceShape::Flat {
            center,
            normal,
            area,
            convex_outline: outline,
            ..
        } = &self.shape
        else {
            return false;
        };
        if (org - *center).dot(*normal) <= 0.0 || outline.len() < 3 {
            return true; // behind
        }
        let k = if size_ratio > FTINY {
            2.0 * weight / size_ratio
        } else {
            0.0
        };
        let split = |c: Vec3, a: f64| org.distance_squared(c) < k * k * 0.25 * a;
        if jitter.is_none() && !split(*center, *area) {
            let rel: Vec<Vec3> = outline.iter().map(|p| *p - org).collect();
            out.extend(plane_sample(
                crate::solid_angle::polygon(&rel, -*normal),
                org,
                *center,
                *normal,
            ));
            return true;
        }
        let fans = outline.len() - 2;
        let mp0 = (MAXSPART / fans as i32).max(1);
        let mut stack: Vec<([Vec3; 3], i32)> = (1..=fans)
            .rev()
            .map(|i| ([outline[0], outline[i], outline[i + 1]], mp0))
            .collect();
        let mut piece = 0u64;
        while let Some((t, mp)) = stack.pop() {
            let c = (t[0] + t[1] + t[2]) / 3.0;
            let a = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
            if mp >= 2 && split(c, a) {
                // Halve across the longest edge (i, j), l the opposite corner.
                let len = |i: usize, j: usize| t[i].distance_squared(t[j]);
                let (i, j, l) =
                    [(0, 1, 2), (1, 2, 0), (2, 0, 1)]
                        .into_iter()
                        .fold((0, 1, 2), |best, e| {
                            if len(e.0, e.1) > len(best.0, best.1) {
                                e
                            } else {
                                best
                            }
                        });
                let m = 0.5 * (t[i] + t[j]);
                stack.push(([t[l], m, t[j]], mp / 2));
                stack.push(([t[l], t[i], m], mp / 2));
                continue;
            }
            if let Some((j, seed)) = jitter {
                let seed = crate::random::derive(seed, piece);
                let (u1, u2) = (
                    crate::random::uniform(seed, 0).sqrt(),
                    crate::random::uniform(seed, 1),
                );
                let p = t[0] * (1.0 - u1) + t[1] * (u1 * (1.0 - u2)) + t[2] * (u1 * u2);
                let mut dir = c + (p - c) * j - org;
                let dist = normalize(&mut dir);
                let cos = -normal.dot(dir);
                if dist > 0.0 && cos > 0.0 {
                    out.push(SourceSample {
                        dir,
                        omega: cos * a / (dist * dist),
                        dist,
                    });
                }
            } else {
                let rel = t.map(|p| p - org);
                out.extend(plane_sample(
                    crate::solid_angle::polygon(&rel, -*normal),
                    org,
                    *center,
                    *normal,
                ));
            }
            piece += 1;
        }
        true
    }

    /// [`Source::exact_samples`] for a disk source.
    fn exact_disk(
        &self,
        org: Vec3,
        weight: f64,
        size_ratio: f64,
        offsets: &dyn Fn(usize) -> Option<[f64; 2]>,
        out: &mut Vec<SourceSample>,
    ) -> bool {
        let SourceShape::Flat {
            center,
            normal,
            radius,
            area,
            ..
        } = &self.shape
        else {
            return false;
        };
        if (org - *center).dot(*normal) <= 0.0 {
            return true; // behind
        }
        let Some(e1) = perpendicular(*normal) else {
            return true;
        };
        let frame = DiskFrame {
            center: *center - org,
            e1,
            e2: normal.cross(e1),
            radius: *radius,
        };
        let cells = if size_ratio > FTINY {
            disk_cells(&frame, weight, size_ratio)
        } else {
            vec![DiskCell::WHOLE]
        };
        for (k, cell) in cells.into_iter().enumerate() {
            if let Some(o) = offsets(k) {
                out.extend(cell.jittered(&frame, *normal, *area, o));
            } else if cell.is_whole() {
                // The disk is convex: V / |V| points into it.
                out.extend(plane_sample(frame.whole(), org, *center, *normal));
            } else {
                out.extend(cell.sample(&frame, org, *normal));
            }
        }
        true
    }

    /// The sample of partition `p` (of `np`), moved from its centre by `offset` (each in
    /// -1..1, times the partition's half-size per axis) when jittered.
    fn sample(
        &self,
        org: Vec3,
        p: Part,
        np: usize,
        offset: Option<[f64; 3]>,
    ) -> Option<SourceSample> {
        let m = f64::from(MAXSPART);
        let mut vpos = [
            f64::from(p.cent[0]) / m,
            f64::from(p.cent[1]) / m,
            f64::from(p.cent[2]) / m,
        ];
        let frac = |i: usize| f64::from(p.size[i]) / m;
        let off = offset.unwrap_or([0.0; 3]);
        for (i, o) in off.iter().enumerate() {
            vpos[i] += o * frac(i);
        }
        match &self.shape {
            SourceShape::Sphere { center, radius } => {
                sphere_sample(*center, *radius, org, vpos, [frac(0), frac(1), frac(2)])
            }
            SourceShape::Flat {
                center,
                normal,
                area,
                u,
                v,
                circular,
                ..
            } => {
                if *circular && np > 1 {
                    // Pull corner samples in toward the circle (srcsamp.c's trim for SCIR).
                    // 2/sqrt(pi): a square of equal area spans this much of the disk.
                    let k = std::f64::consts::FRAC_2_SQRT_PI;
                    let tu = k * (1.0 - 0.5 * vpos[1] * vpos[1]).sqrt();
                    let tv = k * (1.0 - 0.5 * vpos[0] * vpos[0]).sqrt();
                    vpos[0] *= tu;
                    vpos[1] *= tv;
                }
                let mut dir = *center + *u * vpos[0] + *v * vpos[1] - org;
                let d = normalize(&mut dir);
                if d == 0.0 {
                    return None;
                }
                let dom = -normal.dot(dir) * frac(0) * frac(1);
                if dom <= 1e-4 {
                    return None; // behind or edge-on
                }
                Some(SourceSample {
                    dir,
                    omega: dom * area / (d * d),
                    dist: d,
                })
            }
            SourceShape::Cylinder {
                center,
                half_axis,
                radius,
            } => {
                let mut dir = *center + *half_axis * vpos[0] - org;
                let d = normalize(&mut dir);
                if d == 0.0 {
                    return None;
                }
                // Cosine between the direction and the plane across the axis.
                let along = dir.dot(*half_axis);
                let dom = (1.0 - along * along / half_axis.length_squared())
                    .max(0.0)
                    .sqrt()
                    * frac(0);
                if dom <= 1e-4 {
                    return None;
                }
                let area = 2.0 * radius * 2.0 * half_axis.length();
                Some(SourceSample {
                    dir,
                    omega: dom * area / (d * d),
                    dist: d,
                })
            }
            SourceShape::Distant {
                direction,
                solid_angle,
            } => {
                let mut dir = *direction;
                if offset.is_some()
                    && let Some(p) = perpendicular(dir)
                {
                    // Across the source's disk of directions.
                    let r = (solid_angle / std::f64::consts::PI).sqrt();
                    dir += (p * vpos[0] + dir.cross(p) * vpos[1]) * r;
                    normalize(&mut dir);
                }
                Some(SourceSample {
                    dir,
                    omega: frac(0) * frac(1) * frac(2) * solid_angle,
                    dist: FHUGE,
                })
            }
        }
    }
}

/// The sample of a sphere source's partition at `vpos` (each in -1..1) of size `frac`
/// (fractions of the whole per axis): jittered, a point of the cube inscribed in the
/// sphere, so that every shadow ray still meets it (the solid angle stays the whole
/// sphere's).
#[inline]
fn sphere_sample(
    center: Vec3,
    radius: f64,
    org: Vec3,
    vpos: [f64; 3],
    frac: [f64; 3],
) -> Option<SourceSample> {
    let half = radius * (1.0 / 3.0f64).sqrt();
    let mut dir = center + Vec3::from_array(vpos) * half - org;
    let d = normalize(&mut dir);
    if d == 0.0 {
        return None;
    }
    let omega = frac[0] * frac[1] * frac[2] * std::f64::consts::PI * radius * radius;
    Some(SourceSample {
        dir,
        omega: omega / (d * d),
        dist: d,
    })
}

/// A cylinder source's partitions along its axis (`cylpart`): none for points within
/// its extended radius (`None`), one for points very close to or far from it, else
/// halvings while the point is nearer than `2 * weight / ds` half-lengths.
fn cylinder_parts(
    org: Vec3,
    center: Vec3,
    half_axis: Vec3,
    radius: f64,
    weight: f64,
    ds: f64,
) -> Option<Vec<Part>> {
    // Radiance samples within a box around the cylinder: 0.8559 r is its half-width.
    let rad2 = 1.365 * (0.8559 * radius).powi(2);
    let v = org - center;
    let axial = v.dot(half_axis);
    let len2 = half_axis.length_squared();
    let dist2_center = v.length_squared();
    let radial2 = dist2_center - axial * axial / len2;
    if radial2 <= rad2 {
        return None;
    }
    let safe2 = len2 * 4.0 * weight * weight / (ds * ds);
    let root = WHOLE;
    if radial2 <= 4.0 * rad2 || dist2_center >= safe2 {
        return Some(vec![root]);
    }
    let mut out = Vec::new();
    split_cylinder(&mut out, org, root, MAXSPART, center, half_axis, safe2);
    Some(out)
}

fn split_cylinder(
    out: &mut Vec<Part>,
    org: Vec3,
    part: Part,
    mp: i32,
    center: Vec3,
    axis: Vec3,
    d2: f64,
) {
    if mp < 2 || org.distance_squared(center) >= d2 {
        out.push(part);
        return;
    }
    let half = 0.5 * axis;
    let mut lower = part;
    lower.size[0] >>= 1;
    let mut upper = lower;
    lower.cent[0] -= lower.size[0];
    upper.cent[0] += upper.size[0];
    split_cylinder(out, org, lower, mp / 2, center - half, half, d2 * 0.25);
    split_cylinder(out, org, upper, mp / 2, center + half, half, d2 * 0.25);
}

/// Recursive halving of a flat source (`flt_partit`): split the longer side while the
/// point is nearer than `2 * weight / ds` source widths, down to 64 pieces.
fn flat_parts(org: Vec3, center: Vec3, u: Vec3, v: Vec3, weight: f64, ds: f64) -> Vec<Part> {
    let k = 2.0 * weight / ds;
    let k2 = k * k;
    let mut out = Vec::new();
    split_flat(
        &mut out,
        org,
        WHOLE,
        MAXSPART,
        center,
        (u, v),
        (k2 * u.length_squared(), k2 * v.length_squared()),
    );
    out
}

fn split_flat(
    out: &mut Vec<Part>,
    org: Vec3,
    part: Part,
    mp: i32,
    center: Vec3,
    (u, v): (Vec3, Vec3),
    (du2, dv2): (f64, f64),
) {
    let d2 = org.distance_squared(center);
    if mp < 2 || (d2 >= du2 && d2 >= dv2) {
        out.push(part);
        return;
    }
    let (axis, half, uv, duv) = if du2 > dv2 {
        let h = 0.5 * u;
        (0, h, (h, v), (du2 * 0.25, dv2))
    } else {
        let h = 0.5 * v;
        (1, h, (u, h), (du2, dv2 * 0.25))
    };
    let mut lower = part;
    lower.size[axis] >>= 1;
    let mut upper = lower;
    lower.cent[axis] -= lower.size[axis];
    upper.cent[axis] += upper.size[axis];
    split_flat(out, org, lower, mp / 2, center - half, uv, duv);
    split_flat(out, org, upper, mp / 2, center + half, uv, duv);
}

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
