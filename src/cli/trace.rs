//! `radc trace`: rtrace for scene files. Reads rays `ox oy oz dx dy dz` from stdin and
//! writes what `-o` asks for, in rtrace's formats (`%e` and a tab after each number,
//! one ray per line; or binary `-ff`/`-fd`). Takes rtrace's options; the ones radc does
//! not model yet are refused rather than silently ignored.
//!
//! Evaluation follows rtrace with every shadow tested (`-dt 0`) and no irradiance cache
//! (`-aa 0`: ambient values from `-ab` are always computed); light relayed by mirrors
//! (`-dr`) is included. Each input ray's random choices (`-ab`, `-dj`) derive from its
//! line number, so output repeats exactly for any thread count.

use std::io::{BufReader, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use radc_renderer::trace::{Output, RayEncoding, TraceSpec, trace_stream};
use radc_renderer::{Options, Tracer};

use super::USAGE_ERROR;
use super::load::{load_scene, report_functions};
use super::options::{
    Query, Unmodelled, expand_option_files, number, render_option, switch, thread_count,
    version_line, with_threads,
};

const USAGE: &str = "usage: radc trace [-h] [-I] [-o spec] [-f{a|f|d}{a|f|d}] [-ab N] [-ad N] [-as N] [-av r g b] \
[-ds f] [-dj f] [-dx+] [-lr n] [-lw f] [-st f] [-bv] scene.rad...";

#[derive(Debug)]
struct Args {
    header: bool,
    spec: TraceSpec,
    options: Options,
    scenes: Vec<PathBuf>,
    /// `-w`: report the scene's warnings (errors are always reported).
    warnings: bool,
    /// `--allow-commands`: run `!` lines other than the built-in generators.
    allow_commands: bool,
    /// Options given that radc does not honour, reported as warnings.
    unmodelled: Unmodelled,
    /// `-o`'s letters, as given (for `-defaults`).
    output_letters: String,
    /// `-version` or `-defaults`: print instead of tracing.
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
        header: true,
        spec: TraceSpec {
            outputs: vec![Output::Value],
            input: RayEncoding::Ascii,
            output: RayEncoding::Ascii,
            irradiance: false,
            limit_distance: false,
            x_res: 0,
            y_res: 0,
        },
        options: Options::default(),
        scenes: Vec::new(),
        warnings: true,
        allow_commands: false,
        unmodelled: Unmodelled::default(),
        output_letters: "v".into(),
        query: None,
    };
    let mut it = args.iter().map(String::as_str).peekable();
    while let Some(arg) = it.next() {
        match arg {
            s if switch(s, "-h", &mut a.header) => {}
            s if switch(s, "-I", &mut a.spec.irradiance) => {}
            s if switch(s, "-w", &mut a.warnings) => {}
            s if switch(s, "-ld", &mut a.spec.limit_distance) => {}
            "--allow-commands" => a.allow_commands = true,
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
                    a.spec.x_res = v;
                } else {
                    a.spec.y_res = v;
                }
            }
            s if switch(s, "-i", &mut a.options.irradiance_at_hits) => {}
            s if render_option(s, &mut it, &mut a.options, &mut a.unmodelled)? => {}
            s if Query::of(s).is_some() => {
                a.query = Query::of(s);
                return Ok(a);
            }
            s if s.starts_with("-o") => {
                a.spec.outputs = Output::parse(&s[2..])?;
                a.output_letters = s[2..].to_string();
            }
            s if s.starts_with("-f") => {
                let f: Vec<char> = s[2..].chars().collect();
                let (i, o) = match f.as_slice() {
                    [c] => (*c, *c),
                    [i, o] => (*i, *o),
                    _ => return Err(format!("bad format '{s}'")),
                };
                a.spec.input =
                    RayEncoding::from_char(i).ok_or_else(|| format!("bad input format '{i}'"))?;
                a.spec.output =
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

pub fn run(args: &[String]) -> ExitCode {
    let args = match expand_option_files(args) {
        Ok(args) => args,
        Err(e) => {
            eprintln!("radc trace: {e}");
            return ExitCode::from(USAGE_ERROR);
        }
    };
    with_threads(thread_count(&args), || run_parsed(&args))
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
    match a.query {
        Some(Query::Version) => {
            println!("{}", version_line());
            return ExitCode::SUCCESS;
        }
        Some(Query::Defaults) => {
            let settings = super::defaults::TraceSettings {
                warnings: a.warnings,
                threads: thread_count(args),
                x: a.spec.x_res,
                y: a.spec.y_res,
                limit_distance: a.spec.limit_distance,
                header: a.header,
                formats: (a.spec.input.letter(), a.spec.output.letter()),
                outputs: &a.output_letters,
            };
            print!("{}", super::defaults::trace(&settings, &a.options));
            return ExitCode::SUCCESS;
        }
        None => {}
    }
    if a.warnings {
        for w in a.unmodelled.warnings(&a.options) {
            eprintln!("radc trace: warning: {w}");
        }
    }
    let mut scene = match load_scene(&a.scenes, "trace", a.load_options()) {
        Ok(s) => s,
        Err(code) => return code,
    };
    scene.add_virtual_sources(a.options.relays);
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    if a.header {
        let ncomp = a.spec.components();
        let _ = write!(
            out,
            "#?RADIANCE\nradc trace {}\nSOFTWARE= radc {}\nNCOMP={ncomp}\nFORMAT={}\n\n",
            args.join(" "),
            env!("CARGO_PKG_VERSION"),
            a.spec.output.name()
        );
    }
    if a.spec.x_res > 0 && a.spec.y_res > 0 {
        let _ = writeln!(out, "-Y {} +X {}", a.spec.y_res, a.spec.x_res);
    }
    let tracer = Tracer::new(&scene, a.options.clone());
    let stdin = std::io::stdin();
    let input = BufReader::with_capacity(1 << 16, stdin.lock());
    if trace_stream(&tracer, &a.spec, input, &mut out).is_err() {
        return ExitCode::from(1);
    }
    report_functions(&scene, "trace")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switches_toggle() {
        let a = parse_args(&["-h".into(), "-I+".into(), "x.rad".into()]).unwrap();
        assert!(!a.header && a.spec.irradiance);
        assert!(parse_args(&["-ab".into(), "x".into(), "x.rad".into()]).is_err());
    }
}
