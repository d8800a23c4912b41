//! The part of Radiance's `.OBJ` scene library (`src/common/objutil.c`,
//! `convertobj.c`) that genbox uses for finely rounded boxes: vertices, normals and
//! faces collected in memory, then written as Radiance polygons.
//!
//! Behaviour reproduced: faces are kept newest first (so they print in reverse order of
//! creation), a triangle repeating a vertex or any face with area at most 1e-12 is
//! degenerate and skipped, normals are unit vectors stored in single precision, and
//! `normalize()` uses its first-order shortcut for nearly unit vectors.

use crate::printf::g;

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
}

/// `normalize()` from `src/common/fvect.c`: returns the old length.
pub fn normalize(v: &mut [f64; 3]) -> f64 {
    let d = dot(v, v);
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

pub fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
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
        if corners.len() < 3 {
            return;
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
        self.faces.push(face);
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

    /// `toRadiance()` for faces without normals: each face a polygon named
    /// `<group>.<n>`, counted in output order.
    pub fn write_flat(&self, out: &mut String, material: &str, group: &str) {
        let mut count = 0;
        for f in self.faces.iter().rev().filter(|f| !f.degenerate) {
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
}
