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
use radc_renderer::math::{Vec3, normalize};
use radc_renderer::{Options, RayState, Scene, Target, Tracer, picture};
use rayon::prelude::*;

use super::USAGE_ERROR;
use super::ray_text::{c_exp_into, is_space, radiance_number};
use super::report::{self, Sources};

const USAGE: &str = "usage: radc trace [-h] [-I] [-o spec] [-f{a|f|d}{a|f|d}] [-ab N] [-ad N] [-as N] [-av r g b] \
[-ds f] [-dj f] [-dx+] [-lr n] [-lw f] [-st f] [-bv] scene.rad...";

/// Rays evaluated together (in parallel) between writes.
const BATCH: usize = 4096;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Format {
    Ascii,
    Float,
    Double,
    /// Output only: RGBE pixels (`-fac`, `-ffc`), with `-x -y` a picture.
    Color,
}

impl Format {
    fn from_char(c: char) -> Option<Format> {
        match c {
            'a' => Some(Format::Ascii),
            'f' => Some(Format::Float),
            'd' => Some(Format::Double),
            'c' => Some(Format::Color),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Format::Ascii => "ascii",
            Format::Float => "float",
            Format::Double => "double",
            Format::Color => "32-bit_rle_rgbe",
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
    input: Format,
    output: Format,
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
        input: Format::Ascii,
        output: Format::Ascii,
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
                a.input = Format::from_char(i).ok_or_else(|| format!("bad input format '{i}'"))?;
                a.output =
                    Format::from_char(o).ok_or_else(|| format!("bad output format '{o}'"))?;
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
    let tracer = Tracer::new(&scene, a.options.clone());
    let stdin = std::io::stdin();
    let mut input = RayReader::new(BufReader::new(stdin.lock()), a.input);
    let mut last = (Vec3::ZERO, Vec3::ZERO);
    let mut index = 0u64;
    loop {
        let want = remaining.map_or(BATCH, |n| (n as usize).min(BATCH));
        if want == 0 {
            break;
        }
        let (batch, flush, mut done) = input.batch(want);
        if let Some(n) = remaining.as_mut() {
            *n -= (batch.len() + usize::from(flush)) as u64;
            done |= *n == 0;
        }
        // Each ray's random choices derive from its index in the input.
        let results: Vec<RayState> = batch
            .par_iter()
            .enumerate()
            .map(|(k, &(org, dir))| evaluate(&tracer, org, dir, &a, index + k as u64))
            .collect();
        index += (batch.len() + usize::from(flush)) as u64;
        for r in &results {
            write_ray(&mut out, r, &scene, &a);
            last = (r.org, r.dir);
        }
        if flush {
            // A zero direction: an empty record, then flush (rtrace's `bogusray`).
            let mut bogus = RayState::primary(last.0, last.1);
            bogus.normal = -last.1;
            write_ray(&mut out, &bogus, &scene, &a);
            let _ = out.flush();
        }
        if done {
            break;
        }
    }
    if out.flush().is_err() {
        return ExitCode::from(1);
    }
    ExitCode::SUCCESS
}

fn evaluate(tracer: &Tracer<'_>, org: Vec3, mut dir: Vec3, a: &Args, index: u64) -> RayState {
    let length = normalize(&mut dir);
    if a.irradiance {
        tracer.irradiance_seeded(org, dir, index)
    } else {
        // -ld: the direction's length is how far the ray may go.
        let max = if a.limit_distance { length } else { 0.0 };
        tracer.radiance_seeded(org, dir, max, index)
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
    format: Format,
    line: Vec<u8>,
    /// The numbers of the current line (a NaN marks a word that is not one) and the
    /// next to return.
    words: Vec<f64>,
    at: usize,
    eof: bool,
}

impl<R: BufRead> RayReader<R> {
    fn new(input: R, format: Format) -> Self {
        RayReader {
            input,
            format,
            line: Vec::new(),
            words: Vec::new(),
            at: 0,
            eof: false,
        }
    }

    /// Up to `n` rays; stops early after a zero-direction ray (a flush request, not
    /// returned) or at the end of input (or at a word that is not a number).
    fn batch(&mut self, n: usize) -> (Vec<(Vec3, Vec3)>, bool, bool) {
        let mut out = Vec::new();
        while out.len() < n {
            let Some(v) = self.next_six() else {
                return (out, false, true);
            };
            let org = Vec3::new(v[0], v[1], v[2]);
            let dir = Vec3::new(v[3], v[4], v[5]);
            if dir == Vec3::ZERO {
                return (out, true, false);
            }
            out.push((org, dir));
        }
        (out, false, false)
    }

    fn next_six(&mut self) -> Option<[f64; 6]> {
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
            Format::Color => None,
            Format::Ascii => self.next_word(),
            Format::Float => {
                let mut b = [0u8; 4];
                self.input
                    .read_exact(&mut b)
                    .ok()
                    .map(|_| f64::from(f32::from_ne_bytes(b)))
            }
            Format::Double => {
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
        while self.at == self.words.len() {
            self.line.clear();
            self.words.clear();
            self.at = 0;
            if self.input.read_until(b'\n', &mut self.line).ok()? == 0 {
                return None;
            }
            if self.line.is_ascii() {
                for w in self.line.split(|&b| is_space(b)).filter(|w| !w.is_empty()) {
                    // rtrace stops at the first word that is not a number.
                    let Some(x) = radiance_number(w) else {
                        self.words.push(f64::NAN);
                        break;
                    };
                    self.words.push(x);
                }
            } else {
                // Unicode spaces separate words too; a line that is not UTF-8 ends the
                // input.
                let line = std::str::from_utf8(&self.line).ok()?;
                for w in line.split_whitespace() {
                    let Some(x) = radiance_number(w.as_bytes()) else {
                        self.words.push(f64::NAN);
                        break;
                    };
                    self.words.push(x);
                }
            }
        }
        let x = self.words[self.at];
        self.at += 1;
        (!x.is_nan()).then_some(x)
    }
}

fn write_ray(out: &mut impl Write, r: &RayState, scene: &Scene, a: &Args) {
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
                let name = names(r, scene, *o);
                let _ = write!(out, "{name}\t");
            }
            Output::Tilde => {
                let _ = write!(out, "~\t");
            }
            Output::Weight => put(out, a.output, &[r.weight]),
            // Local (u, v) coordinates: zero for every surface but meshes in Radiance.
            Output::LocalCoordinates => put(out, a.output, &[0.0, 0.0]),
        }
    }
    if a.output == Format::Ascii {
        let _ = writeln!(out);
    }
}

fn names(r: &RayState, scene: &Scene, o: Output) -> String {
    let (name, modifier, material) = match r.hit {
        Target::None => return "*".into(),
        Target::Object(id) => match scene.object(id.0) {
            Some(x) => (&x.name, &x.modifier_name, &x.material_name),
            None => return "*".into(),
        },
        Target::Distant(i) => match scene.distant.get(i as usize) {
            Some(x) => (&x.name, &x.modifier_name, &x.material_name),
            None => return "*".into(),
        },
    };
    match o {
        Output::Surface => name.clone(),
        Output::Modifier => modifier.clone(),
        _ => material.clone(),
    }
}

fn put(out: &mut impl Write, f: Format, v: &[f64]) {
    let _ = match f {
        Format::Ascii => v.iter().try_for_each(|x| {
            let mut buf = [0u8; 40];
            let n = c_exp_into(*x, &mut buf);
            buf[n] = b'\t';
            out.write_all(&buf[..=n])
        }),
        Format::Float => v
            .iter()
            .try_for_each(|x| out.write_all(&(*x as f32).to_ne_bytes())),
        Format::Double => v.iter().try_for_each(|x| out.write_all(&x.to_ne_bytes())),
        Format::Color => match v {
            [r, g, b] => out.write_all(&picture::rgbe(Vec3::new(*r, *g, *b))),
            _ => Ok(()),
        },
    };
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
}
