//! Option parsing the commands share: Radiance's switches (`-x`, `-x+`, `-x-`),
//! numbers, the rendering options rtrace and rpict have in common, `-n` threads, and
//! the thread pool they run in.

use std::process::ExitCode;

use radc_renderer::Options;
use radc_renderer::math::Vec3;

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

/// rtrace's `-n N` (processes): here, the number of threads (the last `-n` given; a
/// bad value is reported by the option parser).
pub(super) fn thread_count(args: &[String]) -> usize {
    let at = args.iter().rposition(|a| a == "-n");
    at.and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|n| (1.0..=1024.0).contains(n))
        .map_or(0, |n| n as usize)
}
