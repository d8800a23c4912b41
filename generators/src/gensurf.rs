//! `gensurf material name x(s,t) y(s,t) z(s,t) m n [-e expr] [-f file] [-i] [-o]`
//!
//! Reproduces Radiance's `src/gen/gensurf.c`: the parametric surface `(x, y, z)(s, t)`,
//! `s` and `t` from 0 to 1 in `m` and `n` steps, as quadrilaterals where a cell is flat
//! and pairs of triangles where it is not, the normal following the right-hand rule in
//! (s, t) (`-i` reverses it). A `valid(s,t)` function, if defined, drops vertices where
//! it is not positive. `z` (or all three, when the same name is given for x, y and z)
//! may name a data file of values on the grid, bilinearly interpolated. `-o` writes
//! Wavefront `.OBJ` instead. `-s` interpolates averaged vertex normals across each
//! cell with a `surf.cal` Phong texture (or `.OBJ` normals).

use crate::curves::{CurveEval, CurveProgram};
use crate::mesh::{cross, normalize, sub};
use crate::words::Stream;
use crate::{GenError, Host, command_comment};
use radc_lang::c_number::{atof, format_g as g_body, format_g_width as g, is_flt};

const USAGE: &str = "gensurf material name x(s,t) y(s,t) z(s,t) m n [-s][-o][-e expr][-f file]";
const FTINY: f64 = 1e-6;
/// Bigger grids than this are refused rather than filling memory.
const MAX_CELLS: i64 = 10_000_000;
const MAX_ROW: i64 = 1_000_000;

/// A grid point (`POINT`): whether it is valid (in `.OBJ` output, its vertex number),
/// its position and its (s, t).
#[derive(Clone, Copy, Default)]
struct Point {
    valid: i64,
    /// In `.OBJ` output with `-s`, the normal's number (0 for none).
    nvalid: i64,
    p: [f64; 3],
    /// The averaged normal, with `-s`.
    n: [f64; 3],
    uv: [f64; 2],
}

/// Values on the grid from a data file (`datarec`), s varying fastest.
struct Data {
    border: bool,
    triplets: bool,
    m: usize,
    n: usize,
    values: Vec<f64>,
}

/// Where each coordinate comes from.
enum Source {
    Functions,
    /// z from data, x and y from functions.
    DataZ(Data),
    /// x, y and z from data triplets.
    DataXyz(Data),
}

/// The scene gensurf prints for `args` (the words after `gensurf`); data files, `-f`
/// files and `-` (standard input) come through `host`.
/// On failure (a calcomp error at some point of the curve), what was written up to
/// there, as the C program leaves it on standard output.
pub fn gensurf(args: &[String], host: &mut dyn Host) -> Result<String, crate::Failure> {
    crate::Failure::keeping_partial("gensurf", |out| write(args, host, out))
}

fn write(args: &[String], host: &mut dyn Host, out: &mut String) -> Result<(), GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 7 {
        return Err(usage());
    }
    let mut program = CurveProgram::new()?;
    let (mut objout, mut rev, mut smooth) = (false, false, false);
    let mut i = 7;
    while i < args.len() {
        match args[i].as_str() {
            "-s" => smooth = true,
            "-o" => objout = true,
            "-i" => rev = true,
            option @ ("-e" | "-f") => {
                i += 1;
                let value = args.get(i).ok_or_else(usage)?;
                program.load_option(option, value, host)?;
            }
            _ => return Err(usage()),
        }
        i += 1;
    }
    let (material, name) = (&args[0], &args[1]);
    let m = (program.eval(&args[5])? + 0.5) as i64;
    let n = (program.eval(&args[6])? + 0.5) as i64;
    if m <= 0 || n <= 0 {
        return Err(usage());
    }
    if m.saturating_mul(n) > MAX_CELLS || n > MAX_ROW {
        return Err(GenError::Invalid(format!(
            "{m} by {n}: radc makes at most {MAX_CELLS} cells, {MAX_ROW} to a row"
        )));
    }
    let (m, n) = (m as usize, n as usize);
    let z = &args[4];
    let data_text = if z == "-" {
        Some(host.read_stdin()?)
    } else {
        host.read_file(z).ok()
    };
    // `valid(s,t)`, if the user defined it, is evaluated after the curves.
    let check_valid = program.function_arity("valid") == Some(2);
    let extra: &[&str] = if check_valid { &["valid"] } else { &[] };
    let source = match data_text {
        Some(text) if z == &args[2] && z == &args[3] => {
            let data = load_data(&text, z, m, n, 3)?;
            program.define(&["s", "t"], &[], extra)?;
            Source::DataXyz(data)
        }
        Some(text) => {
            let data = load_data(&text, z, m, n, 1)?;
            program.define(&["s", "t"], &[("X", &args[2]), ("Y", &args[3])], extra)?;
            Source::DataZ(data)
        }
        None => {
            let curves = [("X", &args[2][..]), ("Y", &args[3]), ("Z", z)];
            program.define(&["s", "t"], &curves, extra)?;
            Source::Functions
        }
    };
    *out = command_comment("gensurf", args);
    program.optimize();
    let mut surface = Surface {
        ev: program.evaluator(),
        source,
        check_valid,
        n,
        rev,
        objout,
        smooth,
        nnorms: 0,
        prev_norm: [0.0; 3],
        material,
        name,
        nverts: 0,
        nout: 0,
        out,
    };
    surface.write(m)?;
    Ok(())
}

struct Surface<'a, 'm> {
    ev: CurveEval<'m>,
    source: Source,
    check_valid: bool,
    n: usize,
    rev: bool,
    objout: bool,
    smooth: bool,
    /// `.OBJ` normals written so far, and the last one (`prevNorm`).
    nnorms: i64,
    prev_norm: [f64; 3],
    material: &'a str,
    name: &'a str,
    nverts: i64,
    nout: usize,
    out: &'a mut String,
}

impl Surface<'_, '_> {
    fn write(&mut self, m: usize) -> Result<(), GenError> {
        let n = self.n;
        // Rows hold points -1..=n+1 (index + 1), as the C rows do.
        let mut rows = [
            vec![Point::default(); n + 3],
            vec![Point::default(); n + 3],
            vec![Point::default(); n + 3],
        ];
        // The oracle's -ffast-math build turns `x/m` into `x * (1/m)`.
        let step = 1.0 / m as f64;
        self.row(-step, &mut rows[0])?;
        self.row(0.0, &mut rows[1])?;
        self.row(step, &mut rows[2])?;
        self.normals(&mut rows);
        if self.objout {
            self.out.push_str(&format!(
                "\nusemtl {}\n\no {}\n\n",
                self.material, self.name
            ));
            self.obj_row(&mut rows[1]);
        }
        for i in 0..m {
            rows.rotate_left(1);
            self.row((i + 2) as f64 * step, &mut rows[2])?;
            self.normals(&mut rows);
            if self.objout {
                self.obj_row(&mut rows[1]);
            }
            for j in 0..n {
                let (r0, r1) = (&rows[0], &rows[1]);
                let at = |row: &Vec<Point>, k: usize| row[k + 1];
                let mut orient = j & 1 == 1;
                if !(at(r0, j).valid != 0 && at(r1, j + 1).valid != 0) {
                    orient = true;
                } else if !(at(r1, j).valid != 0 && at(r0, j + 1).valid != 0) {
                    orient = false;
                }
                if orient {
                    self.square(at(r0, j), at(r1, j), at(r0, j + 1), at(r1, j + 1));
                } else {
                    self.square(at(r1, j), at(r1, j + 1), at(r0, j), at(r0, j + 1));
                }
            }
        }
        Ok(())
    }

    /// `comprow()`: points 0..=n of the row at `s`, left alone outside [0, 1]; with
    /// smoothing, points -1..=n+1 at any `s`, for the normals at the edges.
    fn row(&mut self, s: f64, row: &mut [Point]) -> Result<(), GenError> {
        let (first, last) = if self.smooth {
            (-1, self.n as i64 + 1)
        } else if !(-FTINY..=1.0 + FTINY).contains(&s) {
            return Ok(());
        } else {
            (0, self.n as i64)
        };
        let step = 1.0 / self.n as f64;
        for i in first..=last {
            let t = i as f64 * step;
            let slot = &mut row[(i + 1) as usize];
            let point = self.point(s, t)?;
            // An invalid point keeps the normal its slot held before: gensurf reuses
            // row buffers and only overwrites a normal when the point is valid, and
            // the cell's normal interpolation reads all four corners.
            let stale = slot.n;
            *slot = point;
            if point.valid == 0 {
                slot.n = stale;
            }
        }
        Ok(())
    }

    /// `compnorms()`: with smoothing, each valid point of the middle row gets the
    /// normal of the central differences across its neighbours (one-sided where a
    /// neighbour is invalid).
    fn normals(&self, rows: &mut [Vec<Point>; 3]) {
        if !self.smooth {
            return;
        }
        let diff = |a: &[f64; 3], b: &[f64; 3]| sub(a, b);
        for k in 1..=self.n + 1 {
            let (r0, r1, r2) = (&rows[0][k], &rows[1][k], &rows[2][k]);
            if r1.valid == 0 {
                continue;
            }
            let v1 = match (r0.valid != 0, r2.valid != 0) {
                (false, false) => {
                    rows[1][k].n = [0.0; 3];
                    continue;
                }
                (false, true) => diff(&r2.p, &r1.p),
                (true, false) => diff(&r1.p, &r0.p),
                (true, true) => diff(&r2.p, &r0.p),
            };
            let (before, after) = (&rows[1][k - 1], &rows[1][k + 1]);
            let v2 = match (before.valid != 0, after.valid != 0) {
                (false, false) => {
                    rows[1][k].n = [0.0; 3];
                    continue;
                }
                (false, true) => diff(&after.p, &rows[1][k].p),
                (true, false) => diff(&rows[1][k].p, &before.p),
                (true, true) => diff(&after.p, &before.p),
            };
            let mut n = if self.rev {
                cross(&v2, &v1)
            } else {
                cross(&v1, &v2)
            };
            normalize(&mut n);
            rows[1][k].n = n;
        }
    }

    fn point(&mut self, s: f64, t: f64) -> Result<Point, GenError> {
        self.ev.set(&[s, t]);
        let curves = match &self.source {
            Source::Functions => 3,
            Source::DataZ(_) => 2,
            Source::DataXyz(_) => 0,
        };
        if self.check_valid && self.ev.curve(curves + 1)? <= 0.0 {
            return Ok(Point::default());
        }
        let p = match &self.source {
            Source::Functions => [self.ev.curve(1)?, self.ev.curve(2)?, self.ev.curve(3)?],
            Source::DataZ(d) => {
                let (x, y) = (self.ev.curve(1)?, self.ev.curve(2)?);
                [x, y, d.value(s, t, 0)]
            }
            Source::DataXyz(d) => [d.value(s, t, 0), d.value(s, t, 1), d.value(s, t, 2)],
        };
        Ok(Point {
            valid: 1,
            p,
            uv: [s, t],
            ..Point::default()
        })
    }

    /// `putobjrow()`: numbers the row's valid vertices, writing each normal that
    /// differs from the previous one (with `-s`).
    fn obj_row(&mut self, row: &mut [Point]) {
        for point in row.iter_mut().skip(1).take(self.n + 1) {
            if point.valid == 0 {
                continue;
            }
            self.out.push_str("v ");
            self.out.push_str(&vector(&point.p));
            self.nverts += 1;
            point.valid = self.nverts;
            self.out.push_str(&format!(
                "\tvt {} {}\n",
                g_body(point.uv[0], 9),
                g_body(point.uv[1], 9)
            ));
            let n = point.n;
            let zero = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] <= FTINY * FTINY;
            if !self.smooth || zero {
                point.nvalid = 0;
            } else if (0..3).all(|k| (n[k] - self.prev_norm[k]).abs() <= FTINY) {
                point.nvalid = self.nnorms;
            } else {
                self.out.push_str(&format!(
                    "\tvn {} {} {}\n",
                    g_body(n[0], 9),
                    g_body(n[1], 9),
                    g_body(n[2], 9)
                ));
                self.nnorms += 1;
                point.nvalid = self.nnorms;
                self.prev_norm = n;
            }
        }
    }

    /// `putobjvert()`: relative vertex, texture and normal indices.
    fn obj_vertex(&self, p: &Point) -> String {
        let pti = if p.valid != 0 {
            p.valid - self.nverts - 1
        } else {
            0
        };
        let ni = if p.nvalid != 0 {
            p.nvalid - self.nnorms - 1
        } else {
            0
        };
        format!(" {pti}/{pti}/{ni}")
    }

    /// `putsquare()`: one grid cell as a quadrilateral if flat, else two triangles.
    fn square(&mut self, p0: Point, p1: Point, p2: Point, p3: Point) {
        let (p1, p2) = if self.rev { (p2, p1) } else { (p1, p2) };
        let vc1 = unit_normal(&[&p0, &p1, &p2], sub(&p1.p, &p0.p), sub(&p2.p, &p0.p));
        let vc2 = unit_normal(&[&p1, &p2, &p3], sub(&p2.p, &p3.p), sub(&p1.p, &p3.p));
        let flat = match (vc1, vc2) {
            (None, None) => return,
            (Some(a), Some(b)) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2] >= 1.0 - FTINY * FTINY,
            _ => false,
        };
        // Each face with the exact normals that correct its texture's constant term.
        let faces: Vec<Face> = match (flat, vc1, vc2) {
            (true, Some(a), Some(b)) => {
                vec![(vec![&p0, &p1, &p3, &p2], vec![(a, -0.5), (b, -0.5)])]
            }
            (_, a, b) => [
                a.map(|a| (vec![&p0, &p1, &p2], vec![(a, -1.0)])),
                b.map(|b| (vec![&p2, &p1, &p3], vec![(b, -1.0)])),
            ]
            .into_iter()
            .flatten()
            .collect(),
        };
        if self.objout {
            for (face, _) in faces {
                self.out.push('f');
                for p in face {
                    let v = self.obj_vertex(p);
                    self.out.push_str(&v);
                }
                self.out.push('\n');
            }
            return;
        }
        let interp = if self.smooth {
            norm_interp(&p0, &p1, &p2, &p3)
        } else {
            None
        };
        // The texture's constant term, corrected by the exact normal of each face.
        let corrected = |norm3: [f64; 3], terms: &[([f64; 3], f64)]| {
            terms
                .iter()
                .fold(norm3, |v, (n, f)| std::array::from_fn(|k| v[k] + f * n[k]))
        };
        for (face, exact) in faces {
            self.out.push_str(&format!("\n{} ", self.material));
            if let Some((axis, norm)) = &interp {
                let last = corrected(norm[3], &exact);
                self.out.push_str(&format!(
                    "texfunc Phong\n4 surf_dx surf_dy surf_dz surf.cal\n0\n13\t{axis}\n"
                ));
                for row in &norm[..3] {
                    self.out.push_str(&vector(row));
                }
                self.out.push_str(&vector(&last));
                self.out.push_str("\nPhong ");
            }
            self.polygon_body(&face);
        }
    }

    /// `polygon <name>.<n>` and its vertices, after the modifier already written.
    fn polygon_body(&mut self, points: &[&Point]) {
        self.nout += 1;
        self.out.push_str(&format!(
            "polygon {}.{}\n0\n0\n{}\n",
            self.name,
            self.nout,
            3 * points.len()
        ));
        for p in points {
            self.out.push_str(&vector(&p.p));
        }
    }
}

/// `norminterp()`: the bilinear map (in the two coordinates off the dominant axis of
/// the averaged normals) that interpolates the four corner normals, as the texture
/// coefficients; `None` when the corners do not determine one.
fn norm_interp(p0: &Point, p1: &Point, p2: &Point, p3: &Point) -> Option<(usize, [[f64; 3]; 4])> {
    let corners = [p0, p1, p2, p3];
    let mut v1 = p0.n;
    for p in &corners[1..] {
        v1 = std::array::from_fn(|k| v1[k] + p.n[k]);
    }
    let mut ax = if v1[0].abs() > v1[1].abs() { 0 } else { 1 };
    if v1[ax].abs() <= v1[2].abs() {
        ax = 2;
    }
    let (u, v) = ((ax + 1) % 3, (ax + 2) % 3);
    let mut eqn = [[0.0; 4]; 4];
    for (row, p) in eqn.iter_mut().zip(&corners) {
        *row = [p.p[u] * p.p[v], p.p[u], p.p[v], 1.0];
    }
    let inv = invert(&eqn)?;
    let mut res = [[0.0; 3]; 4];
    for (j, out) in res.iter_mut().enumerate() {
        for (i, o) in out.iter_mut().enumerate() {
            // The oracle's -ffast-math build adds the four products in pairs.
            *o = (inv[j][0] * p0.n[i] + inv[j][1] * p1.n[i])
                + (inv[j][2] * p2.n[i] + inv[j][3] * p3.n[i]);
        }
    }
    Some((ax, res))
}

/// `invmat4()`: Gauss-Jordan elimination with partial pivoting, pivots below 1e-6
/// meaning no inverse. Rows are scaled by the pivot's reciprocal, as the oracle's
/// -ffast-math build computes the C code's division.
fn invert(m: &[[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let mut a = *m;
    let mut inv = radc_lang::transform::IDENTITY;
    for i in 0..4 {
        let mut best = FTINY;
        let mut pivot = None;
        for (k, row) in a.iter().enumerate().skip(i) {
            if row[i].abs() > best {
                best = row[i].abs();
                pivot = Some(k);
            }
        }
        let j = pivot?;
        if j != i {
            a.swap(i, j);
            inv.swap(i, j);
        }
        let r = 1.0 / a[i][i];
        for k in 0..4 {
            a[i][k] *= r;
            inv[i][k] *= r;
        }
        for j in 0..4 {
            if j != i {
                let t = a[j][i];
                for k in 0..4 {
                    a[j][k] -= a[i][k] * t;
                    inv[j][k] -= inv[i][k] * t;
                }
            }
        }
    }
    Some(inv)
}

/// One face of a cell, with the exact normals (and their weights) that correct its
/// texture's constant term.
type Face<'p> = (Vec<&'p Point>, Vec<([f64; 3], f64)>);

/// The unit normal of a triangle of valid points from two edge vectors; `None` if a
/// point is invalid or the triangle has no area.
fn unit_normal(points: &[&Point; 3], a: [f64; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    if points.iter().any(|p| p.valid == 0) {
        return None;
    }
    let mut n = cross(&a, &b);
    (normalize(&mut n) != 0.0).then_some(n)
}

/// `"%18.12g %18.12g %18.12g\n"`.
fn vector(p: &[f64; 3]) -> String {
    format!(
        "{} {} {}\n",
        g(p[0], 18, 12),
        g(p[1], 18, 12),
        g(p[2], 18, 12)
    )
}

/// `loaddata()`: `(m+1)(n+1)` values per coordinate with the border, or `mn` without.
fn load_data(text: &str, name: &str, m: usize, n: usize, size: usize) -> Result<Data, GenError> {
    let bad = || GenError::Plain(format!("{name}: bad number of data points"));
    let wanted = (m + 1) * (n + 1) * size;
    let mut words = Stream::new(text);
    let mut values = Vec::with_capacity(wanted.min(1 << 20));
    while values.len() < wanted {
        let Some(w) = words.word(64) else {
            break;
        };
        if !is_flt(&w) {
            return Err(GenError::Invalid(format!(
                "{name}: garbled data value: {w}"
            )));
        }
        values.push(atof(&w));
    }
    let mut data = Data {
        border: true,
        triplets: size == 3,
        m: m + 1,
        n: n + 1,
        values,
    };
    if wanted - data.values.len() == (m + n + 1) * size {
        data.border = false;
        data.m = m;
        data.n = n;
    } else if data.values.len() != wanted {
        return Err(bad());
    }
    if data.m < 2 || data.n < 2 || words.word(64).is_some() {
        return Err(bad());
    }
    Ok(data)
}

impl Data {
    /// `l_dataval()`: coordinate `k` (0 for a single value) at (s, t), bilinear.
    fn value(&self, s: f64, t: f64, k: usize) -> f64 {
        let (dm, dn) = (self.m as i64, self.n as i64);
        let (u, v) = if self.border {
            (s * (dm - 1) as f64, t * (dn - 1) as f64)
        } else {
            (s * dm as f64 - 0.5, t * dn as f64 - 0.5)
        };
        let i = (u as i64).clamp(0, (dm - 2).max(0));
        let j = (v as i64).clamp(0, (dn - 2).max(0));
        let stride = if self.triplets { 3 } else { 1 };
        let at = |row: i64, col: i64| {
            let index = (row * dm + col) as usize * stride + k;
            self.values.get(index).copied().unwrap_or(0.0)
        };
        let (d00, d01, d10, d11) = (at(j, i), at(j, i + 1), at(j + 1, i), at(j + 1, i + 1));
        let (fi, fj) = (i as f64, j as f64);
        (fj + 1.0 - v) * ((fi + 1.0 - u) * d00 + (u - fi) * d01)
            + (v - fj) * ((fi + 1.0 - u) * d10 + (u - fi) * d11)
    }
}
