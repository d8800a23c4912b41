//! Exact solid-angle integrals for the direct calculation with `-dx+` (radc's, not
//! Radiance's): the vector `V = integral of w dw` over the directions `w` in which a
//! source region is seen from a point. For any surface normal `n`, `n . V` is the
//! region's projected solid angle (its form factor times pi) as long as the region is
//! wholly above the surface's horizon, so one sample in direction `V / |V|` standing for
//! the solid angle `|V|` gives a Lambertian surface exactly the irradiance of a uniform
//! source region, whatever the region's size. Radiance instead takes each partition's
//! centre with `cos / d^2` times its area, which is exact only in the limit of small
//! partitions (errors of order `(size / distance)^2`).
//!
//! By Stokes' theorem on the unit sphere, `V = 1/2 closed integral of w x dw` around the
//! region's outline; for a point `R` on the outline (relative to the eye) `w x dw = R x dR
//! / |R|^2`, so a straight edge from `a` to `b` gives `gamma (a x b) / |a x b|` with
//! `gamma` the angle between them (Lambert's formula for polygons), and a circular arc
//! is integrated by Gauss-Legendre quadrature. All points are relative to the eye.

use crate::math::Vec3;

/// `1/2 integral of R x dR / |R|^2` along the straight edge from `a` to `b`, doubled
/// (the halving is done once per outline).
fn edge(a: Vec3, b: Vec3) -> Vec3 {
    let c = a.cross(b);
    let s = c.length();
    if s == 0.0 {
        return Vec3::ZERO;
    }
    c * (s.atan2(a.dot(b)) / s)
}

/// `V` of the planar polygon with vertices `p` (in order, either way round), oriented
/// by `toward` (see [`orient`]).
pub fn polygon(p: &[Vec3], toward: Vec3) -> Vec3 {
    let mut v = Vec3::ZERO;
    for (i, a) in p.iter().enumerate() {
        v += edge(*a, p[(i + 1) % p.len()]);
    }
    orient(0.5 * v, toward)
}

/// Flips `v` to point along `toward`, the normal of the region's plane on the side
/// away from the eye: every direction of a flat region seen from one side has a
/// positive component along it, and so has `V`.
fn orient(v: Vec3, toward: Vec3) -> Vec3 {
    if v.dot(toward) < 0.0 { -v } else { v }
}

/// Gauss-Legendre nodes and weights on [-1, 1], 4 points (exact for degree 7).
const GL4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// A disk source's frame: centre (relative to the eye), orthonormal in-plane axes with
/// `e1 x e2` the disk's normal, and radius.
#[derive(Clone, Copy, Debug)]
pub struct DiskFrame {
    pub center: Vec3,
    pub e1: Vec3,
    pub e2: Vec3,
    pub radius: f64,
}

impl DiskFrame {
    /// The point at fraction `rho` of the radius and angle `phi`, relative to the eye.
    pub fn point(&self, rho: f64, phi: f64) -> Vec3 {
        let (s, c) = phi.sin_cos();
        self.center + (self.e1 * c + self.e2 * s) * (rho * self.radius)
    }

    /// The eye's distance from the circle at fraction `rho` of the radius (a lower
    /// bound on its distance from any arc of it).
    fn distance_to_circle(&self, rho: f64) -> f64 {
        let n = self.e1.cross(self.e2);
        let h = self.center.dot(n);
        let inplane = -self.center + n * h; // the eye's foot, from the centre
        let off = inplane.length() - rho * self.radius;
        (h * h + off * off).sqrt()
    }

    /// `2 x` the outline integral along the arc at fraction `rho`, `phi0` to `phi1`.
    fn arc(&self, rho: f64, phi0: f64, phi1: f64) -> Vec3 {
        let len = (phi1 - phi0).abs() * rho * self.radius;
        let near = self.distance_to_circle(rho).max(1e-300);
        // Pieces of at most an eighth of a turn and at most a third of the eye's
        // distance: 4-point Gauss-Legendre is then good to about 1e-8 relative.
        let pieces = ((phi1 - phi0).abs() / std::f64::consts::FRAC_PI_4)
            .max(3.0 * len / near)
            .ceil()
            .clamp(1.0, 256.0) as usize;
        let step = (phi1 - phi0) / pieces as f64;
        let mut sum = Vec3::ZERO;
        for k in 0..pieces {
            let mid = phi0 + (k as f64 + 0.5) * step;
            for (x, w) in GL4 {
                let phi = mid + 0.5 * step * x;
                let (s, c) = phi.sin_cos();
                let r = self.center + (self.e1 * c + self.e2 * s) * (rho * self.radius);
                let dr = (self.e2 * c - self.e1 * s) * (rho * self.radius);
                sum += r.cross(dr) * (w / r.length_squared());
            }
        }
        sum * (0.5 * step)
    }

    /// `V` of the annular sector `rho0..rho1` (fractions of the radius) by
    /// `phi0..phi1`, oriented toward the disk.
    pub fn sector(&self, (rho0, rho1): (f64, f64), (phi0, phi1): (f64, f64)) -> Vec3 {
        let (a0, a1) = (self.point(rho0, phi0), self.point(rho1, phi0));
        let (b0, b1) = (self.point(rho0, phi1), self.point(rho1, phi1));
        let mut v = edge(a0, a1) + self.arc(rho1, phi0, phi1) + edge(b1, b0);
        if rho0 > 0.0 {
            v += self.arc(rho0, phi1, phi0);
        }
        let n = self.e1.cross(self.e2);
        orient(0.5 * v, if self.center.dot(n) > 0.0 { n } else { -n })
    }

    /// `V` of the whole disk, in closed form: with the eye at height `h` over the
    /// disk's plane and `q` its foot's offset from the centre (`rho = |q|`), the
    /// element-to-disk form factors for an element parallel to the disk and one
    /// perpendicular to it facing the axis are
    ///     F_par  = 1/2 (1 - (h^2 + rho^2 - r^2) / S),
    ///     F_perp = h / (2 rho) (X / S - 1) = 2 h rho r^2 / (S (X + S)),
    /// with X = h^2 + rho^2 + r^2 and S = sqrt(X^2 - 4 rho^2 r^2), and
    /// V = -pi (F_par n + F_perp q / rho) (n the normal on the eye's side). Written
    /// without the differences that cancel for small `rho` or a distant eye.
    pub fn whole(&self) -> Vec3 {
        let mut n = self.e1.cross(self.e2);
        let mut h = -self.center.dot(n);
        if h < 0.0 {
            n = -n;
            h = -h;
        }
        let q = -self.center - n * h;
        let (r2, rho2) = (self.radius * self.radius, q.length_squared());
        let x = h * h + rho2 + r2;
        let s = (((x - 2.0 * self.radius * rho2.sqrt()) * (x + 2.0 * self.radius * rho2.sqrt()))
            .max(0.0))
        .sqrt();
        if s == 0.0 {
            return Vec3::ZERO; // the eye on the rim
        }
        let y = h * h + rho2 - r2;
        let s_minus_y = if y > 0.0 {
            4.0 * r2 * h * h / (s + y)
        } else {
            s - y
        };
        let f_par = 0.5 * s_minus_y / s;
        let f_perp_over_rho = 2.0 * h * r2 / (s * (x + s));
        -std::f64::consts::PI * (n * f_par + q * f_perp_over_rho)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Brute force: integral of w dw over the disk by its area, `cos_src / d^2 dA`,
    /// on a fine polar grid.
    fn disk_by_area(f: &DiskFrame, (r0, r1): (f64, f64), (p0, p1): (f64, f64)) -> Vec3 {
        let n = f.e1.cross(f.e2);
        let (nr, np) = (400, 400);
        let mut v = Vec3::ZERO;
        for i in 0..nr {
            for j in 0..np {
                // Midpoints in rho^2 (equal areas) and phi.
                let t = (i as f64 + 0.5) / nr as f64;
                let rho = (r0 * r0 + t * (r1 * r1 - r0 * r0)).sqrt();
                let phi = p0 + (j as f64 + 0.5) / np as f64 * (p1 - p0);
                let p = f.point(rho, phi);
                let d2 = p.length_squared();
                let da =
                    0.5 * (r1 * r1 - r0 * r0) * (p1 - p0) * f.radius * f.radius / (nr * np) as f64;
                v += p / d2.sqrt() * (n.dot(p).abs() / d2.sqrt() / d2 * da);
            }
        }
        v
    }

    fn frame(center: Vec3, radius: f64) -> DiskFrame {
        let n = Vec3::new(0.3, -0.2, 1.0).normalize();
        let e1 = crate::math::perpendicular(n).expect("a perpendicular");
        DiskFrame {
            center,
            e1,
            e2: n.cross(e1),
            radius,
        }
    }

    #[test]
    fn whole_disk_closed_form_matches_the_outline_and_the_area() {
        for c in [
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(1.5, -0.7, 1.2),
            Vec3::new(0.1, 0.05, -0.4),
            Vec3::new(30.0, 4.0, 9.0),
        ] {
            let f = frame(c, 1.0);
            let closed = f.whole();
            let outline = f.sector((0.0, 1.0), (0.0, 2.0 * PI));
            let area = disk_by_area(&f, (0.0, 1.0), (0.0, 2.0 * PI));
            let scale = closed.length();
            assert!(
                (closed - outline).length() < 1e-8 * scale,
                "{closed} {outline}"
            );
            assert!((closed - area).length() < 1e-4 * scale, "{closed} {area}");
        }
        // On the axis: pi r^2 / (r^2 + h^2) along it.
        let f = DiskFrame {
            center: Vec3::new(0.0, 0.0, 2.0),
            e1: Vec3::X,
            e2: Vec3::Y,
            radius: 1.0,
        };
        let v = f.whole();
        assert!((v - Vec3::new(0.0, 0.0, PI / 5.0)).length() < 1e-15, "{v}");
    }

    #[test]
    fn sectors_match_the_area_and_add_up() {
        let f = frame(Vec3::new(0.4, 0.3, 0.5), 0.8);
        let cell = ((0.3, 0.7), (0.5, 1.6));
        let v = f.sector(cell.0, cell.1);
        let a = disk_by_area(&f, cell.0, cell.1);
        assert!((v - a).length() < 1e-4 * v.length(), "{v} {a}");
        let halves = f.sector((0.0, 1.0), (0.0, PI)) + f.sector((0.0, 1.0), (PI, 2.0 * PI));
        assert!((halves - f.whole()).length() < 1e-9 * halves.length());
    }

    #[test]
    fn polygon_is_lamberts_formula() {
        // A unit square at height 1 under one corner: pi F with the corner formula.
        let p = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(0.0, 1.0, 1.0),
        ];
        let v = polygon(&p, Vec3::Z);
        let s = 2f64.sqrt();
        let f = 2.0 * (1.0 / s * (1.0 / s).atan()) / (2.0 * PI);
        assert!((v.z - PI * f).abs() < 1e-14, "{v}");
        // Reversed, the same.
        let mut q = p;
        q.reverse();
        assert!((polygon(&q, Vec3::Z) - v).length() < 1e-15);
        // A tiny square far away (at height 5.001): its solid angle toward its centre.
        let far: Vec<Vec3> = p
            .iter()
            .map(|x| *x * 1e-3 + Vec3::new(0.0, 0.0, 5.0))
            .collect();
        let w = polygon(&far, Vec3::Z);
        assert!(
            (w.length() - 1e-6 / (5.001f64 * 5.001)).abs() < 1e-6 * w.length(),
            "{w}"
        );
    }
}
