//! `radc trace`: rtrace for scene files. Reads rays `ox oy oz dx dy dz` from stdin and
//! writes what `-o` asks for, in rtrace's formats (`%e` and a tab after each number,
//! one ray per line; or binary `-ff`/`-fd`). Takes rtrace's options; the ones radc does
//! not model yet are refused rather than silently ignored.
//!
//! Evaluation follows rtrace with every shadow tested (`-dt 0`) and no irradiance cache
//! (`-aa 0`: ambient values from `-ab` are always computed); light relayed by mirrors
//! (`-dr`) is included. Each input ray's random choices (`-ab`, `-dj`) derive from its
//! line number, so output repeats exactly for any thread count.

use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use radc_lang::Severity;
use radc_renderer::bvh::Prepared;
use radc_renderer::math::{Bounds, Vec3, normalize};
use radc_renderer::ray::Ray;
use radc_renderer::ray_order::{self, RayOrder};
use radc_renderer::{Options, RayState, Scene, Target, Tracer, picture};
use rayon::prelude::*;

use super::USAGE_ERROR;
use super::ray_text::{c_exp_into, spaced_number};
use super::report::{self, Sources};
use radc_lang::c_number::{is_c_space, real_prefix, real_word};

const USAGE: &str = "usage: radc trace [-h] [-I] [-o spec] [-f{a|f|d}{a|f|d}] [-ab N] [-ad N] [-as N] [-av r g b] \
[-ds f] [-dj f] [-dx+] [-lr n] [-lw f] [-st f] [-bv] scene.rad...";

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

/// How rays are read and values written (rtrace's `-f` letters: `-fad` reads text and
/// writes doubles).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum RayEncoding {
    Ascii,
    Float,
    Double,
    /// Output only: RGBE pixels (`-fac`, `-ffc`), with `-x -y` a picture.
    Color,
}

impl RayEncoding {
    fn from_char(c: char) -> Option<RayEncoding> {
        match c {
            'a' => Some(RayEncoding::Ascii),
            'f' => Some(RayEncoding::Float),
            'd' => Some(RayEncoding::Double),
            'c' => Some(RayEncoding::Color),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            RayEncoding::Ascii => "ascii",
            RayEncoding::Float => "float",
            RayEncoding::Double => "double",
            RayEncoding::Color => "32-bit_rle_rgbe",
        }
    }
}

/// One `-o` letter.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Output {
    Value,
    Origin,
    Direction,
    Point,
    Normal,
    SurfaceNormal,
    EffectiveLength,
    Length,
    Mirrored,
    MirroredLength,
    Unmirrored,
    UnmirroredLength,
    Surface,
    Modifier,
    Material,
    Tilde,
    Weight,
    LocalCoordinates,
}

impl Output {
    fn parse(spec: &str) -> Result<Vec<Output>, String> {
        if spec.is_empty() {
            return Err("empty output specification".into());
        }
        spec.chars()
            .map(|c| {
                Ok(match c {
                    'v' => Output::Value,
                    'o' => Output::Origin,
                    'd' => Output::Direction,
                    'p' => Output::Point,
                    'n' => Output::Normal,
                    'N' => Output::SurfaceNormal,
                    'l' => Output::EffectiveLength,
                    'L' => Output::Length,
                    'r' => Output::Mirrored,
                    'R' => Output::MirroredLength,
                    'x' => Output::Unmirrored,
                    'X' => Output::UnmirroredLength,
                    's' => Output::Surface,
                    'm' => Output::Modifier,
                    'M' => Output::Material,
                    '~' => Output::Tilde,
                    'w' => Output::Weight,
                    'c' => Output::LocalCoordinates,
                    _ => {
                        return Err(format!(
                            "output '{c}' is not supported (radc knows v o d p n N l L r R x X c w s m M ~)"
                        ));
                    }
                })
            })
            .collect()
    }

    fn components(self) -> usize {
        match self {
            Output::Value | Output::Origin | Output::Direction | Output::Point | Output::Normal => {
                3
            }
            Output::SurfaceNormal => 3,
            Output::Tilde => 0,
            Output::LocalCoordinates => 2,
            _ => 1,
        }
    }
}

#[derive(Debug)]
struct Args {
    header: bool,
    irradiance: bool,
    outputs: Vec<Output>,
    input: RayEncoding,
    output: RayEncoding,
    options: Options,
    scenes: Vec<PathBuf>,
    /// `-x`, `-y`: a resolution line after the header, and the number of rays to read.
    x_res: u32,
    y_res: u32,
    /// `-w`: report the scene's warnings (errors are always reported).
    warnings: bool,
    /// `-ld`: the length of each ray's direction limits how far it goes.
    limit_distance: bool,
}

/// Radiance's boolean switches: `-x` toggles, `-x+` sets, `-x-` clears.
pub(super) fn switch(arg: &str, name: &str, value: &mut bool) -> bool {
    match arg.strip_prefix(name) {
        Some("") => *value = !*value,
        Some("+") => *value = true,
        Some("-") => *value = false,
        _ => return false,
    }
    true
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        header: true,
        irradiance: false,
        outputs: vec![Output::Value],
        input: RayEncoding::Ascii,
        output: RayEncoding::Ascii,
        options: Options::default(),
        scenes: Vec::new(),
        x_res: 0,
        y_res: 0,
        warnings: true,
        limit_distance: false,
    };
    let mut it = args.iter().map(String::as_str).peekable();
    while let Some(arg) = it.next() {
        match arg {
            s if switch(s, "-h", &mut a.header) => {}
            s if switch(s, "-I", &mut a.irradiance) => {}
            s if switch(s, "-w", &mut a.warnings) => {}
            s if switch(s, "-ld", &mut a.limit_distance) => {}
            "-n" => {
                number(&mut it, arg)?;
            }
            "-x" | "-y" => {
                let v = number(&mut it, arg)?;
                let v = if (0.0..=f64::from(u32::MAX)).contains(&v) {
                    v as u32
                } else {
                    0
                };
                if arg == "-x" {
                    a.x_res = v;
                } else {
                    a.y_res = v;
                }
            }
            s if switch(s, "-i", &mut a.options.irradiance_at_hits) => {}
            s if render_option(s, &mut it, &mut a.options)? => {}
            s if s.starts_with("-o") => a.outputs = Output::parse(&s[2..])?,
            s if s.starts_with("-f") => {
                let f: Vec<char> = s[2..].chars().collect();
                let (i, o) = match f.as_slice() {
                    [c] => (*c, *c),
                    [i, o] => (*i, *o),
                    _ => return Err(format!("bad format '{s}'")),
                };
                a.input =
                    RayEncoding::from_char(i).ok_or_else(|| format!("bad input format '{i}'"))?;
                a.output =
                    RayEncoding::from_char(o).ok_or_else(|| format!("bad output format '{o}'"))?;
            }
            "-help" | "--help" => return Err(String::new()),
            s if s.starts_with('-') && s.len() > 1 => return Err(format!("unknown option '{s}'")),
            path => a.scenes.push(PathBuf::from(path)),
        }
    }
    if a.scenes.is_empty() {
        return Err("no scene files".into());
    }
    Ok(a)
}

/// Runs `f` in a rayon pool whose threads have room for long ray chains (mirrors,
/// stacks of pass-through surfaces: up to `MAX_CHAIN` nested evaluations).
pub(super) fn with_deep_stacks(f: impl FnOnce() -> ExitCode + Send) -> ExitCode {
    with_threads(0, f)
}

/// `with_deep_stacks` on `threads` threads (0: rayon's default, all cores unless
/// `RAYON_NUM_THREADS` says otherwise).
pub(super) fn with_threads(threads: usize, f: impl FnOnce() -> ExitCode + Send) -> ExitCode {
    match rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .stack_size(256 << 20)
        .build()
    {
        Ok(pool) => pool.install(f),
        Err(_) => f(),
    }
}

/// The next argument as a finite number.
pub(super) fn number<'a>(
    it: &mut impl Iterator<Item = &'a str>,
    what: &str,
) -> Result<f64, String> {
    let v = it.next().ok_or_else(|| format!("{what} needs a value"))?;
    v.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| format!("{what}: '{v}' is not a number"))
}

/// Rendering options shared with `radc render` (rpict's): true when `arg` was one.
pub(super) fn render_option<'a>(
    arg: &str,
    it: &mut impl Iterator<Item = &'a str>,
    o: &mut Options,
) -> Result<bool, String> {
    match arg {
        s if switch(s, "-bv", &mut o.backface_visible) => {}
        "-ab" => o.ambient_bounces = number(it, "-ab")?.clamp(0.0, 1e6) as u32,
        "-ad" => o.ambient_divisions = number(it, "-ad")?.clamp(0.0, 1e9) as u32,
        "-as" => o.ambient_supersamples = number(it, "-as")?.clamp(0.0, 1e9) as u32,
        "-av" => o.ambient = Vec3::new(number(it, "-av")?, number(it, "-av")?, number(it, "-av")?),
        "-ds" => o.source_size_ratio = number(it, "-ds")?,
        "-dj" => o.source_jitter = number(it, "-dj")?.clamp(0.0, 1.0),
        "-lr" => o.max_depth = number(it, "-lr")? as i32,
        "-lw" => o.min_weight = number(it, "-lw")?,
        "-st" => o.specular_threshold = number(it, "-st")?,
        // Accepted for compatibility: radc tests every shadow (-dt 0), always follows
        // relayed paths (-dp), and the rest only matter for indirect light.
        "-dr" => o.relays = number(it, "-dr")?.max(0.0) as u32,
        "-me" => {
            o.medium = Vec3::new(number(it, "-me")?, number(it, "-me")?, number(it, "-me")?)
                .max(Vec3::ZERO)
        }
        "-ma" => {
            let albedo = [number(it, "-ma")?, number(it, "-ma")?, number(it, "-ma")?];
            if albedo.iter().any(|a| *a > 0.0) {
                return Err("a scattering medium (-ma > 0) is not implemented yet; -me is".into());
            }
        }
        "-mg" | "-ms" => {
            number(it, arg)?;
        }
        // The irradiance cache's options: radc does not cache (every ambient value is
        // computed, Radiance's -aa 0), so they change nothing.
        "-dt" | "-dc" | "-dp" | "-ss" | "-aa" | "-ar" | "-aw" => {
            number(it, arg)?;
        }
        "-ai" | "-ae" | "-aI" | "-aE" | "-af" => {
            it.next().ok_or_else(|| format!("{arg} needs a value"))?;
        }
        s if switch(s, "-dv", &mut o.direct_visible) => {}
        s if switch(s, "-dx", &mut o.exact_sources) => {}
        s if s.starts_with("-u") => {}
        _ => return Ok(false),
    }
    o.russian_roulette = o.samples_randomly();
    Ok(true)
}

pub fn run(args: &[String]) -> ExitCode {
    with_threads(thread_count(args), || run_parsed(args))
}

/// rtrace's `-n N` (processes): here, the number of threads (the last `-n` given; a
/// bad value is reported by the option parser).
pub(super) fn thread_count(args: &[String]) -> usize {
    let at = args.iter().rposition(|a| a == "-n");
    at.and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|n| (1.0..=1024.0).contains(n))
        .map_or(0, |n| n as usize)
}

fn run_parsed(args: &[String]) -> ExitCode {
    let a = match parse_args(args) {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("radc trace: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    let mut scene = match load_scene(&a.scenes, "trace", a.warnings) {
        Ok(s) => s,
        Err(code) => return code,
    };
    scene.add_virtual_sources(a.options.relays);
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    if a.header {
        let ncomp: usize = a.outputs.iter().map(|o| o.components()).sum();
        let _ = write!(
            out,
            "#?RADIANCE\nradc trace {}\nSOFTWARE= radc {}\nNCOMP={ncomp}\nFORMAT={}\n\n",
            args.join(" "),
            env!("CARGO_PKG_VERSION"),
            a.output.name()
        );
    }
    if a.x_res > 0 && a.y_res > 0 {
        let _ = writeln!(out, "-Y {} +X {}", a.y_res, a.x_res);
    }
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
    let tracer = Tracer::new(&scene, a.options.clone());
    let stdin = std::io::stdin();
    let mut input = RayReader::new(BufReader::with_capacity(1 << 16, stdin.lock()), a.input);
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
        if let Some(l) = work.run(&rays, index, &tracer, &scene, &a, &mut out) {
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
            write_ray(text, &bogus, &scene, &a);
            let _ = out.write_all(text.bytes());
            let _ = out.flush();
            until_flush = flush_every;
        }
        if done {
            break;
        }
    }
    if out.flush().is_err() {
        return ExitCode::from(1);
    }
    report_functions(&scene, "trace")
}

/// Prints what evaluating the scene's functions warned of (once each), as rtrace
/// prints them; an evaluation that failed outright (Radiance stops there) makes the
/// exit status 1.
pub(super) fn report_functions(scene: &Scene, command: &str) -> ExitCode {
    let Some(functions) = scene.functions.as_deref() else {
        return ExitCode::SUCCESS;
    };
    let (messages, failed) = functions.take_messages();
    for m in messages {
        errln!("radc {command}: {m}");
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
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
        a: &Args,
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
        a: &Args,
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
            self.ends.push(self.text.len as u32);
            if i == last {
                self.last = Some((r.org, r.dir));
            }
        }
    }
}

/// Output bytes: a zero-filled buffer and how much of it is used, so a record is
/// formatted in place, with neither zeroing nor a copy per number.
#[derive(Default)]
struct OutBuf {
    buf: Vec<u8>,
    len: usize,
}

impl OutBuf {
    fn clear(&mut self) {
        self.len = 0;
    }

    fn bytes(&self) -> &[u8] {
        &self.buf[..self.len]
    }

    /// Room for `n` more bytes (at least), from the end of what is used.
    fn room(&mut self, n: usize) -> &mut [u8] {
        if self.len + n > self.buf.len() {
            let size = (self.len + n).max(2 * self.buf.len()).max(4096);
            self.buf.resize(size, 0);
        }
        &mut self.buf[self.len..]
    }

    fn push(&mut self, bytes: &[u8]) {
        let n = bytes.len();
        self.room(n)[..n].copy_from_slice(bytes);
        self.len += n;
    }

    fn push_byte(&mut self, b: u8) {
        self.room(1)[0] = b;
        self.len += 1;
    }

    /// Each of `v` in C's `%e` and a tab.
    fn push_numbers(&mut self, v: &[f64]) {
        let room = self.room(17 * v.len());
        let mut at = 0;
        for x in v {
            if let Ok(text) = <&mut [u8; 16]>::try_from(&mut room[at..at + 16]) {
                let n = c_exp_into(*x, text);
                text[n] = b'\t';
                at += n + 1;
            }
        }
        self.len += at;
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
    fn new(org: Vec3, mut dir: Vec3, a: &Args) -> Primary {
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
    fn evaluate(&self, tracer: &Tracer<'_>, a: &Args, index: u64) -> RayState {
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

/// Reads the scene files as one scene, reports their diagnostics on stderr (warnings
/// only if asked), and compiles it; scenes with errors, or with things radc cannot
/// render, are refused. A compiled scene (`radc build`) is loaded instead.
pub(super) fn load_scene(
    paths: &[PathBuf],
    command: &str,
    warnings: bool,
) -> Result<Scene, ExitCode> {
    if let Some(compiled) = super::build::load_compiled(paths, command) {
        return compiled;
    }
    let mut sources = Sources::default();
    let mut diags = Vec::new();
    let ir = super::check::check_scene(
        paths,
        false,
        radc_lang::scene::Keep::Everything,
        &mut sources,
        &mut diags,
    );
    diags.sort_by_key(|d| (d.span.file, d.span.start));
    // A `!` command's output is part of the scene Radiance renders; without it the
    // numbers would be silently wrong.
    let unexpanded = diags
        .iter()
        .filter(|d| d.code.id == radc_lang::diagnostic::W0303.id)
        .count();
    if !warnings {
        diags.retain(|d| {
            d.severity == Severity::Error || d.code.id == radc_lang::diagnostic::W0303.id
        });
    }
    report::eprint(&diags, &sources);
    if diags.iter().any(|d| d.severity == Severity::Error) {
        errln!("radc {command}: the scene has errors; nothing rendered");
        return Err(ExitCode::from(1));
    }
    if unexpanded > 0 {
        errln!(
            "radc {command}: the scene has {unexpanded} '!' command line(s) radc does not run, so \
             it would render without what they make; run them and include their output"
        );
        return Err(ExitCode::from(1));
    }
    Scene::compile(&ir).map_err(|problems| {
        for p in problems {
            let place = ir
                .get(p.prim)
                .and_then(|prim| {
                    let s = sources.get(prim.span.file)?;
                    let (line, col) = s.lines().line_col(&s.text, prim.span.start as usize);
                    Some(format!("{}:{line}:{col}: ", s.name))
                })
                .unwrap_or_default();
            errln!("radc {command}: {place}cannot render {p}");
        }
        ExitCode::from(1)
    })
}

/// Rays from stdin in rtrace's input formats.
struct RayReader<R> {
    input: R,
    format: RayEncoding,
    /// Lines are scanned in the input's buffer where they can be (`scan_line`); the
    /// others are copied here and split (`read_line`).
    fast: bool,
    line: Vec<u8>,
    /// The numbers of the current line and the next to return; `stop`: after them
    /// comes a word that is not a number, which ends the input.
    words: Vec<f64>,
    at: usize,
    stop: bool,
    eof: bool,
}

impl<R: BufRead> RayReader<R> {
    fn new(input: R, format: RayEncoding) -> Self {
        RayReader {
            input,
            format,
            fast: true,
            line: Vec::new(),
            words: Vec::new(),
            at: 0,
            stop: false,
            eof: false,
        }
    }

    /// Up to `n` rays into `out` (cleared first). Returns whether it stopped early
    /// after a zero-direction ray (a flush request, not returned) and whether the
    /// input ended (or came to a word that is not a number).
    fn batch(&mut self, n: usize, out: &mut Vec<(Vec3, Vec3)>) -> (bool, bool) {
        out.clear();
        while out.len() < n {
            let Some(v) = self.next_six() else {
                return (false, true);
            };
            let org = Vec3::new(v[0], v[1], v[2]);
            let dir = Vec3::new(v[3], v[4], v[5]);
            if dir == Vec3::ZERO {
                return (true, false);
            }
            out.push((org, dir));
        }
        (false, false)
    }

    fn next_six(&mut self) -> Option<[f64; 6]> {
        if self.format == RayEncoding::Ascii && !self.eof {
            // Six numbers of the current line at once (the usual case: one ray a line).
            if self.at == self.words.len() {
                self.next_line()?;
            }
            if let Some(w) = self.words.get(self.at..self.at + 6)
                && !(self.stop && self.at + 6 == self.words.len())
            {
                let mut v = [0.0; 6];
                v.copy_from_slice(w);
                self.at += 6;
                return Some(v);
            }
        }
        let mut v = [0.0; 6];
        for x in &mut v {
            *x = self.next_number()?;
        }
        Some(v)
    }

    fn next_number(&mut self) -> Option<f64> {
        if self.eof {
            return None;
        }
        let r = match self.format {
            // Refused by the option parser: nothing to read.
            RayEncoding::Color => None,
            RayEncoding::Ascii => self.next_word(),
            RayEncoding::Float => {
                let mut b = [0u8; 4];
                self.input
                    .read_exact(&mut b)
                    .ok()
                    .map(|_| f64::from(f32::from_ne_bytes(b)))
            }
            RayEncoding::Double => {
                let mut b = [0u8; 8];
                self.input
                    .read_exact(&mut b)
                    .ok()
                    .map(|_| f64::from_ne_bytes(b))
            }
        };
        if r.is_none() {
            self.eof = true;
        }
        r
    }

    fn next_word(&mut self) -> Option<f64> {
        if self.at == self.words.len() {
            self.next_line()?;
        }
        let x = self.words[self.at];
        self.at += 1;
        (!(self.stop && self.at == self.words.len())).then_some(x)
    }

    /// Reads lines until one has a word; `None` at the end of the input (sets `eof`).
    #[inline(always)]
    fn next_line(&mut self) -> Option<()> {
        while self.at == self.words.len() {
            if self.stop {
                self.eof = true;
                return None;
            }
            self.words.clear();
            self.at = 0;
            if !(self.fast && self.scan_line()) && self.read_line().is_none() {
                self.eof = true;
                return None;
            }
        }
        Some(())
    }

    /// The next line's numbers, read in place in the input's buffer, when the whole
    /// line is there and is nothing but ASCII spaces and numbers (so splitting it would
    /// find the same words); false leaves the line to `read_line`.
    fn scan_line(&mut self) -> bool {
        let Ok(buf) = self.input.fill_buf() else {
            return false;
        };
        let mut at = 0;
        while let Some(&b) = buf.get(at) {
            if b == b'\n' {
                self.input.consume(at + 1);
                return true;
            }
            if is_c_space(b) {
                at += 1;
                continue;
            }
            let word = &buf[at..];
            let number = spaced_number(word).or_else(|| {
                real_prefix(word).filter(|&(_, n)| word.get(n).is_some_and(|&b| is_c_space(b)))
            });
            let Some((x, n)) = number else {
                break;
            };
            self.words.push(x);
            // A space follows the number: the line's end, or skipped.
            if word[n] == b'\n' {
                self.input.consume(at + n + 1);
                return true;
            }
            at += n + 1;
        }
        self.words.clear();
        false
    }

    /// The next line, copied and split into words, as rtrace reads it; `None` at the
    /// end of the input or at a line that is not UTF-8.
    #[cold]
    #[inline(never)]
    fn read_line(&mut self) -> Option<()> {
        self.line.clear();
        if self.input.read_until(b'\n', &mut self.line).ok()? == 0 {
            return None;
        }
        if self.line.is_ascii() {
            for w in self
                .line
                .split(|&b| is_c_space(b))
                .filter(|w| !w.is_empty())
            {
                // rtrace stops at the first word that is not a number.
                let Some(x) = real_word(w) else {
                    self.words.push(f64::NAN);
                    self.stop = true;
                    break;
                };
                self.words.push(x);
            }
        } else {
            // Unicode spaces separate words too; a line that is not UTF-8 ends the
            // input.
            let line = std::str::from_utf8(&self.line).ok()?;
            for w in line.split_whitespace() {
                let Some(x) = real_word(w.as_bytes()) else {
                    self.words.push(f64::NAN);
                    self.stop = true;
                    break;
                };
                self.words.push(x);
            }
        }
        Some(())
    }
}

fn write_ray(out: &mut OutBuf, r: &RayState, scene: &Scene, a: &Args) {
    // The usual record (`-ov`, text) without the general loop.
    if a.output == RayEncoding::Ascii && a.outputs == [Output::Value] {
        out.push_numbers(&r.color.to_array());
        out.push_byte(b'\n');
        return;
    }
    let no_hit = matches!(r.hit, Target::None);
    for o in &a.outputs {
        match o {
            Output::Value => put(out, a.output, &r.color.to_array()),
            Output::Origin => put(out, a.output, &r.org.to_array()),
            Output::Direction => put(out, a.output, &r.dir.to_array()),
            Output::Point => put(out, a.output, &r.point.to_array()),
            Output::Normal => put(
                out,
                a.output,
                &if no_hit {
                    [0.0; 3]
                } else {
                    r.normal.to_array()
                },
            ),
            Output::SurfaceNormal => put(
                out,
                a.output,
                &if no_hit {
                    [0.0; 3]
                } else {
                    r.surface_normal().to_array()
                },
            ),
            Output::EffectiveLength => put(out, a.output, &[r.effective_length()]),
            Output::Length => put(out, a.output, &[r.length]),
            Output::Mirrored => put(out, a.output, &r.mirror_color.to_array()),
            Output::MirroredLength => put(out, a.output, &[r.mirror_length]),
            Output::Unmirrored => put(out, a.output, &(r.color - r.mirror_color).to_array()),
            Output::UnmirroredLength => put(out, a.output, &[r.other_length]),
            Output::Surface | Output::Modifier | Output::Material => {
                out.push(names(r, scene, *o).as_bytes());
                out.push(b"\t");
            }
            Output::Tilde => out.push(b"~\t"),
            Output::Weight => put(out, a.output, &[r.weight]),
            // Local (u, v) coordinates: zero for every surface but meshes in Radiance.
            Output::LocalCoordinates => put(out, a.output, &[0.0, 0.0]),
        }
    }
    if a.output == RayEncoding::Ascii {
        out.push_byte(b'\n');
    }
}

fn names<'s>(r: &RayState, scene: &'s Scene, o: Output) -> &'s str {
    let (name, modifier, material) = match r.hit {
        Target::None => return "*",
        Target::Object(id) => match scene.object(id.0) {
            Some(x) => (&x.name, &x.modifier_name, &x.material_name),
            None => return "*",
        },
        Target::Distant(i) => match scene.distant.get(i as usize) {
            Some(x) => (&x.name, &x.modifier_name, &x.material_name),
            None => return "*",
        },
    };
    match o {
        Output::Surface => name,
        Output::Modifier => modifier,
        _ => material,
    }
}

fn put(out: &mut OutBuf, f: RayEncoding, v: &[f64]) {
    match f {
        RayEncoding::Ascii => out.push_numbers(v),
        RayEncoding::Float => v.iter().for_each(|x| out.push(&(*x as f32).to_ne_bytes())),
        RayEncoding::Double => v.iter().for_each(|x| out.push(&x.to_ne_bytes())),
        RayEncoding::Color => {
            if let [r, g, b] = v {
                out.push(&picture::rgbe(Vec3::new(*r, *g, *b)));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switches_toggle() {
        let a = parse_args(&["-h".into(), "-I+".into(), "x.rad".into()]).unwrap();
        assert!(!a.header && a.irradiance);
        assert!(parse_args(&["-ab".into(), "x".into(), "x.rad".into()]).is_err());
    }

    /// Every batch a reader returns, until the input ends: rays as bits, then the flush
    /// and end flags.
    fn read_all(
        text: &[u8],
        capacity: usize,
        fast: bool,
        n: usize,
    ) -> Vec<(Vec<[u64; 6]>, bool, bool)> {
        let mut reader =
            RayReader::new(BufReader::with_capacity(capacity, text), RayEncoding::Ascii);
        reader.fast = fast;
        let mut rays = Vec::new();
        let mut batches = Vec::new();
        loop {
            let (flush, done) = reader.batch(n, &mut rays);
            let bits = rays
                .iter()
                .map(|(o, d)| {
                    let v = [o.x, o.y, o.z, d.x, d.y, d.z];
                    v.map(f64::to_bits)
                })
                .collect();
            batches.push((bits, flush, done));
            if done || batches.len() > 100_000 {
                return batches;
            }
        }
    }

    /// Reading lines in place in the input's buffer finds the same rays, flushes and
    /// end as copying and splitting every line, on random text with the usual numbers,
    /// odd ones, Unicode spaces, bytes that are not UTF-8, blank and long lines, words
    /// that are not numbers, and lines cut by the buffer's end (small buffers).
    #[test]
    fn lines_read_in_place_as_when_copied() {
        let tokens: [&[u8]; 24] = [
            b"10.925434",
            b"-0.46798942",
            b"0",
            b"-0",
            b"1",
            b"5.",
            b".5",
            b"-.25",
            b"+2",
            b"1e3",
            b"-2.5E-2",
            b"123456789012345678901234567890",
            b"0.1234567890123",
            b"12345678.5",
            b"0.000000001",
            b"1234567.12345678",
            b"9007199254740993",
            b"00000001.5",
            b"7",
            b"3.25",
            b"-1",
            b"0.5",
            b"2",
            b"-3",
        ];
        let spaces: [&[u8]; 9] = [
            b" ",
            b" ",
            b" ",
            b"\t",
            b"  ",
            b"\r",
            b"\x0b",
            b"\x0c",
            "\u{a0}".as_bytes(),
        ];
        let odd: [&[u8]; 7] = [
            b"abc",
            b"1.5x",
            b"\xff",
            "\u{2003}".as_bytes(),
            b"1e",
            b"-",
            "\u{e9}".as_bytes(),
        ];
        let mut seed = 0x5851_f42d_4c95_7f2du64;
        let mut next = |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        let mut compared = 0;
        for case in 0..300 {
            let mut text = Vec::new();
            for _ in 0..next(60) + 1 {
                match next(20) {
                    0 => {}
                    1 => text.extend_from_slice(b"1 2 3 0 0 0"),
                    2 => text.extend_from_slice(b"4 5 6 7 8"),
                    _ => {
                        for k in 0..6 {
                            if k > 0 || next(4) == 0 {
                                text.extend_from_slice(spaces[next(9) as usize]);
                            }
                            text.extend_from_slice(tokens[next(24) as usize]);
                        }
                    }
                }
                if next(8) == 0 {
                    text.extend_from_slice(spaces[next(9) as usize]);
                }
                if case % 3 == 0 && next(40) == 0 {
                    text.extend_from_slice(odd[next(7) as usize]);
                }
                text.push(b'\n');
            }
            if next(2) == 0 {
                text.pop();
            }
            for n in [1, 3, 4096] {
                let want = read_all(&text, 1 << 16, false, n);
                for capacity in [1, 7, 16, 64, 1 << 16] {
                    let got = read_all(&text, capacity, true, n);
                    assert_eq!(
                        got,
                        want,
                        "{:?} capacity {capacity} batch {n}",
                        String::from_utf8_lossy(&text)
                    );
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 300 * 3 * 5);
    }

    /// The fast path is the one the usual input takes.
    #[test]
    fn usual_lines_are_scanned_in_place() {
        let text =
            b"10.925434 13.039251 1.057157 -0.46798942 0.81813978 -0.33411556\n1 2 3 0 0 1\n";
        let mut reader = RayReader::new(BufReader::new(&text[..]), RayEncoding::Ascii);
        assert!(reader.scan_line());
        assert_eq!(reader.words.len(), 6);
        assert_eq!(reader.words[3], -0.46798942);
        reader.words.clear();
        assert!(reader.scan_line());
        assert_eq!(reader.words, [1.0, 2.0, 3.0, 0.0, 0.0, 1.0]);
        reader.words.clear();
        for text in [&b"1 2 abc\n"[..], b"1 2\xc2\xa0 3\n", b"1 2 3"] {
            let mut reader = RayReader::new(BufReader::new(text), RayEncoding::Ascii);
            assert!(!reader.scan_line(), "{text:?}");
            assert!(reader.words.is_empty());
        }
    }

    /// Records formatted in place: numbers, names and binary values, buffer growth.
    #[test]
    fn out_buf_grows_and_keeps_records() {
        let mut out = OutBuf::default();
        let mut want = Vec::new();
        for k in 0..2000 {
            let x = k as f64 * 0.37 - 100.0;
            out.push_numbers(&[x, 0.0, 1e300]);
            out.push(b"name\t");
            out.push_byte(b'\n');
            for v in [x, 0.0, 1e300] {
                let mut b = [0u8; 16];
                let n = c_exp_into(v, &mut b);
                want.extend_from_slice(&b[..n]);
                want.push(b'\t');
            }
            want.extend_from_slice(b"name\t\n");
        }
        assert_eq!(out.bytes(), &want[..]);
        out.clear();
        assert!(out.bytes().is_empty());
    }
}
