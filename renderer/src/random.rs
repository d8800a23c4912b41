//! Reproducible random numbers for Monte Carlo sampling. Radiance draws from one global
//! generator, so its results depend on the order rays are traced in; radc derives every
//! random number by hashing the ray's seed with what it is for (which sample, which
//! source), and each ray's seed from its parent's. A primary ray is seeded by its index
//! (pixel or input line), never by the thread that traces it, so results do not depend
//! on parallelism.

/// SplitMix64's finalizer: a bijective mix with good avalanche.
pub fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A seed for what `salt` names, derived from `seed`.
pub fn derive(seed: u64, salt: u64) -> u64 {
    mix(seed ^ mix(salt.wrapping_add(0x9e37_79b9_7f4a_7c15)))
}

/// A number uniform in `[0, 1)` for `salt` under `seed`.
pub fn uniform(seed: u64, salt: u64) -> f64 {
    (derive(seed, salt) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The seed of primary ray number `index`.
pub fn primary_seed(index: u64) -> u64 {
    mix(index.wrapping_mul(0x2545_f491_4f6c_dd1d) ^ 0x5851_f42d_4c95_7f2d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_is_in_the_unit_interval_and_roughly_uniform() {
        let n = 100_000;
        let mut sum = 0.0;
        let mut buckets = [0u32; 10];
        for i in 0..n {
            let u = uniform(primary_seed(7), i);
            assert!((0.0..1.0).contains(&u));
            sum += u;
            buckets[(u * 10.0) as usize] += 1;
        }
        assert!((sum / n as f64 - 0.5).abs() < 0.005);
        for b in buckets {
            assert!((f64::from(b) - 10_000.0).abs() < 500.0, "{buckets:?}");
        }
    }

    #[test]
    fn seeds_differ_by_salt_and_parent() {
        assert_ne!(derive(1, 2), derive(1, 3));
        assert_ne!(derive(1, 2), derive(2, 2));
        assert_eq!(derive(5, 9), derive(5, 9));
    }
}
