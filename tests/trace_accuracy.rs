//! `radc trace -I` on scenes with closed-form illuminance, against the exact answer and
//! against real rtrace on the same scene with the same options (its values recorded by
//! tests/oracle/regen_accuracy_goldens.py in tests/data/accuracy/cases.json).
//!
//! Two bars. With rtrace's options alone radc reproduces rtrace's estimator (partition
//! centres), so its error must be no larger than rtrace's; both print seven significant
//! digits, so radc is allowed that rounding (1e-6 relative) on top. With radc's `-dx+`
//! (each source partition's exact solid angle) its error must be strictly smaller than
//! rtrace's wherever rtrace's exceeds that rounding, and within the rounding where
//! rtrace is exact too. Measured (rtrace's relative error, radc `-dx+`'s): sphere below
//! and off axis 1e-7 and 6e-8, both exact (a fully visible sphere above the horizon is
//! exact for one centre sample); sphere the horizon cuts 6.4e-2 vs 7.4e-3; disk on axis
//! 2.2e-2 vs 8e-8; rectangle 7.4e-4 vs 3e-7; triangle up to 2.9e-1 vs 3e-7; half-hidden
//! rectangle and disk 7.6e-2 and 5.0e-2 vs 2.4e-2 and 3.0e-2; glowing dome and
//! integrating sphere 1e-6 or less in both (exact: print rounding).
//!
//! The cases with ambient bounces are built so that every hemisphere sample sees the
//! same radiance (a uniform dome, the inside of a sphere), so Monte Carlo adds no noise
//! and the comparison is exact; `room_statistics_agree_with_rtrace` compares means on
//! a scene where it does add noise.
//!
//! `-I` measures 1e-4 in front of the given point, along the normal, in both programs;
//! the formulas use that point.

mod common;

use std::f64::consts::PI;

use std::path::PathBuf;

use serde_json::Value;

fn data() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/accuracy")
}

fn case(id: &str) -> Value {
    let all: Value = serde_json::from_str(
        &std::fs::read_to_string(data().join("cases.json")).expect("cases.json"),
    )
    .expect("cases.json parses");
    all.as_array()
        .expect("a list")
        .iter()
        .find(|c| c["id"] == id)
        .unwrap_or_else(|| panic!("no case {id}"))
        .clone()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("a list")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// Printing seven significant digits: relative errors up to this are rounding.
const ROUNDING: f64 = 1e-6;

/// radc's irradiance (red channel) for each of the case's rays, each repeated
/// `repeat` times, with the case's options and then `extra`.
fn radc(c: &Value, extra: &[&str]) -> Vec<f64> {
    let id = c["id"].as_str().expect("id");
    let options: Vec<String> = c["options"]
        .as_array()
        .expect("options")
        .iter()
        .map(|o| o.as_str().expect("option").to_string())
        .collect();
    let repeat = c["repeat"].as_u64().expect("repeat") as usize;
    let mut input = String::new();
    for ray in c["rays"].as_array().expect("rays") {
        let line: Vec<String> = numbers(ray).iter().map(|x| format!("{x:.17}")).collect();
        for _ in 0..repeat {
            input.push_str(&line.join(" "));
            input.push('\n');
        }
    }
    let mut cmd = common::radc(["trace", "-h", "-I", "-ov"]);
    cmd.args(&options)
        .args(extra)
        .arg(data().join(format!("{id}.rad")));
    let out = common::run(cmd, input.as_bytes());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split_whitespace()
                .next()
                .expect("a value")
                .parse()
                .expect("a number")
        })
        .collect()
}

/// rtrace's value for each of a deterministic case's rays (red channel).
fn rtrace_values(c: &Value) -> Vec<f64> {
    c["values"]
        .as_array()
        .expect("values")
        .iter()
        .map(|v| numbers(v)[0])
        .collect()
}

/// Asserts radc's error on each ray is no larger than rtrace's (plus printing) with
/// rtrace's options, and strictly smaller with `-dx+` where rtrace's error is more than
/// printing (within printing where rtrace's is not). Prints the three errors.
fn more_accurate_than_rtrace(id: &str, exact: &[f64]) {
    more_accurate_than_rtrace_within(id, exact, ROUNDING);
}

/// [`more_accurate_than_rtrace`], radc with rtrace's options allowed `slack` (relative)
/// more error than rtrace.
fn more_accurate_than_rtrace_within(id: &str, exact: &[f64], slack: f64) {
    let c = case(id);
    let theirs = rtrace_values(&c);
    let same = radc(&c, &[]);
    let ours = radc(&c, &["-dx+"]);
    assert_eq!(ours.len(), exact.len(), "{id}: ray count");
    assert_eq!(same.len(), exact.len(), "{id}: ray count");
    for (k, e) in exact.iter().enumerate() {
        let rel = |x: f64| (x - e).abs() / e.abs();
        let (eo, es, et) = (rel(ours[k]), rel(same[k]), rel(theirs[k]));
        println!(
            "{id} ray {k}: exact {e:.7e}; rtrace {:.7e} (error {et:.2e}); radc {:.7e} \
             ({es:.2e}); radc -dx+ {:.7e} ({eo:.2e})",
            theirs[k], same[k], ours[k]
        );
        assert!(
            es <= et + slack,
            "{id}: radc {} (error {es:.2e}) vs rtrace {} (error {et:.2e}), exact {e}",
            same[k],
            theirs[k]
        );
        if et > ROUNDING {
            assert!(
                eo < et,
                "{id}: radc -dx+ {} (error {eo:.2e}) not below rtrace {} (error {et:.2e}), \
                 exact {e}",
                ours[k],
                theirs[k]
            );
        } else {
            assert!(
                eo <= ROUNDING,
                "{id}: radc -dx+ {} (error {eo:.2e}), exact {e}",
                ours[k]
            );
        }
        // And -dx+ is right to begin with (to the partitions a shadow's edge crosses).
        assert!(eo <= 5e-2, "{id}: radc -dx+ {}, exact {e}", ours[k]);
    }
}

/// Asserts radc `-dx+` is exact to `tolerance` (relative) on each ray.
fn dx_exact_to(id: &str, exact: &[f64], tolerance: f64) {
    let ours = radc(&case(id), &["-dx+"]);
    for (o, e) in ours.iter().zip(exact) {
        assert!(
            (o - e).abs() <= tolerance * e.abs(),
            "{id}: radc -dx+ {o}, exact {e} (error {:.2e})",
            (o - e).abs() / e
        );
    }
}

/// The point `-I` measures at, for a ray from `o` with unit normal `n`.
fn measured(o: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    [o[0] + 1e-4 * n[0], o[1] + 1e-4 * n[1], o[2] + 1e-4 * n[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A sphere of radiance L, radius r, centre c seen from p, surface normal n, entirely
/// above the horizon: with sin(alpha) = r / |c - p| and theta the angle between n and
/// the direction to the centre,
///     E = pi L sin^2(alpha) cos(theta).
fn sphere_e(l: f64, r: f64, c: [f64; 3], p: [f64; 3], n: [f64; 3]) -> f64 {
    let v = sub(c, p);
    let d2 = dot(v, v);
    PI * l * r * r / d2 * dot(n, v) / d2.sqrt()
}

/// Lamp L = 100, radius 0.5, centre (0, 0, 5); the point below it faces it.
#[test]
fn sphere_source_directly_below() {
    let n = [0.0, 0.0, 1.0];
    let e = sphere_e(100.0, 0.5, [0.0, 0.0, 5.0], measured([0.0; 3], n), n);
    more_accurate_than_rtrace("sphere-below", &[e]);
}

/// The same lamp, the surface tilted 50 degrees away from it.
#[test]
fn sphere_source_off_axis() {
    let t = 50f64.to_radians();
    let n = [t.sin(), 0.0, t.cos()];
    let e = sphere_e(100.0, 0.5, [0.0, 0.0, 5.0], measured([0.0; 3], n), n);
    more_accurate_than_rtrace("sphere-off-axis", &[e]);
}

/// The same lamp with the surface tilted 87 degrees: the centre is 87 degrees off the
/// normal and the lamp's cone (half-angle alpha = 5.7 degrees) crosses the horizon, so
/// only the part above it counts:
///     E = L integral over the cap of max(0, n . w) dw.
/// With the cap's frame (axis a toward the centre, e1, e2 across), n . w = A cos t +
/// B(p) sin t, A = n . a, B = n . (cos p e1 + sin p e2); for each p the integral over t
/// of (A cos t + B sin t) sin t is A sin^2 t / 2 + B (t / 2 - sin 2t / 4) between the
/// ends of the part of [0, alpha] where that is positive; the integral over p is
/// Gauss-Legendre on 1000 pieces (a fine-grained reference, good to 1e-10). rtrace
/// samples the centre alone: L pi sin^2(alpha) cos(87 degrees), which counts the part
/// below the horizon as negative light and is 6.4% low; radc -dx+ splits the cone
/// (`-ds .05`: 64 pieces) and misses only within the pieces the horizon crosses (0.7%
/// low). (A midpoint sum on a 1500 x 1500 grid of the cap agrees to 1e-9.)
#[test]
fn sphere_source_across_the_horizon() {
    let e = sphere_across_the_horizon_e();
    more_accurate_than_rtrace("sphere-horizon", &[e]);
}

/// [`sphere_source_across_the_horizon`]'s E.
fn sphere_across_the_horizon_e() -> f64 {
    let t = 87f64.to_radians();
    let n = [t.sin(), 0.0, t.cos()];
    let p = measured([0.0; 3], n);
    let v = sub([0.0, 0.0, 5.0], p);
    let d = dot(v, v).sqrt();
    let a = [v[0] / d, v[1] / d, v[2] / d];
    // e1 in the plane of a and n, e2 across both (n . e2 = 0).
    let na = dot(n, a);
    let e1u = [n[0] - na * a[0], n[1] - na * a[1], n[2] - na * a[2]];
    let b1 = dot(n, e1u) / dot(e1u, e1u).sqrt();
    let alpha = (0.5 / d).asin();
    let g = |b: f64, th: f64| na * th.sin().powi(2) / 2.0 + b * (th / 2.0 - (2.0 * th).sin() / 4.0);
    let per_phi = |phi: f64| {
        let b = b1 * phi.cos();
        // A cos t + B sin t = R cos(t - delta): positive within pi/2 of delta.
        let delta = b.atan2(na);
        let lo = (delta - PI / 2.0).clamp(0.0, alpha);
        let hi = (delta + PI / 2.0).clamp(0.0, alpha);
        g(b, hi) - g(b, lo)
    };
    100.0 * gauss_legendre(per_phi, 0.0, 2.0 * PI)
}

/// Jittered (`-dj 1`) samples of the sphere the horizon cuts and of the disk on its
/// axis, 400 rays each: radc -dx+ moves each piece's sample uniformly over the piece
/// (by solid angle on the sphere's cone, by area on the disk), so its mean must be
/// within 4.5 standard errors of the exact E, and the RMS error of one ray's value
/// must be below rtrace's (from its recorded mean and spread). rtrace's jittered
/// samples fill a cube inside the sphere (one sample for all of it: spread 0.13, 11x
/// radc's 0.012) and the disk's pulled-in square (its mean stays 2.4% low).
#[test]
fn jittered_sphere_and_disk_are_unbiased_with_dx() {
    let (l, r, h) = (40.0, 1.0, 2.0 - 1e-4);
    for (id, e) in [
        ("sphere-horizon-jitter", sphere_across_the_horizon_e()),
        ("disk-jitter", PI * l * r * r / (r * r + h * h)),
    ] {
        let c = case(id);
        let ours = radc(&c, &["-dx+"]);
        let n = ours.len() as f64;
        let mean = ours.iter().sum::<f64>() / n;
        let sd = (ours.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let rms = (ours.iter().map(|x| (x - e).powi(2)).sum::<f64>() / n).sqrt();
        let red = numbers(&c["stats"][0][0]);
        let (mt, st) = (red[0], red[1]);
        let rms_t = ((mt - e).powi(2) + st * st * (n - 1.0) / n).sqrt();
        println!(
            "{id}: exact {e:.6}; radc -dx+ mean {mean:.6} sd {sd:.4} rms error {rms:.4}; \
             rtrace mean {mt:.6} sd {st:.4} rms error {rms_t:.4}"
        );
        assert!(
            (mean - e).abs() <= 4.5 * sd / n.sqrt() + 1e-6 * e,
            "{id}: mean {mean} (sd {sd}) vs exact {e}"
        );
        assert!(rms < rms_t, "{id}: rms error {rms} vs rtrace's {rms_t}");
    }
}

/// A Lambertian disk (ring) of radiance L = 40 and radius r = 1, facing a point on its
/// axis at distance h (2 less the 1e-4 offset), parallel to it: integrating
/// L cos^2 / d^2 over the disk,
///     E = pi L r^2 / (r^2 + h^2).
/// rtrace is 2.2% low: it samples the disk at the partition centres of a square of
/// equal area pulled in toward the rim, which are denser than the area near the
/// middle, so every partition stands for the same area though they are not equal.
#[test]
fn disk_source_on_axis() {
    let (l, r, h) = (40.0, 1.0, 2.0 - 1e-4);
    let e = PI * l * r * r / (r * r + h * h);
    more_accurate_than_rtrace("disk-axis", &[e]);
    dx_exact_to("disk-axis", &[e], ROUNDING);
}

/// A rectangle a = 3 by b = 2 of radiance L = 25, parallel to the surface at height
/// c (1.5 less the offset), the point under one corner. With X = a / c, Y = b / c the
/// differential-area-to-rectangle form factor is
///     F = 1/(2 pi) [ X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2)) ]
/// and E = pi L F.
fn rectangle_e() -> f64 {
    corner_rectangle_e(25.0, 3.0, 2.0, 1.5 - 1e-4)
}

fn corner_rectangle_e(l: f64, a: f64, b: f64, c: f64) -> f64 {
    let (x, y): (f64, f64) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    let f = (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI);
    PI * l * f
}

/// rtrace is 7.4e-4 high: partition centres, `cos / d^2` times the area, err by the
/// order of (partition size / distance)^2.
#[test]
fn rectangular_source_form_factor() {
    more_accurate_than_rtrace("rect-corner", &[rectangle_e()]);
    dx_exact_to("rect-corner", &[rectangle_e()], ROUNDING);
}

/// A right triangle (0,0)-(0,2)-(3,0) of radiance L = 25 at height 1.5, seen from three
/// points (under a corner, under its inside, tilted and outside). Lambert's formula for
/// a polygon with corners R_i seen from the point (normal n):
///     E = L/2 sum_i gamma_i n . (R_i x R_i+1) / |R_i x R_i+1|,
/// gamma_i the angle between R_i and R_i+1 (the sign making E positive). rtrace
/// samples a triangle as a square around its centroid (sized by the distance to the
/// nearest edge, its partitions standing for equal shares of the triangle's area):
/// 1.9%, 29% and 1.6% off here; radc -dx+ splits the triangle itself.
fn triangle_e(o: [f64; 3], n: [f64; 3]) -> f64 {
    let p = measured(o, n);
    let corners = [[0.0, 0.0, 1.5], [0.0, 2.0, 1.5], [3.0, 0.0, 1.5]].map(|v| sub(v, p));
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut e = 0.0;
    for i in 0..3 {
        let (a, b) = (corners[i], corners[(i + 1) % 3]);
        let c = cross(a, b);
        let l = dot(c, c).sqrt();
        e += l.atan2(dot(a, b)) * dot(n, c) / l;
    }
    25.0 * (e / 2.0).abs()
}

#[test]
fn triangular_source() {
    let tilt = [0.6, 0.0, 0.8];
    let exact = [
        triangle_e([0.0; 3], [0.0, 0.0, 1.0]),
        triangle_e([1.0, 0.5, 0.0], [0.0, 0.0, 1.0]),
        triangle_e([-1.0, -1.0, 0.0], tilt),
    ];
    more_accurate_than_rtrace("triangle", &exact);
    dx_exact_to("triangle", &exact, ROUNDING);
}

/// The rectangle half hidden: an opaque plane at height z = .75 beyond x = .65 casts
/// its edge, seen from the point, onto the lamp at x_c = .65 (1.5 - 1e-4) / (.75 -
/// 1e-4) (~1.3, inside a partition), so the point sees the corner rectangle x_c by 2:
///     E = pi L F(x_c, 2, c) (the formula above).
/// Without jitter each partition is seen or hidden as a whole, so both programs err by
/// about the light of the partitions the shadow's edge crosses; here rtrace is 7.6% low
/// (it counts none of the column that is partly seen), radc -dx+ 2.4% high (its sample
/// of that column, where most of its light comes from, is seen). The next test shows
/// that the jittered estimate is unbiased.
fn occluded_rectangle_e() -> f64 {
    let c = 1.5 - 1e-4;
    corner_rectangle_e(25.0, 0.65 * c / (0.75 - 1e-4), 2.0, c)
}

#[test]
fn partly_hidden_rectangle() {
    more_accurate_than_rtrace("rect-occluded", &[occluded_rectangle_e()]);
}

/// The half-hidden rectangle with `-dj 1`: random points over each partition, so the
/// shadow's edge is resolved on average: radc's mean over 400 rays, with and without
/// `-dx+` (which leaves jittered samples as they are), must be within 4.5 standard
/// errors of the exact E and agree with rtrace's mean. radc's spread is twice
/// rtrace's here (0.44 vs 0.22): its offsets are independent per partition, while
/// rtrace's under -u- come from its quasi-random sequence and are not (under -u+
/// rtrace's spread is 0.41, like radc's), so the bound on the spread is 3x here.
#[test]
fn jittered_partly_hidden_rectangle_is_unbiased() {
    let e = occluded_rectangle_e();
    for extra in [&[][..], &["-dx+"][..]] {
        let (mean, sd, n) = agree_with_rtrace_given("rect-occluded-jitter", extra, 3.0)[0];
        let se = sd / (n as f64).sqrt();
        assert!(
            (mean - e).abs() <= 4.5 * se + 1e-6 * e,
            "{extra:?}: mean {mean} (se {se}) vs exact {e}"
        );
    }
}

/// The disk half hidden: an opaque plane at z = 1 beyond x = .25 hides the disk beyond
/// the chord x_c = .25 h / (1 - 1e-4) (~.5). Seen from the axis, the visible part gives,
/// with R(phi) the distance from the centre to the edge of the visible part in
/// direction phi (1, or x_c / cos phi where that is less),
///     E = L integral over phi of R^2 / (2 (h^2 + R^2)) dphi
/// (the disk formula above, sector by sector), integrated here with Gauss-Legendre
/// on the pieces between the chord's ends (a fine-grained reference, good to 1e-12).
/// rtrace is 5.0% low, radc -dx+ 3% low (the partitions the chord crosses).
#[test]
fn partly_hidden_disk() {
    let (l, h) = (40.0, 2.0 - 1e-4);
    let xc: f64 = 0.25 * h / (1.0 - 1e-4);
    let edge = |phi: f64| {
        let c = phi.cos();
        let r = if c > 0.0 { (xc / c).min(1.0) } else { 1.0 };
        r * r / (2.0 * (h * h + r * r))
    };
    let end = xc.acos();
    let e = l * (gauss_legendre(edge, -end, end) + gauss_legendre(edge, end, 2.0 * PI - end));
    more_accurate_than_rtrace("disk-occluded", &[e]);
}

/// Composite 4-point Gauss-Legendre on 1000 pieces of [a, b].
fn gauss_legendre(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const GL4: [(f64, f64); 4] = [
        (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
        (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    ];
    let n = 1000;
    let step = (b - a) / n as f64;
    (0..n)
        .map(|i| {
            let mid = a + (i as f64 + 0.5) * step;
            GL4.iter()
                .map(|(x, w)| w * f(mid + 0.5 * step * x))
                .sum::<f64>()
                * 0.5
                * step
        })
        .sum()
}

/// The same rectangle with jittered samples (`-dj 1`): each partition is sampled at a
/// random point, so the mean of many rays tends to the exact form factor (which the
/// partition centres of `-dj 0` miss by 7e-4). radc's mean over 400 rays must be
/// within 4.5 standard errors of the exact E, and agree with rtrace's mean as below.
#[test]
fn jittered_rectangle_is_unbiased() {
    let e = rectangle_e();
    let (mean, sd, n) = agree_with_rtrace("rect-jitter")[0];
    let se = sd / (n as f64).sqrt();
    assert!(
        (mean - e).abs() <= 4.5 * se + 1e-6 * e,
        "mean {mean} (se {se}) vs exact {e}"
    );
    assert!(se < 2e-3 * e, "jitter too noisy: se {se}");
}

/// A glowing dome (a `glow` bubble of radiance L = 2 with no source radius, so only
/// ambient rays see it) over a black floor: one ambient bounce sees L in every
/// direction of the upper hemisphere, and
///     E = integral of L cos over the hemisphere = pi L,
/// at the centre and off it alike. Both programs are exact here (errors 5e-7, print
/// rounding): a dome of uniform radiance gives every hemisphere sample the same value.
#[test]
fn uniform_glowing_hemisphere() {
    more_accurate_than_rtrace("glow-dome", &[2.0 * PI, 2.0 * PI]);
}

/// An integrating sphere: a Lambertian bubble of reflectance rho = 0.5 and radius R = 1
/// around a lamp of radiance L = 1e5 and radius r = 1e-3 at its centre.
///
/// Direct: on the wall E0 = pi L s with s = (r/R)^2 (the sphere formula); at the
/// measured point, 1e-4 inside, E0' = pi L s' with s' = (r/R')^2, R' = R - 1e-4.
/// Indirect: from any point of a sphere's inside, every equal area of the wall has the
/// same form factor, so a wall of uniform radiance Lw gives E = pi Lw, less the
/// cosine-weighted cone the lamp hides (a fraction sin^2 = s; ambient rays that meet a
/// light source count nothing, as it is counted directly). The direct light is uniform,
/// so every bounce is: the wall reached by the k-th of N ambient bounces has
///     L_N = rho E0 / pi (past the last bounce, with -av 0),
///     L_k = rho / pi (E0 + pi (1 - s) L_(k+1)),
/// and the measured E = E0' + pi (1 - s') L_1. With many bounces L_k tends to
///     L_inf = rho E0 / pi / (1 - rho (1 - s)),
/// i.e. E -> E0 / (1 - rho) for a small lamp, the textbook E_direct / (1 - rho) (the
/// indirect part being E0 rho / (1 - rho) = Phi / A * rho / (1 - rho) with the lamp's
/// flux Phi = 4 pi^2 r^2 L spread over the wall's A = 4 pi R^2).
/// Both programs are exact here (errors at print rounding): the lamp is a fully
/// visible sphere and every ambient sample sees the same wall radiance.
fn integrating_sphere(bounces: Option<usize>) -> f64 {
    let (l, r, big_r, rho) = (1e5, 1e-3, 1.0, 0.5);
    let s = (r / big_r) * (r / big_r);
    let rp = big_r - 1e-4;
    let sp = (r / rp) * (r / rp);
    let e0 = PI * l * s;
    let l_inf = rho * e0 / PI / (1.0 - rho * (1.0 - s));
    let l1 = match bounces {
        Some(n) => {
            let mut lk = rho * e0 / PI;
            for _ in 1..n {
                lk = rho / PI * (e0 + PI * (1.0 - s) * lk);
            }
            lk
        }
        None => l_inf,
    };
    PI * l * sp + PI * (1.0 - sp) * l1
}

/// Three bounces, `-av 0`: the finite sum above.
#[test]
fn integrating_sphere_three_bounces() {
    let e = integrating_sphere(Some(3));
    more_accurate_than_rtrace("integrating-ab3", &[e, e]);
}

/// The limit of many bounces: with `-av` set to (1 - s) L_inf the wall past the first
/// bounce already has its converged radiance rho E0 / pi + rho (1 - s) L_inf = L_inf,
/// so one bounce gives the converged E.
#[test]
fn integrating_sphere_converged() {
    more_accurate_than_rtrace("integrating-converged", &[integrating_sphere(None)]);
}

/// Where Monte Carlo does add noise (a grey room with a red wall and a ceiling lamp,
/// `-ab 1` and `-ab 2`, 16 hemisphere samples): each ray traced 400 times, radc's mean
/// must lie within 4.5 standard errors of rtrace's mean (the combined standard error of
/// the two means, from each program's sample deviation; chance of a false failure
/// below 1e-5 per ray), and its spread must be comparable (between half and twice
/// rtrace's).
#[test]
fn room_statistics_agree_with_rtrace() {
    agree_with_rtrace("room-ab1");
    agree_with_rtrace("room-ab2");
}

/// Compares radc's mean and spread on each of a stochastic case's rays with rtrace's;
/// returns radc's (mean, sd, count) per ray.
fn agree_with_rtrace(id: &str) -> Vec<(f64, f64, usize)> {
    agree_with_rtrace_given(id, &[], 2.0)
}

/// [`agree_with_rtrace`] with `extra` options for radc, its spread allowed to be up to
/// `spread` times rtrace's (or 1 / `spread`).
fn agree_with_rtrace_given(id: &str, extra: &[&str], spread: f64) -> Vec<(f64, f64, usize)> {
    let c = case(id);
    let n = c["repeat"].as_u64().expect("repeat") as usize;
    let ours = radc(&c, extra);
    let mut out = Vec::new();
    for (k, stats) in c["stats"].as_array().expect("stats").iter().enumerate() {
        let red = numbers(&stats[0]);
        let (mt, st) = (red[0], red[1]);
        let block = &ours[k * n..(k + 1) * n];
        let mo = block.iter().sum::<f64>() / n as f64;
        let so = (block.iter().map(|x| (x - mo).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
        let se = ((so * so + st * st) / n as f64).sqrt();
        assert!(
            (mo - mt).abs() <= 4.5 * se + 1e-9,
            "{id} ray {k}: radc mean {mo} (sd {so}) vs rtrace {mt} (sd {st})"
        );
        println!("{id} {extra:?} ray {k}: radc mean {mo} sd {so}; rtrace mean {mt} sd {st}");
        assert!(
            so <= spread * st + 1e-9 && so >= st / spread - 1e-9,
            "{id} ray {k}: radc sd {so} vs rtrace {st}"
        );
        out.push((mo, so, n));
    }
    out
}
