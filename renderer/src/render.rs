//! rpict's render loop: one primary ray through each pixel centre, rows in parallel,
//! then the sources too small to be hit by a pixel's ray drawn in
//! ([`crate::small_sources`]). Each pixel's random choices derive from its index, so a
//! picture is the same for any thread count.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::camera::Camera;
use crate::math::Color;
use crate::{Target, Tracer};

/// The `w` by `h` picture `camera` sees, top row first, counting finished rows in
/// `rows_done` (for a progress display).
pub fn render_picture(
    tracer: &Tracer<'_>,
    camera: &Camera,
    w: u32,
    h: u32,
    rows_done: &AtomicUsize,
) -> Vec<Color> {
    let done = rows_done;
    // Top row first; pixel centres at ((i + .5) / w, (j + .5) / h) with j counted upward.
    let mut pixels: Vec<Color> = (0..h)
        .into_par_iter()
        .flat_map_iter(|row| {
            let j = h - 1 - row;
            let row_pixels: Vec<Color> = (0..w)
                .map(move |i| {
                    let x = (f64::from(i) + 0.5) / f64::from(w);
                    let y = (f64::from(j) + 0.5) / f64::from(h);
                    // Outside a fisheye's circle the picture is black.
                    // Random choices derive from the pixel's index, not the thread.
                    let index = u64::from(row) * u64::from(w) + u64::from(i);
                    camera.ray(x, y).map_or(Color::ZERO, |(org, dir, max)| {
                        tracer.radiance_seeded(org, dir, max, index).color
                    })
                })
                .collect();
            done.fetch_add(1, Ordering::Relaxed);
            row_pixels
        })
        .collect();
    crate::small_sources::draw(tracer, camera, w, h, 1.0, &mut pixels);
    pixels
}

/// Rays sampled over the view to tell whether the view point is inside something.
const PROBE: u32 = 16;

/// rpict renders whatever the view sees; a view point inside a closed object mostly sees
/// the backs of its faces, and usually renders black. A warning saying so, if most of a
/// grid of view rays hit a surface from behind.
pub fn inside_geometry(tracer: &Tracer<'_>, camera: &Camera) -> Option<String> {
    let (mut hits, mut backs) = (0u32, 0u32);
    let mut nearest: Option<(f64, u32)> = None;
    for j in 0..PROBE {
        for i in 0..PROBE {
            let (x, y) = (
                (f64::from(i) + 0.5) / f64::from(PROBE),
                (f64::from(j) + 0.5) / f64::from(PROBE),
            );
            let Some((org, dir, max)) = camera.ray(x, y) else {
                continue;
            };
            let r = tracer.radiance_within(org, dir, max);
            let Target::Object(id) = r.hit else {
                continue;
            };
            hits += 1;
            if r.surface_normal().dot(r.dir) > 0.0 {
                backs += 1;
                if nearest.is_none_or(|(t, _)| r.length < t) {
                    nearest = Some((r.length, id.0));
                }
            }
        }
    }
    let probes = PROBE * PROBE;
    if hits < probes / 2 || backs * 10 < hits * 9 {
        return None;
    }
    let name = nearest
        .and_then(|(_, id)| tracer.scene().object(id))
        .map(|o| format!(" (the nearest is '{}')", o.name))
        .unwrap_or_default();
    let p = camera.position();
    Some(format!(
        "the view point ({} {} {}) seems to be inside geometry: {backs} of {probes} view rays \
         hit the back of a surface{name}",
        p.x, p.y, p.z
    ))
}
