//! Indirect light by Monte Carlo: what a diffuse surface reflects of the light arriving
//! from other surfaces (`multambient` and `doambient` in ambient.c and ambcomp.c, with
//! Radiance's `-aa 0`: no irradiance cache, every value computed afresh).
//!
//! While fewer than `-ab` ambient rays lead to a ray, its diffuse hits sample the
//! hemisphere above the surface: an `n` by `n` grid of strata (`n = sqrt(-ad * weight)`,
//! as ambcomp.c sizes it, so weaker rays take fewer samples), one jittered cosine-weighted
//! direction per stratum, so that the mean radiance seen is the irradiance over `pi`.
//! `-as` adds samples, at full weight, to the strata whose values differ most from their
//! neighbours (ambcomp.c's super-sampling). Past the last bounce, or when no sample
//! could be traced, the constant `-av` stands in, as in Radiance.
//!
//! The cache options (`-aa`, `-ar`, `-ai`, `-ae`, `-af`, `-aw`) are accepted and do not
//! change results: radc computes every value, which is what `-aa 0` asks of Radiance.

use crate::integrator::{RayKind, RayState, Tracer};
use crate::math::{Color, FTINY, Vec3, brightness, intensity, normalize, perpendicular};

impl Tracer<'_> {
    /// The ambient (indirect) light a diffuse hit reflects with coefficient `coef`, for
    /// a surface facing `normal`; `-av` times `coef` when no more bounces are left.
    pub fn ambient(&self, r: &RayState, coef: Color, normal: Vec3) -> Color {
        let o = self.options();
        if intensity(coef) <= FTINY {
            return Color::ZERO;
        }
        if o.ambient_divisions == 0 || r.ambient_depth >= o.ambient_bounces {
            return coef * o.ambient;
        }
        self.sample_hemisphere(r, coef, normal)
            .unwrap_or(coef * o.ambient)
    }

    fn sample_hemisphere(&self, r: &RayState, coef: Color, normal: Vec3) -> Option<Color> {
        let o = self.options();
        let ux = perpendicular(normal)?;
        let uy = normal.cross(ux);
        let ad = f64::from(o.ambient_divisions);
        // ambcomp.c: fewer samples for weaker rays, but not so few that each would fall
        // below -lw and be dropped.
        let mut wt = r.weight;
        if o.min_weight > 0.0 {
            wt = wt.min(0.8 * intensity(coef) * r.weight / (ad * o.min_weight));
        }
        let n = ((ad * wt).sqrt() + 0.5).max(1.0) as usize;
        // At most a million samples per hemisphere, whatever -ad asks.
        let n = n.min(1 << 10);
        let strata = n * n;
        let acoef = coef / strata as f64;
        let mut sums = vec![Color::ZERO; strata];
        let mut counts = vec![0u32; strata];
        for i in 0..n {
            for j in 0..n {
                let k = i * n + j;
                if let Some(c) = self.ambient_sample(r, acoef, normal, ux, uy, n, i, j, 0) {
                    sums[k] += c;
                    counts[k] = 1;
                }
            }
        }
        let ok = counts.iter().filter(|&&c| c > 0).count();
        if ok == 0 {
            return None;
        }
        let extra = (f64::from(o.ambient_supersamples) * wt + 0.5) as usize;
        if extra > 0 && ok == strata && strata > 1 {
            // Rank the strata by how much they differ from their neighbours.
            let b: Vec<f64> = sums.iter().map(|c| brightness(*c)).collect();
            let mut err = vec![0.0f64; strata];
            for i in 0..n {
                for j in 0..n {
                    let k = i * n + j;
                    if i + 1 < n {
                        let d = (b[k] - b[k + n]).powi(2);
                        err[k] += d;
                        err[k + n] += d;
                    }
                    if j + 1 < n {
                        let d = (b[k] - b[k + 1]).powi(2);
                        err[k] += d;
                        err[k + 1] += d;
                    }
                }
            }
            let mut order: Vec<usize> = (0..strata).collect();
            order.sort_by(|&a, &c| err[c].total_cmp(&err[a]).then(a.cmp(&c)));
            for s in 0..extra {
                let k = order[s % strata];
                let (i, j) = (k / n, k % n);
                if let Some(c) = self.ambient_sample(r, acoef, normal, ux, uy, n, i, j, counts[k]) {
                    sums[k] += c;
                    counts[k] += 1;
                }
            }
        }
        let mut total = Color::ZERO;
        for (s, c) in sums.iter().zip(&counts) {
            if *c > 0 {
                total += *s / f64::from(*c);
            }
        }
        // Strata whose rays were too weak to trace are filled with the mean of the rest.
        Some(total * (strata as f64 / ok as f64))
    }

    /// Sample number `m` of stratum (`i`, `j`) of an `n` by `n` grid: the radiance seen,
    /// times the ray's coefficient.
    #[allow(clippy::too_many_arguments)]
    fn ambient_sample(
        &self,
        r: &RayState,
        acoef: Color,
        normal: Vec3,
        ux: Vec3,
        uy: Vec3,
        n: usize,
        i: usize,
        j: usize,
        m: u32,
    ) -> Option<Color> {
        let salt = (((i * n + j) as u64) << 20) | u64::from(m);
        let mut child = self.spawn_salted(r, RayKind::AMBIENT, Some(acoef), salt)?;
        let sx = (j as f64 + crate::random::uniform(child.seed, 1)) / n as f64;
        let sy = (i as f64 + crate::random::uniform(child.seed, 2)) / n as f64;
        let (dx, dy) = square_to_disk(sx, sy);
        let dz = (1.0 - dx * dx - dy * dy).max(0.0).sqrt();
        child.dir = ux * dx + uy * dy + normal * dz;
        if normalize(&mut child.dir) == 0.0 {
            return None;
        }
        self.trace(&mut child);
        Some(child.color * child.coef)
    }
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disk: it keeps
/// strata compact and areas proportional, so a stratified square gives stratified
/// cosine-weighted directions (Radiance's `SDsquare2disk` does the same job).
pub fn square_to_disk(x: f64, y: f64) -> (f64, f64) {
    let a = 2.0 * x - 1.0;
    let b = 2.0 * y - 1.0;
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let q = std::f64::consts::FRAC_PI_4;
    let (radius, phi) = if a.abs() > b.abs() {
        (a, q * (b / a))
    } else {
        (b, 2.0 * q - q * (a / b))
    };
    (radius * phi.cos(), radius * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Options;
    use crate::scene::Scene;
    use crate::scene::tests::IrBuilder;
    use radc_lang::scene::ir::PrimKind;

    /// A closed grey bubble of reflectance rho = 0.5 and nothing else, with `-av` av:
    /// past the last bounce the wall's radiance is rho av, so with one bounce every
    /// hemisphere sample sees rho av and E = pi rho av exactly, whatever the sample
    /// directions; with two, the wall first reached has rho^2 av and E = pi rho^2 av.
    fn furnace() -> Scene {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        b.add(
            "bubble",
            "wall",
            Some(grey),
            PrimKind::Bubble {
                center: [0.0; 3],
                radius: 2.0,
            },
        );
        Scene::compile(&b.scene).expect("compiles")
    }

    fn options(bounces: u32) -> Options {
        Options {
            ambient: Color::splat(0.3),
            ambient_bounces: bounces,
            ambient_divisions: 64,
            ambient_supersamples: 16,
            russian_roulette: true,
            ..Options::default()
        }
    }

    #[test]
    fn one_bounce_in_a_furnace_is_exact() {
        let scene = furnace();
        let t = Tracer::new(&scene, options(1));
        for (i, n) in [Vec3::Z, Vec3::X, Vec3::new(0.6, 0.0, -0.8)]
            .iter()
            .enumerate()
        {
            let e = t
                .irradiance_seeded(Vec3::new(0.3, -0.2, 0.1), *n, i as u64)
                .color;
            let want = std::f64::consts::PI * 0.5 * 0.3;
            assert!((e.x - want).abs() < 1e-9 * want, "{e} vs {want}");
        }
        let t = Tracer::new(&scene, options(2));
        let e = t.irradiance_seeded(Vec3::ZERO, Vec3::Z, 3).color;
        let want = std::f64::consts::PI * 0.25 * 0.3;
        assert!((e.x - want).abs() < 1e-9 * want, "{e} vs {want}");
    }

    /// Random choices come from the ray's index: the same index gives the same value,
    /// others differ, and the values do not depend on which thread traces them.
    #[test]
    fn sampling_is_reproducible_and_thread_independent() {
        let mut b = IrBuilder::default();
        let grey = b.plastic("grey", 0.5);
        let lamp = b.add("light", "lamp", None, PrimKind::Light { color: [10.0; 3] });
        b.square("floor", grey, 0.0, true);
        b.square("panel", lamp, 1.0, false);
        b.add(
            "sphere",
            "ball",
            Some(grey),
            PrimKind::Sphere {
                center: [0.3, 0.0, 0.3],
                radius: 0.2,
            },
        );
        let scene = Scene::compile(&b.scene).expect("compiles");
        let t = Tracer::new(&scene, options(2));
        let value = |i: u64| {
            t.irradiance_seeded(Vec3::new(-0.2, 0.1, 0.0), Vec3::Z, i)
                .color
        };
        assert_eq!(value(5), value(5));
        assert_ne!(value(5), value(6));
        let serial: Vec<Color> = (0..64).map(value).collect();
        let parallel: Vec<Color> = std::thread::scope(|s| {
            let hs: Vec<_> = (0..4u64)
                .map(|k| s.spawn(move || (k * 16..k * 16 + 16).map(value).collect::<Vec<_>>()))
                .collect();
            hs.into_iter()
                .flat_map(|h| h.join().expect("thread"))
                .collect()
        });
        assert_eq!(serial, parallel);
    }

    /// Equal areas of the square map to equal areas of the disk: the fraction of points
    /// of a fine grid landing within radius 0.5 is a quarter.
    #[test]
    fn square_to_disk_keeps_areas() {
        let n = 400;
        let mut inner = 0;
        for i in 0..n {
            for j in 0..n {
                let (x, y) =
                    square_to_disk((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                let r2 = x * x + y * y;
                assert!(r2 <= 1.0 + 1e-12);
                if r2 < 0.25 {
                    inner += 1;
                }
            }
        }
        let frac = f64::from(inner) / f64::from(n * n);
        assert!((frac - 0.25).abs() < 0.005, "{frac}");
    }
}
