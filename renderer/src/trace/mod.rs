//! rtrace's ray pipeline: rays read from a stream in batches, evaluated in parallel in
//! chunks (in space order for scenes bigger than a core's cache), and their records
//! written in input order. Each ray's random choices (`-ab`, `-dj`) derive from its
//! index in the input, so the output is the same for any thread count and any order of
//! evaluation. The CLI's `radc trace` (and rtrace by its name) parse options and write
//! the header; everything from the first ray on is here.
//!
//! Ray text (`ray_text.rs`) has fast exact paths for the usual shapes of numbers that
//! fall back on `lang::c_number`'s definitions, so the text is theirs bit for bit; lines of
//! ASCII spaces and numbers are read in place in the input's buffer. Each chunk is
//! formatted into its own reused byte buffer. In a scene whose nodes and surfaces exceed
//! 1 MiB a batch holds 2^18 rays and is traced in `RayOrder::sort`'s order. `-x` flushes
//! every `x` rays as rtrace does, so a program sending one ray at a time gets each answer.
//! A chunk makes each ray ready (direction normalized, slab values prepared: `Primary`,
//! `Tracer::radiance_prepared`) before it traces the ray ahead, so a ray's first divisions
//! overlap the previous ray.

mod encoding;
mod ray_text;
mod reader;
mod record;

use std::io::{BufRead, Write};

use rayon::prelude::*;

use crate::bvh::Prepared;
use crate::math::{Bounds, Vec3, normalize};
use crate::ray::Ray;
use crate::ray_order::{self, RayOrder};
use crate::{RayState, Scene, Tracer};

pub use encoding::{Output, RayEncoding};
pub use ray_text::{c_exp_into, spaced_number};
pub use reader::RayReader;
use record::{OutBuf, write_ray};

/// Rays read, then evaluated together (in parallel), between writes, in a scene that
/// fits in cache: few enough that the batch's rays and output stay in cache too.
const BATCH: usize = 4096;
/// The same in a scene traced in space order (`SORT_ABOVE_BYTES`): the more rays a
/// batch holds, the nearer neighbours in the order are (on `bench/`'s terrain, least
/// CPU time of three for 1,000,000 rays: 1.29 s in batches of 16,384, 0.98 s of
/// 65,536, 0.81 s of 262,144, 0.78 s of 1,048,576).
const SORTED_BATCH: usize = 1 << 18;

/// Batches of fewer rays are traced in input order.
const SORT_MIN: usize = 64;
/// Scenes whose nodes and surfaces take more bytes than this (a core's L2 cache here)
/// have their batches traced in space order; smaller ones stay in cache whatever the
/// order, and sorting would only cost time (about 1% of `bench/`'s room's).
const SORT_ABOVE_BYTES: usize = 1 << 20;
const _: () = assert!(BATCH <= ray_order::MAX_RAYS && SORTED_BATCH <= ray_order::MAX_RAYS);

/// Rays one parallel task evaluates and formats.
const CHUNK: usize = 128;

/// What a trace run reads and writes beyond the rendering options.
#[derive(Clone, Debug)]
pub struct TraceSpec {
    /// `-o`: what each record holds.
    pub outputs: Vec<Output>,
    /// `-f`: how rays are read and values written.
    pub input: RayEncoding,
    pub output: RayEncoding,
    /// `-I`: irradiance at each ray's origin, facing its direction, instead of radiance.
    pub irradiance: bool,
    /// `-ld`: the length of each ray's direction limits how far it goes.
    pub limit_distance: bool,
    /// `-x`, `-y`: with `-y`, the number of rays to read; with `-x`, how often to flush.
    pub x_res: u32,
    pub y_res: u32,
}

impl TraceSpec {
    /// Values in each record (rtrace's `NCOMP`).
    pub fn components(&self) -> usize {
        self.outputs.iter().map(|o| o.components()).sum()
    }
}

/// Reads rays from `input` until it ends (or `-y`'s count is reached), traces them in
/// the tracer's scene and writes their records to `out`, flushing as rtrace does (every `-x` rays
/// when `-y` is 0 or `-x` is 1, and at each zero-direction ray). The error is the
/// final flush's: a closed output.
pub fn trace_stream(
    tracer: &Tracer<'_>,
    a: &TraceSpec,
    input: impl BufRead,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let scene = tracer.scene();
    // With -y, rtrace stops after a picture's worth of rays.
    let mut remaining: Option<u64> = match (a.x_res, a.y_res) {
        (_, 0) => None,
        (x, y) if x > 1 => Some(u64::from(x) * u64::from(y)),
        (_, y) => Some(u64::from(y)),
    };
    // rtrace flushes its output every -x rays when -y is 0 or -x is 1: how a program
    // that sends rays one at a time gets each answer back before sending the next.
    let flush_every = (a.x_res > 0 && (a.y_res == 0 || a.x_res == 1)).then_some(a.x_res as usize);
    let mut until_flush = flush_every;
    if flush_every.is_some() {
        let _ = out.flush();
    }
    let mut input = RayReader::new(input, a.input);
    let mut work = Work {
        space: scene
            .bvh
            .extent()
            .filter(|_| scene.traversal_bytes() > SORT_ABOVE_BYTES),
        ..Work::default()
    };
    let batch = if work.space.is_some() {
        SORTED_BATCH
    } else {
        BATCH
    };
    let mut rays = Vec::with_capacity(batch);
    let mut last = (Vec3::ZERO, Vec3::ZERO);
    let mut index = 0u64;
    loop {
        let want = remaining
            .map_or(batch, |n| (n as usize).min(batch))
            .min(until_flush.unwrap_or(batch));
        if want == 0 {
            break;
        }
        let (flush, mut done) = input.batch(want, &mut rays);
        if let Some(n) = remaining.as_mut() {
            *n -= (rays.len() + usize::from(flush)) as u64;
            done |= *n == 0;
        }
        if let Some(l) = work.run(&rays, index, tracer, scene, a, out) {
            last = l;
        }
        index += (rays.len() + usize::from(flush)) as u64;
        if let Some(n) = until_flush.as_mut() {
            *n -= rays.len();
            if *n == 0 {
                let _ = out.flush();
                until_flush = flush_every;
            }
        }
        if flush {
            // A zero direction: an empty record, then flush (rtrace's `bogusray`).
            let mut bogus = RayState::primary(last.0, last.1);
            bogus.normal = -last.1;
            let text = &mut work.chunks[0].text;
            text.clear();
            write_ray(text, &bogus, scene, a);
            let _ = out.write_all(text.bytes());
            let _ = out.flush();
            until_flush = flush_every;
        }
        if done {
            break;
        }
    }
    out.flush()
}

/// What evaluating a batch of rays uses, kept from batch to batch.
#[derive(Default)]
struct Work {
    /// One per parallel task; at least one after a batch (the flush record's).
    chunks: Vec<Chunk>,
    /// The scene's box, when batches are traced in space order (`SORT_ABOVE_BYTES`).
    space: Option<Bounds>,
    /// The batch's indices in the order traced.
    order: RayOrder,
    /// The rays in that order, each with its index.
    queue: Vec<(u32, (Vec3, Vec3))>,
    /// Per ray in input order: its chunk and the range of its record there.
    places: Vec<(u32, u32, u32)>,
}

impl Work {
    /// Evaluates `rays` (numbered from `index` in the input) in chunks in parallel,
    /// each chunk formatting into its own buffer, and writes the records in input
    /// order. Each ray's random choices derive from its index in the input, so the
    /// output is the same for any thread count and any order of evaluation. Returns
    /// the last ray's origin and direction (normalized), if any.
    fn run(
        &mut self,
        rays: &[(Vec3, Vec3)],
        index: u64,
        tracer: &Tracer<'_>,
        scene: &Scene,
        a: &TraceSpec,
        out: &mut impl Write,
    ) -> Option<(Vec3, Vec3)> {
        let used = rays.len().div_ceil(CHUNK);
        if self.chunks.len() < used.max(1) {
            self.chunks.resize_with(used.max(1), Chunk::default);
        }
        let extent = self.space.filter(|_| rays.len() >= SORT_MIN);
        let last = rays.len().wrapping_sub(1) as u32;
        let order = match extent {
            Some(extent) => {
                let order = self.order.sort(rays, extent);
                // The rays in the order traced: one pass whose cache misses overlap,
                // rather than one miss per ray in the middle of tracing it.
                self.queue.clear();
                self.queue
                    .extend(order.iter().map(|&i| (i, rays[i as usize])));
                self.queue
                    .par_chunks(CHUNK)
                    .zip(self.chunks.par_iter_mut())
                    .for_each(|(queue, chunk)| {
                        chunk.trace(queue.iter().copied(), last, index, tracer, scene, a);
                    });
                order
            }
            None => {
                rays.par_chunks(CHUNK)
                    .zip(self.chunks.par_iter_mut())
                    .enumerate()
                    .for_each(|(c, (rays, chunk))| {
                        let first = (c * CHUNK) as u32;
                        let rays = (first..).zip(rays.iter().copied());
                        chunk.trace(rays, last, index, tracer, scene, a);
                    });
                &[]
            }
        };
        let chunks = &self.chunks[..used];
        if extent.is_some() {
            // Each ray's record, found through where its chunk put it, in input order.
            self.places.resize(rays.len(), (0, 0, 0));
            for (c, chunk) in chunks.iter().enumerate() {
                let mut start = 0;
                for (k, &end) in chunk.ends.iter().enumerate() {
                    self.places[order[c * CHUNK + k] as usize] = (c as u32, start, end);
                    start = end;
                }
            }
            for &(c, start, end) in &self.places[..rays.len()] {
                let text = chunks[c as usize].text.bytes();
                let _ = out.write_all(&text[start as usize..end as usize]);
            }
        } else {
            for chunk in chunks {
                let _ = out.write_all(chunk.text.bytes());
            }
        }
        chunks.iter().find_map(|c| c.last)
    }
}

/// Rays evaluated and formatted by one task, and the last one's origin and direction.
#[derive(Default)]
struct Chunk {
    text: OutBuf,
    /// Where each ray's record ends in `text`.
    ends: Vec<u32>,
    /// The origin and direction of the batch's last ray, if this chunk traced it.
    last: Option<(Vec3, Vec3)>,
}

impl Chunk {
    /// Evaluates and formats `rays` (each with its index in the batch, which begins
    /// at `index` in the input), noting the origin and direction of the batch's ray
    /// `last` if it is among them.
    fn trace(
        &mut self,
        rays: impl Iterator<Item = (u32, (Vec3, Vec3))>,
        last: u32,
        index: u64,
        tracer: &Tracer<'_>,
        scene: &Scene,
        a: &TraceSpec,
    ) {
        self.text.clear();
        self.ends.clear();
        self.last = None;
        // Each ray is made ready (its direction normalized, its slab values computed)
        // before the one ahead of it is traced: the square root and divisions that
        // start a ray then overlap the previous ray's work instead of stalling it.
        let mut rays = rays.map(|(i, (org, dir))| (i, Primary::new(org, dir, a)));
        let mut next = rays.next();
        while let Some((i, ray)) = next {
            next = rays.next();
            let r = ray.evaluate(tracer, a, index + u64::from(i));
            write_ray(&mut self.text, &r, scene, a);
            self.ends.push(self.text.bytes().len() as u32);
            if i == last {
                self.last = Some((r.org, r.dir));
            }
        }
    }
}

/// An input ray made ready to trace: its direction normalized, with the length it had
/// (`-ld`), and its slab values ([`Prepared`]) unless `-I` makes it no ray.
struct Primary {
    org: Vec3,
    dir: Vec3,
    length: f64,
    prepared: Option<Prepared>,
}

impl Primary {
    #[inline(always)]
    fn new(org: Vec3, mut dir: Vec3, a: &TraceSpec) -> Primary {
        let length = normalize(&mut dir);
        let prepared = (!a.irradiance).then(|| Prepared::of(&Ray::new(org, dir)));
        Primary {
            org,
            dir,
            length,
            prepared,
        }
    }

    #[inline(always)]
    fn evaluate(&self, tracer: &Tracer<'_>, a: &TraceSpec, index: u64) -> RayState {
        let (org, dir) = (self.org, self.dir);
        match &self.prepared {
            Some(prepared) => {
                // -ld: the direction's length is how far the ray may go.
                let max = if a.limit_distance { self.length } else { 0.0 };
                tracer.radiance_prepared(org, dir, max, index, prepared)
            }
            None => tracer.irradiance_seeded(org, dir, index),
        }
    }
}
