//! The renderer's pure calcomp library functions, computed exactly as the reference
//! Radiance build computes them, so a radc render can match rtrace/rpict to the last
//! digit: `noise3 noise3x noise3y noise3z fnoise3` (src/rt/noise3.c) and `erf erfc`
//! (src/rt/func.c, which calls src/common/erf.c: Radiance links its own Hart & Cheney
//! erf, not the C library's).
//!
//! The reference build (pyradiance's Radiance 6.0) is compiled with `-ffast-math`, and
//! the compiler reassociated some of the arithmetic the C source writes: the Perlin
//! fade of `z` is applied as `(b-a)*z²*P(z)`, the partial derivatives multiply by 2000
//! instead of dividing by `EPSILON`, the corner averages of `fnoise3` add in a tree,
//! and `erf` multiplies its small-argument quotient in another order. Each function
//! below follows the machine code's order where it differs from the source, and says
//! so; `tests/data/renderer-math/` pins it against rtrace.
//!
//! Not here: `arg`, `source_corr`, `source_theta`, `source_phi` read the ray being
//! shaded, and `fprism_val` (src/rt/fprism.c) traces a prismatic glazing for the
//! current ray from parameters read out of the calcomp context, so none of them is a
//! function of its arguments alone.

/// Step of the finite differences behind `noise3x/y/z` and the smallest cell of
/// `fnoise3` (noise3.c's `EPSILON`).
const EPSILON: f64 = 0.0005;

/// `1/EPSILON` as the reference build uses it: fast-math turned noise3.c's division
/// by `EPSILON` into a multiplication by this constant, which rounds differently.
const INV_EPSILON: f64 = 2000.0;

/// The value of a renderer library function `name` at `args`, or `None` when `name`
/// is not one of the pure functions this module holds or `args` has the wrong count
/// (the checker reports that; the renderer never calls with it).
pub fn call(name: &str, args: &[f64]) -> Option<f64> {
    match (name, args) {
        ("noise3", &[x, y, z]) => Some(noise3(x, y, z)),
        ("noise3x", &[x, y, z]) => Some(noise3x(x, y, z)),
        ("noise3y", &[x, y, z]) => Some(noise3y(x, y, z)),
        ("noise3z", &[x, y, z]) => Some(noise3z(x, y, z)),
        ("fnoise3", &[x, y, z]) => Some(fnoise3(x, y, z)),
        ("erf", &[x]) => Some(erf(x)),
        ("erfc", &[x]) => Some(erfc(x)),
        _ => None,
    }
}

/// Ken Perlin's "improved noise" (2002) at a point: what noise3.c's `perlin_noise`
/// returns, in [-1, 1] for coordinates within ±2^31.
pub fn noise3(x: f64, y: f64, z: f64) -> f64 {
    perlin([x, y, z])
}

/// `noise3x`: noise3.c's backward difference `(f(p) - f(p - EPSILON·x̂)) / EPSILON`,
/// not the analytic gradient.
pub fn noise3x(x: f64, y: f64, z: f64) -> f64 {
    partial([x, y, z], 0)
}

/// `noise3y`: the backward difference along y (see [`noise3x`]).
pub fn noise3y(x: f64, y: f64, z: f64) -> f64 {
    partial([x, y, z], 1)
}

/// `noise3z`: the backward difference along z (see [`noise3x`]).
pub fn noise3z(x: f64, y: f64, z: f64) -> f64 {
    partial([x, y, z], 2)
}

fn partial(p: [f64; 3], axis: usize) -> f64 {
    let mut q = p;
    q[axis] -= EPSILON;
    (perlin(p) - perlin(q)) * INV_EPSILON
}

/// noise3.c's one-point cache, shared by `noise3` and its three partials. For finite
/// coordinates it only saves work, and the pure functions above give the same values.
/// It is observable with NaN: the reference build compares coordinates with fast-math
/// `!=`, which is false when either side is NaN, so a NaN coordinate "matches" the
/// cached point and the call returns the previous point's values (and a cached NaN
/// point matches everything after it). A renderer that wants that, too, keeps one of
/// these per evaluation context, as Radiance keeps one per process.
#[derive(Clone, Debug, Default)]
pub struct Noise3Cache {
    point: Option<[f64; 3]>,
    value: f64,
    partials: [Option<f64>; 3],
}

impl Noise3Cache {
    /// `noise3` through the cache.
    pub fn noise3(&mut self, p: [f64; 3]) -> f64 {
        self.refresh(p);
        self.value
    }

    /// `noise3x` (axis 0), `noise3y` (1) or `noise3z` (2) through the cache; the
    /// difference is taken at the cached point, as noise3.c takes it.
    pub fn partial(&mut self, p: [f64; 3], axis: usize) -> f64 {
        let cached = self.refresh(p);
        let axis = axis.min(2);
        if let Some(v) = self.partials[axis] {
            return v;
        }
        let mut q = cached;
        q[axis] -= EPSILON;
        let v = (self.value - perlin(q)) * INV_EPSILON;
        self.partials[axis] = Some(v);
        v
    }

    fn refresh(&mut self, p: [f64; 3]) -> [f64; 3] {
        // `a != b` compiled without NaN checks (ucomisd + jne) is false when unordered.
        let differs = |a: f64, b: f64| a != b && !a.is_nan() && !b.is_nan();
        match self.point {
            Some(c) if !(0..3).any(|i| differs(p[i], c[i])) => c,
            _ => {
                self.point = Some(p);
                self.value = perlin(p);
                self.partials = [None; 3];
                p
            }
        }
    }
}

/// Perlin's permutation of 0..=255, the table of "Improving Noise" that noise3.c uses.
#[rustfmt::skip]
const PERMUTATION: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122,
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54,
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169,
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64,
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212,
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213,
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104,
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241,
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157,
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93,
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
];

fn perm(i: i32) -> i32 {
    i32::from(PERMUTATION[(i & 0xff) as usize])
}

/// x86-64's `cvttsd2si` into 32 bits, which C's `(int)x` compiles to: truncation,
/// and `i32::MIN` for NaN and anything out of range (Rust's `as` saturates instead).
fn trunc_i32(x: f64) -> i32 {
    if x > -2_147_483_649.0 && x < 2_147_483_648.0 {
        x as i32
    } else {
        i32::MIN
    }
}

/// `cvttsd2si` into 64 bits, C's `(long)x`: `i64::MIN` for NaN and out of range.
fn trunc_i64(x: f64) -> i64 {
    if (-9_223_372_036_854_775_808.0..9_223_372_036_854_775_808.0).contains(&x) {
        x as i64
    } else {
        i64::MIN
    }
}

/// The lattice cell of one coordinate and the offset in it, as noise3.c finds them:
/// `(int)x - (x < 0)`, which floors within ±2^31 (an integer negative coordinate
/// lands one cell low, at offset 1) and beyond it wraps from `INT_MIN` (x86-64's
/// answer for an out-of-range conversion) to `INT_MAX`, leaving a huge offset.
fn cell(x: f64) -> (i32, f64) {
    let i = trunc_i32(x).wrapping_sub(i32::from(x < 0.0));
    (i, x - f64::from(i))
}

/// The quintic fade `6t⁵ - 15t⁴ + 10t³` without its `t²` factor: the reference build
/// evaluates the fade as `(((6t - 15)t + 10)t)·t²`, and for `z` keeps the factors apart.
fn fade_poly(t: f64) -> f64 {
    ((t * 6.0 - 15.0) * t + 10.0) * t
}

fn fade(t: f64) -> f64 {
    fade_poly(t) * (t * t)
}

fn lerp(t: f64, a: f64, b: f64) -> f64 {
    a + t * (b - a)
}

/// One of Perlin's 12 gradient directions (16 with repeats) dotted with the offset.
fn grad(hash: i32, x: f64, y: f64, z: f64) -> f64 {
    let h = hash & 15;
    let u = if h < 8 { x } else { y };
    let v = match h {
        0..=3 => y,
        12 | 14 => x,
        _ => z,
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

fn perlin(p: [f64; 3]) -> f64 {
    let (xi, x) = cell(p[0]);
    let (yi, y) = cell(p[1]);
    let (zi, z) = cell(p[2]);
    let (xi, yi, zi) = (xi & 0xff, yi & 0xff, zi & 0xff);
    let (u, v) = (fade(x), fade(y));
    let a = perm(xi) + yi;
    let (aa, ab) = (perm(a) + zi, perm(a + 1) + zi);
    let b = perm(xi + 1) + yi;
    let (ba, bb) = (perm(b) + zi, perm(b + 1) + zi);
    let layer = |aa: i32, ab: i32, ba: i32, bb: i32, z: f64| {
        lerp(
            v,
            lerp(u, grad(perm(aa), x, y, z), grad(perm(ba), x - 1.0, y, z)),
            lerp(
                u,
                grad(perm(ab), x, y - 1.0, z),
                grad(perm(bb), x - 1.0, y - 1.0, z),
            ),
        )
    };
    let near = layer(aa, ab, ba, bb, z);
    let far = layer(aa + 1, ab + 1, ba + 1, bb + 1, z - 1.0);
    // lerp(fade(z), near, far) with the fade's factors applied one at a time.
    near + (far - near) * (z * z) * fade_poly(z)
}

/// noise3.c's `frand`: a hash of a 64-bit seed to [-1, 1), with C `long` arithmetic
/// wrapping as the machine code wraps it.
fn frand(seed: i64) -> f64 {
    let s = (seed << 13) ^ seed;
    let poly = s.wrapping_mul(s).wrapping_mul(15731).wrapping_add(789_221);
    let r = s.wrapping_mul(poly).wrapping_add(1_376_312_589) & 0x7fff_ffff;
    1.0 - r as f64 / 1_073_741_824.0
}

fn frand3(v: [i64; 3]) -> f64 {
    frand(
        v[0].wrapping_mul(17)
            .wrapping_add(v[1].wrapping_mul(23))
            .wrapping_add(v[2].wrapping_mul(29)),
    )
}

/// `fnoise3`: noise3.c's fractal noise, a midpoint displacement on an integer lattice
/// of step `EPSILON` (coordinates are scaled by 2000 into C `long`s, so huge or NaN
/// coordinates become `LONG_MIN`, and the lattice sums wrap around), refined from the
/// unit cell around the point down to one lattice step in ten halvings.
pub fn fnoise3(x: f64, y: f64, z: f64) -> f64 {
    let p = [x, y, z];
    let mut s: i64 = 2000;
    let t = p.map(|c| trunc_i64(c * 2000.0));
    let mut beg = p.map(|c| trunc_i64(2000.0 * c.floor()));
    let mut fval = [0.0; 8];
    for (j, f) in fval.iter_mut().enumerate() {
        let v: [i64; 3] =
            std::array::from_fn(|i| beg[i].wrapping_add(if j >> i & 1 == 1 { s } else { 0 }));
        *f = frand3(v);
    }
    // The first cube's corners are multiples of 2^-30 below 1 in magnitude, so their
    // sum is exact in any order; the reference build's tree is kept all the same.
    let f = &fval;
    let mut fc = (((f[6] + f[7]) + (f[0] + f[4])) + ((f[1] + f[5]) + (f[2] + f[3]))) * 0.125;
    loop {
        s >>= 1;
        if s == 0 {
            return fc;
        }
        let step = s as f64 * EPSILON;
        let centre: [i64; 3] = beg.map(|b| b.wrapping_add(s));
        let branch = (0..3).fold(0usize, |b, i| b | (usize::from(t[i] > centre[i]) << i));
        let toward = |v: &mut [i64; 3], i: usize| {
            v[i] = if branch >> i & 1 == 1 {
                v[i].wrapping_add(s)
            } else {
                v[i].wrapping_sub(s)
            };
        };
        fc += step * frand3(centre);
        fval[!branch & 7] = fc;
        for i in 0..3 {
            let mut v = centre;
            toward(&mut v, i);
            let mut sum = 0.0;
            for (j, f) in fval.iter().enumerate() {
                if !(j ^ branch) & 1 << i != 0 {
                    sum += f;
                }
            }
            fval[!(branch ^ 1 << i) & 7] = 0.25 * sum + step * frand3(v);
        }
        for i in 0..3 {
            let mut v = centre;
            toward(&mut v, (i + 1) % 3);
            toward(&mut v, (i + 2) % 3);
            let sum = fval[branch & !(1 << i)] + fval[branch | 1 << i];
            fval[branch ^ 1 << i] = 0.5 * sum + step * frand3(v);
        }
        for (i, b) in beg.iter_mut().enumerate() {
            if branch >> i & 1 == 1 {
                *b = b.wrapping_add(s);
            }
        }
        // Later cubes are not exact: noise3.c adds the corners in j order, the
        // reference build in this tree (the compiler vectorised the loop).
        let f = &fval;
        fc = (((f[1] + f[3]) + (f[5] + f[7])) + ((f[0] + f[2]) + (f[4] + f[6]))) * 0.125;
    }
}

/// Hart & Cheney's #5667 for `erfc`, as src/common/erf.c uses it, numerator and
/// denominator from the constant term up; all of erf.c's `erfc` range uses it (its
/// small-argument branch is commented out). Written as the shortest decimals of the
/// doubles the reference build holds (erf.c's longer digits round to these).
const ERFC_P: [f64; 8] = [
    1826.3348842295113,
    2898.0293292167657,
    2320.4395902516353,
    1143.2620707038861,
    368.5196154710011,
    77.08161730368428,
    9.675807882987266,
    0.5641877825507398,
];
const ERFC_Q: [f64; 9] = [
    1826.3348842295113,
    4958.82756472114,
    6089.542423272444,
    4429.612803883682,
    2094.3843677895397,
    661.7361207107654,
    137.12559605006223,
    17.14980943627608,
    1.0,
];
/// erf.c's rational series for `erf` below 0.5, in powers of x².
const ERF_P: [f64; 7] = [
    80437.36309608402,
    7404.071427101515,
    3017.827885365076,
    38.0140318123903,
    14.33838421917482,
    -0.2888051372075941,
    0.007547728033418632,
];
const ERF_Q: [f64; 6] = [
    80437.36309608402,
    34216.52579246285,
    6379.600173244283,
    658.0701554592405,
    38.01907139519394,
    1.0,
];
/// 2/√π, erf.c's `torp` (the same double as the reference build's; a test checks).
const TWO_OVER_SQRT_PI: f64 = std::f64::consts::FRAC_2_SQRT_PI;

fn horner(coefficients: &[f64], x: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |acc, c| acc * x + c)
}

/// `erf` as Radiance's own erf.c computes it (rtrace links it in place of libm's, so
/// neither glibc's `erf` nor the `libm` crate would do: glibc's differs from rtrace at
/// 125 of the 758 golden arguments): a rational series below 0.5, `1 - erfc` up to
/// 10, ±1 beyond.
pub fn erf(x: f64) -> f64 {
    let (sign, a) = if x < 0.0 { (-1.0, -x) } else { (1.0, x) };
    if a < 0.5 {
        let a2 = a * a;
        // erf.c writes sign·(2/√π)·x·n/d; fast-math multiplied it as (n·(2/√π))·(x·sign).
        (horner(&ERF_P, a2) * TWO_OVER_SQRT_PI) * (a * sign) / horner(&ERF_Q, a2)
    } else if a >= 10.0 {
        sign
    } else {
        sign * (1.0 - erfc(a))
    }
}

/// `erfc` as erf.c computes it: `2 - erfc(-x)` for negative x, 0 from 10 on (where
/// glibc's keeps its tiny values), and `exp(-x²)·n(x)/d(x)` between, with the C
/// library's `exp`: rtrace calls the system's glibc `exp`, and Rust's `f64::exp` calls
/// the same function, so on another C library the two could part in the last bit.
pub fn erfc(x: f64) -> f64 {
    if x < 0.0 {
        return 2.0 - erfc(-x);
    }
    if x >= 10.0 {
        return 0.0;
    }
    (-(x * x)).exp() * horner(&ERFC_P, x) / horner(&ERFC_Q, x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perlin_noise_vanishes_on_the_integer_lattice() {
        for p in [
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 3.0],
            [-1.0, -7.0, 255.0],
            [256.0, -257.0, 4.0],
        ] {
            assert_eq!(noise3(p[0], p[1], p[2]), 0.0, "{p:?}");
        }
    }

    #[test]
    fn cells_floor_within_int_range_and_wrap_beyond_it() {
        assert_eq!(cell(2.25), (2, 0.25));
        assert_eq!(cell(-0.25), (-1, 0.75));
        // An integer negative coordinate: (int)x - 1, offset 1 (noise3.c's `x < 0`).
        assert_eq!(cell(-1.0), (-2, 1.0));
        assert_eq!(cell(2_147_483_647.5), (i32::MAX, 0.5));
        // Out of range, cvttsd2si gives INT_MIN; `- (x < 0)` then wraps to INT_MAX.
        assert_eq!(cell(2_147_483_648.0), (i32::MIN, 4_294_967_296.0));
        assert_eq!(cell(-2_147_483_649.0), (i32::MAX, -4_294_967_296.0));
        assert_eq!(cell(f64::NAN).0, i32::MIN);
    }

    #[test]
    fn partials_are_backward_differences_scaled_by_2000() {
        let (x, y, z) = (0.3, -1.7, 2.9);
        let f = noise3(x, y, z);
        assert_eq!(noise3x(x, y, z), (f - noise3(x - EPSILON, y, z)) * 2000.0);
        assert_eq!(noise3y(x, y, z), (f - noise3(x, y - EPSILON, z)) * 2000.0);
        assert_eq!(noise3z(x, y, z), (f - noise3(x, y, z - EPSILON)) * 2000.0);
    }

    #[test]
    fn the_cache_gives_the_pure_values_for_finite_points() {
        let mut cache = Noise3Cache::default();
        for p in [
            [0.1, 0.2, 0.3],
            [0.1, 0.2, 0.3],
            [5.5, -2.25, 1e4],
            [0.1, 0.2, 0.3],
        ] {
            assert_eq!(cache.partial(p, 1), noise3y(p[0], p[1], p[2]));
            assert_eq!(cache.noise3(p), noise3(p[0], p[1], p[2]));
            assert_eq!(cache.partial(p, 0), noise3x(p[0], p[1], p[2]));
            assert_eq!(cache.partial(p, 2), noise3z(p[0], p[1], p[2]));
        }
    }

    #[test]
    fn the_cache_answers_a_nan_point_with_the_previous_point() {
        let mut cache = Noise3Cache::default();
        let before = cache.noise3([0.1, 0.2, 0.3]);
        assert_eq!(cache.noise3([f64::NAN, 0.2, 0.3]), before);
        assert_eq!(
            cache.partial([0.1, f64::NAN, 0.3], 0),
            noise3x(0.1, 0.2, 0.3)
        );
        assert!(noise3(f64::NAN, 0.2, 0.3).is_nan());
        // A cold cache computes the NaN point itself.
        assert!(Noise3Cache::default().noise3([f64::NAN, 0.0, 0.0]).is_nan());
    }

    #[test]
    fn frand_stays_in_its_range_with_wrapping_seeds() {
        for seed in [
            0,
            1,
            -1,
            17 * 2000,
            i64::MAX,
            i64::MIN,
            0x1234_5678_9abc_def0,
        ] {
            let r = frand(seed);
            assert!((-1.0..=1.0).contains(&r), "{seed}: {r}");
        }
    }

    #[test]
    fn fractal_noise_is_finite_even_where_coordinates_saturate() {
        for p in [
            [0.0, 0.0, 0.0],
            [-3.7, 2.2, 9.9],
            [1e16, -1e17, 5.0],
            [f64::MAX, -f64::MAX, 1e300],
        ] {
            let f = fnoise3(p[0], p[1], p[2]);
            assert!(f.is_finite() && f.abs() < 2.0, "{p:?}: {f}");
        }
        assert_eq!(trunc_i64(1e19), i64::MIN);
        assert_eq!(trunc_i64(-9_223_372_036_854_775_808.0), i64::MIN);
        assert_eq!(trunc_i64(-2.5), -2);
    }

    #[test]
    fn erf_and_erfc_keep_erf_c_symmetries_and_limits() {
        for x in [0.0, 0.1, 0.4999, 0.5, 1.0, 3.0, 9.99] {
            assert_eq!(erf(-x), -erf(x), "{x}");
            assert!((erf(x) + erfc(x) - 1.0).abs() < 1e-15, "{x}");
            assert_eq!(erfc(-x), 2.0 - erfc(x), "{x}");
        }
        assert_eq!(
            (erf(10.0), erf(-10.0), erf(f64::INFINITY)),
            (1.0, -1.0, 1.0)
        );
        assert_eq!(
            (erfc(10.0), erfc(-10.0), erfc(f64::NEG_INFINITY)),
            (0.0, 2.0, 2.0)
        );
        assert!(erf(f64::NAN).is_nan() && erfc(f64::NAN).is_nan());
        assert!((erf(1.0) - 0.842_700_792_949_714_9).abs() < 1e-15);
        // erf.c's `torp` as the reference build's binary holds it.
        assert_eq!(TWO_OVER_SQRT_PI.to_bits(), 0x3FF2_0DD7_5042_9B6D);
    }

    #[test]
    fn call_knows_only_the_pure_functions_at_their_arity() {
        assert_eq!(call("erf", &[0.5]), Some(erf(0.5)));
        assert_eq!(
            call("noise3z", &[1.5, 2.0, -3.0]),
            Some(noise3z(1.5, 2.0, -3.0))
        );
        assert_eq!(
            call("fnoise3", &[1.5, 2.0, -3.0]),
            Some(fnoise3(1.5, 2.0, -3.0))
        );
        for name in [
            "arg",
            "source_corr",
            "source_theta",
            "source_phi",
            "fprism_val",
            "sin",
        ] {
            assert_eq!(call(name, &[1.0, 2.0, 3.0]), None, "{name}");
        }
        assert_eq!(call("noise3", &[1.0, 2.0]), None);
        assert_eq!(call("erfc", &[]), None);
    }
}
