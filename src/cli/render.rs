//! `radc render`: rpict for scene files. Writes a Radiance picture (RGBE, new-style RLE)
//! to stdout or `-o file`, one ray through the centre of each pixel (rpict `-pj 0
//! -ps 1`), with rpict's view options and the lighting options of `radc trace`.
//! `-o x.png` writes a tone-mapped PNG (`radc_picture::tonemap`) instead; `-o` may be
//! given more than once. Given a Radiance picture instead of a scene, `-o x.png` makes
//! a PNG of that picture. `-e file` sends messages to a file, as rpict's does. On a
//! terminal, stderr shows the progress.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};

use radc_renderer::camera::View;
use radc_renderer::math::Color;
use radc_renderer::render::{inside_geometry, render_picture};
use radc_renderer::{Options, Tracer, picture};

use super::USAGE_ERROR;
use super::load::{load_scene, report_functions};
use super::options::{Query, Unmodelled, expand_option_files, number, render_option, version_line};

const USAGE: &str = "usage: radc render [-vf file] [-vt{v|l|h|a|c|s}] [-vp x y z] [-vd x y z] [-vu x y z] [-vh deg] \
[-vv deg] [-x res] [-y res] [-pa aspect] [-ab N] [-ad N] [-as N] [-av r g b] [-dj frac] [-dx+] [-e errfile] \
[-o picture.hdr|x.png]... scene.rad...|scene.rsc";

struct Args {
    view: View,
    x: u32,
    y: u32,
    pixel_aspect: f64,
    options: Options,
    /// `-o`: pictures to write, Radiance or (`.png`) tone-mapped; none: stdout.
    outputs: Vec<PathBuf>,
    /// `-e`: where messages go.
    errors: Option<PathBuf>,
    scenes: Vec<PathBuf>,
    warnings: bool,
    /// `--allow-commands`: run `!` lines other than the built-in generators.
    allow_commands: bool,
    /// Options given that radc does not honour, reported as warnings.
    unmodelled: Unmodelled,
    /// `-version` or `-defaults`: print instead of rendering.
    query: Option<Query>,
}

impl Args {
    fn load_options(&self) -> radc_loader::LoadOptions {
        radc_loader::LoadOptions {
            warnings: self.warnings,
            allow_commands: self.allow_commands,
        }
    }
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        view: View::default(),
        x: 512,
        y: 512,
        pixel_aspect: 1.0,
        // rpict's defaults differ from rtrace's here.
        options: Options {
            source_size_ratio: 0.25,
            max_depth: 7,
            relays: 1,
            ambient_divisions: 512,
            ambient_supersamples: 128,
            ..Options::default()
        },
        outputs: Vec::new(),
        errors: None,
        scenes: Vec::new(),
        warnings: true,
        allow_commands: false,
        unmodelled: Unmodelled::default(),
        query: None,
    };
    let words: Vec<&str> = args.iter().map(String::as_str).collect();
    let mut it = words.iter().copied().enumerate().peekable();
    while let Some((at, arg)) = it.next() {
        let used = a.view.option(&words[at..])?;
        if used > 0 {
            for _ in 1..used {
                it.next();
            }
            continue;
        }
        let mut it = std::iter::from_fn(|| it.next().map(|(_, w)| w));
        match arg {
            "-vf" => {
                super::options::view_file(&mut a.view, it.next().ok_or("-vf needs a file name")?)?;
            }
            "-x" | "-y" => {
                let v = number(&mut it, arg)?;
                if !(1.0..=32767.0).contains(&v) {
                    return Err(format!("{arg} must be between 1 and 32767"));
                }
                if arg == "-x" {
                    a.x = v as u32;
                } else {
                    a.y = v as u32;
                }
            }
            "-pa" => a.pixel_aspect = number(&mut it, arg)?,
            s if Query::of(s).is_some() => {
                a.query = Query::of(s);
                return Ok(a);
            }
            "-pj" => a.unmodelled.pixel_jitter(number(&mut it, arg)?),
            // Adaptive sampling (-ps spacing, -pt its tolerance): radc traces every
            // pixel, the limit -ps 1 reaches; -t is progress reporting; -n threads.
            "-ps" | "-pt" | "-t" | "-n" => {
                number(&mut it, arg)?;
            }
            // Motion blur and depth of field change the picture: refused until modelled.
            "-pm" | "-pd" => {
                if number(&mut it, arg)? > 0.0 {
                    let what = if arg == "-pm" {
                        "motion blur"
                    } else {
                        "depth of field"
                    };
                    return Err(format!("{arg}: {what} is not implemented (only {arg} 0)"));
                }
            }
            "-o" => a
                .outputs
                .push(PathBuf::from(it.next().ok_or("-o needs a file name")?)),
            "--allow-commands" => a.allow_commands = true,
            "-e" => a.errors = Some(PathBuf::from(it.next().ok_or("-e needs a file name")?)),
            s if super::options::switch(s, "-w", &mut a.warnings) => {}
            s if render_option(s, &mut it, &mut a.options, &mut a.unmodelled)? => {}
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

pub fn run(args: &[String]) -> ExitCode {
    let args = match expand_option_files(args) {
        Ok(args) => args,
        Err(e) => {
            eprintln!("radc render: {e}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    super::options::with_threads(super::options::thread_count(&args), || run_parsed(&args))
}

fn run_parsed(args: &[String]) -> ExitCode {
    let a = match parse_args(args) {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("radc render: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    match a.query {
        Some(Query::Version) => {
            println!("{}", version_line());
            return ExitCode::SUCCESS;
        }
        Some(Query::Defaults) => {
            let text =
                super::defaults::render(&a.view, a.x, a.y, a.pixel_aspect, a.warnings, &a.options);
            print!("{text}");
            return ExitCode::SUCCESS;
        }
        None => {}
    }
    if let Some(path) = &a.errors
        && let Err(e) = super::error_file::redirect(path)
    {
        eprintln!(
            "radc render: cannot open error file {}: {e}",
            path.display()
        );
        return ExitCode::from(USAGE_ERROR);
    }
    if a.warnings {
        for w in a.unmodelled.warnings(&a.options) {
            errln!("radc render: warning: {w}");
        }
    }
    if let Some(code) = picture_to_png(&a) {
        return code;
    }
    let camera = match a.view.camera() {
        Ok(c) => c,
        Err(e) => {
            errln!("radc render: {e}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    let mut scene = match load_scene(&a.scenes, "render", a.load_options()) {
        Ok(s) => s,
        Err(code) => return code,
    };
    scene.add_virtual_sources(a.options.relays);
    let (w, h) = camera.fit_resolution(a.x, a.y, a.pixel_aspect);
    if w == 0 || h == 0 {
        errln!(
            "radc render: -x {} -y {} with pixel aspect {} leaves a {w} by {h} picture",
            a.x,
            a.y,
            a.pixel_aspect
        );
        return ExitCode::from(USAGE_ERROR);
    }
    // The picture is held in memory: refuse sizes that cannot be.
    if u64::from(w) * u64::from(h) > 1 << 28 {
        errln!("radc render: a {w} by {h} picture is too large");
        return ExitCode::from(USAGE_ERROR);
    }
    let tracer = Tracer::new(&scene, a.options.clone());
    if a.warnings
        && let Some(warning) = inside_geometry(&tracer, &camera)
    {
        errln!("radc render: warning: {warning}");
    }
    let done = AtomicUsize::new(0);
    let progress = std::io::stderr().is_terminal() && !super::error_file::redirected();
    let pixels = std::thread::scope(|s| {
        if progress {
            s.spawn(|| show_progress(&done, h as usize));
        }
        let pixels = render_picture(&tracer, &camera, w, h, &done);
        // Rows done: tells the progress thread to finish.
        done.store(usize::MAX, Ordering::Relaxed);
        pixels
    });
    if a.warnings && pixels.iter().all(|c| *c == Color::ZERO) {
        errln!(
            "radc render: warning: the picture is black: no light reaches the view (no light \
             sources or -av, or the view is enclosed)"
        );
    }
    let header = vec![
        format!("radc render {}", args.join(" ")),
        format!("SOFTWARE= radc {}", env!("CARGO_PKG_VERSION")),
        format!("VIEW= {}", a.view.header()),
    ];
    if a.outputs.is_empty() {
        let stdout = std::io::stdout();
        let mut out = std::io::BufWriter::new(stdout.lock());
        if let Err(e) = picture::write(&mut out, &header, w, h, &pixels).and_then(|_| out.flush()) {
            errln!("radc render: cannot write the picture: {e}");
            return ExitCode::from(1);
        }
    }
    for path in &a.outputs {
        let written = if is_png(path) {
            write_png(path, w, h, &pixels)
        } else {
            std::fs::File::create(path).and_then(|f| {
                let mut out = std::io::BufWriter::new(f);
                picture::write(&mut out, &header, w, h, &pixels)?;
                out.flush()
            })
        };
        if let Err(e) = written {
            errln!("radc render: cannot write {}: {e}", path.display());
            return ExitCode::from(1);
        }
    }
    report_functions(&scene, "render")
}

/// `radc render -o x.png picture.hdr`: the one input is a Radiance picture and every
/// output a PNG, so the picture itself is tone-mapped to PNG (nothing is rendered).
/// `None` when the input is not a picture or the outputs are not all PNGs (then the
/// scene loader explains that a picture is not a scene).
fn picture_to_png(a: &Args) -> Option<ExitCode> {
    let [input] = &a.scenes[..] else { return None };
    radc_loader::picture_description(input)?;
    if a.outputs.is_empty() || !a.outputs.iter().all(|p| is_png(p)) {
        return None;
    }
    let picture = match std::fs::read(input)
        .map_err(|e| e.to_string())
        .and_then(|b| radc_picture::Picture::read(&b).map_err(|e| e.to_string()))
    {
        Ok(p) => p,
        Err(e) => {
            errln!("radc render: {}: {e}", input.display());
            return Some(ExitCode::from(1));
        }
    };
    if picture.format() == radc_picture::Format::Xyze {
        errln!(
            "radc render: {}: is an XYZE picture; the PNG tone map takes RGB (convert it \
             with Radiance's 'ra_xyze -r' first)",
            input.display()
        );
        return Some(ExitCode::from(1));
    }
    let px: Vec<Color> = picture
        .standard_pixels()
        .into_iter()
        .map(|c| {
            let [r, g, b] = radc_picture::decode(c);
            Color::new(f64::from(r), f64::from(g), f64::from(b))
        })
        .collect();
    for path in &a.outputs {
        if let Err(e) = write_png(path, picture.width(), picture.height(), &px) {
            errln!("radc render: cannot write {}: {e}", path.display());
            return Some(ExitCode::from(1));
        }
    }
    Some(ExitCode::SUCCESS)
}

fn is_png(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

/// An 8-bit sRGB PNG, tone-mapped with the automatic exposure (`radc_picture::tonemap`).
fn write_png(path: &Path, w: u32, h: u32, pixels: &[Color]) -> std::io::Result<()> {
    let px: Vec<[f64; 3]> = pixels.iter().map(|c| c.to_array()).collect();
    let file = std::fs::File::create(path)?;
    radc_picture::png_out::write_png(std::io::BufWriter::new(file), w, h, &px)
}

/// A percentage on stderr (a terminal), rewritten in place until `done` says the rows
/// are finished; then the line is cleared.
fn show_progress(done: &AtomicUsize, rows: usize) {
    let mut err = std::io::stderr();
    loop {
        let n = done.load(Ordering::Relaxed);
        if n == usize::MAX {
            let _ = write!(err, "\r{:60}\r", "");
            return;
        }
        let pct = n * 100 / rows.max(1);
        let bar = "#".repeat(pct / 5);
        let _ = write!(err, "\rradc render: [{bar:<20}] {pct:3}% ({n}/{rows} rows)");
        let _ = err.flush();
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
}
