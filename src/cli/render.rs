//! `radc render`: rpict for scene files. Writes a Radiance picture (RGBE, new-style RLE)
//! to stdout or `-o file`, one ray through the centre of each pixel (rpict `-pj 0
//! -ps 1`), with rpict's view options and the lighting options of `radc trace`.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use radc_renderer::camera::{Projection, View};
use radc_renderer::math::{Color, Vec3};
use radc_renderer::{Options, Tracer, picture};
use rayon::prelude::*;

use super::USAGE_ERROR;
use super::trace::{load_scene, number, render_option};

const USAGE: &str = "usage: radc render [-vt{v|l}] [-vp x y z] [-vd x y z] [-vu x y z] [-vh deg] \
[-vv deg] [-x res] [-y res] [-pa aspect] [-ab 0] [-av r g b] [-o picture.hdr] scene.rad...";

struct Args {
    view: View,
    x: u32,
    y: u32,
    pixel_aspect: f64,
    options: Options,
    output: Option<PathBuf>,
    scenes: Vec<PathBuf>,
}

fn vector<'a>(it: &mut impl Iterator<Item = &'a str>, what: &str) -> Result<Vec3, String> {
    Ok(Vec3::new(
        number(it, what)?,
        number(it, what)?,
        number(it, what)?,
    ))
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
            ..Options::default()
        },
        output: None,
        scenes: Vec::new(),
    };
    let mut it = args.iter().map(String::as_str);
    while let Some(arg) = it.next() {
        match arg {
            "-vtv" => a.view.projection = Projection::Perspective,
            "-vtl" => a.view.projection = Projection::Parallel,
            s if s.starts_with("-vt") => {
                return Err(format!(
                    "view type '{s}' is not supported yet (-vtv, -vtl are)"
                ));
            }
            "-vp" => a.view.position = vector(&mut it, arg)?,
            "-vd" => a.view.direction = vector(&mut it, arg)?,
            "-vu" => a.view.up = vector(&mut it, arg)?,
            "-vh" => a.view.horizontal = number(&mut it, arg)?,
            "-vv" => a.view.vertical = number(&mut it, arg)?,
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
    let scene = match load_scene(&a.scenes, "render") {
        Ok(s) => s,
        Err(code) => return code,
    };
    let (w, h) = camera.fit_resolution(a.x, a.y, a.pixel_aspect);
    let (w, h) = (w.max(1), h.max(1));
    let tracer = Tracer::new(&scene, a.options.clone());
    // Top row first; pixel centres at ((i + .5) / w, (j + .5) / h) with j counted upward.
    let pixels: Vec<Color> = (0..h)
        .into_par_iter()
        .flat_map_iter(|row| {
            let j = h - 1 - row;
            let (camera, tracer) = (&camera, &tracer);
            (0..w).map(move |i| {
                let (org, dir) = camera.ray(
                    (f64::from(i) + 0.5) / f64::from(w),
                    (f64::from(j) + 0.5) / f64::from(h),
                );
                tracer.radiance(org, dir).color
            })
        })
        .collect();
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
