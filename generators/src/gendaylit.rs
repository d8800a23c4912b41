//! `gendaylit month day hour [-y year] [-P|-W|-L|-G|-E] values [options]`,
//! `gendaylit -ang altitude azimuth ...`, `gendaylit -defaults`
//!
//! Reproduces Radiance's `src/gen/gendaylit.c`: the Perez all-weather sky. The sky's
//! state is Perez's clearness epsilon and brightness delta (Solar Energy 44(5), 1990),
//! given directly (`-P`) or derived from measured direct and diffuse irradiance (`-W`
//! direct normal, `-G` direct horizontal), illuminance (`-L`, by iterating Perez's
//! luminous efficacy models) or global irradiance alone (`-E`, with the diffuse
//! fraction of Erbs, Klein and Duffie, Solar Energy 28(4), 1982). The relative
//! luminance is Perez, Seals and Michalsky's (Solar Energy 50(3), 1993), normalized so
//! that it integrates over the 145 patches of the Tregenza sky to the diffuse
//! horizontal value; the sun is a 0.533 degree `source` carrying all the direct part.
//! The output names `perezlum.cal`'s `skybright` (`perezlum_c.cal` with `-C`).
//!
//! The C program keeps its tables in `float`s and compares epsilon as a `float` when it
//! picks a coefficient bin: both are kept here, so every printed digit matches.
//! Where it gives up it prints an "error sky" (all zero) and exits successfully; where
//! it fails (a negative `-i`, an epsilon it cannot place, an unknown `-O`) it exits 1
//! after the command line it has already printed.

use crate::sun::{Site, declination, julian_day};
use crate::words::atoi;
use crate::{Failure, GenError};
use radc_lang::c_number::atof;
use std::f64::consts::PI;

/// gendaylit's name for itself in messages (its `argv[0]`, as run from PATH).
const PROGRAM: &str = "gendaylit";

/// Radiance's white-light luminous efficacy, lm/W (`color.h` `WHTEFFICACY`).
const WHITE_EFFICACY: f64 = 179.0;
/// Solar constants: irradiance (W/m^2) and illuminance (lux).
const SOLAR_CONSTANT_E: f64 = 1367.0;
const SOLAR_CONSTANT_L: f64 = 127500.0;
/// Half the angle the sun subtends, degrees.
const HALF_SUN_ANGLE: f64 = 0.2665;
/// The range the Perez parameters are held in.
const CLEARNESS_MIN: f64 = 1.0;
const CLEARNESS_MAX: f64 = 12.01;
const BRIGHTNESS_MIN: f64 = 0.01;
const BRIGHTNESS_MAX: f64 = 0.6;
/// The dew point (degrees C) assumed without `-d`; it gives 2 cm of precipitable water.
const DEFAULT_DEW_POINT: f64 = 10.97353115;

/// Perez, Seals and Michalsky 1993, table 1: for each of the 8 clearness bins, the
/// coefficients a..e of the luminance model as `p1 + p2 Z + delta (p3 + p4 Z)` (Z the
/// solar zenith angle, radians). In the first bin c and d take other forms (see
/// [`model_coefficients`]). Stored as `float`s, as gendaylit holds them.
const PEREZ_LUMINANCE: [[[f32; 4]; 5]; 8] = [
    [
        [1.3525, -0.2576, -0.2690, -1.4366],
        [-0.7670, 0.0007, 1.2734, -0.1233],
        [2.8000, 0.6004, 1.2375, 1.000],
        [1.8734, 0.6297, 0.9738, 0.2809],
        [0.0356, -0.1246, -0.5718, 0.9938],
    ],
    [
        [-1.2219, -0.7730, 1.4148, 1.1016],
        [-0.2054, 0.0367, -3.9128, 0.9156],
        [6.9750, 0.1774, 6.4477, -0.1239],
        [-1.5798, -0.5081, -1.7812, 0.1080],
        [0.2624, 0.0672, -0.2190, -0.4285],
    ],
    [
        [-1.1000, -0.2515, 0.8952, 0.0156],
        [0.2782, -0.1812, -4.5000, 1.1766],
        [24.7219, -13.0812, -37.7000, 34.8438],
        [-5.0000, 1.5218, 3.9229, -2.6204],
        [-0.0156, 0.1597, 0.4199, -0.5562],
    ],
    [
        [-0.5484, -0.6654, -0.2672, 0.7117],
        [0.7234, -0.6219, -5.6812, 2.6297],
        [33.3389, -18.3000, -62.2500, 52.0781],
        [-3.5000, 0.0016, 1.1477, 0.1062],
        [0.4659, -0.3296, -0.0876, -0.0329],
    ],
    [
        [-0.6000, -0.3566, -2.5000, 2.3250],
        [0.2937, 0.0496, -5.6812, 1.8415],
        [21.0000, -4.7656, -21.5906, 7.2492],
        [-3.5000, -0.1554, 1.4062, 0.3988],
        [0.0032, 0.0766, -0.0656, -0.1294],
    ],
    [
        [-1.0156, -0.3670, 1.0078, 1.4051],
        [0.2875, -0.5328, -3.8500, 3.3750],
        [14.0000, -0.9999, -7.1406, 7.5469],
        [-3.4000, -0.1078, -1.0750, 1.5702],
        [-0.0672, 0.4016, 0.3017, -0.4844],
    ],
    [
        [-1.0000, 0.0211, 0.5025, -0.5119],
        [-0.3000, 0.1922, 0.7023, -1.6317],
        [19.0000, -5.0000, 1.2438, -1.9094],
        [-4.0000, 0.0250, 0.3844, 0.2656],
        [1.0468, -0.3788, -2.4517, 1.4656],
    ],
    [
        [-1.0500, 0.0289, 0.4260, 0.3590],
        [-0.3250, 0.1156, 0.7781, 0.0025],
        [31.0625, -14.5000, -46.1148, 55.3750],
        [-7.2312, 0.4050, 13.3500, 0.6234],
        [1.5000, -0.6426, 1.8564, 0.5636],
    ],
];

/// Upper clearness bounds of Perez's first seven bins (the eighth runs to the top).
const CLEARNESS_BINS: [f64; 7] = [1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200];

/// The luminous efficacy models of Perez et al. 1990 (table 4): for each clearness bin,
/// `a + b W + c f(Z) + d g(delta)` lm/W with W the precipitable water (cm).
struct Efficacy {
    a: [f64; 8],
    b: [f64; 8],
    c: [f64; 8],
    d: [f64; 8],
}

/// Diffuse horizontal efficacy: f = cos Z, g = ln delta.
const DIFFUSE_EFFICACY: Efficacy = Efficacy {
    a: [
        97.24, 107.22, 104.97, 102.39, 100.71, 106.42, 141.88, 152.23,
    ],
    b: [-0.46, 1.15, 2.96, 5.59, 5.94, 3.83, 1.90, 0.35],
    c: [12.00, 0.59, -5.53, -13.95, -22.75, -36.15, -53.24, -45.27],
    d: [-8.91, -3.95, -8.77, -13.90, -23.74, -28.83, -14.03, -7.98],
};

/// Direct normal efficacy: f = exp(5.73 Z - 5), g = delta.
const DIRECT_EFFICACY: Efficacy = Efficacy {
    a: [57.20, 98.99, 109.83, 110.34, 106.36, 107.19, 105.75, 101.18],
    b: [-4.55, -3.46, -4.90, -5.84, -3.97, -1.25, 0.77, 1.58],
    c: [-2.98, -1.21, -1.71, -1.99, -1.75, -1.51, -1.26, -1.10],
    d: [117.12, 12.38, -8.81, -4.56, -6.16, -26.73, -34.44, -8.29],
};

/// The Berlin daylight locus (A. Diakite, TU Berlin) that `-C` colours the sky with.
const BERLIN_LOCUS: [f32; 11] = [
    -4.843e9, 2.5568e6, 0.24282e3, 0.23258, -4.843e9, 2.5568e6, 0.24282e3, 0.23258, -1.2848,
    1.7519, -0.093786,
];
/// The CIE daylight locus (`-CIE`).
const CIE_LOCUS: [f32; 11] = [
    -4.607e9, 2.9678e6, 0.09911e3, 0.244063, -2.0064e9, 1.9018e6, 0.24748e3, 0.23704, -3.0, 2.87,
    -0.275,
];

/// Which pair of measurements describes the sky.
#[derive(Clone, Copy, PartialEq)]
enum Input {
    /// `-P epsilon delta`.
    Perez,
    /// `-W direct-normal diffuse-horizontal` irradiance.
    NormalIrradiance,
    /// `-L direct-normal diffuse-horizontal` illuminance.
    Illuminance,
    /// `-G direct-horizontal diffuse-horizontal` irradiance.
    HorizontalIrradiance,
    /// `-E global-horizontal` irradiance.
    Global,
}

/// How gendaylit stops early: an error sky (printed, exit status 0), or a failure.
enum Stop {
    ErrorSky,
    Fail(GenError),
}

/// Everything gendaylit.c keeps in globals.
struct Daylight {
    site: Site,
    year: i64,
    month: i64,
    day: i64,
    hour: f64,
    solar_time: bool,
    altitude: f64,
    azimuth: f64,
    /// Local solar time; 0 with `-ang`, as the C global starts.
    st: f64,
    input: Input,
    /// 0 visible W/m^2/sr, 1 solar W/m^2/sr, 2 cd/m^2.
    output: i64,
    clearness: f64,
    brightness: f64,
    diffuse_illuminance: f64,
    direct_illuminance: f64,
    diffuse_irradiance: f64,
    direct_irradiance: f64,
    global_irradiance: f64,
    sun_zenith: f64,
    /// Day of the year; 0 with `-ang`.
    day_number: f64,
    precipitable_water: f64,
    dew_point: f64,
    cloudy: bool,
    sun: bool,
    /// `-b`: only `-defaults` shows it.
    zenith_brightness: f64,
    turbidity: f64,
    ground_reflectance: f64,
    /// `-i`, minutes, a `float` in the C program.
    interval: f32,
    color: bool,
    /// The daylight locus, `float`s in the C program.
    locus: [f32; 11],
    quiet: bool,
    sun_dir: [f64; 3],
    coefficients: [f64; 5],
    diffuse_normalization: f64,
    solar_radiance: f64,
    ground: f64,
    warnings: Vec<String>,
}

/// The sky gendaylit prints for `args` (the words after `gendaylit`); its warnings
/// go to `host`.
pub fn gendaylit(args: &[String], host: &mut dyn crate::Host) -> Result<String, Failure> {
    let mut sky = Daylight::new();
    if args.len() == 1 && args[0] == "-defaults" {
        return Ok(sky.defaults());
    }
    sky.parse(args).map_err(|e| Failure::new(PROGRAM, e))?;
    let mut out = String::from("#");
    out.push_str(&format!(" {PROGRAM}"));
    for a in args {
        out.push(' ');
        out.push_str(a);
    }
    out.push('\n');
    let result = match sky.compute(&mut out) {
        Ok(()) => {
            sky.print(&mut out);
            Ok(())
        }
        Err(Stop::ErrorSky) => {
            sky.print_error_sky(&mut out);
            Ok(())
        }
        Err(Stop::Fail(e)) => Err(e),
    };
    for w in &sky.warnings {
        host.warn(w);
    }
    match result {
        Ok(()) => Ok(out),
        Err(error) => Err(Failure {
            program: PROGRAM.to_string(),
            partial: out,
            error,
        }),
    }
}

/// gendaylit's complaint about its command line, then its usage text, on standard
/// error; it exits 1.
fn usage_error(why: &str) -> GenError {
    let p = PROGRAM;
    GenError::Plain(format!(
        "{p}: Use error - {why}\n\n\
         Usage: {p}      month day hour [-y year]\t[...]\n   \
         or: {p} -ang altitude azimuth\t\t[...]\n\
         \t\tfollowed by:\t  -P          epsilon delta [options]\n\
         \t\t\t or:\t  [-W|-L|-G]  direct_value diffuse_value [options]\n\
         \t\t\t or:\t  -E          global_irradiance [options]\n\n    \
         Description:\n\
         \t-P epsilon delta  (these are the Perez parameters) \n\
         \t-W direct-normal-irradiance diffuse-horizontal-irradiance (W/m^2)\n\
         \t-L direct-normal-illuminance diffuse-horizontal-illuminance (lux)\n\
         \t-G direct-horizontal-irradiance diffuse-horizontal-irradiance (W/m^2)\n\
         \t-E global-horizontal-irradiance (W/m^2)\n\n\
         \tOutput specification with option:\n\
         \t-O [0|1|2]  (0=output in W/m^2/sr visible, 1=output in W/m^2/sr solar, 2=output in candela/m^2), default is 0 \n\
         \tgendaylit version 2.5 (2018/04/18)  \n"
    ))
}

/// C's `%.Nf`, with C's words for infinities and NaN.
fn f(x: f64, precision: usize) -> String {
    if x.is_finite() {
        format!("{x:.precision$}")
    } else {
        radc_lang::c_number::format_g(x, precision)
    }
}

fn e(x: f64, precision: usize) -> String {
    radc_lang::c_number::format_e(x, precision)
}

fn radians(degrees: f64) -> f64 {
    degrees * (PI / 180.0)
}

/// The Tregenza sky: 145 patches in 8 rows from the horizon up, as (zenith angle,
/// azimuth) in degrees of each patch centre.
fn tregenza_patches() -> Vec<(f32, f32)> {
    const ROWS: [(f32, u32); 8] = [
        (84.0, 30),
        (72.0, 30),
        (60.0, 24),
        (48.0, 24),
        (36.0, 18),
        (24.0, 12),
        (12.0, 6),
        (0.0, 1),
    ];
    let mut patches = Vec::with_capacity(145);
    for (theta, count) in ROWS {
        for k in 0..count {
            patches.push((theta, (k * (360 / count)) as f32));
        }
    }
    patches
}

/// Perez's clearness bin (0..7) for epsilon, compared as the `float` gendaylit passes.
fn clearness_bin(epsilon: f64) -> usize {
    let eps = f64::from(epsilon as f32);
    CLEARNESS_BINS.iter().position(|&b| eps < b).unwrap_or(7)
}

/// The five coefficients of the luminance model for a clearness, brightness and solar
/// zenith angle (radians). Perez's correction: for 1.065 < epsilon < 2.8 delta is at
/// least 0.2.
fn model_coefficients(zenith: f64, epsilon: f64, delta: f64) -> [f64; 5] {
    let delta = if epsilon > 1.065 && epsilon < 2.8 && delta < 0.2 {
        0.2
    } else {
        delta
    };
    let bin = clearness_bin(epsilon);
    let x = PEREZ_LUMINANCE[bin].map(|row| row.map(f64::from));
    let linear = |r: &[f64; 4]| r[0] + r[1] * zenith + delta * (r[2] + r[3] * zenith);
    let mut c = [0.0; 5];
    if bin == 0 {
        c[0] = linear(&x[0]);
        c[1] = linear(&x[1]);
        c[4] = linear(&x[4]);
        c[2] = (delta * (x[2][0] + x[2][1] * zenith)).powf(x[2][2]).exp() - x[2][3];
        c[3] = -(delta * (x[3][0] + x[3][1] * zenith)).exp() + x[3][2] + delta * x[3][3];
    } else {
        for (ci, row) in c.iter_mut().zip(&x) {
            *ci = linear(row);
        }
    }
    c
}

/// Perez's relative luminance at zenith angle `dzeta` and angle `gamma` from the sun.
fn relative_luminance(c: &[f64; 5], dzeta: f64, gamma: f64) -> f64 {
    (1.0 + c[0] * (c[1] / dzeta.cos()).exp())
        * (1.0 + c[2] * (c[3] * gamma).exp() + c[4] * gamma.cos() * gamma.cos())
}

impl Efficacy {
    fn value(&self, bin: usize, water: f64, f: f64, g: f64) -> f64 {
        self.a[bin] + self.b[bin] * water + self.c[bin] * f + self.d[bin] * g
    }
}

impl Daylight {
    fn new() -> Self {
        Daylight {
            site: Site::san_francisco(),
            year: 0,
            month: 0,
            day: 0,
            hour: 0.0,
            solar_time: false,
            altitude: 0.0,
            azimuth: 0.0,
            st: 0.0,
            input: Input::Perez,
            output: 0,
            clearness: 0.0,
            brightness: 0.0,
            diffuse_illuminance: 0.0,
            direct_illuminance: 0.0,
            diffuse_irradiance: 0.0,
            direct_irradiance: 0.0,
            global_irradiance: 0.0,
            sun_zenith: 0.0,
            day_number: 0.0,
            precipitable_water: 0.0,
            dew_point: DEFAULT_DEW_POINT,
            cloudy: false,
            sun: true,
            zenith_brightness: -1.0,
            turbidity: 0.1,
            ground_reflectance: 0.2,
            interval: 0.0,
            color: false,
            locus: BERLIN_LOCUS,
            quiet: false,
            sun_dir: [0.0; 3],
            coefficients: [0.0; 5],
            diffuse_normalization: 0.0,
            solar_radiance: 0.0,
            ground: 0.0,
            warnings: Vec::new(),
        }
    }

    fn warn(&mut self, line: String) {
        if !self.quiet {
            self.warnings.push(line);
        }
    }

    fn parse(&mut self, args: &[String]) -> Result<(), GenError> {
        if args.len() < 3 {
            return Err(usage_error("arg count"));
        }
        if args[0] == "-ang" {
            self.altitude = atof(&args[1]) * (PI / 180.0);
            self.azimuth = atof(&args[2]) * (PI / 180.0);
        } else {
            self.month = atoi(&args[0]);
            if !(1..=12).contains(&self.month) {
                return Err(usage_error("bad month"));
            }
            self.day = atoi(&args[1]);
            if !(1..=31).contains(&self.day) {
                return Err(usage_error("bad day"));
            }
            self.hour = atof(&args[2]);
            if !(0.0..24.0).contains(&self.hour) {
                return Err(usage_error("bad hour"));
            }
            self.solar_time = args[2].starts_with('+');
        }
        let mut i = 3;
        while i < args.len() {
            let word = args[i].as_bytes();
            let plus = word.first() == Some(&b'+');
            if !plus && word.first() != Some(&b'-') {
                return Err(usage_error("bad option"));
            }
            // The C program reads past the end of its arguments here; radc stops.
            let mut value = || {
                i += 1;
                args.get(i)
                    .map(|s| atof(s))
                    .ok_or_else(|| usage_error("missing option value"))
            };
            match word.get(1) {
                Some(b'd') => {
                    let td = value()?;
                    self.dew_point = if (-40.0..=40.0).contains(&td) {
                        td
                    } else {
                        DEFAULT_DEW_POINT
                    };
                }
                Some(b's') => {
                    self.cloudy = false;
                    self.sun = plus;
                }
                Some(b'y') => {
                    i += 1;
                    let y = args
                        .get(i)
                        .ok_or_else(|| usage_error("missing option value"))?;
                    self.year = atoi(y);
                }
                Some(b'R') => {
                    // A solar radiance gendaylit reads and never uses.
                    value()?;
                }
                Some(b'c') => {
                    self.cloudy = true;
                    self.sun = false;
                }
                Some(b'C') => {
                    if word.get(2) == Some(&b'I') && word.get(3) == Some(&b'E') {
                        self.locus = CIE_LOCUS;
                    } else {
                        self.color = true;
                    }
                }
                Some(b'l') => {
                    let mut l = [0.0f32; 7];
                    for v in &mut l {
                        *v = value()? as f32;
                    }
                    self.locus = [
                        l[0], l[1], l[2], l[3], l[0], l[1], l[2], l[3], l[4], l[5], l[6],
                    ];
                }
                Some(b't') => self.turbidity = value()?,
                Some(b'w') => self.quiet = true,
                Some(b'b') => self.zenith_brightness = value()?,
                Some(b'g') => self.ground_reflectance = value()?,
                Some(b'a') => self.site.latitude = value()? * (PI / 180.0),
                Some(b'o') => self.site.longitude = value()? * (PI / 180.0),
                Some(b'm') => self.site.meridian = value()? * (PI / 180.0),
                // `output = atof(...)` into an int: truncated toward zero.
                Some(b'O') => self.output = value()? as i64,
                Some(b'P') => {
                    self.input = Input::Perez;
                    self.clearness = value()?;
                    self.brightness = value()?;
                }
                Some(c @ (b'W' | b'L' | b'G')) => {
                    let (direct, diffuse) = (value()?, value()?);
                    if *c == b'L' {
                        self.input = Input::Illuminance;
                        self.direct_illuminance = direct;
                        self.diffuse_illuminance = diffuse;
                    } else {
                        self.input = if *c == b'W' {
                            Input::NormalIrradiance
                        } else {
                            Input::HorizontalIrradiance
                        };
                        self.direct_irradiance = direct;
                        self.diffuse_irradiance = diffuse;
                    }
                }
                Some(b'E') => {
                    self.input = Input::Global;
                    self.global_irradiance = value()?;
                }
                Some(b'i') => self.interval = value()? as f32,
                _ => return Err(usage_error(&format!("unknown option: {}", args[i]))),
            }
            i += 1;
        }
        let site = &self.site;
        if self.month != 0
            && !self.solar_time
            && (site.meridian - site.longitude).abs() > 45.0 * PI / 180.0
        {
            // Printed whatever -w says.
            self.warnings.push(format!(
                "{PROGRAM}: warning: {} hours btwn. standard meridian and longitude",
                f((site.longitude - site.meridian) * (12.0 / PI), 1)
            ));
        }
        self.precipitable_water = (0.07 * self.dew_point - 0.075).exp();
        Ok(())
    }

    /// Sunrise or sunset (local solar time, hours) from the sunset hour angle, which
    /// gendaylit holds in a `float`.
    fn sun_up_hours(&self, sign: f64) -> f64 {
        let jd = julian_day(self.month, self.day);
        let w = (-(self.site.latitude.tan() * declination(jd).tan())) as f32;
        let root = f64::from(1.0f32 - w * w).sqrt();
        12.0 + sign * (PI / 2.0 - f64::from(w).atan2(root)) * 180.0 / (PI * 15.0)
    }

    /// `computesky()`.
    fn compute(&mut self, out: &mut String) -> Result<(), Stop> {
        if self.month != 0 {
            self.sun_position()?;
        }
        if !self.cloudy && self.altitude > 87.0 * PI / 180.0 {
            self.warn(format!(
                "{PROGRAM}: warning - sun too close to zenith, reducing altitude to 87 degrees"
            ));
            self.altitude = 87.0 * PI / 180.0;
        }
        self.sun_dir = self.direction();
        self.sun_zenith = 90.0 - self.altitude * (180.0 / PI);
        self.sky_parameters(out)?;
        self.coefficients = self.checked_coefficients("coeff_lum_perez")?;
        self.normalize()?;
        Ok(())
    }

    fn direction(&self) -> [f64; 3] {
        let (alt, azi) = (self.altitude, self.azimuth);
        [-azi.sin() * alt.cos(), -azi.cos() * alt.cos(), alt.sin()]
    }

    /// The sun's place from date and time, with `-i`'s correction near sunrise and
    /// sunset; an error sky when the sun is down.
    fn sun_position(&mut self) -> Result<(), Stop> {
        let site = &self.site;
        self.st = self.hour;
        let sd = if self.year != 0 {
            let mjd = site.almanac_date(self.year, self.month, self.day, self.hour);
            let (sd, solar) = site.declination_and_time(mjd);
            if !self.solar_time {
                self.st = solar;
            }
            sd
        } else {
            let jd = julian_day(self.month, self.day);
            if !self.solar_time {
                self.st = self.hour + site.solar_time_adjustment(jd);
            }
            declination(jd)
        };
        let (sunrise, sunset) = (self.sun_up_hours(-1.0), self.sun_up_hours(1.0));
        let (m, d, h) = (self.month, self.day, self.hour);
        let mut down = self.st < sunrise || self.st > sunset;
        if self.interval != 0.0 {
            if self.interval < 0.0 {
                return Err(Stop::Fail(GenError::Plain("time interval negative".into())));
            }
            let half = f64::from(self.interval / 120.0);
            let corrected = format!("Solar position corrected at time step {m} {d} {}", f(h, 3));
            if (sunrise - self.st).abs() <= half {
                self.st = (self.st + half + sunrise) / 2.0;
                self.warn(corrected.clone());
            }
            if (sunset - self.st).abs() < half {
                self.st = (self.st - half + sunset) / 2.0;
                self.warn(corrected);
            }
            down = self.st < sunrise - half || self.st > sunset + half;
            if down {
                self.warn(format!(
                    "Warning: sun position too low, printing error sky at {m} {d} {}",
                    f(h, 3)
                ));
            }
        } else if down {
            self.warn(format!(
                "Warning: sun altitude below zero at time step {m} {d} {}, printing error sky",
                f(h, 2)
            ));
        }
        self.altitude = self.site.altitude(sd, self.st);
        self.azimuth = self.site.azimuth(sd, self.st);
        if down {
            return Err(Stop::ErrorSky);
        }
        self.day_number = julian_day(self.month, self.day) as f64;
        Ok(())
    }

    /// Epsilon and delta, and the irradiances and illuminances, from whichever pair
    /// the command line gave.
    fn sky_parameters(&mut self, out: &mut String) -> Result<(), Stop> {
        match self.input {
            Input::Perez => {
                self.hold_parameters();
                self.diffuse_irradiance = self.diffuse_from_brightness();
                self.direct_irradiance = self.direct_from_clearness();
                self.check_irradiances()?;
                self.illuminances()?;
            }
            Input::NormalIrradiance => {
                self.check_irradiances()?;
                self.parameters_from_irradiances()?;
            }
            Input::Illuminance => {
                self.check_illuminances()?;
                self.irradiances_from_illuminances()?;
                self.hold_parameters();
            }
            Input::HorizontalIrradiance => {
                if self.altitude <= 0.0 {
                    self.warn(
                        "Warning: sun altitude < 0, proceed with irradiance values of zero".into(),
                    );
                    self.direct_irradiance = 0.0;
                    self.diffuse_irradiance = 0.0;
                } else {
                    self.direct_irradiance /= self.altitude.sin();
                }
                self.check_irradiances()?;
                self.parameters_from_irradiances()?;
            }
            Input::Global => {
                self.erbs(out);
                self.check_irradiances()?;
                self.parameters_from_irradiances()?;
            }
        }
        Ok(())
    }

    /// Epsilon and delta from the irradiances, then the illuminances.
    fn parameters_from_irradiances(&mut self) -> Result<(), Stop> {
        self.brightness = self.sky_brightness();
        self.clearness = self.sky_clearness();
        self.hold_parameters();
        self.illuminances()
    }

    /// Illuminances by Perez's efficacies, for the outputs that need them.
    fn illuminances(&mut self) -> Result<(), Stop> {
        if self.output == 0 || self.output == 2 {
            self.diffuse_illuminance = self.diffuse_irradiance * self.diffuse_efficacy()?;
            self.direct_illuminance = self.direct_irradiance * self.direct_efficacy();
            self.check_illuminances()?;
        }
        Ok(())
    }

    /// Erbs, Klein and Duffie's diffuse fraction of the global irradiance, as a
    /// function of the clearness index kt; the split is reported in the output.
    fn erbs(&mut self, out: &mut String) {
        if self.altitude <= 0.0 {
            if self.global_irradiance > 50.0 {
                self.warn(
                    "Warning: global irradiance higher than 50 W/m^2 while the sun altitude is lower than zero"
                        .into(),
                );
            }
            self.global_irradiance = 0.0;
            self.diffuse_irradiance = 0.0;
            self.direct_irradiance = 0.0;
            return;
        }
        let s0 = SOLAR_CONSTANT_E * self.eccentricity() * self.altitude.sin();
        if self.global_irradiance > s0 {
            self.warn(
                "Warning: global irradiance is higher than the time-dependent solar constant s0"
                    .into(),
            );
            self.global_irradiance = s0 * 0.999;
        }
        let g = self.global_irradiance;
        let kt = g / s0;
        if kt <= 0.22 {
            self.diffuse_irradiance = g * (1.0 - 0.09 * kt);
        } else if kt <= 0.8 {
            self.diffuse_irradiance = g
                * (0.9511 - 0.1604 * kt + 4.388 * kt.powi(2) - 16.638 * kt.powi(3)
                    + 12.336 * kt.powi(4));
        } else if kt < 1.0 {
            self.diffuse_irradiance = g * 0.165;
        }
        self.direct_irradiance = g - self.diffuse_irradiance;
        out.push_str(&format!(
            "# erbs_s0, erbs_kt, irr_dir_h, irr_diff: {} {} {} {}\n",
            f(s0, 3),
            f(kt, 3),
            f(self.direct_irradiance, 3),
            f(self.diffuse_irradiance, 3)
        ));
        out.push_str("# WARNING: the -E option is only recommended for a rough estimation!\n");
        self.direct_irradiance /= self.altitude.sin();
    }

    /// `check_parametrization()`: epsilon and delta held in range (a too-high epsilon
    /// just under the top).
    fn hold_parameters(&mut self) {
        if self.clearness < CLEARNESS_MIN {
            self.clearness = CLEARNESS_MIN;
        }
        if self.clearness > CLEARNESS_MAX {
            self.clearness = CLEARNESS_MAX - 0.001;
        }
        self.brightness = self.brightness.clamp(BRIGHTNESS_MIN, BRIGHTNESS_MAX);
    }

    fn check_irradiances(&mut self) -> Result<(), Stop> {
        if self.direct_irradiance < 0.0 {
            self.warn("Warning: direct irradiance < 0. Using 0.0".into());
            self.direct_irradiance = 0.0;
        }
        if self.diffuse_irradiance < 0.0 {
            self.warn("Warning: diffuse irradiance < 0. Using 0.0".into());
            self.diffuse_irradiance = 0.0;
        }
        if self.direct_irradiance + self.diffuse_irradiance == 0.0 && self.altitude > 0.0 {
            self.warn("Warning: zero irradiance at sun altitude > 0, printing error sky".into());
            return Err(Stop::ErrorSky);
        }
        if self.direct_irradiance > SOLAR_CONSTANT_E {
            self.warn("Warning: direct irradiance exceeds solar constant".into());
            return Err(Stop::ErrorSky);
        }
        Ok(())
    }

    fn check_illuminances(&mut self) -> Result<(), Stop> {
        if self.direct_illuminance < 0.0 {
            self.warn("Warning: direct illuminance < 0. Using 0.0".into());
            self.direct_illuminance = 0.0;
        }
        if self.diffuse_illuminance < 0.0 {
            self.warn("Warning: diffuse illuminance < 0. Using 0.0".into());
            self.diffuse_illuminance = 0.0;
        }
        if self.direct_illuminance + self.diffuse_illuminance == 0.0 && self.altitude > 0.0 {
            self.warn("Warning: zero illuminance at sun altitude > 0, printing error sky".into());
            return Err(Stop::ErrorSky);
        }
        if self.direct_illuminance > SOLAR_CONSTANT_L {
            self.warn("Warning: direct illuminance exceeds solar constant".into());
            return Err(Stop::ErrorSky);
        }
        Ok(())
    }

    /// `get_eccentricity()`: (R0/R)^2 on the day of the year (Spencer's series).
    fn eccentricity(&self) -> f64 {
        let a = (self.day_number - 1.0) * (2.0 * PI / 365.0);
        1.00011
            + 0.034221 * a.cos()
            + 0.00128 * a.sin()
            + 0.000719 * (2.0 * a).cos()
            + 0.000077 * (2.0 * a).sin()
    }

    /// `air_mass()`: Kasten's relative optical air mass; the zenith angle is held at
    /// 90 degrees (for the rest of the run, as the C program changes its global).
    fn air_mass(&mut self) -> f64 {
        if self.sun_zenith > 90.0 {
            self.warn("Warning: air mass has reached the maximal value".into());
            self.sun_zenith = 90.0;
        }
        let z = self.sun_zenith;
        1.0 / ((z * (PI / 180.0)).cos() + 0.15 * ((93.885 - z).ln() * -1.253).exp())
    }

    /// Perez's delta: diffuse irradiance times air mass over the extraterrestrial.
    fn sky_brightness(&mut self) -> f64 {
        self.diffuse_irradiance * self.air_mass() / (SOLAR_CONSTANT_E * self.eccentricity())
    }

    /// `1.041 Z^3`, the zenith term of Perez's epsilon, its constants gathered as the
    /// reference build (-ffast-math) gathers them.
    fn zenith_cube(&self) -> f64 {
        let z = self.sun_zenith;
        z * z * z * (1.041 * (PI / 180.0) * (PI / 180.0) * (PI / 180.0))
    }

    /// Perez's epsilon.
    fn sky_clearness(&self) -> f64 {
        let (dif, dir) = (self.diffuse_irradiance, self.direct_irradiance);
        ((dif + dir) / dif + self.zenith_cube()) / (1.0 + self.zenith_cube())
    }

    fn diffuse_from_brightness(&mut self) -> f64 {
        self.brightness / self.air_mass() * (SOLAR_CONSTANT_E * self.eccentricity())
    }

    fn direct_from_clearness(&mut self) -> f64 {
        let diffuse = self.diffuse_from_brightness();
        diffuse * ((self.clearness - 1.0) * (1.0 + self.zenith_cube()))
    }

    /// The bin of the efficacy models: `[1, 1.065)`, ... `[6.2, top)`.
    fn efficacy_bin(&self, top: f64) -> Option<usize> {
        let eps = self.clearness;
        if eps.is_nan() {
            // A sun below the horizon with -G or -E makes epsilon 0/0. The reference
            // build (-ffast-math) then takes a bin rather than the error sky; the
            // efficacy multiplies zero irradiances, so which bin does not show.
            return Some(7);
        }
        let mut bounds = vec![1.0];
        bounds.extend(CLEARNESS_BINS);
        bounds.push(top);
        (0..8)
            .rev()
            .find(|&k| eps >= bounds[k] && eps < bounds[k + 1])
    }

    /// Perez's diffuse horizontal luminous efficacy; an error sky past the top bin.
    fn diffuse_efficacy(&mut self) -> Result<f64, Stop> {
        self.hold_parameters();
        let Some(bin) = self.efficacy_bin(CLEARNESS_MAX) else {
            self.warn(format!(
                "Warning: sky clearness (= {}) too high, printing error sky",
                f(self.clearness, 3)
            ));
            return Err(Stop::ErrorSky);
        };
        let z = (self.sun_zenith * (PI / 180.0)).cos();
        Ok(DIFFUSE_EFFICACY.value(bin, self.precipitable_water, z, self.brightness.ln()))
    }

    /// Perez's direct normal luminous efficacy, never negative.
    fn direct_efficacy(&self) -> f64 {
        // Its bins reach 12.1, so an epsilon held in range always has one.
        let bin = self.efficacy_bin(12.1).unwrap_or(7);
        let z = (self.sun_zenith * (5.73 * PI / 180.0) - 5.0).exp();
        DIRECT_EFFICACY
            .value(bin, self.precipitable_water, z, self.brightness)
            .max(0.0)
    }

    /// `illu_to_irra_index()`: irradiances from illuminances, by nine rounds of
    /// Perez's efficacies starting from the solar constants' ratio.
    fn irradiances_from_illuminances(&mut self) -> Result<(), Stop> {
        self.diffuse_irradiance = self.diffuse_illuminance * SOLAR_CONSTANT_E / SOLAR_CONSTANT_L;
        self.direct_irradiance = self.direct_illuminance * SOLAR_CONSTANT_E / SOLAR_CONSTANT_L;
        self.clearness = self.sky_clearness();
        self.brightness = self.sky_brightness();
        self.hold_parameters();
        // The C loop also runs while epsilon and delta are in range, which holding
        // them guarantees: it always stops at its count.
        for _ in 0..9 {
            self.diffuse_irradiance = self.diffuse_illuminance / self.diffuse_efficacy()?;
            let direct = self.direct_efficacy();
            self.direct_irradiance = if direct < 0.1 {
                0.0
            } else {
                self.direct_illuminance / direct
            };
            self.brightness = self.sky_brightness();
            self.clearness = self.sky_clearness();
            self.hold_parameters();
        }
        Ok(())
    }

    /// The model's coefficients for this sky; a failure for an epsilon outside the
    /// bins (only 12.01 itself, which holding leaves as it is).
    fn checked_coefficients(&self, function: &str) -> Result<[f64; 5], Stop> {
        let eps = self.clearness;
        // Written as the C test is, so that a NaN epsilon (see `efficacy_bin`) passes.
        #[allow(clippy::manual_range_contains)]
        if eps < CLEARNESS_MIN || eps >= CLEARNESS_MAX {
            return Err(Stop::Fail(GenError::Plain(format!(
                "Error: epsilon out of range in function {function}!"
            ))));
        }
        Ok(model_coefficients(
            radians(self.sun_zenith),
            eps,
            self.brightness,
        ))
    }

    /// The diffuse normalization (the model integrated over the Tregenza patches
    /// against the diffuse horizontal value), the sun's radiance and the ground's.
    fn normalize(&mut self) -> Result<(), Stop> {
        let z = radians(self.sun_zenith);
        let c = self.checked_coefficients("calc_rel_lum_perez")?;
        let mut integral = 0.0;
        for (theta, phi) in tregenza_patches() {
            let (theta, phi) = (radians(f64::from(theta)), radians(f64::from(phi)));
            let cos_gamma = z.cos() * theta.cos() + z.sin() * theta.sin() * phi.cos();
            let gamma = if cos_gamma > 1.0 && cos_gamma < 1.1 {
                0.0
            } else if cos_gamma > 1.1 {
                return Err(Stop::Fail(GenError::Plain(
                    "error in calculation of gamma (angle between point and sun".into(),
                )));
            } else {
                cos_gamma.acos()
            };
            // Each patch's luminance is kept in a `float`.
            let lv = relative_luminance(&c, theta, gamma) as f32;
            integral += f64::from(lv) * theta.cos();
        }
        let integral = integral * (2.0 * PI / 145.0);
        self.diffuse_normalization = match self.output {
            0 => self.diffuse_illuminance / integral / WHITE_EFFICACY,
            1 => self.diffuse_irradiance / integral,
            2 => self.diffuse_illuminance / integral,
            _ => {
                return Err(Stop::Fail(GenError::Plain(
                    "Wrong output specification.".into(),
                )));
            }
        };
        let sun_solid_angle = 2.0 * PI * (1.0 - (HALF_SUN_ANGLE * PI / 180.0).cos());
        self.solar_radiance = match self.output {
            0 => self.direct_illuminance / sun_solid_angle / WHITE_EFFICACY,
            1 => self.direct_irradiance / sun_solid_angle,
            _ => self.direct_illuminance / sun_solid_angle,
        };
        self.ground = self.ground_radiance(&c, z);
        if self.coefficients[1] > 0.0 {
            self.warn(format!(
                "Warning: positive Perez parameter B (= {}), printing error sky",
                f(self.coefficients[1], 6)
            ));
            return Err(Stop::ErrorSky);
        }
        Ok(())
    }

    /// The ground: the zenith luminance times gensky's CIE normalization for clear
    /// (epsilon >= 6) or intermediate skies (0.777778 for an overcast epsilon of 1),
    /// plus the sun's share, times the ground reflectance.
    fn ground_radiance(&self, c: &[f64; 5], z: f64) -> f64 {
        let zenith = relative_luminance(c, 0.0, z) * self.diffuse_normalization;
        let alt = self.altitude;
        let eps = self.clearness;
        // Epsilon is held at 1 or more, so these three cases are all there are
        // (gendaylit.c leaves the factor unset below 1).
        let norm = if eps >= 6.0 {
            let f2 = 0.274
                * (0.91
                    + 10.0 * (-3.0 * (PI / 2.0 - alt)).exp()
                    + 0.45 * self.sun_dir[2] * self.sun_dir[2]);
            cie_normalization(false, alt) / f2 / PI
        } else if eps > 1.0 {
            let f2 = (2.739 + 0.9891 * (0.3119 + 2.6 * alt).sin())
                * (-(PI / 2.0 - alt) * (0.4441 + 1.48 * alt)).exp();
            cie_normalization(true, alt) / f2 / PI
        } else {
            0.777778
        };
        let mut ground = zenith * norm;
        if self.sun && eps > 1.0 {
            ground += 6.8e-5 / PI * self.solar_radiance * self.sun_dir[2];
        }
        ground * self.ground_reflectance
    }

    /// `printsky()`.
    fn print(&mut self, out: &mut String) {
        self.print_sun_comments(out);
        out.push_str(&format!(
            "# epsilon, delta, atmospheric precipitable water content : {} {} {} \n",
            f(self.clearness, 4),
            f(self.brightness, 4),
            f(self.precipitable_water, 4)
        ));
        let d = self.sun_dir;
        if self.sun {
            // A NaN epsilon prints the sun's (zero) radiance, as the
            // reference build's comparison does.
            let s = if self.clearness > 1.0 || self.clearness.is_nan() {
                let r = e(self.solar_radiance, 3);
                format!("{r} {r} {r}")
            } else {
                "0.0 0.0 0.0".to_string()
            };
            out.push_str(&format!("\nvoid light solar\n0\n0\n3 {s}\n"));
            out.push_str(&format!(
                "\nsolar source sun\n0\n0\n4 {} {} {} {}\n",
                f(d[0], 6),
                f(d[1], 6),
                f(d[2], 6),
                f(2.0 * HALF_SUN_ANGLE, 6)
            ));
        }
        if self.color && self.clearness < 4.5 && self.clearness > 1.065 {
            // Not silenced by -w.
            self.warnings.extend([
                format!(
                    "\twarning: sky clearness(epsilon)= {} ",
                    f(self.clearness, 6)
                ),
                "\twarning: intermediate sky!! ".to_string(),
                "\twarning: color model for intermediate sky pending  ".to_string(),
                "\twarning: no color output ! ".to_string(),
            ]);
            self.color = false;
        }
        let c = self.coefficients.map(|x| f(x, 6));
        let common = format!(
            "{} {} {} {} {} {} {} {} {} {}",
            e(self.diffuse_normalization, 3),
            e(self.ground, 3),
            c[0],
            c[1],
            c[2],
            c[3],
            c[4],
            f(d[0], 6),
            f(d[1], 6),
            f(d[2], 6)
        );
        if self.color {
            let locus: Vec<String> = self.locus.iter().map(|&x| f(f64::from(x), 6)).collect();
            out.push_str(&format!(
                "\nvoid colorfunc skyfunc\n4 skybright_r skybright_g skybright_b perezlum_c.cal\n0\n22 {common} {} {}\n",
                f(self.clearness, 6),
                locus.join(" ")
            ));
        } else {
            out.push_str(&format!(
                "\nvoid brightfunc skyfunc\n2 skybright perezlum.cal\n0\n10 {common} \n"
            ));
        }
    }

    fn print_sun_comments(&self, out: &mut String) {
        out.push_str(&format!("# Local solar time: {}\n", f(self.st, 2)));
        out.push_str(&format!(
            "# Solar altitude and azimuth: {} {}\n",
            f(self.altitude * (180.0 / PI), 1),
            f(self.azimuth * (180.0 / PI), 1)
        ));
    }

    /// `print_error_sky()`: a sky of zero brightness, the sun's direction kept.
    fn print_error_sky(&mut self, out: &mut String) {
        self.sun_dir = self.direction();
        self.print_sun_comments(out);
        let d = self.sun_dir;
        out.push_str(&format!(
            "\nvoid brightfunc skyfunc\n2 skybright perezlum.cal\n0\n10 0.00 0.00  0.000 0.000 0.000 0.000 0.000  {} {} {} \n",
            f(d[0], 6),
            f(d[1], 6),
            f(d[2], 6)
        ));
    }

    fn defaults(&self) -> String {
        let s = &self.site;
        format!(
            "-g {}\t\t\t# Ground plane reflectance\n\
             -t {}\t\t\t# Atmospheric betaturbidity\n\
             -a {}\t\t\t# Site latitude (degrees)\n\
             -o {}\t\t\t# Site longitude (degrees)\n\
             -m {}\t\t\t# Standard meridian (degrees)\n",
            f(self.ground_reflectance, 6),
            f(self.turbidity, 6),
            f(s.latitude * (180.0 / PI), 6),
            f(s.longitude * (180.0 / PI), 6),
            f(s.meridian * (180.0 / PI), 6)
        )
    }
}

/// gensky's `normsc()`: the polynomial fit, in the altitude, of the CIE clear or
/// intermediate sky's horizontal illuminance relative to its zenith luminance.
fn cie_normalization(intermediate: bool, altitude: f64) -> f64 {
    let coefficients: [f64; 5] = if intermediate {
        [3.5556, -2.7152, -1.3081, 1.0660, 0.60227]
    } else {
        [2.766521, 0.547665, -0.369832, 0.009237, 0.059229]
    };
    let x = (altitude - PI / 4.0) / (PI / 4.0);
    coefficients[..4]
        .iter()
        .rev()
        .fold(coefficients[4], |acc, &c| acc * x + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tregenza_sky_has_145_patches_from_the_horizon_up() {
        let p = tregenza_patches();
        assert_eq!(p.len(), 145);
        assert_eq!(p[0], (84.0, 0.0));
        assert_eq!(p[31], (72.0, 12.0));
        assert_eq!(p[61], (60.0, 15.0));
        assert_eq!(p[144], (0.0, 0.0));
    }

    #[test]
    fn epsilon_is_binned_as_a_float() {
        // 2.8 and 6.2 as floats are just below themselves: gendaylit puts an epsilon
        // of exactly 2.8 in the fifth bin and 6.2 in the seventh, not the next ones.
        assert_eq!(clearness_bin(2.8), 4);
        assert_eq!(clearness_bin(2.8000001), 5);
        assert_eq!(clearness_bin(6.2), 6);
        assert_eq!(clearness_bin(1.0649), 0);
        assert_eq!(clearness_bin(12.0), 7);
    }
}
