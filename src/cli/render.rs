//! `radc render`: rpict for scene files. Writes a Radiance picture (RGBE, new-style RLE)
//! to stdout or `-o file`, one ray through the centre of each pixel (rpict `-pj 0
//! -ps 1`), with rpict's view options and the lighting options of `radc trace`.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use radc_renderer::camera::View;
use radc_renderer::math::Color;
use radc_renderer::{Options, Tracer, picture};
use rayon::prelude::*;

use super::USAGE_ERROR;
use super::trace::{load_scene, number, render_option};

const USAGE: &str = "usage: radc render [-vf file] [-vt{v|l|h|a|c|s}] [-vp x y z] [-vd x y z] [-vu x y z] [-vh deg] \
[-vv deg] [-x res] [-y res] [-pa aspect] [-ab N] [-ad N] [-as N] [-av r g b] [-dj frac] [-o picture.hdr] scene.rad...";

struct Args {
    view: View,
    x: u32,
    y: u32,
    pixel_aspect: f64,
    options: Options,
    output: Option<PathBuf>,
    scenes: Vec<PathBuf>,
    warnings: bool,
}

/// View options from a view file (`-vf`): any words of the file before its first
/// empty line (so a picture's header works too), view options taken, the rest ignored.
fn view_file(view: &mut View, path: &str) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read view file '{path}': {e}"))?;
    let text = String::from_utf8_lossy(&bytes);
    let head = text.split("\n\n").next().unwrap_or("");
    let words: Vec<&str> = head.split_whitespace().collect();
    let mut i = 0;
    while i < words.len() {
        i += view.option(&words[i..])?.max(1);
    }
    Ok(())
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
        output: None,
        scenes: Vec::new(),
        warnings: true,
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
            "-vf" => view_file(&mut a.view, it.next().ok_or("-vf needs a file name")?)?,
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
            // rpict's sampling options: radc always traces one ray per pixel centre.
            "-pj" | "-ps" | "-pt" | "-pm" | "-pd" | "-t" | "-n" => {
                number(&mut it, arg)?;
            }
            "-o" => a.output = Some(PathBuf::from(it.next().ok_or("-o needs a file name")?)),
            s if super::trace::switch(s, "-w", &mut a.warnings) => {}
            s if render_option(s, &mut it, &mut a.options)? => {}
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
    super::trace::with_deep_stacks(|| run_parsed(args))
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
    let camera = match a.view.camera() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("radc render: {e}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    let mut scene = match load_scene(&a.scenes, "render", a.warnings) {
        Ok(s) => s,
        Err(code) => return code,
    };
    scene.add_virtual_sources(a.options.relays);
    let (w, h) = camera.fit_resolution(a.x, a.y, a.pixel_aspect);
    let (w, h) = (w.max(1), h.max(1));
    // The picture is held in memory: refuse sizes that cannot be.
    if u64::from(w) * u64::from(h) > 1 << 28 {
        eprintln!("radc render: a {w} by {h} picture is too large");
        return ExitCode::from(USAGE_ERROR);
    }
    let tracer = Tracer::new(&scene, a.options.clone());
    // Top row first; pixel centres at ((i + .5) / w, (j + .5) / h) with j counted upward.
    let pixels: Vec<Color> = (0..h)
        .into_par_iter()
        .flat_map_iter(|row| {
            let j = h - 1 - row;
            let (camera, tracer) = (&camera, &tracer);
            (0..w).map(move |i| {
                let x = (f64::from(i) + 0.5) / f64::from(w);
                let y = (f64::from(j) + 0.5) / f64::from(h);
                // Outside a fisheye's circle the picture is black.
                // Random choices derive from the pixel's index, not the thread.
                let index = u64::from(row) * u64::from(w) + u64::from(i);
                camera.ray(x, y).map_or(Color::ZERO, |(org, dir, max)| {
                    tracer.radiance_seeded(org, dir, max, index).color
                })
            })
        })
        .collect();
    let mut pixels = pixels;
    radc_renderer::small_sources::draw(&tracer, &camera, w, h, 1.0, &mut pixels);
    let header = vec![
        format!("radc render {}", args.join(" ")),
        format!("SOFTWARE= radc {}", env!("CARGO_PKG_VERSION")),
        format!("VIEW= {}", a.view.header()),
    ];
    let written = match &a.output {
        Some(path) => std::fs::File::create(path).and_then(|f| {
            let mut out = std::io::BufWriter::new(f);
            picture::write(&mut out, &header, w, h, &pixels)?;
            out.flush()
        }),
        None => {
            let stdout = std::io::stdout();
            let mut out = std::io::BufWriter::new(stdout.lock());
            picture::write(&mut out, &header, w, h, &pixels).and_then(|_| out.flush())
        }
    };
    match written {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("radc render: cannot write the picture: {e}");
            ExitCode::from(1)
        }
    }
}
