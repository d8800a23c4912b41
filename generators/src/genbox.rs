//! `genbox material name xsize ysize zsize [-i] [-b bevel | -r round [-n nsegs][-s]] [-o]`
//!
//! Reproduces Radiance's `src/gen/genbox.c`. A vertex is a 6-bit code: bits 0-2 pick
//! the far (1) or near (0) side on x, y, z; bits 3-5 pull that coordinate in by the
//! bevel. Faces are named by the letters of their vertex codes. `-i` swaps near and far,
//! which turns every face inside out. Rounding finer than one segment per quarter circle
//! (`-n` above 2, or `-r` with `-i`, which defaults to 32 segments) and `-o` go through
//! Radiance's `.OBJ` scene library instead: see `mesh.rs` (Radiance polygons, `-s`
//! Phong smoothing) and `wavefront.rs` (`-o`).

use crate::mesh::{Corner, Mesh, cross, normalize, sub};
use crate::words::atoi;
use crate::{GenError, command_comment};
use radc_lang::c_number::{atof, format_g_width as g};

const USAGE: &str =
    "genbox material name xsize ysize zsize [-i] [-b bevel | -r round [-n nsegs][-s]] [-o]";

/// Most subdivision levels for rounded corners (`-n 256`: 65536 triangles each, about
/// 50 MB of output in all).
const MAX_LEVELS: u32 = 8;

/// The characters naming vertex codes 0..63 in face names.
const LETTERS: &[u8] = b"0123456789._ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz";

struct Box3 {
    material: String,
    name: String,
    size: [f64; 3],
    bevel: f64,
    reversed: bool,
}

/// The scene genbox prints for `args` (the words after `genbox`).
pub fn genbox(args: &[String]) -> Result<String, GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 5 {
        return Err(usage());
    }
    let size = [atof(&args[2]), atof(&args[3]), atof(&args[4])];
    if size.iter().any(|&s| s <= 0.0) {
        return Err(usage());
    }
    let mut b = Box3 {
        material: args[0].clone(),
        name: args[1].clone(),
        size,
        bevel: 0.0,
        reversed: false,
    };
    let (mut rounded, mut nsegs, mut obj_out, mut smooth) = (false, 1_i64, false, false);
    let mut i = 5;
    while i < args.len() {
        let opt = args[i].as_bytes();
        if opt.first() != Some(&b'-') {
            return Err(usage());
        }
        let mut value = || {
            i += 1;
            args.get(i).ok_or_else(usage)
        };
        match opt.get(1) {
            Some(b'o') => obj_out = true,
            Some(b'i') => b.reversed = true,
            Some(b's') => smooth = true,
            Some(c @ (b'r' | b'b')) => {
                rounded |= *c == b'r';
                b.bevel = atof(value()?);
                if b.bevel <= 0.0 {
                    return Err(usage());
                }
            }
            Some(b'n') => {
                nsegs = atoi(value()?);
                if nsegs <= 0 {
                    return Err(usage());
                }
            }
            _ => return Err(usage()),
        }
        i += 1;
    }
    if (obj_out || b.reversed) && nsegs == 1 {
        nsegs = 32;
    }
    // The C code's `rounde`: 1 + log2 of the segments per quarter circle.
    let mut levels = u32::from(rounded);
    if rounded {
        let mut n = nsegs - 1;
        while {
            n >>= 1;
            n != 0
        } {
            levels += 1;
        }
    }
    // Each level quadruples the triangles of every rounded corner; past this the
    // output runs to gigabytes, so refuse rather than exhaust memory.
    if levels > MAX_LEVELS {
        return Err(GenError::Invalid(format!(
            "-n {nsegs} needs {} triangles per corner; radc allows -n up to {}",
            4_u64.saturating_pow(levels),
            1_u32 << MAX_LEVELS
        )));
    }
    let mut out = command_comment("genbox", args);
    let mut w = Writer {
        b: &b,
        out: &mut out,
        mesh: (levels > 1 || obj_out).then(Mesh::default),
        vid: [None; 64],
        levels,
    };
    w.write(rounded);
    if let Some(mut mesh) = w.mesh.take() {
        if !smooth {
            mesh.remove_normals();
        }
        if !obj_out {
            mesh.write_radiance(&mut out, &b.material, &b.name);
        } else {
            if levels > 0 {
                mesh.coalesce_vertices(2.0 * crate::mesh::FTINY);
            }
            mesh.write_obj(&mut out, &b.material, &b.name);
        }
    }
    Ok(out)
}

/// Where faces go: straight to Radiance text, or (for fine rounding) into a mesh first.
struct Writer<'a> {
    b: &'a Box3,
    out: &'a mut String,
    mesh: Option<Mesh>,
    /// Mesh vertex of each vertex code, once made (`overtex()`).
    vid: [Option<usize>; 64],
    levels: u32,
}

impl Writer<'_> {
    fn write(&mut self, rounded: bool) {
        let bevelled = self.b.bevel > 0.0;
        if bevelled {
            for f in [
                [0o51, 0o55, 0o54, 0o50],
                [0o64, 0o66, 0o62, 0o60],
                [0o32, 0o33, 0o31, 0o30],
                [0o53, 0o52, 0o56, 0o57],
                [0o65, 0o61, 0o63, 0o67],
                [0o36, 0o34, 0o35, 0o37],
            ] {
                self.side(&f);
            }
        }
        if bevelled && !rounded {
            for f in [
                [0o31, 0o51, 0o50, 0o30],
                [0o60, 0o62, 0o32, 0o30],
                [0o50, 0o54, 0o64, 0o60],
                [0o34, 0o36, 0o66, 0o64],
                [0o37, 0o57, 0o56, 0o36],
                [0o52, 0o62, 0o66, 0o56],
                [0o52, 0o53, 0o33, 0o32],
                [0o57, 0o67, 0o63, 0o53],
                [0o61, 0o31, 0o33, 0o63],
                [0o65, 0o67, 0o37, 0o35],
                [0o55, 0o51, 0o61, 0o65],
                [0o34, 0o54, 0o55, 0o35],
            ] {
                self.side(&f);
            }
            for c in [
                [0o30, 0o50, 0o60],
                [0o51, 0o31, 0o61],
                [0o32, 0o62, 0o52],
                [0o64, 0o54, 0o34],
                [0o36, 0o56, 0o66],
                [0o65, 0o35, 0o55],
                [0o53, 0o63, 0o33],
                [0o37, 0o67, 0o57],
            ] {
                self.corner(&c);
            }
        }
        if bevelled && rounded {
            for (a, b) in [
                (0o70, 0o71),
                (0o70, 0o74),
                (0o70, 0o72),
                (0o73, 0o71),
                (0o73, 0o72),
                (0o73, 0o77),
                (0o75, 0o71),
                (0o75, 0o74),
                (0o75, 0o77),
                (0o76, 0o72),
                (0o76, 0o74),
                (0o76, 0o77),
            ] {
                self.cylinder(a, b);
            }
            for v in 0o70..=0o77 {
                self.sphere(v);
            }
        }
        if !bevelled {
            for f in [
                [1, 5, 4, 0],
                [4, 6, 2, 0],
                [2, 3, 1, 0],
                [3, 2, 6, 7],
                [5, 1, 3, 7],
                [6, 4, 5, 7],
            ] {
                self.side(&f);
            }
        }
    }

    fn side(&mut self, codes: &[usize; 4]) {
        let levels = self.levels;
        let Some(mesh) = self.mesh.as_mut() else {
            self.b.polygon(self.out, codes);
            return;
        };
        let ids = codes.map(|c| overtex(mesh, &mut self.vid, self.b, c));
        let normal = if levels > 0 {
            let p = |k: usize| mesh.vertices[ids[k]];
            let n = cross(&sub(&p(1), &p(0)), &sub(&p(2), &p(1)));
            mesh.add_normal(n)
        } else {
            None
        };
        mesh.add_face(
            ids.iter()
                .map(|&vertex| Corner { vertex, normal })
                .collect(),
        );
    }

    fn corner(&mut self, codes: &[usize; 3]) {
        let Some(mesh) = self.mesh.as_mut() else {
            self.b.polygon(self.out, codes);
            return;
        };
        let ids = codes.map(|c| overtex(mesh, &mut self.vid, self.b, c));
        mesh.add_face(
            ids.iter()
                .map(|&vertex| Corner {
                    vertex,
                    normal: None,
                })
                .collect(),
        );
    }

    fn cylinder(&mut self, v0: usize, v1: usize) {
        let b = self.b;
        let Some(mesh) = self.mesh.as_mut() else {
            b.header(self.out, "cylinder", &[v0, v1]);
            self.out.push_str("0\n0\n7\n");
            b.vertex(self.out, v0);
            b.vertex(self.out, v1);
            self.out.push_str(&format!("\t{}\n", g(b.bevel, 18, 12)));
            return;
        };
        let nsgn = if b.reversed { -1.0 } else { 1.0 };
        let nseg = 1_u32 << self.levels.min(30);
        let astep = 0.5 * std::f64::consts::PI / f64::from(nseg);
        let i0 = overtex(mesh, &mut self.vid, b, v0);
        let i1 = overtex(mesh, &mut self.vid, b, v1);
        let (p0, p1) = (mesh.vertices[i0], mesh.vertices[i1]);
        let side = |k: usize| b.bevel * (1.0 - 2.0 * f64::from(u8::from(p1[k] < 0.5 * b.size[k])));
        let mut axis = [[0.0; 3]; 2];
        match (v0 ^ v1) & 0o7 {
            1 => {
                axis[1][1] = side(1);
                axis[0][2] = side(2);
            }
            2 => {
                axis[0][0] = side(0);
                axis[1][2] = side(2);
            }
            4 => {
                axis[0][1] = side(1);
                axis[1][0] = side(0);
            }
            _ => {}
        }
        let add = |p: &[f64; 3], o: &[f64; 3]| [p[0] + o[0], p[1] + o[1], p[2] + o[2]];
        let scaled = |o: &[f64; 3]| [o[0] * nsgn, o[1] * nsgn, o[2] * nsgn];
        let mut prev = [
            mesh.add_vertex(add(&p0, &axis[0])),
            mesh.add_vertex(add(&p1, &axis[0])),
        ];
        let mut prev_normal = mesh.add_normal(scaled(&axis[0]));
        for i in 1..=nseg {
            let (c0, c1) = ((astep * f64::from(i)).cos(), (astep * f64::from(i)).sin());
            let voff: [f64; 3] = std::array::from_fn(|j| c0 * axis[0][j] + c1 * axis[1][j]);
            let n0 = mesh.add_vertex(add(&p0, &voff));
            let n1 = mesh.add_vertex(add(&p1, &voff));
            let normal = mesh.add_normal(scaled(&voff));
            let corner = |vertex, normal| Corner { vertex, normal };
            mesh.add_face(vec![
                corner(prev[0], prev_normal),
                corner(prev[1], prev_normal),
                corner(n1, normal),
                corner(n0, normal),
            ]);
            prev = [n0, n1];
            prev_normal = normal;
        }
    }

    fn sphere(&mut self, v0: usize) {
        let b = self.b;
        let levels = self.levels;
        let Some(mesh) = self.mesh.as_mut() else {
            b.header(self.out, "sphere", &[v0]);
            self.out.push_str("0\n0\n4\n");
            b.vertex(self.out, v0);
            self.out.push_str(&format!("\t{}\n", g(b.bevel, 18, 12)));
            return;
        };
        let mut cdir = [[0.0; 3]; 3];
        for (i, d) in cdir.iter_mut().enumerate() {
            let far = ((v0 >> i) & 1 == 1) ^ b.reversed;
            d[i] = if far { 1.0 } else { -1.0 };
        }
        if matches!(v0 & 0o7, 0 | 3 | 5 | 6) {
            cdir.swap(0, 1);
        }
        let id = overtex(mesh, &mut self.vid, b, v0);
        let orig = mesh.vertices[id];
        let corner = Octant {
            mesh,
            orig,
            bevel: b.bevel,
            nsgn: if b.reversed { -1.0 } else { 1.0 },
        };
        corner.subdivide(cdir[0], cdir[1], cdir[2], levels);
    }
}

/// A rounded corner as a subdivided spherical triangle (`osubcorner()`).
struct Octant<'m> {
    mesh: &'m mut Mesh,
    orig: [f64; 3],
    bevel: f64,
    nsgn: f64,
}

impl Octant<'_> {
    fn subdivide(self, c0: [f64; 3], c1: [f64; 3], c2: [f64; 3], levels: u32) -> Self {
        if levels == 0 {
            let mut corner = |c: &[f64; 3]| {
                let p = std::array::from_fn(|k| self.orig[k] + self.bevel * c[k]);
                let vertex = self.mesh.add_vertex(p);
                let normal = self.mesh.add_normal(c.map(|x| x * self.nsgn));
                Corner { vertex, normal }
            };
            let face = vec![corner(&c0), corner(&c1), corner(&c2)];
            self.mesh.add_face(face);
            return self;
        }
        let mid = |a: &[f64; 3], b: &[f64; 3]| {
            let mut m = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
            normalize(&mut m);
            m
        };
        let (m01, m12, m20) = (mid(&c0, &c1), mid(&c1, &c2), mid(&c2, &c0));
        let lvl = levels - 1;
        self.subdivide(c0, m01, m20, lvl)
            .subdivide(c1, m12, m01, lvl)
            .subdivide(c2, m20, m12, lvl)
            .subdivide(m01, m12, m20, lvl)
    }
}

/// `overtex()`: the mesh vertex for a vertex code, made on first use.
fn overtex(mesh: &mut Mesh, vid: &mut [Option<usize>; 64], b: &Box3, code: usize) -> usize {
    let code = code & 0o77;
    if let Some(id) = vid[code] {
        return id;
    }
    let p = std::array::from_fn(|axis| b.coordinate(code, axis));
    let id = mesh.add_vertex(p);
    vid[code] = Some(id);
    id
}

impl Box3 {
    fn header(&self, out: &mut String, kind: &str, codes: &[usize]) {
        let letters: String = codes.iter().map(|&c| LETTERS[c & 0o77] as char).collect();
        out.push_str(&format!(
            "\n{} {kind} {}.{letters}\n",
            self.material, self.name
        ));
    }

    fn polygon(&self, out: &mut String, codes: &[usize]) {
        self.header(out, "polygon", codes);
        out.push_str(&format!("0\n0\n{}\n", 3 * codes.len()));
        for &v in codes {
            self.vertex(out, v);
        }
    }

    /// Coordinate `axis` of the vertex with this code.
    fn coordinate(&self, code: usize, axis: usize) -> f64 {
        let far = ((code >> axis) & 1 == 1) ^ self.reversed;
        let inset = (code >> axis) & 0o10 != 0;
        match (inset, far) {
            (true, true) => self.size[axis] - self.bevel,
            (true, false) => self.bevel,
            (false, true) => self.size[axis],
            (false, false) => 0.0,
        }
    }

    fn vertex(&self, out: &mut String, code: usize) {
        for axis in 0..3 {
            out.push('\t');
            out.push_str(&g(self.coordinate(code, axis), 18, 12));
        }
        out.push('\n');
    }
}
