//! The solar geometry of Radiance's sky generators (`src/gen/sun.c`), shared by gensky
//! and gendaylit: day of the year, declination, the standard-to-solar time correction,
//! the sun's altitude and azimuth, and Michalsky's almanac algorithm for `-y year`.

use std::f64::consts::PI;

const DEG: f64 = PI / 180.0;

/// The site: radians, longitude and meridian positive west.
pub(crate) struct Site {
    pub(crate) latitude: f64,
    pub(crate) longitude: f64,
    pub(crate) meridian: f64,
}

impl Site {
    /// sun.c's defaults: San Francisco (latitude 0.66 rad, longitude 2.13 rad west,
    /// meridian 120 degrees west).
    pub(crate) fn san_francisco() -> Self {
        Site {
            latitude: 0.66,
            longitude: 2.13,
            meridian: 120.0 * DEG,
        }
    }
}

/// `sdec()`: the solar declination (radians) on day `jd` of the year.
pub(crate) fn declination(jd: i64) -> f64 {
    0.4093 * ((2.0 * PI / 365.0) * (jd - 81) as f64).sin()
}

/// `jdate()`: day of the year, ignoring leap years.
pub(crate) fn julian_day(month: i64, day: i64) -> i64 {
    const START: [i64; 12] = [0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334];
    START[(month - 1).clamp(0, 11) as usize] + day
}

impl Site {
    /// `stadj()`: hours from standard to solar time.
    pub(crate) fn solar_time_adjustment(&self, jd: i64) -> f64 {
        0.170 * ((4.0 * PI / 373.0) * (jd - 80) as f64).sin()
            - 0.129 * ((2.0 * PI / 355.0) * (jd - 8) as f64).sin()
            + (12.0 / PI) * (self.meridian - self.longitude)
    }

    /// `salt()`.
    pub(crate) fn altitude(&self, sd: f64, st: f64) -> f64 {
        (self.latitude.sin() * sd.sin() - self.latitude.cos() * sd.cos() * (st * (PI / 12.0)).cos())
            .asin()
    }

    /// `sazi()`.
    pub(crate) fn azimuth(&self, sd: f64, st: f64) -> f64 {
        -(sd.cos() * (st * (PI / 12.0)).sin()).atan2(
            -self.latitude.cos() * sd.sin()
                - self.latitude.sin() * sd.cos() * (st * (PI / 12.0)).cos(),
        )
    }

    /// `mjdate()`: days from noon UT, 1 January 2000.
    pub(crate) fn almanac_date(&self, year: i64, month: i64, day: i64, hour: f64) -> f64 {
        let mut jd = julian_day(month, day);
        jd += i64::from(month > 2 && year & 3 == 0);
        jd += (year - 1949) * 365 + (year - 1949) / 4;
        let hour = hour + self.meridian * (12.0 / PI);
        jd as f64 + hour * (1.0 / 24.0) + (2432916.5 - 2451545.0)
    }

    /// `msdec()`: solar declination and local solar time from the almanac date.
    pub(crate) fn declination_and_time(&self, mjd: f64) -> (f64, f64) {
        let l_mean = wrap(280.460 * DEG + 0.9856474 * DEG * mjd, 2.0 * PI);
        let g = wrap(357.528 * DEG + 0.9856003 * DEG * mjd, 2.0 * PI);
        let l = l_mean + 1.915 * DEG * g.sin() + 0.020 * DEG * (2.0 * g).sin();
        let ep = 23.439 * DEG - 4e-7 * DEG * mjd;
        let sin_l = l.sin();
        let ra = (sin_l * ep.cos()).atan2(l.cos());
        let utime = 24.0 * (mjd - mjd.floor()) + 12.0;
        let gmst = 6.697375 + 0.0657098242 * mjd + utime;
        let lmst = gmst - self.longitude * (12.0 / PI);
        let st = wrap(lmst - ra * (12.0 / PI) + 12.0, 24.0);
        ((ep.sin() * sin_l).asin(), st)
    }
}

/// `norm_cir()`: into `[0, p)` by whole turns (bounded, unlike the C loop, so a huge
/// date cannot hang).
fn wrap(r: f64, p: f64) -> f64 {
    if !r.is_finite() {
        return r;
    }
    let mut r = r;
    if !(-1e6 * p..=1e6 * p).contains(&r) {
        r = r.rem_euclid(p);
    }
    while r < 0.0 {
        r += p;
    }
    while r >= p {
        r -= p;
    }
    r
}
