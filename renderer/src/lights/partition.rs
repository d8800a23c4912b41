//! Radiance's partitioned source samples (`srcsamp.c`): flat, spherical and cylindrical
//! sources split into up to `MAXSPART` parts, finer for nearer points and smaller
//! `-ds`, each part sampled at its (jittered) centre.

use super::*;
use crate::math::{FHUGE, FTINY, Vec3, normalize, perpendicular};

/// A leaf partition: centre and size per axis in partition units (`MAXSPART` is the
/// whole source).
#[derive(Clone, Copy, Debug)]
pub(super) struct Part {
    pub(super) cent: [i32; 3],
    pub(super) size: [i32; 3],
}

/// The whole source as one partition.
pub(super) const WHOLE: Part = Part {
    cent: [0; 3],
    size: [MAXSPART; 3],
};

/// The sample for a flat region's vector solid angle `vs` (relative to `org`): its
/// direction and length, and the distance to the source's plane that way; `None` when
/// the region is seen edge-on.
pub(super) fn plane_sample(
    vs: Vec3,
    org: Vec3,
    center: Vec3,
    normal: Vec3,
) -> Option<SourceSample> {
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
pub(super) fn halve(
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

/// The sample of a sphere source's partition at `vpos` (each in -1..1) of size `frac`
/// (fractions of the whole per axis): jittered, a point of the cube inscribed in the
/// sphere, so that every shadow ray still meets it (the solid angle stays the whole
/// sphere's).
#[inline]
pub(super) fn sphere_sample(
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
pub(super) fn cylinder_parts(
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

pub(super) fn split_cylinder(
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
pub(super) fn flat_parts(
    org: Vec3,
    center: Vec3,
    u: Vec3,
    v: Vec3,
    weight: f64,
    ds: f64,
) -> Vec<Part> {
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

pub(super) fn split_flat(
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

impl Source {
    /// Whether a point is too far from a `glow` source to be lit by it.
    #[inline]
    pub(super) fn skipped_from(&self, org: Vec3) -> bool {
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
    pub(super) fn partition_samples(
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
    pub(super) fn accepted(&self, org: Vec3, mut s: SourceSample) -> Option<SourceSample> {
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

    /// The sample of partition `p` (of `np`), moved from its centre by `offset` (each in
    /// -1..1, times the partition's half-size per axis) when jittered.
    pub(super) fn sample(
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
