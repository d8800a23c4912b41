//! `radc cnt`: Radiance's cnt, every combination of counters `0..N0`, `0..N1`, ...
//! (the last counting fastest), one tab before each number, or with `-s` the same
//! lines in random order. The shuffle is a random bijection of the line numbers (a
//! Feistel network with cycle walking), so it needs no memory for the lines, where
//! Radiance's keeps an occupancy tree of up to 1.94 billion bits; its order is random,
//! as Radiance's is, not Radiance's order.

use std::io::Write;
use std::process::ExitCode;

/// Radiance's `MAXDIM`.
const MAX_COUNTERS: usize = 50;

fn usage() -> ExitCode {
    eprintln!("Usage: cnt [-s] N0 [N1 ..]");
    ExitCode::from(1)
}

pub fn run(args: &[String]) -> ExitCode {
    let mut args = args;
    let shuffle = args.first().is_some_and(|a| a.starts_with("-s"));
    if shuffle {
        args = &args[1..];
    }
    let counts: Vec<u64> = args
        .iter()
        .map(radc_lang::c_number::atol)
        .filter(|n| *n > 1)
        .map(|n| n as u64)
        .collect();
    if counts.is_empty() || counts.len() != args.len() || counts.len() > MAX_COUNTERS {
        return usage();
    }
    let Some(total) = counts.iter().try_fold(1u64, |t, n| t.checked_mul(*n)) else {
        eprintln!("cnt: the counters make more lines than can be numbered");
        return ExitCode::from(1);
    };
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
    let permutation = shuffle.then(|| Permutation::new(total, seed()));
    let mut line = Vec::with_capacity(16 * counts.len());
    let mut digits = itoa_buffer();
    for i in 0..total {
        let mut value = permutation.as_ref().map_or(i, |p| p.apply(i));
        line.clear();
        // Line number `value` in mixed radix, the last counter fastest.
        let mut place = [0u64; MAX_COUNTERS];
        for (k, n) in counts.iter().enumerate().rev() {
            place[k] = value % n;
            value /= n;
        }
        for p in &place[..counts.len()] {
            line.push(b'\t');
            line.extend_from_slice(digits.format(*p));
        }
        line.push(b'\n');
        if out.write_all(&line).is_err() {
            return ExitCode::from(1);
        }
    }
    match out.flush() {
        Ok(()) => ExitCode::SUCCESS,
        Err(_) => ExitCode::from(1),
    }
}

/// Decimal digits of a `u64` without allocating.
struct Digits([u8; 20]);

fn itoa_buffer() -> Digits {
    Digits([0; 20])
}

impl Digits {
    fn format(&mut self, mut v: u64) -> &[u8] {
        let mut at = self.0.len();
        loop {
            at -= 1;
            self.0[at] = b'0' + (v % 10) as u8;
            v /= 10;
            if v == 0 {
                break;
            }
        }
        &self.0[at..]
    }
}

/// A shuffle seed from the clock and the process, as Radiance seeds its shuffle from
/// the time.
fn seed() -> u64 {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    now ^ (u64::from(std::process::id()) << 32)
}

/// A random bijection of `0..n`: a four-round Feistel network on the smallest even
/// number of bits holding `n`, applied again while the result is `n` or more (cycle
/// walking stays inside `0..n` and keeps it a bijection).
struct Permutation {
    n: u64,
    half_bits: u32,
    keys: [u64; 4],
}

impl Permutation {
    fn new(n: u64, seed: u64) -> Permutation {
        let bits = 64 - n.saturating_sub(1).leading_zeros();
        let half_bits = bits.div_ceil(2).max(1);
        let mut keys = [0; 4];
        for (i, k) in keys.iter_mut().enumerate() {
            *k = radc_renderer::random::derive(seed, i as u64);
        }
        Permutation { n, half_bits, keys }
    }

    fn round(&self, x: u64) -> u64 {
        let mask = (1u64 << self.half_bits) - 1;
        let (mut left, mut right) = (x >> self.half_bits, x & mask);
        for k in self.keys {
            let f = radc_renderer::random::derive(right, k) & mask;
            (left, right) = (right, left ^ f);
        }
        (left << self.half_bits) | right
    }

    fn apply(&self, i: u64) -> u64 {
        let mut x = self.round(i);
        while x >= self.n {
            x = self.round(x);
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shuffle_is_a_permutation_of_every_line() {
        for n in [2u64, 3, 7, 64, 1000, 4097] {
            let p = Permutation::new(n, 12345);
            let mut seen = vec![false; n as usize];
            for i in 0..n {
                let j = p.apply(i);
                assert!(j < n && !seen[j as usize], "n {n}: {i} -> {j}");
                seen[j as usize] = true;
            }
            if n > 10 {
                assert!((0..n).any(|i| p.apply(i) != i), "n {n}: not shuffled");
            }
        }
    }
}
