//! Radiance's ra_xyze. Converts an RGBE picture to XYZE (CIE XYZ, with
//! the EXPOSURE that keeps Y in luminance units: 1/179), `-r` an XYZE (or RGBE) picture
//! to RGBE in the standard primaries or `-p rx ry gx gy bx by wx wy`, colours below the
//! gamut's floor desaturated to it (`clipgamut`). `-o` undoes the header's exposure,
//! `-e` scales (`+N`/`-N`: stops), `-c`/`-u` choose run-length or flat scanlines (flat
//! for XYZE, encoded for RGBE by default). `ra_xyze [options] [input [output]]`.
//!
//! The arithmetic is `spec_rgb.c`'s: matrices computed in double from single-precision
//! chromaticities and kept in single precision, colours transformed in single
//! precision. White balancing (a von Kries transform, needed when the input and output
//! whites differ) is not supported and is refused.

use radc_lang::c_number::{atof, format_e};

use super::Run;
use crate::color::{CIE_BF, CIE_GF, CIE_RF, WHITE_EFFICACY};
use crate::{Format, Picture, decode, encode, scanline};

/// Chromaticities (x, y) of red, green, blue and white, in single precision as
/// `RGBPRIMS`.
pub type Prims = [[f32; 2]; 4];
type Matrix = [[f32; 3]; 3];

/// Radiance's standard primaries (`STDPRIMS`) and neutral white (`xyneu`).
pub const STD: Prims = [
    [0.640, 0.330],
    [0.290, 0.600],
    [0.150, 0.060],
    [1. / 3., 1. / 3.],
];
const NEUTRAL: [f32; 2] = [1. / 3., 1. / 3.];

/// `CEQ` and `XYEQ`: equal within 1e-4.
fn ceq(a: f64, b: f64) -> bool {
    a <= b + 1e-4 && b <= a + 1e-4
}
fn xy_eq(a: [f32; 2], b: [f32; 2]) -> bool {
    ceq(f64::from(a[0]), f64::from(b[0])) && ceq(f64::from(a[1]), f64::from(b[1]))
}

/// The three `C_?D` terms of `spec_rgb.c`.
fn c_terms(p: &Prims) -> [f64; 3] {
    let [r, g, b, w] = p.map(|c| c.map(f64::from));
    let (x, y) = (0, 1);
    [
        (1. / w[y]) * (w[x] * (g[y] - b[y]) - w[y] * (g[x] - b[x]) + g[x] * b[y] - b[x] * g[y]),
        (1. / w[y]) * (w[x] * (b[y] - r[y]) - w[y] * (b[x] - r[x]) - r[x] * b[y] + b[x] * r[y]),
        (1. / w[y]) * (w[x] * (r[y] - g[y]) - w[y] * (r[x] - g[x]) + r[x] * g[y] - g[x] * r[y]),
    ]
}

/// `comprgb2xyzmat`.
fn rgb_to_xyz(p: &Prims) -> Option<Matrix> {
    let [r, g, b, w] = p.map(|c| c.map(f64::from));
    if ceq(w[0], 0.) || ceq(w[1], 0.) {
        return None;
    }
    let [cr, cg, cb] = c_terms(p);
    let d = r[0] * (g[1] - b[1]) + g[0] * (b[1] - r[1]) + b[0] * (r[1] - g[1]);
    if ceq(d, 0.) {
        return None;
    }
    let m = |v: f64| v as f32;
    Some([
        [m(r[0] * cr / d), m(g[0] * cg / d), m(b[0] * cb / d)],
        [m(r[1] * cr / d), m(g[1] * cg / d), m(b[1] * cb / d)],
        [
            m((1. - r[0] - r[1]) * cr / d),
            m((1. - g[0] - g[1]) * cg / d),
            m((1. - b[0] - b[1]) * cb / d),
        ],
    ])
}

/// `compxyz2rgbmat`.
fn xyz_to_rgb(p: &Prims) -> Option<Matrix> {
    let [r, g, b, w] = p.map(|c| c.map(f64::from));
    if ceq(w[0], 0.) || ceq(w[1], 0.) {
        return None;
    }
    let [cr, cg, cb] = c_terms(p);
    if ceq(cr, 0.) || ceq(cg, 0.) || ceq(cb, 0.) {
        return None;
    }
    let m = |v: f64| v as f32;
    Some([
        [
            m((g[1] - b[1] - b[0] * g[1] + b[1] * g[0]) / cr),
            m((b[0] - g[0] - b[0] * g[1] + g[0] * b[1]) / cr),
            m((g[0] * b[1] - b[0] * g[1]) / cr),
        ],
        [
            m((b[1] - r[1] - b[1] * r[0] + r[1] * b[0]) / cg),
            m((r[0] - b[0] - r[0] * b[1] + b[0] * r[1]) / cg),
            m((b[0] * r[1] - r[0] * b[1]) / cg),
        ],
        [
            m((r[1] - g[1] - r[1] * g[0] + g[1] * r[0]) / cb),
            m((g[0] - r[0] - g[0] * r[1] + r[0] * g[1]) / cb),
            m((r[0] * g[1] - g[0] * r[1]) / cb),
        ],
    ])
}

/// `multcolormat(m3, m2, m1)`: m1 times m2, in single precision.
fn multiply(m2: &Matrix, m1: &Matrix) -> Matrix {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| m1[i][0] * m2[0][j] + m1[i][1] * m2[1][j] + m1[i][2] * m2[2][j])
    })
}

/// `colortrans`, in single precision.
fn transform(m: &Matrix, c: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|i| m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2])
}

/// `clipgamut(col, bright(col), CGAMUT_LOWER, black, white)`: a colour with a negative
/// component moved toward the grey of its brightness until it has none.
fn clip_below(c: [f32; 3]) -> [f32; 3] {
    let brt = CIE_RF * f64::from(c[0]) + CIE_GF * f64::from(c[1]) + CIE_BF * f64::from(c[2]);
    if brt < 0.0 {
        return [0.0; 3];
    }
    // The grey of that brightness between black and white.
    let grey = [0, 1, 2].map(|_| (brt * 1.0 + (1. - brt) * 0.0) as f32);
    let mut vv = 1.0f64;
    let mut clipped = false;
    for i in 0..3 {
        if c[i] < 0.0 {
            let v = (0.0 - f64::from(grey[i])) / (f64::from(c[i]) - f64::from(grey[i]));
            if v < vv {
                vv = v;
            }
            clipped = true;
        }
    }
    if !clipped {
        return c;
    }
    [0, 1, 2].map(|i| (vv * f64::from(c[i]) + (1. - vv) * f64::from(grey[i])) as f32)
}

/// ra_xyze's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct Options {
    pub flat: Option<bool>,
    pub rgb_out: bool,
    pub out_prims: Prims,
    pub original: bool,
    pub exposure: f64,
}

/// The picture converted; `what` names the input in messages.
pub fn convert(o: &Options, run: &Run, data: &[u8], what: &str) -> Result<Vec<u8>, String> {
    let picture = Picture::read(data).map_err(|e| format!("{what}: {e}"))?;
    let xyz_in = match picture.format_name.as_deref() {
        Some(Format::RGBE) => false,
        Some(Format::XYZE) => true,
        _ => return Err(format!("{what}: unrecognized/missing input file format")),
    };
    let mut out = Vec::new();
    let mut in_prims = STD;
    let mut original = if o.original { 1.0 } else { -1.0 };
    for line in &picture.header.lines {
        if line.format().is_some()
            || line.0.starts_with(b"WAVELENGTH_SPLITS=")
            || line.0.starts_with(b"NCOMP=")
        {
            if let Some(n) = line.value_after("NCOMP=")
                && atof(&n) as i64 != 3
            {
                return Err(format!("{what}: bad number of color components"));
            }
            continue;
        }
        if original > 0.0
            && let Some(v) = line.value_after("EXPOSURE=")
        {
            original *= atof(&v);
            continue;
        }
        if let Some(v) = line.value_after("PRIMARIES=") {
            let n: Vec<f32> = v.split_whitespace().map_while(|w| w.parse().ok()).collect();
            // primsval assigns what sscanf read, in order.
            for (k, x) in n.iter().take(8).enumerate() {
                in_prims[k / 2][k % 2] = *x;
            }
            continue;
        }
        out.extend_from_slice(&line.0);
    }
    out.extend_from_slice(run.command_line.as_bytes());
    let mut exp_do = o.exposure;
    let mut exp_report = o.exposure;
    if original > 0.0 {
        exp_do /= original;
    }
    let white_balance = "white balancing between different whites is not supported by radc ra_xyze";
    let mut m = if o.rgb_out {
        let m = if xyz_in {
            if !xy_eq(o.out_prims[3], NEUTRAL) {
                return Err(white_balance.into());
            }
            xyz_to_rgb(&o.out_prims)
        } else {
            if !xy_eq(in_prims[3], o.out_prims[3]) {
                return Err(white_balance.into());
            }
            // comprgb2rgbWBmat: to XYZ, the (identity) white balance, to the output.
            let identity = [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
            rgb_to_xyz(&in_prims).and_then(|to_xyz| {
                let m = multiply(&to_xyz, &identity);
                xyz_to_rgb(&o.out_prims).map(|to_rgb| multiply(&m, &to_rgb))
            })
        };
        if xyz_in {
            if original > 0.0 {
                exp_do /= WHITE_EFFICACY;
            } else {
                exp_report *= WHITE_EFFICACY;
            }
        }
        m
    } else {
        let m = if xyz_in {
            Some([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])
        } else {
            if !xy_eq(in_prims[3], NEUTRAL) {
                return Err(white_balance.into());
            }
            rgb_to_xyz(&in_prims)
        };
        if !xyz_in {
            if original > 0.0 {
                exp_do *= WHITE_EFFICACY;
            } else {
                exp_report /= WHITE_EFFICACY;
            }
        }
        m
    }
    .ok_or(format!("{what}: bad primaries"))?;
    for row in &mut m {
        for v in row {
            *v = (f64::from(*v) * exp_do) as f32;
        }
    }
    if !(0.99..=1.01).contains(&exp_report) {
        out.extend_from_slice(format!("EXPOSURE={}\n", format_e(exp_report, 4)).as_bytes());
    }
    if o.rgb_out {
        let p = o.out_prims;
        out.extend_from_slice(
            format!(
                "PRIMARIES= {:.4} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4}\n",
                p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], p[3][0], p[3][1]
            )
            .as_bytes(),
        );
        out.extend_from_slice(b"FORMAT=32-bit_rle_rgbe\n");
    } else {
        out.extend_from_slice(b"FORMAT=32-bit_rle_xyze\n");
    }
    out.push(b'\n');
    out.extend_from_slice(picture.resolution.line().as_bytes());
    let flat = o.flat.unwrap_or(!o.rgb_out);
    let mut scan = Vec::new();
    for s in 0..picture.resolution.scan_count() {
        scan.clear();
        for &p in picture.scanline(s) {
            let mut c = transform(&m, decode(p));
            if o.rgb_out {
                c = clip_below(c);
            }
            scan.push(encode(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])));
        }
        if flat {
            scan.iter().for_each(|p| out.extend_from_slice(p));
        } else {
            scanline::write(&scan, &mut out);
        }
    }
    Ok(out)
}
