//! Arbitrary numbers as a batch of rays and a scene box for `RayOrder::sort` (NaN,
//! infinities, zero and huge directions, boxes inside out): the order must be a
//! permutation of the batch, whatever the numbers, and nothing may panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_renderer::math::{Bounds, Vec3};
use radc_renderer::ray_order::RayOrder;

fuzz_target!(|data: &[u8]| {
    let numbers: Vec<f64> = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let Some((extent, rest)) = numbers.split_first_chunk::<6>() else {
        return;
    };
    let extent = Bounds {
        min: Vec3::new(extent[0], extent[1], extent[2]),
        max: Vec3::new(extent[3], extent[4], extent[5]),
    };
    let rays: Vec<(Vec3, Vec3)> = rest
        .chunks_exact(6)
        .map(|r| (Vec3::new(r[0], r[1], r[2]), Vec3::new(r[3], r[4], r[5])))
        .collect();
    let mut order = RayOrder::default().sort(&rays, extent).to_vec();
    order.sort_unstable();
    assert!(
        order.iter().copied().eq(0..rays.len() as u32),
        "not a permutation"
    );
});
