//! `-defaults` of `radc trace` and `radc render`: the settings in force, one option per
//! line in rtrace's and rpict's layout (`-dt 0.030000\t\t\t# direct threshold`), so a
//! user comparing with Radiance's list reads them side by side. The values are the ones
//! radc computes with: where radc does not model an option, the line shows the value radc
//! behaves as (`-aa 0`, `-dt 0`, `-u-`) and says so.

use radc_lang::c_number::format_e;
use radc_renderer::Options;
use radc_renderer::camera::{Projection, View};
use std::fmt::Write;

/// One line: the option and its value, padded with tabs to the comment as Radiance's
/// `printdefaults` pads them.
fn line(out: &mut String, option: &str, comment: &str) {
    let tabs = match option.len() {
        0..8 => "\t\t\t\t",
        8..16 => "\t\t\t",
        16..24 => "\t\t",
        _ => "\t",
    };
    let _ = writeln!(out, "{option}{tabs}# {comment}");
}

fn on_off(value: bool) -> char {
    if value { '+' } else { '-' }
}

/// `-ab 0        `: an integer as `%-9d` (rtrace's layout).
fn int(option: &str, value: impl std::fmt::Display) -> String {
    format!("{option} {value:<9}")
}

fn triple(option: &str, v: radc_renderer::math::Vec3) -> String {
    format!("{option} {:.6} {:.6} {:.6}", v.x, v.y, v.z)
}

/// The options rtrace and rpict share, from `-i` on.
fn shared(out: &mut String, o: &Options) {
    line(
        out,
        &format!("-i{}", on_off(o.irradiance_at_hits)),
        if o.irradiance_at_hits {
            "irradiance calculation on"
        } else {
            "irradiance calculation off"
        },
    );
    line(
        out,
        "-u-",
        "correlated sampling (radc's own reproducible sequence)",
    );
    line(
        out,
        &format!("-bv{}", on_off(o.backface_visible)),
        if o.backface_visible {
            "back face visibility on"
        } else {
            "back face visibility off"
        },
    );
    line(
        out,
        "-dt 0.000000",
        "direct threshold (radc tests every shadow)",
    );
    line(
        out,
        &format!("-ds {:.6}", o.source_size_ratio),
        "direct sampling",
    );
    line(out, &format!("-dj {:.6}", o.source_jitter), "direct jitter");
    line(out, &int("-dr", o.relays), "direct relays");
    line(
        out,
        &format!("-dv{}", on_off(o.direct_visible)),
        if o.direct_visible {
            "direct visibility on"
        } else {
            "direct visibility off"
        },
    );
    line(
        out,
        &format!("-dx{}", on_off(o.exact_sources)),
        "exact source samples (radc's own)",
    );
    line(out, "-ss 1.000000", "specular sampling");
    line(
        out,
        &format!("-st {:.6}", o.specular_threshold),
        "specular threshold",
    );
    line(out, &triple("-av", o.ambient), "ambient value");
    line(out, &int("-ab", o.ambient_bounces), "ambient bounces");
    line(
        out,
        "-aa 0.000000",
        "ambient accuracy (radc has no irradiance cache yet)",
    );
    line(out, &int("-ad", o.ambient_divisions), "ambient divisions");
    line(
        out,
        &int("-as", o.ambient_supersamples),
        "ambient super-samples",
    );
    let m = o.medium;
    line(
        out,
        &format!(
            "-me {} {} {}",
            format_e(m.x, 2),
            format_e(m.y, 2),
            format_e(m.z, 2)
        ),
        "mist extinction coefficient",
    );
    line(
        out,
        "-ma 0.000000 0.000000 0.000000",
        "mist scattering albedo",
    );
    let roulette = if o.max_depth <= 0 {
        "limit reflection (Russian roulette)"
    } else {
        "limit reflection"
    };
    line(out, &int("-lr", o.max_depth), roulette);
    line(
        out,
        &format!("-lw {}", format_e(o.min_weight, 2)),
        "limit weight",
    );
}

/// What rtrace settings radc trace has beyond the shared ones.
pub(super) struct TraceSettings<'a> {
    pub warnings: bool,
    pub threads: usize,
    pub x: u32,
    pub y: u32,
    pub limit_distance: bool,
    pub header: bool,
    pub formats: (char, char),
    pub outputs: &'a str,
}

fn format_name(c: char) -> &'static str {
    match c {
        'a' => "ascii",
        'f' => "float",
        'd' => "double",
        'c' => "color",
        _ => "?",
    }
}

pub(super) fn trace(s: &TraceSettings<'_>, o: &Options) -> String {
    let mut out = String::new();
    line(
        &mut out,
        &format!("-w{}", on_off(s.warnings)),
        if s.warnings {
            "warning messages on"
        } else {
            "warning messages off"
        },
    );
    let threads = if s.threads == 0 {
        "all cores".to_string()
    } else {
        s.threads.to_string()
    };
    line(
        &mut out,
        &format!("-n {threads}"),
        "number of rendering threads",
    );
    line(&mut out, &int("-x", s.x), "flush interval");
    line(&mut out, &int("-y", s.y), "y resolution");
    line(
        &mut out,
        &format!("-ld{}", on_off(s.limit_distance)),
        if s.limit_distance {
            "limit distance on"
        } else {
            "limit distance off"
        },
    );
    line(
        &mut out,
        &format!("-h{}", on_off(s.header)),
        if s.header {
            "output header"
        } else {
            "no header"
        },
    );
    let (i, o_) = s.formats;
    line(
        &mut out,
        &format!("-f{i}{o_}"),
        &format!(
            "format input/output = {}/{}",
            format_name(i),
            format_name(o_)
        ),
    );
    line(
        &mut out,
        &format!("-o{:<9}", s.outputs),
        "output specification",
    );
    line(&mut out, "-pRGB", "standard RGB color output");
    shared(&mut out, o);
    out
}

fn projection_letter(p: Projection) -> (char, &'static str) {
    match p {
        Projection::Perspective => ('v', "perspective"),
        Projection::Parallel => ('l', "parallel"),
        Projection::Hemispherical => ('h', "hemispherical fisheye"),
        Projection::Angular => ('a', "angular fisheye"),
        Projection::Cylindrical => ('c', "cylindrical panorama"),
        Projection::Planispheric => ('s', "planisphere"),
    }
}

pub(super) fn render(
    view: &View,
    x: u32,
    y: u32,
    aspect: f64,
    warnings: bool,
    o: &Options,
) -> String {
    let mut out = String::new();
    let (letter, name) = projection_letter(view.projection);
    line(
        &mut out,
        &format!("-vt{letter}"),
        &format!("view type {name}"),
    );
    line(&mut out, &triple("-vp", view.position), "view point");
    line(&mut out, &triple("-vd", view.direction), "view direction");
    line(&mut out, &triple("-vu", view.up), "view up");
    line(
        &mut out,
        &format!("-vh {:.6}", view.horizontal),
        "view horizontal size",
    );
    line(
        &mut out,
        &format!("-vv {:.6}", view.vertical),
        "view vertical size",
    );
    line(
        &mut out,
        &format!("-vo {:.6}", view.fore),
        "view fore clipping plane",
    );
    line(
        &mut out,
        &format!("-va {:.6}", view.aft),
        "view aft clipping plane",
    );
    line(&mut out, &format!("-vs {:.6}", view.shift), "view shift");
    line(&mut out, &format!("-vl {:.6}", view.lift), "view lift");
    line(&mut out, &int("-x ", x), "x resolution");
    line(&mut out, &int("-y ", y), "y resolution");
    line(&mut out, "-pRGB", "standard RGB color output");
    line(&mut out, &format!("-pa {aspect:.6}"), "pixel aspect ratio");
    line(
        &mut out,
        "-pj 0.000000",
        "pixel jitter (radc traces pixel centres)",
    );
    line(&mut out, "-pm 0.000000", "pixel motion");
    line(&mut out, "-pd 0.000000", "pixel depth-of-field");
    line(
        &mut out,
        &int("-ps", 1),
        "pixel sample (radc traces every pixel)",
    );
    line(
        &mut out,
        &format!("-w{}", on_off(warnings)),
        if warnings {
            "warning messages on"
        } else {
            "warning messages off"
        },
    );
    shared(&mut out, o);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_laid_out_as_radiance_lays_them_out() {
        let text = trace(
            &TraceSettings {
                warnings: true,
                threads: 1,
                x: 0,
                y: 0,
                limit_distance: false,
                header: true,
                formats: ('a', 'a'),
                outputs: "v",
            },
            &Options::default(),
        );
        // The lines whose values radc shares with rtrace's defaults are rtrace's, byte
        // for byte (`rtrace -defaults` of Radiance 6.0a).
        for expected in [
            "-w+\t\t\t\t# warning messages on\n",
            "-x 0        \t\t\t# flush interval\n",
            "-ld-\t\t\t\t# limit distance off\n",
            "-h+\t\t\t\t# output header\n",
            "-faa\t\t\t\t# format input/output = ascii/ascii\n",
            "-ds 0.200000\t\t\t# direct sampling\n",
            "-dr 2        \t\t\t# direct relays\n",
            "-av 0.000000 0.000000 0.000000\t# ambient value\n",
            "-ab 0        \t\t\t# ambient bounces\n",
            "-ad 1024     \t\t\t# ambient divisions\n",
            "-me 0.00e+00 0.00e+00 0.00e+00\t# mist extinction coefficient\n",
            "-lr -10      \t\t\t# limit reflection (Russian roulette)\n",
            "-lw 1.00e-04\t\t\t# limit weight\n",
        ] {
            assert!(text.contains(expected), "{expected:?} not in\n{text}");
        }
    }
}
