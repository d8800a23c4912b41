//! Wavefront `.OBJ` output for genbox `-o`: Radiance's `coalesceVertices()`,
//! `deleteUnreferenced()` (`src/common/objutil.c`) and `toOBJ()`
//! (`src/common/writewfobj.c`) over the [`Mesh`] genbox builds.

use crate::mesh::{FTINY, Mesh};
use radc_lang::c_number::{format_e as e, format_g as g_body};
use std::collections::HashMap;

/// The most texture or normal variants `replace_vertex()` keeps per vertex.
const MAX_VARIANTS: usize = 9;

impl Mesh {
    /// `coalesceVertices()`: vertices that print alike to the digits `eps` allows are
    /// merged into the first of them, with their normals merged when within `eps`.
    pub fn coalesce_vertices(&mut self, eps: f64) {
        if eps >= 1.0 || self.vertices.len() <= 3 {
            return;
        }
        let digits = if eps <= 5e-15 {
            15
        } else {
            let mut n = 0;
            let mut d = eps;
            while d < 0.5 {
                n += 1;
                d *= 10.0;
            }
            n
        };
        let mut seen: HashMap<String, usize> = HashMap::new();
        for i in 0..self.vertices.len() {
            let p = self.vertices[i];
            let key = format!(
                "{} {} {}",
                e(p[0], digits),
                e(p[1], digits),
                e(p[2], digits)
            );
            match seen.get(&key) {
                Some(&first) => self.replace_vertex(i, first, eps),
                None => {
                    seen.insert(key, i);
                }
            }
        }
    }

    /// `replace_vertex()`: `prev` becomes `repl` in every face using it, unless a face
    /// already uses both.
    fn replace_vertex(&mut self, prev: usize, repl: usize, eps: f64) {
        if self.uses[prev].is_empty() {
            return;
        }
        let corner_of =
            |f: &crate::mesh::Face, v: usize| f.corners.iter().rposition(|c| c.vertex == v);
        if self.uses[repl]
            .iter()
            .any(|&f| self.faces[f].corners.iter().any(|c| c.vertex == prev))
        {
            return;
        }
        let mut variants: Vec<usize> = Vec::new();
        for &f in &self.uses[repl] {
            let Some(j) = corner_of(&self.faces[f], repl) else {
                continue;
            };
            let Some(nid) = self.faces[f].corners[j].normal else {
                continue;
            };
            match self.same_normal(&variants, nid, eps) {
                Some(v) => self.faces[f].corners[j].normal = Some(v),
                None => {
                    variants.push(nid);
                    if variants.len() >= MAX_VARIANTS {
                        break;
                    }
                }
            }
        }
        let moved = std::mem::take(&mut self.uses[prev]);
        for &f in &moved {
            let Some(j) = corner_of(&self.faces[f], prev) else {
                continue;
            };
            self.faces[f].corners[j].vertex = repl;
            if self.face_area(&self.faces[f]).0 <= FTINY * FTINY {
                self.faces[f].degenerate = true;
            }
            let nid = self.faces[f].corners[j].normal;
            if let Some(v) = nid.and_then(|n| self.same_normal(&variants, n, eps)) {
                self.faces[f].corners[j].normal = Some(v);
            }
        }
        let mut merged = moved;
        merged.append(&mut self.uses[repl]);
        self.uses[repl] = merged;
    }

    /// The first of `variants` that is `nid` or within `eps` of it (`norm_diff()`,
    /// which compares in single precision).
    fn same_normal(&self, variants: &[usize], nid: usize, eps: f64) -> Option<usize> {
        let n = self.normals[nid];
        variants.iter().copied().find(|&v| {
            let m = self.normals[v];
            v == nid || (0..3).all(|k| f64::from((m[k] - n[k]).abs()) <= eps)
        })
    }

    /// `deleteUnreferenced()`: drops vertices no face uses and normals no corner uses,
    /// renumbering the rest in order.
    pub fn delete_unreferenced(&mut self) {
        let mut vmap = vec![None; self.vertices.len()];
        let mut kept = Vec::new();
        let mut uses = Vec::new();
        for (i, u) in self.uses.iter_mut().enumerate() {
            if !u.is_empty() {
                vmap[i] = Some(kept.len());
                kept.push(self.vertices[i]);
                uses.push(std::mem::take(u));
            }
        }
        let mut used = vec![false; self.normals.len()];
        for c in self.faces.iter().flat_map(|f| &f.corners) {
            if let Some(n) = c.normal {
                used[n] = true;
            }
        }
        let mut nmap = vec![None; self.normals.len()];
        let mut normals = Vec::new();
        for (i, n) in self.normals.iter().enumerate() {
            if used[i] {
                nmap[i] = Some(normals.len());
                normals.push(*n);
            }
        }
        for c in self.faces.iter_mut().flat_map(|f| &mut f.corners) {
            c.vertex = vmap[c.vertex].unwrap_or(0);
            c.normal = c.normal.and_then(|n| nmap[n]);
        }
        self.vertices = kept;
        self.uses = uses;
        self.normals = normals;
    }

    /// `toOBJ()`: counts, vertices, normals, then each group's faces (newest first)
    /// with relative (negative) indices. Every face belongs to `group` and `material`.
    pub fn write_obj(&mut self, out: &mut String, material: &str, group: &str) {
        self.delete_unreferenced();
        let (nv, nn) = (self.vertices.len() as i64, self.normals.len() as i64);
        out.push_str(&format!(
            "#\n# {} final faces\n#\t{nv} vertices, 0 texture coordinates, {nn} surface normals\n#\n\n",
            self.faces.len()
        ));
        out.push_str("# Vertex positions\n");
        for v in &self.vertices {
            out.push_str(&format!(
                "v {} {} {}\n",
                g_body(v[0], 12),
                g_body(v[1], 12),
                g_body(v[2], 12)
            ));
        }
        out.push_str("\n# Vertex texture coordinates\n\n# Vertex normals\n");
        for n in &self.normals {
            out.push_str(&format!(
                "vn {:.6} {:.6} {:.6}\n",
                f64::from(n[0]),
                f64::from(n[1]),
                f64::from(n[2])
            ));
        }
        out.push('\n');
        // The scene starts with a default group and material; genbox names its own,
        // unless it chose those very names.
        let groups: &[&str] = if group == DEFAULT_GROUP {
            &[DEFAULT_GROUP]
        } else {
            &[DEFAULT_GROUP, group]
        };
        for (gid, name) in groups.iter().enumerate() {
            out.push_str(&format!("# Face group\ng {name}\n"));
            if gid == groups.len() - 1 && !self.faces.is_empty() {
                out.push_str(&format!("usemtl {material}\n"));
                for f in self.faces.iter().rev() {
                    out.push('f');
                    for c in &f.corners {
                        out.push_str(&format!(" {}//", c.vertex as i64 - nv));
                        if let Some(n) = c.normal {
                            out.push_str(&(n as i64 - nn).to_string());
                        }
                    }
                    out.push('\n');
                }
            }
            out.push_str(&format!("# End of face group {name}\n\n"));
        }
    }
}

const DEFAULT_GROUP: &str = "DEFAULT_GROUP";
