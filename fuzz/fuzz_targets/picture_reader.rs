//! Arbitrary bytes as a Radiance picture: the reader must return a picture or an error,
//! never panic or allocate without bound. A picture that reads is written back and must
//! read again to the same picture, and is sampled as a `colorpict` pattern would be.
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_picture::{ColorPicture, Picture};

fuzz_target!(|data: &[u8]| {
    let Ok(picture) = Picture::read_with_limit(data, 1 << 20) else {
        return;
    };
    let mut out = Vec::new();
    picture.write(&mut out).expect("writing to memory");
    let back = Picture::read_with_limit(&out, 1 << 20).expect("a written picture reads back");
    assert_eq!(back, picture);
    let _ = picture.standard_pixels();
    if let Ok(pattern) = ColorPicture::new(&picture) {
        for (u, v) in [(0.0, 0.0), (0.5, 0.5), (1.0, 1.0), (-3.0, 7.0), (f64::NAN, 1e300)] {
            let _ = pattern.value(u, v);
        }
    }
});
