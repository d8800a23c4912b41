//! `radc vwrays`: Radiance's vwrays, the rays of a view or of a picture's view, for
//! `rtrace` to evaluate (`vwrays -ff -vf v.vf | rtrace -ffc $(vwrays -d -vf v.vf)
//! scene.oct > v.hdr`). The rays come from `radc_renderer::view_rays`, the camera
//! `radc render` uses; this file reads the options and writes the rays.

use std::io::{BufRead, Write};
use std::process::ExitCode;

use radc_picture::{Header, Resolution};
use radc_renderer::camera::View;
use radc_renderer::math::FTINY;
use radc_renderer::trace::RayEncoding;
use radc_renderer::view_rays::{ViewRays, write_ray};

const USAGE: &str =
    "Usage: vwrays [ -i -u -f{a|f|d} -c rept | -d ] { view opts .. | picture [zbuf] }";

struct Args {
    view: View,
    x: i64,
    y: i64,
    pixel_aspect: f64,
    jitter: f64,
    repeat: u32,
    format: RayEncoding,
    dimensions_only: bool,
    from_stdin: bool,
    unbuffered: bool,
    picture: Option<String>,
}

fn atoi(s: Option<&str>) -> i64 {
    s.map_or(0, radc_lang::c_number::atol)
}

fn parse(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        view: View::default(),
        x: 512,
        y: 512,
        pixel_aspect: 1.0,
        jitter: 0.0,
        repeat: 1,
        format: RayEncoding::Ascii,
        dimensions_only: false,
        from_stdin: false,
        unbuffered: false,
        picture: None,
    };
    if args.is_empty() {
        return Err(String::new());
    }
    let words: Vec<&str> = args.iter().map(String::as_str).collect();
    let mut i = 0;
    while i < words.len() && words[i].starts_with('-') {
        let w = words[i];
        let next = words.get(i + 1).copied();
        match w {
            "-fa" => a.format = RayEncoding::Ascii,
            "-ff" => a.format = RayEncoding::Float,
            "-fd" => a.format = RayEncoding::Double,
            "-vf" => {
                let path = next.ok_or_else(String::new)?;
                if !super::options::view_file(&mut a.view, path)? {
                    return Err(format!("{path}: no view in file"));
                }
                i += 1;
            }
            "-d" => a.dimensions_only = true,
            "-x" | "-y" => {
                let v = atoi(next);
                if v <= 0 {
                    let which = if w == "-x" { 'x' } else { 'y' };
                    return Err(format!("vwrays: bad {which} resolution"));
                }
                if w == "-x" {
                    a.x = v;
                } else {
                    a.y = v;
                }
                i += 1;
            }
            "-c" => {
                a.repeat = atoi(next).clamp(1, 1 << 20) as u32;
                i += 1;
            }
            "-pa" | "-pj" | "-pd" => {
                let v = next.map_or(0.0, radc_lang::c_number::atof);
                match w {
                    "-pa" => a.pixel_aspect = v,
                    "-pj" => a.jitter = v,
                    _ if v > FTINY => {
                        return Err(
                            "vwrays: -pd (depth of field) is not implemented; only -pd 0".into(),
                        );
                    }
                    _ => {}
                }
                i += 1;
            }
            "-i" => a.from_stdin = true,
            "-u" => a.unbuffered = true,
            _ if w.starts_with("-v") => {
                let used = a.view.option(&words[i..]).map_err(|_| String::new())?;
                if used == 0 {
                    return Err(String::new());
                }
                i += used - 1;
            }
            _ => return Err(String::new()),
        }
        i += 1;
    }
    match &words[i..] {
        [] => {}
        [picture] => a.picture = Some(picture.to_string()),
        [_, zbuf] if !a.dimensions_only => {
            return Err(format!(
                "vwrays: depth buffers ({zbuf}) are not implemented; give the picture alone"
            ));
        }
        [picture, _] => a.picture = Some(picture.to_string()),
        _ => return Err(String::new()),
    }
    Ok(a)
}

/// The view and resolution of a picture, from its header's view lines and its
/// resolution line.
fn picture_view(view: &mut View, path: &str) -> Result<Resolution, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("vwrays: cannot read {path}: {e}"))?;
    let (header, end) = Header::parse(&bytes).map_err(|e| format!("vwrays: {path}: {e}"))?;
    let Some(words) = header.view() else {
        return Err(format!("{path}: no view in picture"));
    };
    let words: Vec<&str> = words.split_whitespace().collect();
    let mut i = 0;
    while i < words.len() {
        i += view.option(&words[i..]).unwrap_or(0).max(1);
    }
    let (res, _) =
        Resolution::parse(&bytes[end..]).ok_or_else(|| format!("{path}: no view in picture"))?;
    Ok(res)
}

pub fn run(args: &[String]) -> ExitCode {
    let mut a = match parse(args) {
        Ok(a) => a,
        Err(e) => {
            if e.is_empty() {
                eprintln!("{USAGE}");
            } else {
                eprintln!("{e}");
            }
            return ExitCode::from(1);
        }
    };
    let given = match &a.picture {
        Some(path) => match picture_view(&mut a.view, path) {
            Ok(res) => Some(res),
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(1);
            }
        },
        None => None,
    };
    let camera = match a.view.camera() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("vwrays: {e}");
            return ExitCode::from(1);
        }
    };
    let resolution = given.unwrap_or_else(|| {
        let clamp = |v: i64| v.clamp(1, i64::from(u32::MAX)) as u32;
        let (x, y) = camera.fit_resolution(clamp(a.x), clamp(a.y), a.pixel_aspect);
        Resolution::standard(x.max(1), y.max(1))
    });
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    if a.dimensions_only {
        let ld = if a.view.aft > FTINY { " -ld+" } else { "" };
        let _ = writeln!(out, "-x {} -y {}{ld}", resolution.x, resolution.y);
        return flushed(out);
    }
    let rays = ViewRays {
        camera: &camera,
        resolution,
        jitter: a.jitter,
        repeat: a.repeat,
    };
    let mut batch = Vec::new();
    if a.from_stdin {
        let stdin = std::io::stdin();
        let mut words = Vec::new();
        let mut index = 0u64;
        for line in stdin.lock().split(b'\n') {
            let Ok(line) = line else { break };
            let text = String::from_utf8_lossy(&line);
            words.extend(text.split_whitespace().map(str::to_string));
            while words.len() >= 2 {
                let (px, py) = (
                    radc_lang::c_number::strtod(words[0].as_bytes()),
                    radc_lang::c_number::strtod(words[1].as_bytes()),
                );
                if px.len != words[0].len() || py.len != words[1].len() {
                    let _ = out.flush();
                    eprintln!("vwrays: expected px py on input");
                    return ExitCode::from(1);
                }
                words.drain(..2);
                batch.clear();
                rays.pixel(px.value, py.value, index, &mut batch);
                index += 1;
                for r in &batch {
                    if write_ray(&mut out, a.format, r).is_err() {
                        return ExitCode::from(1);
                    }
                }
                if a.unbuffered && out.flush().is_err() {
                    return ExitCode::from(1);
                }
            }
        }
        if !words.is_empty() {
            let _ = out.flush();
            eprintln!("vwrays: expected px py on input");
            return ExitCode::from(1);
        }
        return flushed(out);
    }
    for s in 0..resolution.scan_count() {
        batch.clear();
        rays.scanline(s, &mut batch);
        for r in &batch {
            if write_ray(&mut out, a.format, r).is_err() {
                return ExitCode::from(1);
            }
        }
    }
    flushed(out)
}

fn flushed(mut out: impl Write) -> ExitCode {
    match out.flush() {
        Ok(()) => ExitCode::SUCCESS,
        Err(_) => ExitCode::from(1),
    }
}
