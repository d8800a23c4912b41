//! The part of Radiance's `.OBJ` scene library (`src/common/objutil.c`,
//! `convertobj.c`) that genbox uses for finely rounded boxes: vertices, normals and
//! faces collected in memory, then written as Radiance polygons.
//!
//! Behaviour reproduced: faces are kept newest first (so they print in reverse order of
//! creation), a triangle repeating a vertex or any face with area at most 1e-12 is
//! degenerate and skipped, normals are unit vectors stored in single precision, and
//! `normalize()` uses its first-order shortcut for nearly unit vectors.

use radc_lang::c_number::format_g_width as g;

pub const FTINY: f64 = 1e-6;

/// One corner of a face: vertex index and optional normal index.
#[derive(Clone, Copy, Debug)]
pub struct Corner {
    pub vertex: usize,
    pub normal: Option<usize>,
}

pub struct Face {
    pub corners: Vec<Corner>,
    pub degenerate: bool,
}

#[derive(Default)]
pub struct Mesh {
    pub vertices: Vec<[f64; 3]>,
    pub normals: Vec<[f32; 3]>,
    /// In order of creation; output walks it backwards, as the C list is pushed at the head.
    pub faces: Vec<Face>,
    /// For each vertex, the faces using it, most recently linked first (`vflist`).
    pub uses: Vec<Vec<usize>>,
}

/// `normalize()` from `src/common/fvect.c`: returns the old length.
///
/// The oracle's Radiance is built with `-ffast-math`, and its compiled `normalize`
/// sums the squares as `x² + (y² + z²)`; the last bit of every normal depends on it.
pub fn normalize(v: &mut [f64; 3]) -> f64 {
    let d = v[0] * v[0] + (v[1] * v[1] + v[2] * v[2]);
    if d == 0.0 {
        return 0.0;
    }
    let (len, scale) = if (1.0 - FTINY..=1.0 + FTINY).contains(&d) {
        let len = 0.5 + 0.5 * d;
        (len, 2.0 - len)
    } else {
        let len = d.sqrt();
        (len, 1.0 / len)
    };
    for x in v.iter_mut() {
        *x *= scale;
    }
    len
}

pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

impl Mesh {
    pub fn add_vertex(&mut self, p: [f64; 3]) -> usize {
        self.vertices.push(p);
        self.uses.push(Vec::new());
        self.vertices.len() - 1
    }

    /// `addNormal()`: `None` for a zero vector.
    pub fn add_normal(&mut self, n: [f64; 3]) -> Option<usize> {
        let mut n = n;
        if normalize(&mut n) == 0.0 {
            return None;
        }
        self.normals.push([n[0] as f32, n[1] as f32, n[2] as f32]);
        Some(self.normals.len() - 1)
    }

    /// `addFace()`: faces under three corners are dropped.
    pub fn add_face(&mut self, corners: Vec<Corner>) {
        let Some(face) = self.make_face(corners) else {
            return;
        };
        let id = self.faces.len();
        for (k, c) in face.corners.iter().enumerate() {
            let first = face.corners[..k].iter().all(|d| d.vertex != c.vertex);
            if let (true, Some(list)) = (first, self.uses.get_mut(c.vertex)) {
                list.insert(0, id);
            }
        }
        self.faces.push(face);
    }

    /// A face with its degeneracy decided as `addFace()` decides it.
    fn make_face(&self, corners: Vec<Corner>) -> Option<Face> {
        if corners.len() < 3 {
            return None;
        }
        let repeats = corners.len() == 3
            && (corners[0].vertex == corners[1].vertex
                || corners[0].vertex == corners[2].vertex
                || corners[1].vertex == corners[2].vertex);
        let mut face = Face {
            corners,
            degenerate: repeats,
        };
        if !face.degenerate && self.face_area(&face).0 <= FTINY * FTINY {
            face.degenerate = true;
        }
        Some(face)
    }

    /// `faceArea()`: area and unit normal (zero if the area is zero).
    pub fn face_area(&self, f: &Face) -> (f64, [f64; 3]) {
        if f.degenerate {
            return (0.0, [0.0; 3]);
        }
        let p = |k: usize| &self.vertices[f.corners[k].vertex];
        let p0 = p(0);
        let mut n = [0.0; 3];
        let mut v1 = sub(p(1), p0);
        for k in 2..f.corners.len() {
            let v2 = sub(p(k), p0);
            let c = cross(&v1, &v2);
            n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
            v1 = v2;
        }
        let area = 0.5 * normalize(&mut n);
        if area == 0.0 {
            (0.0, [0.0; 3])
        } else {
            (area, n)
        }
    }

    pub fn remove_normals(&mut self) {
        for f in &mut self.faces {
            for c in &mut f.corners {
                c.normal = None;
            }
        }
    }

    /// `toRadiance()`: faces whose vertex normals bend away from the face normal are
    /// triangulated and written as Phong-smoothed triangles (a `texfunc` using
    /// tmesh.cal per triangle); the rest as plain polygons. Names are `<group>.<n>`,
    /// counted in output order, smoothed triangles first.
    pub fn write_radiance(&mut self, out: &mut String, material: &str, group: &str) {
        let mut count = 0;
        let list: Vec<usize> = (0..self.faces.len()).rev().collect();
        let mut smoothed = vec![false; self.faces.len()];
        for &i in &list {
            if !self.faces[i].degenerate {
                smoothed[i] = self.check_smooth(i);
            }
        }
        if smoothed.iter().any(|&s| s) {
            // dupScene() copies the chosen faces by pushing each at the head, so the copy
            // lists them oldest first.
            let chosen: Vec<Face> = list
                .iter()
                .rev()
                .filter(|&&i| smoothed[i])
                .map(|&i| Face {
                    corners: self.faces[i].corners.clone(),
                    degenerate: false,
                })
                .collect();
            for f in self.triangulate(chosen) {
                if f.corners.len() == 3 && self.write_smooth(out, material, group, &f, count + 1) {
                    count += 1;
                }
            }
        }
        for &i in &list {
            let f = &self.faces[i];
            if f.degenerate || smoothed[i] {
                continue;
            }
            count += 1;
            out.push_str(&format!(
                "\n{material} polygon {group}.{count}\n0\n0\n{}\n",
                3 * f.corners.len()
            ));
            for c in &f.corners {
                let v = self.vertices[c.vertex];
                out.push_str(&format!(
                    "\t{} {} {}\n",
                    g(v[0], 18, 12),
                    g(v[1], 18, 12),
                    g(v[2], 18, 12)
                ));
            }
        }
    }

    /// `checksmooth()`: whether face `i` needs smoothing; a face whose normals all
    /// point against it is turned around instead.
    fn check_smooth(&mut self, i: usize) -> bool {
        let f = &self.faces[i];
        let Some(normals) = f
            .corners
            .iter()
            .map(|c| c.normal)
            .collect::<Option<Vec<usize>>>()
        else {
            return false;
        };
        let (area, n) = self.face_area(f);
        if area == 0.0 {
            return false;
        }
        let fnrm = n.map(|x| x as f32);
        let mut reversed = 0;
        let mut all_checked = true;
        for &k in normals.iter().rev() {
            let t = self.normals[k];
            let d = f64::from(t[0] * fnrm[0] + t[1] * fnrm[1] + t[2] * fnrm[2]);
            if d >= COSTOL {
                continue;
            }
            if d > -COSTOL {
                all_checked = false;
                break;
            }
            reversed += 1;
        }
        if all_checked && reversed == 0 {
            return false;
        }
        if reversed == normals.len() {
            self.faces[i].corners.reverse();
            return false;
        }
        true
    }

    /// `triangulateScene()` on a face list (head first): polygons are cut into
    /// triangles pushed at the head, and the polygons cut are dropped.
    fn triangulate(&self, list: Vec<Face>) -> Vec<Face> {
        let mut made: Vec<Face> = Vec::new();
        let mut kept = Vec::new();
        for mut f in list {
            if f.corners.len() > 3 && !f.degenerate {
                let (area, n) = self.face_area(&f);
                if area != 0.0 {
                    let n = n.map(|x| x as f32);
                    let mut major = usize::from(n[1] * n[1] > n[0] * n[0]);
                    if n[2] * n[2] > n[major] * n[major] {
                        major = 2;
                    }
                    let (ax, ay) = ((major + 1) % 3, (major + 2) % 3);
                    let poly: Vec<[f64; 2]> = f
                        .corners
                        .iter()
                        .map(|c| {
                            let p = self.vertices[c.vertex];
                            [p[ax], p[ay]]
                        })
                        .collect();
                    let rev = poly_area(&poly) < 0.0;
                    let ok = poly_triangulate(&poly, |a, b, c| {
                        let (a, c) = if rev { (c, a) } else { (a, c) };
                        let corners = vec![f.corners[a], f.corners[b], f.corners[c]];
                        if let Some(t) = self.make_face(corners) {
                            made.push(t);
                        }
                    });
                    if ok {
                        continue;
                    }
                    f.degenerate = true;
                }
            }
            kept.push(f);
        }
        made.reverse();
        made.extend(kept);
        made
    }

    /// `trismooth()`: a triangle with barycentric normal interpolation. False (and
    /// nothing written) for a triangle too thin to interpolate on.
    fn write_smooth(
        &self,
        out: &mut String,
        material: &str,
        group: &str,
        f: &Face,
        n: usize,
    ) -> bool {
        let p = |k: usize| self.vertices[f.corners[k].vertex];
        let Some(bcm) = Barycentric::new(p(0), p(1), p(2)) else {
            return false;
        };
        let mut com = [[0.0; 3]; 3];
        for (i, c) in f.corners.iter().enumerate() {
            let t = c.normal.map_or([0.0; 3], |k| self.normals[k]);
            for (row, &x) in com.iter_mut().zip(&t) {
                row[i] = f64::from(x);
            }
        }
        out.push_str(&format!(
            "\n{material} texfunc {PHONG}\n4 dx dy dz tmesh.cal\n0\n{}\t{}\n",
            1 + 3 * 3,
            bcm.axis
        ));
        for row in &com {
            let (a, b) = (row[0] - row[2], row[1] - row[2]);
            let tm = &bcm.tm;
            out.push_str(&format!(
                "{:14.8} {:14.8} {:14.8}\n",
                tm[0][0] * a + tm[1][0] * b,
                tm[0][1] * a + tm[1][1] * b,
                tm[0][2] * a + tm[1][2] * b + row[2]
            ));
        }
        out.push_str(&format!("\n{PHONG} polygon {group}.{n}\n0\n0\n9\n"));
        for k in 0..3 {
            let v = p(k);
            out.push_str(&format!(
                "\t{} {} {}\n",
                g(v[0], 18, 12),
                g(v[1], 18, 12),
                g(v[2], 18, 12)
            ));
        }
        true
    }
}

/// Cosine of the angle within which a vertex normal agrees with its face (`tmesh.h`).
const COSTOL: f64 = 0.999995;
/// The texture name smoothed triangles use (`convertobj.c`).
const PHONG: &str = "Phong";

/// `BARYCCM` from `src/common/tmesh.c`: maps a point's two minor coordinates to its
/// barycentric weights.
struct Barycentric {
    axis: usize,
    tm: [[f64; 3]; 2],
}

impl Barycentric {
    /// `comp_baryc()`; `None` for a degenerate triangle.
    fn new(v1: [f64; 3], v2: [f64; 3], v3: [f64; 3]) -> Option<Barycentric> {
        let va = cross(&sub(&v1, &v2), &sub(&v3, &v2));
        let mut axis = usize::from(va[1] * va[1] > va[0] * va[0]);
        if va[2] * va[2] > va[axis] * va[axis] {
            axis = 2;
        }
        let (ax0, ax1) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut tm = [[0.0; 3]; 2];
        let mut v = [v1, v2, v3];
        for row in &mut tm {
            let [v1, v2, v3] = v;
            let vab = [v1[ax0] - v2[ax0], v1[ax1] - v2[ax1]];
            let vcb = [v3[ax0] - v2[ax0], v3[ax1] - v2[ax1]];
            let d = vcb[0] * vcb[0] + vcb[1] * vcb[1];
            if d <= FTINY * FTINY {
                return None;
            }
            let d = (vcb[0] * vab[0] + vcb[1] * vab[1]) / d;
            let mut w = [vab[0] - vcb[0] * d, vab[1] - vcb[1] * d];
            let d = w[0] * w[0] + w[1] * w[1];
            if d <= FTINY * FTINY {
                return None;
            }
            let d = 1.0 / d;
            w[0] *= d;
            w[1] *= d;
            *row = [w[0], w[1], -(v2[ax0] * w[0] + v2[ax1] * w[1])];
            v = [v2, v3, v1];
        }
        Some(Barycentric { axis, tm })
    }
}

/// `polyArea()` from `src/common/triangulate.c`: positive counter-clockwise.
fn poly_area(p: &[[f64; 2]]) -> f64 {
    let mut a = 0.0;
    let mut prev = p.len() - 1;
    for q in 0..p.len() {
        a += p[prev][0] * p[q][1] - p[q][0] * p[prev][1];
        prev = q;
    }
    a * 0.5
}

const EPSILON: f64 = 0.0000000001;

/// `insideTriangle()`.
fn inside_triangle(a: [f64; 2], b: [f64; 2], c: [f64; 2], p: [f64; 2]) -> bool {
    let (ax, ay) = (c[0] - b[0], c[1] - b[1]);
    let (bx, by) = (a[0] - c[0], a[1] - c[1]);
    let (cx, cy) = (b[0] - a[0], b[1] - a[1]);
    let (apx, apy) = (p[0] - a[0], p[1] - a[1]);
    let (bpx, bpy) = (p[0] - b[0], p[1] - b[1]);
    let (cpx, cpy) = (p[0] - c[0], p[1] - c[1]);
    let a_bp = ax * bpy - ay * bpx;
    let c_ap = cx * apy - cy * apx;
    let b_cp = bx * cpy - by * cpx;
    a_bp >= 0.0 && b_cp >= 0.0 && c_ap >= 0.0
}

/// `polySnip()`: 1 if `u v w` is an ear, -1 if the three are collinear, 0 if not.
fn poly_snip(p: &[[f64; 2]], u: usize, v: usize, w: usize, vs: &[usize]) -> i32 {
    let (a, b, c) = (p[vs[u]], p[vs[v]], p[vs[w]]);
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if cross < EPSILON {
        return if cross > -EPSILON { -1 } else { 0 };
    }
    for (k, &vk) in vs.iter().enumerate() {
        if k == u || k == v || k == w {
            continue;
        }
        let q = p[vk];
        if q == a || q == b || q == c {
            continue;
        }
        if inside_triangle(a, b, c, q) {
            return 0;
        }
    }
    1
}

/// `polyTriangulate()`: ear clipping, calling `emit` with each triangle's corner
/// indices; false if the polygon is not simple.
fn poly_triangulate(p: &[[f64; 2]], mut emit: impl FnMut(usize, usize, usize)) -> bool {
    let n = p.len();
    if n < 3 {
        return false;
    }
    let mut vs: Vec<usize> = if poly_area(p) > 0.0 {
        (0..n).collect()
    } else {
        (0..n).rev().collect()
    };
    let mut count = 2 * vs.len();
    let mut v = vs.len() - 1;
    while vs.len() > 2 {
        if count == 0 {
            return false;
        }
        count -= 1;
        let nv = vs.len();
        let u = if v < nv { v } else { 0 };
        v = if u + 1 < nv { u + 1 } else { 0 };
        let w = if v + 1 < nv { v + 1 } else { 0 };
        let result = poly_snip(p, u, v, w, &vs);
        if result > 0 {
            emit(vs[u], vs[v], vs[w]);
        }
        if result != 0 {
            vs.remove(v);
            count = 2 * vs.len();
        }
    }
    true
}
