//! Arbitrary bytes as the payload of a compiled scene (`.rsc`) behind a valid header and
//! checksum, so that every input reaches the decoder and its index validation, which a
//! corrupt or foreign file cannot (the checksum stops those first). A scene that
//! decodes is traced: loading a file must never make the renderer panic either.
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_renderer::scene_file::{decode, frame};
use radc_renderer::{Options, Tracer};

fuzz_target!(|data: &[u8]| {
    let Ok(file) = frame(data) else {
        return;
    };
    if let Ok(scene) = decode(&file) {
        let tracer = Tracer::new(&scene, Options::default());
        for (o, d) in [
            ([0.0, 0.0, 2.0], [0.0, 0.0, -1.0]),
            ([1.0, -3.0, 0.5], [0.0, 1.0, 0.0]),
            ([1e5, 1e5, 1e5], [-0.57735, -0.57735, -0.57735]),
        ] {
            let _ = tracer.radiance(o.into(), d.into());
        }
    }
});
