//! Vectors, colours and the tolerances Radiance uses (`src/common/fvect.h`).

pub use glam::DVec3 as Vec3;

/// An RGB colour (or coefficient). Radiance keeps colours in `float`; radc keeps `f64`.
pub type Color = Vec3;

/// Radiance's absolute tolerance: hits at `t <= FTINY` are rejected, coincident hits are
/// those within `FTINY` of each other.
pub const FTINY: f64 = 1e-6;
/// Radiance's "infinite" distance: the length reported for a ray that hits nothing.
pub const FHUGE: f64 = 1e10;

pub fn vec3(a: [f64; 3]) -> Vec3 {
    Vec3::from_array(a)
}

/// Normalizes `v` in place the way Radiance's `normalize()` does (a first-order step when
/// the length is already within `FTINY` of 1) and returns the old length, 0 for a zero
/// vector (left unchanged).
pub fn normalize(v: &mut Vec3) -> f64 {
    let d = v.length_squared();
    if d == 0.0 || !d.is_finite() {
        return 0.0;
    }
    let (len, scale) = if (1.0 - FTINY..=1.0 + FTINY).contains(&d) {
        let len = 0.5 + 0.5 * d;
        (len, 2.0 - len)
    } else {
        let len = d.sqrt();
        (len, 1.0 / len)
    };
    *v *= scale;
    len
}

/// The largest component: Radiance's `intens()`, used as a ray's weight.
pub fn intensity(c: Color) -> f64 {
    c.max_element()
}

/// Luminance-like brightness with Radiance's default primaries (`pbright()`).
pub fn brightness(c: Color) -> f64 {
    0.265074126 * c.x + 0.670114631 * c.y + 0.064811243 * c.z
}

/// A unit vector perpendicular to unit `v`, chosen as Radiance's `getperpendicular()`
/// does without randomization (rtrace `-u-`): crossed with the last axis along which `v`
/// is small.
pub fn perpendicular(v: Vec3) -> Option<Vec3> {
    let axis = (0..3).rev().find(|&i| v[i] > -0.6 && v[i] < 0.6)?;
    let mut e = Vec3::ZERO;
    e[axis] = 1.0;
    let mut p = e.cross(v);
    (normalize(&mut p) > 0.0).then_some(p)
}

/// Axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Bounds {
    pub min: Vec3,
    pub max: Vec3,
}

impl Bounds {
    pub const EMPTY: Bounds = Bounds {
        min: Vec3::splat(f64::INFINITY),
        max: Vec3::splat(f64::NEG_INFINITY),
    };

    pub fn point(p: Vec3) -> Bounds {
        Bounds { min: p, max: p }
    }

    pub fn union(self, o: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    pub fn surface_area(&self) -> f64 {
        let d = (self.max - self.min).max(Vec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// Grown by `FTINY` plus a few ulps of its coordinates, so that rounding in a
    /// shape's own intersection test never lets a hit fall outside its box.
    pub fn padded(self) -> Bounds {
        let mag = self.min.abs().max(self.max.abs()).max_element();
        let pad = Vec3::splat(FTINY + mag * 1e-12);
        Bounds {
            min: self.min - pad,
            max: self.max + pad,
        }
    }

    /// `hit`, with the distance the ray enters the box (0 from inside): a box hit with
    /// a NaN exit (the ray in a slab plane) enters at minus infinity, so it passes any
    /// later comparison with a limit, as `hit` would.
    #[inline]
    pub fn entry(&self, org: Vec3, inv_dir: Vec3, tmax: f64) -> Option<f64> {
        let a = (self.min - org) * inv_dir;
        let b = (self.max - org) * inv_dir;
        let lo = a.min(b);
        let hi = a.max(b);
        let t0 = lo.x.max(lo.y).max(lo.z).max(0.0);
        let t1 = hi.x.min(hi.y).min(hi.z).min(tmax);
        let t0 = if t0.is_nan() { 0.0 } else { t0 };
        if t1.is_nan() {
            Some(f64::NEG_INFINITY)
        } else {
            (t0 <= t1).then_some(t0)
        }
    }

    /// Slab test: the parameter range `[t0, t1]` of the ray inside the box, if any
    /// overlaps `[0, tmax]`.
    pub fn hit(&self, org: Vec3, inv_dir: Vec3, tmax: f64) -> bool {
        self.entry(org, inv_dir, tmax).is_some()
    }
}

/// Asks for every cache line of `x` (a hint: no effect on results), so that a miss
/// overlaps with other work instead of stalling the first read.
#[inline(always)]
pub fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let p = (x as *const T).cast::<i8>();
        for offset in (0..std::mem::size_of::<T>()).step_by(64) {
            // SAFETY: a prefetch never faults and reads nothing the program sees; the
            // address lies inside the live `x`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(offset)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalize_returns_length() {
        let mut v = Vec3::new(3.0, 0.0, 4.0);
        assert_eq!(normalize(&mut v), 5.0);
        assert!((v.length() - 1.0).abs() < 1e-15);
        let mut z = Vec3::ZERO;
        assert_eq!(normalize(&mut z), 0.0);
    }

    #[test]
    fn perpendicular_is_perpendicular() {
        for v in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::new(1.0, 1.0, 1.0).normalize(),
        ] {
            let p = perpendicular(v).unwrap();
            assert!(p.dot(v).abs() < 1e-12);
            assert!((p.length() - 1.0).abs() < 1e-12);
        }
    }
}
