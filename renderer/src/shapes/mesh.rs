//! Meshes (o_mesh.c): a mesh file's triangles under a BVH of their own, shared by every
//! `mesh` primitive that places the file, each placement a transform of the ray into
//! the mesh's frame, so the scene's tree holds one leaf per placement (a two-level
//! BVH).
//!
//! Whether a ray passes inside a triangle is decided as o_mesh.c decides it, by the
//! side of each edge the ray passes (Segura and Feito's signed volumes), but with
//! signs that are exact: each vertex is projected once into a frame sheared along the
//! ray (Woop, Benthin and Wald 2013), and each edge's side is the exact sign of a 2x2
//! determinant of those projections (a floating-point filter, then Kahan's fused
//! evaluation when the filter cannot tell). The signs are then those of one fixed
//! planar configuration, the same for every triangle around an edge or a vertex, and
//! an edge or vertex exactly on the ray counts as inside: no ray slips between the
//! triangles of a closed mesh, along an edge or through a vertex. (o_mesh.c's
//! rounded volumes, zero counting as negative, let rays through vertices escape.)
//! The distance and normal are o_mesh.c's. Positions are decoded from the file's
//! 32-bit fractions as `getmeshvert` decodes them, in the mesh's frame; distances there
//! are scaled back by the transform's scale.

use std::sync::Arc;

use radc_lang::compiled::MeshFile;
use radc_lang::transform::Transform;

use crate::bvh::Bvh;
use crate::math::{Bounds, FTINY, Vec3, normalize, vec3};
use crate::ray::{Ray, ShapeHit};

/// A mesh file's triangles under their tree. The file's triangle list is used as it
/// is, through the tree's slot order: nothing is copied.
pub struct MeshGeometry {
    pub file: Arc<MeshFile>,
    bvh: Bvh,
    bounds: Bounds,
}

impl std::fmt::Debug for MeshGeometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "MeshGeometry({} triangles)", self.file.triangles.len())
    }
}

impl MeshGeometry {
    /// Builds the tree over the file's triangles.
    pub fn new(file: Arc<MeshFile>) -> MeshGeometry {
        let triangle_bounds = |i: usize| {
            let [a, b, c] = file.triangles[i].map(|v| vec3(file.position(v)));
            Bounds {
                min: a.min(b).min(c),
                max: a.max(b).max(c),
            }
        };
        let bvh = Bvh::build_with(file.triangles.len(), triangle_bounds);
        let bounds = bvh.extent().unwrap_or(Bounds::EMPTY);
        MeshGeometry { file, bvh, bounds }
    }

    pub fn triangle_count(&self) -> usize {
        self.file.triangles.len()
    }

    /// Bytes held beyond the file's data: the tree.
    pub fn bytes(&self) -> usize {
        self.bvh.bytes()
    }

    /// The file's index of the triangle in `slot`.
    #[inline(always)]
    fn triangle_at(&self, slot: u32) -> Option<u32> {
        self.bvh.primitive(slot)
    }

    #[inline(always)]
    fn position(&self, v: u32) -> Vec3 {
        vec3(self.file.position(v))
    }

    /// The distance to triangle `slot` and its (unnormalised) normal, if the ray hits
    /// it nearer than `best` (`mesh_hit`'s plane, after the inside test below).
    #[inline(always)]
    fn hit(&self, ray: &Sheared, slot: u32, best: f64) -> Option<(f64, Vec3)> {
        let t = *self.file.triangles.get(self.triangle_at(slot)? as usize)?;
        let [p0, p1, p2] = t.map(|v| self.position(v));
        let [q0, q1, q2] = [p0, p1, p2].map(|p| ray.project(p));
        let e0 = orientation(q0, q1);
        let e1 = orientation(q1, q2);
        if (e0 < 0.0 && e1 > 0.0) || (e0 > 0.0 && e1 < 0.0) {
            return None;
        }
        let e2 = orientation(q2, q0);
        let (lo, hi) = (e0.min(e1).min(e2), e0.max(e1).max(e2));
        if (lo < 0.0 && hi > 0.0) || (lo == 0.0 && hi == 0.0) {
            return None;
        }
        let nrm = (p0 - p2).cross(p1 - p0);
        let d = ray.ray.dir.dot(nrm);
        if d == 0.0 {
            return None;
        }
        let d = (p0 - ray.ray.org).dot(nrm) / d;
        (d > FTINY && d < best).then_some((d, nrm))
    }

    /// The nearest triangle along a ray in the mesh's frame: slot, distance, normal.
    fn nearest(&self, ray: &Ray, limit: f64) -> Option<(u32, f64, Vec3)> {
        let mut best: Option<(u32, f64, Vec3)> = None;
        let sheared = Sheared::of(ray);
        self.bvh.traverse(ray, limit, |slot| {
            let bound = best.map_or(limit, |b| b.1);
            if let Some((d, n)) = self.hit(&sheared, slot, bound) {
                best = Some((slot, d, n));
                return d;
            }
            bound
        });
        best
    }
}

/// A ray in a frame that runs along it: the axes permuted so the ray's largest
/// direction component is the third, and the other two sheared away (Woop et al.).
struct Sheared {
    ray: Ray,
    kx: usize,
    ky: usize,
    kz: usize,
    sx: f64,
    sy: f64,
}

impl Sheared {
    fn of(ray: &Ray) -> Sheared {
        let d = ray.dir.abs();
        let kz = if d.x > d.y && d.x > d.z {
            0
        } else if d.y > d.z {
            1
        } else {
            2
        };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if ray.dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Sheared {
            ray: *ray,
            kx,
            ky,
            kz,
            sx: ray.dir[kx] / ray.dir[kz],
            sy: ray.dir[ky] / ray.dir[kz],
        }
    }

    /// A point's two coordinates across the ray, relative to the ray's origin.
    #[inline(always)]
    fn project(&self, p: Vec3) -> [f64; 2] {
        let a = p - self.ray.org;
        [
            a[self.kx] - self.sx * a[self.kz],
            a[self.ky] - self.sy * a[self.kz],
        ]
    }
}

/// `a.x b.y - a.y b.x` with the exact sign (and exactly zero when it is zero): the
/// plain difference where its error bound allows (Shewchuk's `orient2d` filter),
/// else Kahan's evaluation with fused multiply-adds, whose relative error is below
/// two ulps (Jeannerod, Louvet and Muller 2013).
#[inline(always)]
fn orientation(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (p, q) = (a[0] * b[1], a[1] * b[0]);
    let det = p - q;
    if det.abs() > (p.abs() + q.abs()) * 3.330_669_073_875_471_6e-16 {
        return det;
    }
    kahan_difference(a[0], b[1], a[1], b[0])
}

#[cold]
fn kahan_difference(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let w = c * d;
    let e = (-c).mul_add(d, w);
    let f = a.mul_add(b, -w);
    f + e
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
        let Some(index) = g.triangle_at(slot) else {
            return MeshSurface::default();
        };
        let Some(&tri) = file.triangles.get(index as usize) else {
            return MeshSurface::default();
        };
        let material = file
            .triangle_materials
            .get(index as usize)
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
        let Some((d, _)) = g.hit(&Sheared::of(&local), slot, f64::INFINITY) else {
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

#[cfg(test)]
mod watertight {
    use super::*;

    fn cube() -> Arc<MeshGeometry> {
        let bytes = std::fs::read(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/data/trace/scenes/box.rtm"
        ))
        .expect("box.rtm (Radiance's obj2mesh of box.obj)");
        Arc::new(MeshGeometry::new(Arc::new(
            MeshFile::read(&bytes).expect("a mesh"),
        )))
    }

    fn placed(g: &Arc<MeshGeometry>, scale: f64, shift: f64) -> MeshShape {
        let words = [
            "-s".to_string(),
            format!("{scale:e}"),
            "-t".into(),
            format!("{shift:e}"),
            format!("{:e}", -shift),
            format!("{:e}", shift * 0.5),
        ];
        let spanned: Vec<(&str, radc_lang::Span)> = words
            .iter()
            .map(|w| (w.as_str(), radc_lang::Span::default()))
            .collect();
        MeshShape::new(
            g.clone(),
            Transform::parse(&spanned).unwrap(),
            Transform::parse_inverse(&spanned).unwrap(),
        )
    }

    /// Rays aimed exactly at the closed cube's shared edges and corners (decoded vertex
    /// positions, and points between them), each going on towards the cube's centre,
    /// must hit it where aimed, at every scale and far from the origin: none slips
    /// between the two triangles of an edge or the faces of a corner.
    #[test]
    fn rays_at_shared_edges_and_corners_always_hit() {
        let g = cube();
        let file = &g.file;
        let n = file.vertices.len() as u32;
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for scale in [1e-4, 1e-2, 1.0, 1e3, 1e5] {
            for shift in [0.0, 1e3, 1e8] {
                if shift > 1e6 * scale {
                    // Beyond what f64 holds of the cube: 1e8 away a 1e-4 cube is 1e-8
                    // wide in ulps of 1.5e-8.
                    continue;
                }
                let mesh = placed(&g, scale, shift);
                let world = |p: Vec3| vec3(mesh.forward.point(p.to_array()));
                let centre = world(Vec3::splat(0.5));
                let mut tested = 0;
                let mut bad = 0;
                for t in &file.triangles {
                    for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                        assert!(a < n && b < n);
                        let (pa, pb) = (vec3(file.position(a)), vec3(file.position(b)));
                        for f in [0.0, 0.5, next()] {
                            let target = world(pa + (pb - pa) * f);
                            let mut toward = centre - target;
                            toward += Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5)
                                * (0.3 * toward.length());
                            let dir = toward.normalize();
                            let dist = 2.0 * scale;
                            let ray = Ray::new(target - dir * dist, dir);
                            let hit = mesh.intersect_within(&ray, f64::INFINITY);
                            let Some(h) = hit else {
                                panic!("scale {scale} shift {shift}: ray at {target} missed");
                            };
                            if (h.t - dist).abs() > 1e-3 * dist {
                                eprintln!(
                                    "scale {scale} shift {shift}: hit at {} not {dist}; edge {a} {b} f {f} pa {pa} pb {pb} local {:?}",
                                    h.t,
                                    mesh.local_ray(&ray)
                                );
                                bad += 1;
                            }
                            tested += 1;
                        }
                    }
                }
                assert_eq!(tested, file.triangles.len() * 9);
                assert_eq!(bad, 0);
            }
        }
    }
}
