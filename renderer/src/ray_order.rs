//! The order to trace a batch of rays in, so that rays traced one after another cross
//! nearby space and read the same BVH nodes and surfaces while those are still in
//! cache.
//!
//! Rays read from a file often come in no useful order: sensor points spread over a
//! building, random samples. On a scene larger than the cache (the 320,000-triangle
//! terrain: 44 MB of nodes and triangles), rays taken as they come fetch most of their
//! nodes and triangles from memory, and memory, not arithmetic, sets the speed.
//! Sorting a batch along a Z-order (Morton) curve through the scene's box makes
//! neighbours in the order neighbours in space. Results do not depend on the order:
//! a ray's random choices derive from its index in the input, and output is written
//! in input order.

use crate::math::{Bounds, Vec3};

/// Bits of a ray's index in its sort key: a batch holds at most `1 << INDEX_BITS` rays.
const INDEX_BITS: u32 = 20;
/// Bits per axis of the cell a ray's key names: 1,024 cells along the box's longest
/// side, where a batch puts a few hundred rays per cell row.
const CELL_BITS: u32 = 10;
/// Bits of the cell code sorted per radix pass: three passes for `3 * CELL_BITS`.
const RADIX_BITS: u32 = 10;
const PASSES: u32 = 3 * CELL_BITS / RADIX_BITS;

/// Most rays [`RayOrder::sort`] orders at once.
pub const MAX_RAYS: usize = 1 << INDEX_BITS;

/// An order of a batch's rays and the scratch space that computes it, kept from
/// batch to batch.
#[derive(Default)]
pub struct RayOrder {
    keys: Vec<u64>,
    spare: Vec<u64>,
    order: Vec<u32>,
}

impl RayOrder {
    /// The indices of `rays` (origin, direction) in the order to trace them: by the
    /// Z-order of the point halfway along each ray's stretch inside `extent` (the
    /// scene's box), where its nearest hit most likely lies; rays in the same cell
    /// keep their input order. A ray that misses the box is placed by its origin,
    /// clamped to the box. Rays beyond [`MAX_RAYS`] follow the rest, as given.
    pub fn sort(&mut self, rays: &[(Vec3, Vec3)], extent: Bounds) -> &[u32] {
        let n = rays.len().min(MAX_RAYS);
        let size = (extent.max - extent.min).max_element();
        // Cubic cells: a flat scene's thin axis gets few cells, not as many as its
        // long ones.
        let scale = if size > 0.0 && size.is_finite() {
            f64::from((1u32 << CELL_BITS) - 1) / size
        } else {
            0.0
        };
        self.keys.clear();
        self.keys
            .extend(rays[..n].iter().enumerate().map(|(i, &(org, dir))| {
                let p = midpoint(org, dir, extent);
                // `as` saturates, and takes NaN to 0: any ray gets a cell.
                let cell = |a: usize| ((p[a] - extent.min[a]) * scale) as u64;
                let z = spread(cell(0)) | spread(cell(1)) << 1 | spread(cell(2)) << 2;
                z << INDEX_BITS | i as u64
            }));
        radix_sort(&mut self.keys, &mut self.spare);
        self.order.clear();
        let index = MAX_RAYS as u64 - 1;
        self.order
            .extend(self.keys.iter().map(|k| (k & index) as u32));
        self.order.extend(n as u32..rays.len() as u32);
        &self.order
    }
}

/// Sorts `keys` by their cell codes (the bits above `INDEX_BITS`), stably: a radix
/// sort, a few instructions per key and pass where a comparison sort of a batch
/// takes over a hundred.
fn radix_sort(keys: &mut Vec<u64>, spare: &mut Vec<u64>) {
    const DIGITS: usize = 1 << RADIX_BITS;
    spare.clear();
    spare.resize(keys.len(), 0);
    for pass in 0..PASSES {
        let shift = INDEX_BITS + pass * RADIX_BITS;
        let digit = |k: u64| (k >> shift) as usize % DIGITS;
        let mut start = [0usize; DIGITS];
        for &k in keys.iter() {
            start[digit(k)] += 1;
        }
        let mut sum = 0;
        for s in start.iter_mut() {
            (*s, sum) = (sum, sum + *s);
        }
        for &k in keys.iter() {
            let d = digit(k);
            if let Some(slot) = spare.get_mut(start[d]) {
                *slot = k;
            }
            start[d] += 1;
        }
        std::mem::swap(keys, spare);
    }
}

/// The point halfway along the part of the ray inside `b`, or the origin clamped to
/// `b` if the ray misses it. `f64::max`/`min` skip the NaN of a zero direction
/// component on a box plane.
fn midpoint(org: Vec3, dir: Vec3, b: Bounds) -> Vec3 {
    let inv = dir.recip();
    let (lo, hi) = ((b.min - org) * inv, (b.max - org) * inv);
    let (near, far) = (lo.min(hi), lo.max(hi));
    let t0 = near.x.max(near.y).max(near.z).max(0.0);
    let t1 = far.x.min(far.y).min(far.z);
    let p = if t0 <= t1 && t1.is_finite() {
        org + dir * (0.5 * (t0 + t1))
    } else {
        org
    };
    p.clamp(b.min, b.max.max(b.min))
}

/// The low `CELL_BITS` bits of `v`, two zero bits after each.
fn spread(v: u64) -> u64 {
    let mut x = v.min((1 << CELL_BITS) - 1);
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::uniform;

    fn order_of(rays: &[(Vec3, Vec3)], extent: Bounds) -> Vec<u32> {
        RayOrder::default().sort(rays, extent).to_vec()
    }

    fn unit_box() -> Bounds {
        Bounds {
            min: Vec3::ZERO,
            max: Vec3::splat(100.0),
        }
    }

    #[test]
    fn spread_puts_two_zeros_after_each_bit() {
        assert_eq!(spread(0b1011), 0b001_000_001_001);
        assert_eq!(spread(u64::MAX), 0x1249_2492_4924_9249 & ((1 << 30) - 1));
    }

    #[test]
    fn radix_sort_sorts_by_cell_and_keeps_the_input_order_within_one() {
        let mut keys: Vec<u64> = (0..5000u64)
            .map(|i| ((uniform(5, i) * 4000.0) as u64) << INDEX_BITS | i)
            .collect();
        let mut want = keys.clone();
        want.sort_unstable();
        radix_sort(&mut keys, &mut Vec::new());
        assert_eq!(keys, want);
        let mut top = vec![u64::MAX, 0, 1 << 62];
        radix_sort(&mut top, &mut Vec::new());
        assert_eq!(top, [0, 1 << 62, u64::MAX]);
    }

    #[test]
    fn rays_along_a_line_come_out_in_order_along_it() {
        // Vertical rays through the box at x = 0.5, 1.5, ..., given shuffled: Z-order
        // along one axis (the others fixed) is that axis's order.
        let mut xs: Vec<u32> = (0..100).collect();
        for i in (1..xs.len()).rev() {
            xs.swap(
                i,
                (uniform(3, i as u64) * (i + 1) as f64) as usize % (i + 1),
            );
        }
        let rays: Vec<_> = xs
            .iter()
            .map(|&x| {
                (
                    Vec3::new(f64::from(x) + 0.5, 50.0, 200.0),
                    Vec3::new(0.0, 0.0, -1.0),
                )
            })
            .collect();
        let order = order_of(&rays, unit_box());
        let along: Vec<u32> = order.iter().map(|&i| xs[i as usize]).collect();
        assert_eq!(along, (0..100).collect::<Vec<_>>());
    }

    #[test]
    fn the_order_is_a_permutation_whatever_the_rays() {
        let odd = [
            (Vec3::splat(f64::NAN), Vec3::X),
            (Vec3::ZERO, Vec3::ZERO),
            (Vec3::splat(f64::INFINITY), Vec3::splat(f64::NEG_INFINITY)),
            (Vec3::new(0.0, 50.0, 50.0), Vec3::Y),
            (Vec3::splat(1e300), Vec3::Z),
            (Vec3::splat(-1e300), Vec3::splat(1e-300)),
        ];
        for extent in [unit_box(), Bounds::point(Vec3::ONE), Bounds::EMPTY] {
            let mut order = order_of(&odd, extent);
            order.sort_unstable();
            assert_eq!(order, (0..odd.len() as u32).collect::<Vec<_>>());
        }
        assert!(order_of(&[], unit_box()).is_empty());
    }

    #[test]
    fn neighbours_in_the_order_are_near_in_space() {
        // Random rays down onto a flat box (a terrain's): the order's steps between
        // the points where they cross the middle plane are a small part of random ones.
        let extent = Bounds {
            min: Vec3::new(0.0, 0.0, 2.0),
            max: Vec3::new(100.0, 100.0, 8.0),
        };
        let rays: Vec<_> = (0..4096u64)
            .map(|i| {
                let r = |k: u64| uniform(1, 4 * i + k);
                let org = Vec3::new(100.0 * r(0), 100.0 * r(1), 15.0);
                let dir = Vec3::new(2.0 * r(2) - 1.0, 2.0 * r(3) - 1.0, -1.0);
                (org, dir)
            })
            .collect();
        let at = |(o, d): (Vec3, Vec3)| o + d * ((5.0 - o.z) / d.z);
        let path = |ids: &mut dyn Iterator<Item = usize>| {
            let points: Vec<Vec3> = ids.map(|i| at(rays[i])).collect();
            points.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>()
        };
        let sorted = path(&mut order_of(&rays, extent).iter().map(|&i| i as usize));
        let given = path(&mut (0..rays.len()));
        assert!(sorted < 0.1 * given, "sorted {sorted}, as given {given}");
    }
}
