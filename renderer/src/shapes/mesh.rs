//! Meshes (o_mesh.c): a mesh file's triangles under a BVH of their own, shared by every
//! `mesh` primitive that places the file, each placement a transform of the ray into
//! the mesh's frame, so the scene's tree holds one leaf per placement (a two-level
//! BVH).
//!
//! Triangles are tested as o_mesh.c tests them (Segura and Feito's signed volumes of
//! the ray with each edge, then the plane): an edge's sign is computed with its
//! vertices in ascending number (the file's vertex order) and negated for the other
//! direction, and a volume of exactly zero counts as negative, so the two triangles
//! sharing an edge always disagree about it and a ray through the edge hits exactly
//! one of them: no ray slips between triangles, and none hits both. Positions are
//! decoded from the file's 32-bit fractions as `getmeshvert` decodes them, in the
//! mesh's frame; distances there are scaled back by the transform's scale.

use std::sync::Arc;

use radc_lang::compiled::MeshFile;
use radc_lang::transform::Transform;

use crate::bvh::Bvh;
use crate::math::{Bounds, FTINY, Vec3, normalize, vec3};
use crate::ray::{Ray, ShapeHit};

/// A mesh file's triangles in BVH slot order, with their tree.
pub struct MeshGeometry {
    pub file: Arc<MeshFile>,
    /// Per slot: the triangle's vertices.
    triangles: Vec<[u32; 3]>,
    /// Per slot: the triangle's index in the file.
    file_index: Vec<u32>,
    bvh: Bvh,
    bounds: Bounds,
}

impl std::fmt::Debug for MeshGeometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "MeshGeometry({} triangles)", self.triangles.len())
    }
}

impl MeshGeometry {
    /// Builds the tree over the file's triangles.
    pub fn new(file: Arc<MeshFile>) -> MeshGeometry {
        let bounds: Vec<Bounds> = file
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| vec3(file.position(v)));
                Bounds {
                    min: a.min(b).min(c),
                    max: a.max(b).max(c),
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds);
        let file_index = bvh.order().to_vec();
        let triangles = file_index
            .iter()
            .map(|&i| file.triangles[i as usize])
            .collect();
        let all = bounds.iter().fold(Bounds::EMPTY, |a, b| a.union(*b));
        MeshGeometry {
            file,
            triangles,
            file_index,
            bvh,
            bounds: all,
        }
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Bytes held beyond the file's vertex data: the tree and the triangles.
    pub fn bytes(&self) -> usize {
        self.bvh.bytes()
            + std::mem::size_of_val(self.triangles.as_slice())
            + std::mem::size_of_val(self.file_index.as_slice())
    }

    #[inline(always)]
    fn position(&self, v: u32) -> Vec3 {
        vec3(self.file.position(v))
    }

    /// o_mesh.c's `volume_sign` for the edge from `a` to `b`.
    #[inline(always)]
    fn volume_sign(&self, ray: &Ray, a: u32, b: u32) -> i32 {
        let (lo, hi, reversed) = if a > b { (b, a, true) } else { (a, b, false) };
        let v1 = self.position(lo);
        let v2d = self.position(hi) - ray.org;
        let (o, d) = (ray.org, ray.dir);
        let mut vol = (v1.x - o.x) * (v2d.y * d.z - v2d.z * d.y);
        vol += (v1.y - o.y) * (v2d.z * d.x - v2d.x * d.z);
        vol += (v1.z - o.z) * (v2d.x * d.y - v2d.y * d.x);
        let sign = if vol > 0.0 { 1 } else { -1 };
        if reversed { -sign } else { sign }
    }

    /// The distance to triangle `slot` and its (unnormalised) normal, if the ray hits
    /// it nearer than `best` (`mesh_hit`).
    #[inline(always)]
    fn hit(&self, ray: &Ray, slot: u32, best: f64) -> Option<(f64, Vec3)> {
        let t = *self.triangles.get(slot as usize)?;
        let s1 = self.volume_sign(ray, t[0], t[1]);
        if s1 != self.volume_sign(ray, t[1], t[2]) || s1 != self.volume_sign(ray, t[2], t[0]) {
            return None;
        }
        let [p0, p1, p2] = t.map(|v| self.position(v));
        let nrm = (p0 - p2).cross(p1 - p0);
        let d = ray.dir.dot(nrm);
        if d == 0.0 {
            return None;
        }
        let d = (p0 - ray.org).dot(nrm) / d;
        (d > FTINY && d < best).then_some((d, nrm))
    }

    /// The nearest triangle along a ray in the mesh's frame: slot, distance, normal.
    fn nearest(&self, ray: &Ray, limit: f64) -> Option<(u32, f64, Vec3)> {
        let mut best: Option<(u32, f64, Vec3)> = None;
        self.bvh.traverse(ray, limit, |slot| {
            let bound = best.map_or(limit, |b| b.1);
            if let Some((d, n)) = self.hit(ray, slot, bound) {
                best = Some((slot, d, n));
                return d;
            }
            bound
        });
        best
    }
}

/// A `mesh` primitive: its file's geometry and its placement.
#[derive(Clone, Debug)]
pub struct MeshShape {
    pub geometry: Arc<MeshGeometry>,
    /// The transform (`x.f`, scale made positive) and its inverse (`x.b`).
    pub forward: Transform,
    pub backward: Transform,
    bounds: Bounds,
}

impl PartialEq for MeshShape {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.geometry, &other.geometry)
            && self.forward == other.forward
            && self.backward == other.backward
    }
}

/// What the shading of a mesh hit needs beyond the hit: the triangle's material index
/// in the file (-1: none), the smoothed normal's perturbation and the (u,v).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeshSurface {
    pub material: i16,
    pub pert: Vec3,
    pub uv: [f64; 2],
}

/// Compiled scene files do not hold meshes yet: writing one fails with this message,
/// which `radc build` reports.
impl serde::Serialize for MeshShape {
    fn serialize<S: serde::Serializer>(&self, _: S) -> Result<S::Ok, S::Error> {
        Err(serde::ser::Error::custom(
            "scenes with meshes cannot be stored in compiled scene files yet",
        ))
    }
}

impl<'de> serde::Deserialize<'de> for MeshShape {
    fn deserialize<D: serde::Deserializer<'de>>(_: D) -> Result<Self, D::Error> {
        Err(serde::de::Error::custom(
            "compiled scene files do not hold meshes",
        ))
    }
}

impl MeshShape {
    pub fn new(
        geometry: Arc<MeshGeometry>,
        mut forward: Transform,
        mut backward: Transform,
    ) -> Self {
        forward.scale = forward.scale.abs();
        backward.scale = backward.scale.abs();
        let b = geometry.bounds;
        let mut bounds = Bounds::EMPTY;
        for i in 0..8 {
            let corner = [
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            ];
            bounds = bounds.union(Bounds::point(vec3(forward.point(corner))));
        }
        MeshShape {
            geometry,
            forward,
            backward,
            bounds: bounds.padded(),
        }
    }

    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// The ray in the mesh's frame, its direction unit length again (`o_mesh`).
    fn local_ray(&self, ray: &Ray) -> Ray {
        let b = &self.backward;
        let org = vec3(b.point(ray.org.to_array()));
        let dir = vec3(b.vector(ray.dir.to_array())) / b.scale;
        Ray::new(org, dir)
    }

    /// The nearest hit no farther than `tmax`; `sub` is the triangle's slot.
    pub fn intersect_within(&self, ray: &Ray, tmax: f64) -> Option<ShapeHit> {
        let local = self.local_ray(ray);
        let limit = if tmax.is_finite() {
            tmax * self.backward.scale
        } else {
            f64::INFINITY
        };
        let (slot, d, nrm) = self.geometry.nearest(&local, limit)?;
        let t = d * self.forward.scale;
        if t > tmax {
            return None;
        }
        let mut normal = vec3(self.forward.vector(nrm.to_array()));
        normalize(&mut normal);
        Some(ShapeHit {
            t,
            normal,
            rod: -ray.dir.dot(normal),
            sub: slot,
        })
    }

    /// The material, smoothed normal and (u,v) of a hit on triangle `slot`, found
    /// again along `ray` (`o_mesh` after the hit), in world coordinates; the
    /// perturbation is relative to `normal`, the hit's world normal.
    pub fn surface(&self, ray: &Ray, slot: u32, normal: Vec3) -> MeshSurface {
        let g = &*self.geometry;
        let file = &*g.file;
        let Some(&tri) = g.triangles.get(slot as usize) else {
            return MeshSurface::default();
        };
        let material = g
            .file_index
            .get(slot as usize)
            .and_then(|&i| file.triangle_materials.get(i as usize))
            .copied()
            .unwrap_or(-1);
        let mut out = MeshSurface {
            material,
            ..MeshSurface::default()
        };
        let normals = tri.map(|v| file.normal(v));
        let uvs = tri.map(|v| file.uv(v));
        let smooth = normals.iter().all(Option::is_some);
        let mapped = uvs.iter().all(Option::is_some);
        if !smooth && !mapped {
            return out;
        }
        let local = self.local_ray(ray);
        let Some((d, _)) = g.hit(&local, slot, f64::INFINITY) else {
            return out;
        };
        let p = local.org + local.dir * d;
        let [v0, v1, v2] = tri.map(|v| g.position(v));
        let Some(wt) = barycentric(p, v0, v1, v2) else {
            return out;
        };
        if let [Some(n0), Some(n1), Some(n2)] = normals {
            let local_pert: [f64; 3] =
                std::array::from_fn(|i| wt[0] * n0[i] + wt[1] * n1[i] + wt[2] * n2[i]);
            let mut pert = vec3(self.forward.vector(local_pert));
            if normalize(&mut pert) != 0.0 {
                out.pert = pert - normal;
            }
        }
        if let [Some(a), Some(b), Some(c)] = uvs {
            out.uv = std::array::from_fn(|i| wt[0] * a[i] + wt[1] * b[i] + wt[2] * c[i]);
        }
        out
    }
}

/// tmesh.c's `get_baryc` (`comp_baryc` then `eval_baryc`): weights of `p` on the
/// triangle, in the plane of its major axis; `None` for a degenerate triangle.
fn barycentric(p: Vec3, v1: Vec3, v2: Vec3, v3: Vec3) -> Option<[f64; 3]> {
    let va = (v1 - v2).cross(v3 - v2);
    let mut ax = usize::from(va.y * va.y > va.x * va.x);
    if va.z * va.z > va[ax] * va[ax] {
        ax = 2;
    }
    let (ax0, ax1) = ((ax + 1) % 3, (ax + 2) % 3);
    let mut tm = [[0.0; 3]; 2];
    let mut v = [v1, v2, v3];
    for row in &mut tm {
        let [a, b, c] = v;
        let vab = [a[ax0] - b[ax0], a[ax1] - b[ax1]];
        let vcb = [c[ax0] - b[ax0], c[ax1] - b[ax1]];
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
        *row = [w[0], w[1], -(b[ax0] * w[0] + b[ax1] * w[1])];
        v = [b, c, a];
    }
    let (u, w) = (p[ax0], p[ax1]);
    let w0 = u * tm[0][0] + w * tm[0][1] + tm[0][2];
    let w1 = u * tm[1][0] + w * tm[1][1] + tm[1][2];
    Some([w0, w1, 1.0 - w1 - w0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn barycentric_weights_recover_the_vertices() {
        let (a, b, c) = (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.2),
        );
        for (p, want) in [
            (a, [1.0, 0.0, 0.0]),
            (b, [0.0, 1.0, 0.0]),
            (c, [0.0, 0.0, 1.0]),
        ] {
            let w = barycentric(p, a, b, c).unwrap();
            for i in 0..3 {
                assert!((w[i] - want[i]).abs() < 1e-12, "{w:?}");
            }
        }
        assert!(barycentric(a, a, a, b).is_none());
    }
}
