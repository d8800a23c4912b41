//! radc's exact source samples (`-dx+`): each partition given its exact solid angle
//! (`crate::solid_angle`): cap cells for spheres, fans for convex polygons, annular
//! sectors for disks.
//!
//! Parallelograms keep Radiance's partitions; disks are split by the same rule into
//! annular sectors of equal area, and each partition's sample points along its exact
//! vector solid angle `V` (the integral of the direction over the partition's solid
//! angle) with solid angle `|V|`, so a fully visible partition above the horizon lights a
//! Lambertian surface exactly (distant sources: one cap). A sphere's cone of directions is
//! split into pieces of equal solid angle; other convex polygons into triangles (the whole
//! polygon while the point is far, then its fan, each halved across its longest edge),
//! whose `V` is exact too; cylinders and concave polygons keep Radiance's samples. With
//! `-dj`, disk and triangle pieces are jittered uniformly by area and sphere pieces
//! uniformly by solid angle (unbiased at `-dj 1`; Radiance's jittered disk samples stay
//! 2.4% low on the disk test case, and its sphere samples, points of a cube inside the
//! sphere, spread 11x more where the horizon cuts it). Off by default: rtrace's own errors
//! (order `(size / distance)^2` per partition, 1-3% at `-ds 0.2`) are far above the 1e-3
//! to which radc reproduces rtrace.

use super::partition::*;
use super::*;
use crate::math::{FHUGE, FTINY, Vec3, normalize, perpendicular};
use crate::solid_angle::DiskFrame;

/// An annular sector of a disk source: `rho` in fractions of the radius, `phi` in
/// radians from the frame's `e1` toward `e2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct DiskCell {
    pub(super) rho: (f64, f64),
    pub(super) phi: (f64, f64),
}

impl DiskCell {
    const WHOLE: DiskCell = DiskCell {
        rho: (0.0, 1.0),
        phi: (0.0, 2.0 * std::f64::consts::PI),
    };

    pub(super) fn is_whole(&self) -> bool {
        *self == DiskCell::WHOLE
    }

    /// Area as a fraction of the disk's.
    pub(super) fn area_fraction(&self) -> f64 {
        let (r0, r1) = self.rho;
        (r1 * r1 - r0 * r0) * (self.phi.1 - self.phi.0) / (2.0 * std::f64::consts::PI)
    }

    /// The centroid, as (fraction of the radius, angle).
    pub(super) fn centroid(&self) -> (f64, f64) {
        let (r0, r1) = self.rho;
        let half = 0.5 * (self.phi.1 - self.phi.0);
        let rc =
            2.0 / 3.0 * (r1 * r1 * r1 - r0 * r0 * r0) / (r1 * r1 - r0 * r0) * half.sin() / half;
        (rc, self.phi.0 + half)
    }

    /// The two halves of equal area: across the radius or across the angle, whichever
    /// side is longer.
    pub(super) fn split(&self) -> [DiskCell; 2] {
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
    pub(super) fn jittered(
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
    pub(super) fn sample(
        &self,
        frame: &DiskFrame,
        org: Vec3,
        normal: Vec3,
    ) -> Option<SourceSample> {
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
pub(super) struct Cap {
    pub(super) axis: Vec3,
    e1: Vec3,
    e2: Vec3,
    pub(super) alpha: f64,
}

/// A piece of a [`Cap`]: angles from the axis and around it (from `e1` toward `e2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct CapCell {
    pub(super) theta: (f64, f64),
    pub(super) phi: (f64, f64),
}

impl Cap {
    pub(super) fn whole(&self) -> CapCell {
        CapCell {
            theta: (0.0, self.alpha),
            phi: (0.0, 2.0 * std::f64::consts::PI),
        }
    }

    /// `V` of a piece, in closed form: with `w = cos t axis + sin t (cos p e1 + sin p
    /// e2)` and `dw = sin t dt dp`, the axial part is `(sin^2 t1 - sin^2 t0) / 2 dp`
    /// and the parts across are `S (sin p1 - sin p0)` along `e1`, `S (cos p0 - cos p1)`
    /// along `e2`, with `S = [t / 2 - sin 2t / 4]` from `t0` to `t1`.
    pub(super) fn vector(&self, c: &CapCell) -> Vec3 {
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
    pub(super) fn direction(&self, c: &CapCell, o: [f64; 2]) -> Vec3 {
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
    pub(super) fn omega(&self) -> f64 {
        (self.theta.0.cos() - self.theta.1.cos()) * (self.phi.1 - self.phi.0)
    }

    /// The two halves of equal solid angle, across the longer side.
    pub(super) fn split(&self) -> [CapCell; 2] {
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
pub(super) fn cap_cells(cap: &Cap, d: f64, radius: f64, weight: f64, ds: f64) -> Vec<CapCell> {
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
pub(super) fn disk_cells(frame: &DiskFrame, weight: f64, ds: f64) -> Vec<DiskCell> {
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
    pub(super) fn exact_samples(
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
    pub(super) fn exact_convex(
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
    pub(super) fn exact_disk(
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
}
