//! `genprism material name { - | vfile | N x1 y1 .. xN yN } [-l lx ly lz][-r radius][-c][-e]`
//!
//! Reproduces Radiance's `src/gen/genprism.c`: a polygon in the xy plane extruded along
//! the length vector (default 0 0 1). The vertex order together with the extrusion
//! direction decides which way the surfaces face. `-r` rounds the edges with cylinders
//! and spheres, `-c` says the outline is already closed, `-e` drops the end caps.

use crate::words::atoi;
use crate::{GenError, Host, command_comment};
use radc_lang::c_number::{atof, format_g_width as g, is_c_space, strtod};

const USAGE: &str =
    "genprism material name { - | vfile | N v1 v2 .. vN } [-l lvect][-r radius][-c][-e]";
const MAX_VERTICES: usize = 1024;
const FTINY: f64 = 1e-6;

struct Prism {
    material: String,
    name: String,
    verts: Vec<[f64; 2]>,
    l: [f64; 3],
    ldir: f64,
    closed: bool,
    /// Corner radius times the extrusion direction's sign (the C code's `crad`).
    crad: f64,
    /// Unit edge vectors and corner trims, for rounding.
    u: Vec<[f64; 2]>,
    a: Vec<f64>,
}

/// The scene genprism prints for `args` (the words after `genprism`); a vertex file
/// or `-` (standard input) is read through `host`.
pub fn genprism(args: &[String], host: &mut dyn Host) -> Result<String, GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 3 {
        return Err(usage());
    }
    let source = &args[2];
    let (verts, mut an) = if source == "-" {
        (read_vertices(&host.read_stdin()?, "<stdin>")?, 3)
    } else if source.as_bytes().first().is_some_and(u8::is_ascii_digit) {
        let n = atoi(source).max(0) as usize;
        if args.len() - 2 < 2 * n {
            return Err(usage());
        }
        if n > MAX_VERTICES {
            return Err(GenError::Invalid("too many vertices".into()));
        }
        let coord = |k: usize| args.get(k).map(|s| atof(s)).ok_or_else(usage);
        let verts = (0..n)
            .map(|i| Ok([coord(2 * i + 3)?, coord(2 * i + 4)?]))
            .collect::<Result<Vec<_>, GenError>>()?;
        (verts, 2 * n + 3)
    } else {
        (read_vertices(&host.read_file(source)?, source)?, 3)
    };
    if verts.len() < 3 {
        return Err(GenError::Invalid("not enough vertices".into()));
    }
    let mut p = Prism {
        material: args[0].clone(),
        name: args[1].clone(),
        verts,
        l: [0.0, 0.0, 1.0],
        ldir: 1.0,
        closed: false,
        crad: 0.0,
        u: Vec::new(),
        a: Vec::new(),
    };
    let mut ends = true;
    while an < args.len() {
        let opt = args[an].as_bytes();
        if opt.first() != Some(&b'-') {
            return Err(usage());
        }
        let mut value = || {
            an += 1;
            args.get(an).map(|s| atof(s)).ok_or_else(usage)
        };
        match opt.get(1) {
            Some(b'l') => {
                p.l = [value()?, value()?, value()?];
                p.ldir = if p.l[2] < -FTINY {
                    -1.0
                } else if p.l[2] > FTINY {
                    1.0
                } else {
                    return Err(GenError::Invalid("illegal extrusion vector".into()));
                };
            }
            Some(b'r') => p.crad = value()?,
            Some(b'e') => ends = !ends,
            Some(b'c') => p.closed = !p.closed,
            _ => return Err(usage()),
        }
        an += 1;
    }
    let mut out = String::new();
    if p.crad > FTINY {
        if p.crad > p.ldir * p.l[2] {
            return Err(GenError::Invalid("rounding greater than height".into()));
        }
        p.crad *= p.ldir;
        p.compute_rounding()?;
        out.push_str(&command_comment("genprism", args));
        if ends {
            p.rounded_ends(&mut out);
        }
        p.sides(&mut out, true);
    } else {
        out.push_str(&command_comment("genprism", args));
        if ends {
            p.ends(&mut out);
        }
        p.sides(&mut out, false);
    }
    Ok(out)
}

/// `fscanf(fp, "%lf %lf", ...)` until a pair fails, as genprism reads a vertex file.
fn read_vertices(text: &str, name: &str) -> Result<Vec<[f64; 2]>, GenError> {
    let mut rest = text;
    let mut next = || {
        let n = strtod(rest.as_bytes());
        rest = rest.get(n.len..)?;
        (n.len > 0).then_some(n.value)
    };
    let mut verts = Vec::new();
    while let (Some(x), Some(y)) = (next(), next()) {
        verts.push([x, y]);
        if verts.len() >= MAX_VERTICES {
            let more = rest.bytes().any(|b| !is_c_space(b));
            if more {
                return Err(GenError::Invalid(format!("{name}: too many vertices")));
            }
            break;
        }
    }
    Ok(verts)
}

fn line3(out: &mut String, x: f64, y: f64, z: f64) {
    out.push_str(&format!(
        "\t{}\t{}\t{}\n",
        g(x, 18, 12),
        g(y, 18, 12),
        g(z, 18, 12)
    ));
}

impl Prism {
    fn header(&self, out: &mut String, kind: &str, suffix: &str) {
        out.push_str(&format!(
            "\n{} {kind} {}.{suffix}\n",
            self.material, self.name
        ));
    }

    fn ends(&self, out: &mut String) {
        let n = self.verts.len();
        self.header(out, "polygon", "b");
        out.push_str(&format!("0\n0\n{}\n", 3 * n));
        for v in &self.verts {
            line3(out, v[0], v[1], 0.0);
        }
        self.header(out, "polygon", "t");
        out.push_str(&format!("0\n0\n{}\n", 3 * n));
        for v in self.verts.iter().rev() {
            line3(out, v[0] + self.l[0], v[1] + self.l[1], self.l[2]);
        }
    }

    fn sides(&self, out: &mut String, rounded: bool) {
        let n = self.verts.len();
        let last = if self.closed { n - 1 } else { n };
        for i in 0..last {
            let j = (i + 1) % n;
            if rounded {
                self.rounded_side(out, i, j);
            } else {
                self.side(out, i, j);
            }
        }
    }

    fn side(&self, out: &mut String, n0: usize, n1: usize) {
        let (v0, v1, l) = (self.verts[n0], self.verts[n1], self.l);
        self.header(out, "polygon", &(n0 + 1).to_string());
        out.push_str("0\n0\n12\n");
        line3(out, v0[0], v0[1], 0.0);
        line3(out, v0[0] + l[0], v0[1] + l[1], l[2]);
        line3(out, v1[0] + l[0], v1[1] + l[1], l[2]);
        line3(out, v1[0], v1[1], 0.0);
    }

    /// Edge unit vectors `u` and corner trims `a` (signed by turning direction).
    fn compute_rounding(&mut self) -> Result<(), GenError> {
        let n = self.verts.len();
        self.u = vec![[0.0; 2]; n];
        self.a = vec![0.0; n];
        let mut v0 = self.verts[n - 1];
        for i in 0..n {
            let v1 = self.verts[i];
            let mut u = [v0[0] - v1[0], v0[1] - v1[1]];
            let len = (u[0] * u[0] + u[1] * u[1]).sqrt();
            if len <= FTINY {
                return Err(GenError::Invalid("Degenerate side in prism".into()));
            }
            u[0] /= len;
            u[1] /= len;
            self.u[i] = u;
            v0 = v1;
        }
        let mut w1 = self.u[0];
        for i in (0..n).rev() {
            let w0 = self.u[i];
            let d = w0[0] * w1[0] + w0[1] * w1[1];
            if 1.0 + d <= FTINY {
                return Err(GenError::Invalid("Overlapping sides in prism".into()));
            }
            self.a[i] = if 1.0 - d <= 0.0 {
                0.0
            } else {
                let a = ((1.0 - d) / (1.0 + d)).sqrt();
                if w1[0] * w0[1] - w1[1] * w0[0] < 0.0 {
                    -a
                } else {
                    a
                }
            };
            w1 = w0;
        }
        Ok(())
    }

    /// Rounded corner `i` in the plane, on the end displaced by `shift` (the C code
    /// adds the displacement before the rounding offset; the order changes the last bit).
    fn corner(&self, i: usize, shift: Option<[f64; 2]>) -> [f64; 2] {
        let (v, u, a, r) = (self.verts[i], self.u[i], self.a[i], self.crad);
        let (ox, oy) = (r * (a * u[0] - u[1]), r * (a * u[1] + u[0]));
        match shift {
            None => [v[0] + ox, v[1] + oy],
            Some(l) => [v[0] + l[0] + ox, v[1] + l[1] + oy],
        }
    }

    fn rounded_ends(&self, out: &mut String) {
        let n = self.verts.len();
        let (l, r) = (self.l, self.crad);
        self.header(out, "polygon", "b");
        out.push_str(&format!("0\n0\n{}\n", 3 * n));
        for i in 0..n {
            let c = self.corner(i, None);
            line3(out, c[0], c[1], 0.0);
        }
        self.header(out, "polygon", "t");
        out.push_str(&format!("0\n0\n{}\n", 3 * n));
        for i in (0..n).rev() {
            let c = self.corner(i, Some([l[0], l[1]]));
            line3(out, c[0], c[1], l[2]);
        }
        self.rim(out, "b", None, r);
        self.rim(out, "t", Some([l[0], l[1]]), l[2] - r);
    }

    /// The corner spheres and edge cylinders around one end, at height `z`.
    fn rim(&self, out: &mut String, end: &str, shift: Option<[f64; 2]>, z: f64) {
        let n = self.verts.len();
        let at = |i: usize| {
            let c = self.corner(i, shift);
            [c[0], c[1], z]
        };
        let radius = self.ldir * self.crad;
        let mut c0 = at(n - 1);
        let first = c0;
        for i in 0..n {
            let c1 = if i < n - 1 { at(i) } else { first };
            if self.ldir * self.a[i] > 0.0 {
                self.header(out, "sphere", &format!("{end}c{}", i + 1));
                out.push_str(&format!(
                    "0\n0\n4 {} {} {} {}\n",
                    g(c1[0], 18, 12),
                    g(c1[1], 18, 12),
                    g(c1[2], 18, 12),
                    g(radius, 18, 12)
                ));
            }
            self.header(out, "cylinder", &format!("{end}e{}", i + 1));
            out.push_str("0\n0\n7\n");
            line3(out, c0[0], c0[1], c0[2]);
            line3(out, c1[0], c1[1], c1[2]);
            out.push_str(&format!("\t{}\n", g(radius, 18, 12)));
            c0 = c1;
        }
    }

    fn rounded_side(&self, out: &mut String, n0: usize, n1: usize) {
        let (l, r, u1) = (self.l, self.crad, self.u[n1]);
        let (v0, v1) = (self.verts[n0], self.verts[n1]);
        let (a0, a1) = (self.a[n0], self.a[n1]);
        let llen = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        let s = self.ldir * (l[1] * u1[0] - l[0] * u1[1]) / llen;
        let t = if s.abs() > FTINY {
            let c = (1.0 - s * s).sqrt();
            [(c - 1.0) * u1[1], (1.0 - c) * u1[0], s]
        } else {
            [0.0; 3]
        };
        self.header(out, "polygon", &(n0 + 1).to_string());
        out.push_str("0\n0\n12\n");
        line3(
            out,
            v0[0] + r * (t[0] - a0 * u1[0]),
            v0[1] + r * (t[1] - a0 * u1[1]),
            r * (t[2] + 1.0),
        );
        line3(
            out,
            v0[0] + l[0] + r * (t[0] - a0 * u1[0]),
            v0[1] + l[1] + r * (t[1] - a0 * u1[1]),
            l[2] + r * (t[2] - 1.0),
        );
        line3(
            out,
            v1[0] + l[0] + r * (t[0] + a1 * u1[0]),
            v1[1] + l[1] + r * (t[1] + a1 * u1[1]),
            l[2] + r * (t[2] - 1.0),
        );
        line3(
            out,
            v1[0] + r * (t[0] + a1 * u1[0]),
            v1[1] + r * (t[1] + a1 * u1[1]),
            r * (t[2] + 1.0),
        );
        if self.ldir * a1 < 0.0 {
            return;
        }
        self.header(out, "cylinder", &format!("e{}", n0 + 1));
        out.push_str("0\n0\n7\n");
        line3(
            out,
            v1[0] + r * (a1 * u1[0] - u1[1]),
            v1[1] + r * (a1 * u1[1] + u1[0]),
            r,
        );
        line3(
            out,
            v1[0] + l[0] + r * (a1 * u1[0] - u1[1]),
            v1[1] + l[1] + r * (a1 * u1[1] + u1[0]),
            l[2] - r,
        );
        out.push_str(&format!("\t{}\n", g(self.ldir * r, 18, 12)));
    }
}
