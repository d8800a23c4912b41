//! `radc cnt` as Radiance's cnt writes it (`cnt 2 3` below is cnt's output, byte for
//! byte), the shuffle a permutation of the same lines, and its usage errors.

mod common;

use common::{radc, run};

#[test]
fn counts_as_radiance_counts() {
    let out = run(radc(["cnt", "2", "3"]), b"");
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "\t0\t0\n\t0\t1\n\t0\t2\n\t1\t0\n\t1\t1\n\t1\t2\n"
    );
    let shuffled = run(radc(["cnt", "-s", "7", "11"]), b"");
    assert!(shuffled.status.success());
    let plain = run(radc(["cnt", "7", "11"]), b"");
    let sorted = |b: &[u8]| {
        let mut l: Vec<String> = String::from_utf8_lossy(b)
            .lines()
            .map(str::to_string)
            .collect();
        l.sort();
        l
    };
    assert_eq!(sorted(&shuffled.stdout), sorted(&plain.stdout));
    assert_eq!(sorted(&plain.stdout).len(), 77);
    for bad in [&["cnt"][..], &["cnt", "1"], &["cnt", "3", "x"]] {
        let out = run(radc(bad), b"");
        assert_eq!(out.status.code(), Some(1), "{bad:?}");
        assert!(String::from_utf8_lossy(&out.stderr).starts_with("Usage: cnt [-s] N0"));
    }
}
