//! `gensky month day hour [options]`, `gensky -ang altitude azimuth [options]`,
//! `gensky -defaults`
//!
//! Reproduces Radiance's `src/gen/gensky.c` and its solar geometry (`src/gen/sun.c`):
//! a CIE clear (`+s`/`-s`), overcast (`-c`), uniform (`-u`) or intermediate (`+i`/`-i`)
//! sky as a `skybright.cal` brightfunc, with a `light`/`source` sun for sunny skies.
//! The site defaults to San Francisco (latitude 0.66 rad, longitude 2.13 rad west,
//! meridian 120 degrees west). With `-y year` the sun comes from Michalsky's almanac
//! algorithm; without, from the older Julian-day approximations.

use crate::sun::{Site, declination, julian_day};
use crate::words::atoi;
use crate::{GenError, command_comment};
use radc_lang::c_number::atof;
use std::f64::consts::PI;

const USAGE: &str = "gensky month day hour [options]\n   Or: gensky -ang altitude azimuth [options]\n   Or: gensky -defaults";
/// Luminous efficacies (lm/W) from `src/common/color.h`: D65 for sky, illuminant B
/// for the sun.
const SKY_EFFICACY: f64 = 203.0;
const SUN_EFFICACY: f64 = 208.0;

/// Time zones gensky knows, with their standard meridians (degrees west). The first
/// match wins, so `AST` and `NDT` mean their North American zones.
const TIME_ZONES: &[(&str, f64)] = &[
    ("YST", 135.0),
    ("YDT", 120.0),
    ("PST", 120.0),
    ("PDT", 105.0),
    ("MST", 105.0),
    ("MDT", 90.0),
    ("CST", 90.0),
    ("CDT", 75.0),
    ("EST", 75.0),
    ("EDT", 60.0),
    ("AST", 60.0),
    ("ADT", 45.0),
    ("NST", 52.5),
    ("NDT", 37.5),
    ("GMT", 0.0),
    ("BST", -15.0),
    ("CET", -15.0),
    ("CEST", -30.0),
    ("EET", -30.0),
    ("EEST", -45.0),
    ("AST", -45.0),
    ("ADT", -60.0),
    ("GST", -60.0),
    ("GDT", -75.0),
    ("IST", -82.5),
    ("IDT", -97.5),
    ("JST", -135.0),
    ("NDT", -150.0),
    ("NZST", -180.0),
    ("NZDT", -195.0),
];

#[derive(Clone, Copy, PartialEq)]
enum SkyType {
    Clear = 1,
    Overcast = 2,
    Uniform = 3,
    Intermediate = 4,
}

/// Which unit a brightness was given in: none (computed), radiance, irradiance.
#[derive(Clone, Copy, PartialEq)]
enum Given {
    No,
    Radiance,
    Irradiance,
}

struct Sky {
    site: Site,
    year: i64,
    month: i64,
    day: i64,
    hour: f64,
    solar_time: bool,
    altitude: f64,
    azimuth: f64,
    kind: SkyType,
    sun: bool,
    zenith: f64,
    zenith_given: Given,
    turbidity: f64,
    ground_reflectance: f64,
    solar: f64,
    solar_given: Given,
    /// Lines for standard error.
    warnings: Vec<&'static str>,
}

/// The sky gensky prints for `args` (the words after `gensky`).
/// gensky's warning (the sun moved down from the zenith) goes to `host` as well as
/// into the output's comments, as the C program prints it on both.
pub fn gensky(args: &[String], host: &mut dyn crate::Host) -> Result<String, GenError> {
    let usage = |why: &str| GenError::Usage(format!("{why}\n{USAGE}"));
    let mut sky = Sky {
        site: Site::san_francisco(),
        year: 0,
        month: 0,
        day: 0,
        hour: 0.0,
        solar_time: false,
        altitude: 0.0,
        azimuth: 0.0,
        kind: SkyType::Clear,
        sun: true,
        zenith: 0.0,
        zenith_given: Given::No,
        turbidity: 2.45,
        ground_reflectance: 0.2,
        solar: 0.0,
        solar_given: Given::No,
        warnings: Vec::new(),
    };
    if args.len() == 1 && args[0] == "-defaults" {
        return Ok(sky.defaults());
    }
    if args.len() < 3 {
        return Err(usage("arg count"));
    }
    let mut got_meridian = false;
    if args[0] == "-ang" {
        sky.altitude = atof(&args[1]) * (PI / 180.0);
        sky.azimuth = atof(&args[2]) * (PI / 180.0);
    } else {
        sky.month = atoi(&args[0]);
        if !(1..=12).contains(&sky.month) {
            return Err(usage("bad month"));
        }
        sky.day = atoi(&args[1]);
        if !(1..=31).contains(&sky.day) {
            return Err(usage("bad day"));
        }
        got_meridian = sky.parse_hour(&args[2])?;
    }
    let mut i = 3;
    while i < args.len() {
        let opt = args[i].as_bytes();
        let plus = opt.first() == Some(&b'+');
        if !plus && opt.first() != Some(&b'-') {
            return Err(usage("bad option"));
        }
        let mut value = || {
            i += 1;
            args.get(i).ok_or_else(|| usage("missing option value"))
        };
        match opt.get(1) {
            Some(b's') => {
                sky.kind = SkyType::Clear;
                sky.sun = plus;
            }
            Some(b'y') => sky.year = atoi(value()?),
            Some(c @ (b'r' | b'R')) => {
                sky.solar_given = if *c == b'R' {
                    Given::Irradiance
                } else {
                    Given::Radiance
                };
                sky.solar = atof(value()?);
            }
            Some(b'c') => sky.kind = SkyType::Overcast,
            Some(b'u') => sky.kind = SkyType::Uniform,
            Some(b'i') => {
                sky.kind = SkyType::Intermediate;
                sky.sun = plus;
            }
            Some(b't') => sky.turbidity = atof(value()?),
            Some(c @ (b'b' | b'B')) => {
                sky.zenith_given = if *c == b'B' {
                    Given::Irradiance
                } else {
                    Given::Radiance
                };
                sky.zenith = atof(value()?);
            }
            Some(b'g') => sky.ground_reflectance = atof(value()?),
            Some(b'a') => sky.site.latitude = atof(value()?) * (PI / 180.0),
            Some(b'o') => sky.site.longitude = atof(value()?) * (PI / 180.0),
            Some(b'm') => {
                // A time zone on the hour overrides -m.
                let m = atof(value()?);
                if !got_meridian {
                    sky.site.meridian = m * (PI / 180.0);
                }
            }
            _ => return Err(usage(&format!("unknown option: {}", args[i]))),
        }
        i += 1;
    }
    let mut out = command_comment("gensky", args);
    let derived = sky.compute(&mut out);
    sky.print(&derived, &mut out);
    for w in &sky.warnings {
        host.warn(w);
    }
    Ok(out)
}

impl Sky {
    /// `cvthour()`: `H`, `H.h`, `H:MM`, a leading `+` for solar time, and an optional
    /// time zone after standard time. True if a time zone set the meridian.
    fn parse_hour(&mut self, hs: &str) -> Result<bool, GenError> {
        let b = hs.as_bytes();
        let mut cp = 0;
        self.solar_time = b.first() == Some(&b'+');
        if self.solar_time {
            cp += 1;
        }
        let skip_digits = |mut k: usize| {
            while b.get(k).is_some_and(u8::is_ascii_digit) {
                k += 1;
            }
            k
        };
        cp = skip_digits(cp);
        if b.get(cp) == Some(&b':') {
            cp += 1;
            self.hour = atoi(hs) as f64 + atoi(&hs[cp..]) as f64 / 60.0;
        } else {
            self.hour = atof(hs);
            if b.get(cp) == Some(&b'.') {
                cp += 1;
            }
        }
        cp = skip_digits(cp);
        let zone = &b[cp..];
        if zone.is_empty() {
            return Ok(false);
        }
        if self.solar_time || !zone[0].is_ascii_alphabetic() {
            return Err(GenError::Invalid(format!("bad time format: {hs}")));
        }
        // gensky upper-cases by clearing bit 5, for every character.
        let upper: Vec<u8> = zone.iter().map(|c| c & !0x20).collect();
        match TIME_ZONES.iter().find(|(name, _)| name.as_bytes() == upper) {
            Some(&(_, meridian)) => {
                self.site.meridian = f64::from(meridian as f32) * (PI / 180.0);
                Ok(true)
            }
            // gensky lists the zones it knows after the complaint.
            None => Err(GenError::Invalid(format!(
                "unknown time zone: {}\nKnown time zones:\n\t{}",
                String::from_utf8_lossy(zone),
                TIME_ZONES
                    .iter()
                    .map(|(name, _)| *name)
                    .collect::<Vec<_>>()
                    .join(" ")
            ))),
        }
    }

    fn overcast(&self) -> bool {
        matches!(self.kind, SkyType::Overcast | SkyType::Uniform)
    }

    /// `computesky()`, writing its comment lines to `out`.
    fn compute(&mut self, out: &mut String) -> Derived {
        let site = &self.site;
        if self.month != 0 {
            let mut st = self.hour;
            let sd = if self.year != 0 {
                let mjd = site.almanac_date(self.year, self.month, self.day, self.hour);
                let (sd, solar) = site.declination_and_time(mjd);
                if !self.solar_time {
                    st = solar;
                }
                sd
            } else {
                let jd = julian_day(self.month, self.day);
                if !self.solar_time {
                    st = self.hour + site.solar_time_adjustment(jd);
                }
                declination(jd)
            };
            self.altitude = site.altitude(sd, st);
            self.azimuth = site.azimuth(sd, st);
            out.push_str(&format!("# Local solar time: {st:.2}\n"));
            out.push_str(&format!(
                "# Solar altitude and azimuth: {:.1} {:.1}\n",
                180.0 / PI * self.altitude,
                180.0 / PI * self.azimuth
            ));
        }
        if !self.overcast() && self.altitude > 87.0 * PI / 180.0 {
            out.push_str("# warning - sun too close to zenith, reducing altitude to 87 degrees\n");
            self.warnings
                .push("gensky: warning - sun too close to zenith, reducing altitude to 87 degrees");
            self.altitude = 87.0 * PI / 180.0;
        }
        let (alt, azi) = (self.altitude, self.azimuth);
        let dir = [-azi.sin() * alt.cos(), -azi.cos() * alt.cos(), alt.sin()];
        let mut f2 = 0.0;
        let norm = match self.kind {
            SkyType::Uniform => 1.0,
            SkyType::Overcast => 0.777778,
            SkyType::Clear => {
                f2 = 0.274
                    * (0.91 + 10.0 * (-3.0 * (PI / 2.0 - alt)).exp() + 0.45 * dir[2] * dir[2]);
                self.normalization() / f2 / PI
            }
            SkyType::Intermediate => {
                f2 = (2.739 + 0.9891 * (0.3119 + 2.6 * alt).sin())
                    * (-(PI / 2.0 - alt) * (0.4441 + 1.48 * alt)).exp();
                self.normalization() / f2 / PI
            }
        };
        match self.zenith_given {
            Given::Irradiance => self.zenith /= norm * PI,
            Given::Radiance => {}
            Given::No => {
                let mut z = if self.overcast() {
                    8.6 * dir[2] + 0.123
                } else {
                    (1.376 * self.turbidity - 1.81) * alt.tan() + 0.38
                };
                if self.kind == SkyType::Intermediate {
                    z = (z + 8.6 * dir[2] + 0.123) / 2.0;
                }
                self.zenith = if z < 0.0 {
                    0.0
                } else {
                    z * (1000.0 / SKY_EFFICACY)
                };
            }
        }
        let mut ground = self.zenith * norm;
        out.push_str(&format!("# Ground ambient level: {ground:.1}\n"));
        if !self.overcast() && dir[2] > 0.0 && (self.solar_given == Given::No || self.solar > 0.0) {
            match self.solar_given {
                Given::Irradiance => self.solar /= 5.98e-5 * dir[2],
                Given::Radiance => {}
                Given::No => {
                    self.solar = 1.5e9 / SUN_EFFICACY * (1.147 - 0.147 / dir[2].max(0.16));
                    if self.kind == SkyType::Intermediate {
                        self.solar *= 0.15;
                    }
                }
            }
            ground += 6e-5 / PI * self.solar * dir[2];
        } else {
            self.sun = false;
        }
        Derived {
            dir,
            f2,
            ground: ground * self.ground_reflectance,
        }
    }

    /// `normsc()`: polynomial fit of the normalization factor in the altitude.
    fn normalization(&self) -> f64 {
        let coefficients: [f64; 5] = if self.kind == SkyType::Intermediate {
            [3.5556, -2.7152, -1.3081, 1.0660, 0.60227]
        } else {
            [2.766521, 0.547665, -0.369832, 0.009237, 0.059229]
        };
        let x = (self.altitude - PI / 4.0) / (PI / 4.0);
        coefficients.iter().rev().fold(0.0, |acc, &c| acc * x + c)
    }

    fn print(&self, d: &Derived, out: &mut String) {
        if self.sun {
            let s = c_e(self.solar, 3);
            out.push_str(&format!("\nvoid light solar\n0\n0\n3 {s} {s} {s}\n"));
            out.push_str(&format!(
                "\nsolar source sun\n0\n0\n4 {:.6} {:.6} {:.6} 0.5\n",
                d.dir[0], d.dir[1], d.dir[2]
            ));
        }
        out.push_str("\nvoid brightfunc skyfunc\n2 skybr skybright.cal\n0\n");
        if self.overcast() {
            out.push_str(&format!(
                "3 {} {} {}\n",
                self.kind as i32,
                c_e(self.zenith, 3),
                c_e(d.ground, 3)
            ));
        } else {
            out.push_str(&format!(
                "7 {} {} {} {} {:.6} {:.6} {:.6}\n",
                self.kind as i32,
                c_e(self.zenith, 3),
                c_e(d.ground, 3),
                c_e(d.f2, 3),
                d.dir[0],
                d.dir[1],
                d.dir[2]
            ));
        }
    }

    fn defaults(&self) -> String {
        let mut out = String::from("+s\t\t\t\t# Sunny sky with sun\n");
        out.push_str(&format!(
            "-g {:.6}\t\t\t# Ground plane reflectance\n",
            self.ground_reflectance
        ));
        out.push_str(&format!(
            "-t {:.6}\t\t\t# Atmospheric turbidity\n",
            self.turbidity
        ));
        let s = &self.site;
        out.push_str(&format!(
            "-a {:.6}\t\t\t# Site latitude (degrees)\n",
            s.latitude * (180.0 / PI)
        ));
        out.push_str(&format!(
            "-o {:.6}\t\t\t# Site longitude (degrees)\n",
            s.longitude * (180.0 / PI)
        ));
        out.push_str(&format!(
            "-m {:.6}\t\t\t# Standard meridian (degrees)\n",
            s.meridian * (180.0 / PI)
        ));
        out
    }
}

/// Values `computesky()` leaves in globals for `printsky()`.
struct Derived {
    dir: [f64; 3],
    f2: f64,
    ground: f64,
}

/// `%.Pe` as C prints it.
fn c_e(x: f64, precision: usize) -> String {
    radc_lang::c_number::format_e(x, precision)
}
