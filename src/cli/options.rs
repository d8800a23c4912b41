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

/// Options rtrace and rpict take that change what Radiance computes but that radc does
/// not model yet. radc computes as if they had the value in brackets; each given
/// otherwise is reported as a warning naming it (never silently accepted):
/// the irradiance cache (`-aa 0`: every ambient value computed; `-ar -aw -ai -ae -aI
/// -aE -af` only matter to the cache), probabilistic shadow testing (`-dt 0`, with its
/// `-dc`), specular sampling (`-ss 1`), correlated sampling (`-u-`), and for rpict pixel
/// jitter (`-pj 0`).
#[derive(Debug, Default)]
pub(super) struct Unmodelled {
    cache_accuracy: Option<f64>,
    cache_options: Vec<String>,
    ambient_file: Option<String>,
    shadow_threshold: Option<f64>,
    specular_sampling: Option<f64>,
    uncorrelated: bool,
    pixel_jitter: Option<f64>,
}

impl Unmodelled {
    /// rpict's `-pj`: radc traces each pixel at its centre.
    pub(super) fn pixel_jitter(&mut self, value: f64) {
        self.pixel_jitter = Some(value);
    }

    /// One warning per option whose value radc does not honour under `o` (cache
    /// options matter only with `-ab > 0`).
    pub(super) fn warnings(&self, o: &Options) -> Vec<String> {
        let mut out = Vec::new();
        let indirect = o.ambient_bounces > 0 && o.ambient_divisions > 0;
        if indirect {
            if let Some(aa) = self.cache_accuracy.filter(|a| *a > 0.0) {
                out.push(format!(
                    "-aa {aa}: radc has no irradiance cache yet and computes every ambient \
                     value (as -aa 0): slower, noisier per sample, without the cache's bias"
                ));
            }
            if !self.cache_options.is_empty() {
                out.push(format!(
                    "{}: irradiance cache options, ignored (radc computes as -aa 0)",
                    self.cache_options.join(" ")
                ));
            }
            if let Some(file) = &self.ambient_file {
                out.push(format!(
                    "-af {file}: no ambient file is read or written (radc has no irradiance cache yet)"
                ));
            }
        }
        if let Some(dt) = self.shadow_threshold.filter(|d| *d > 0.0) {
            out.push(format!(
                "-dt {dt}: radc tests every shadow ray (as -dt 0): results are rtrace's at \
                 -dt 0, not at -dt {dt}"
            ));
        }
        if let Some(ss) = self.specular_sampling.filter(|s| *s != 1.0) {
            out.push(format!(
                "-ss {ss}: radc samples each rough highlight once (as -ss 1)"
            ));
        }
        if self.uncorrelated {
            out.push("-u+: radc's sampling is its own reproducible sequence (as -u-)".into());
        }
        if let Some(pj) = self.pixel_jitter.filter(|p| *p > 0.0) {
            out.push(format!(
                "-pj {pj}: radc traces one ray through each pixel's centre (as -pj 0)"
            ));
        }
        out
    }
}

/// Rendering options shared with `radc render` (rpict's): true when `arg` was one.
pub(super) fn render_option<'a>(
    arg: &str,
    it: &mut impl Iterator<Item = &'a str>,
    o: &mut Options,
    unmodelled: &mut Unmodelled,
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
        "-dr" => o.relays = number(it, "-dr")?.max(0.0) as u32,
        // -dp sets how densely Radiance pretests relayed source paths; radc follows
        // every relayed path, which is what the pretest approximates: no effect on values.
        "-dp" => {
            number(it, arg)?;
        }
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
        // The scattering medium's eccentricity and sampling distance: without an
        // albedo (refused above) nothing scatters, so they change nothing.
        "-mg" | "-ms" => {
            number(it, arg)?;
        }
        "-aa" => unmodelled.cache_accuracy = Some(number(it, arg)?),
        "-ar" | "-aw" => {
            let v = number(it, arg)?;
            unmodelled.cache_options.push(format!("{arg} {v}"));
        }
        "-ai" | "-ae" | "-aI" | "-aE" => {
            let v = it.next().ok_or_else(|| format!("{arg} needs a value"))?;
            unmodelled.cache_options.push(format!("{arg} {v}"));
        }
        "-af" => {
            let v = it.next().ok_or_else(|| format!("{arg} needs a value"))?;
            unmodelled.ambient_file = Some(v.to_string());
        }
        "-dt" => unmodelled.shadow_threshold = Some(number(it, arg)?),
        // -dc is the certainty of -dt's shadow tests: with every shadow tested (-dt 0),
        // it changes nothing.
        "-dc" => {
            number(it, arg)?;
        }
        "-ss" => unmodelled.specular_sampling = Some(number(it, arg)?),
        s if switch(s, "-u", &mut unmodelled.uncorrelated) => {}
        s if switch(s, "-dv", &mut o.direct_visible) => {}
        s if switch(s, "-dx", &mut o.exact_sources) => {}
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

/// Most words an option list may grow to through `@file` and `$VAR` (Radiance's
/// `MAXARGEXP`); past it an option file that names itself is reported, not followed
/// forever.
const MAX_EXPANDED_WORDS: usize = 4096;

/// rtrace's and rpict's `expandarg`: a word `@file` is replaced by the words of the
/// file and `$VAR` by the words of the environment variable, split at white space (no
/// quoting, as Radiance splits them), and the new words are looked at again, so option
/// files may name others. Radiance expands only where it reads an option; a scene or
/// option value beginning with `@` or `$` is in practice never meant literally, and here
/// is expanded too.
pub(super) fn expand_option_files(args: &[String]) -> Result<Vec<String>, String> {
    let mut out: Vec<String> = Vec::with_capacity(args.len());
    let mut pending: Vec<String> = args.iter().rev().cloned().collect();
    let mut expansions = 0;
    while let Some(word) = pending.pop() {
        let words = if let Some(path) = word.strip_prefix('@').filter(|p| !p.is_empty()) {
            let text = std::fs::read(path).map_err(|e| format!("cannot expand '{word}': {e}"))?;
            String::from_utf8_lossy(&text)
                .split_ascii_whitespace()
                .map(str::to_string)
                .collect::<Vec<_>>()
        } else if let Some(name) = word.strip_prefix('$').filter(|n| !n.is_empty()) {
            let value = std::env::var(name)
                .map_err(|_| format!("cannot expand '{word}': no such environment variable"))?;
            value.split_ascii_whitespace().map(str::to_string).collect()
        } else {
            out.push(word);
            continue;
        };
        expansions += 1;
        if expansions > MAX_EXPANDED_WORDS
            || out.len() + pending.len() + words.len() > MAX_EXPANDED_WORDS
        {
            return Err(format!(
                "cannot expand '{word}': more than {MAX_EXPANDED_WORDS} words (does an option file name itself?)"
            ));
        }
        pending.extend(words.into_iter().rev());
    }
    Ok(out)
}

/// What rtrace and rpict answer instead of rendering: `-version` and `-defaults`
/// (Radiance stops reading options at either and exits 0 after printing).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Query {
    Version,
    Defaults,
}

impl Query {
    pub(super) fn of(arg: &str) -> Option<Query> {
        match arg {
            "-version" => Some(Query::Version),
            "-defaults" => Some(Query::Defaults),
            _ => None,
        }
    }
}

/// `-version`: Radiance's form (`RADIANCE 6.0a ...`), which version checks read as the
/// second word (frads, honeybee-radiance: at least 5), followed by radc's own version.
pub(super) fn version_line() -> String {
    format!("RADIANCE 6.0a (radc {})", env!("CARGO_PKG_VERSION"))
}

/// View options from a view file (`-vf`): any words of the file before its first
/// empty line (so a picture's header works too), view options taken, the rest ignored.
/// True when the file held a view option.
pub(super) fn view_file(
    view: &mut radc_renderer::camera::View,
    path: &str,
) -> Result<bool, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read view file '{path}': {e}"))?;
    let text = String::from_utf8_lossy(&bytes);
    let head = text.split("\n\n").next().unwrap_or("");
    let words: Vec<&str> = head.split_whitespace().collect();
    let mut i = 0;
    let mut found = false;
    while i < words.len() {
        let used = view.option(&words[i..])?;
        found |= used > 0;
        i += used.max(1);
    }
    Ok(found)
}
