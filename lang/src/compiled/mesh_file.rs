//! Radiance's compiled mesh files (`.rtm`, written by obj2mesh; readmesh.c and mesh.c).
//!
//! After the information header (`FORMAT=Radiance_tmesh`): a 2-byte magic number that
//! also gives the writer's `sizeof(OBJECT)`, the bounding cube (origin and size as
//! `%.12g` text), the (u,v) limits, obj2mesh's octree of triangles (skipped: radc
//! builds its own tree), the materials as a binary scene section, then patches of up
//! to 256 vertices. A vertex is three 32-bit fractions of the cube, an optional
//! 4-byte direction code (dircode.c) and optional 32-bit (u,v) fractions; a triangle
//! names three vertices of its patch, or (joiners) vertices of other patches by ID.
//!
//! radc keeps the vertices in their 32-bit form, numbered patch by patch, so a
//! vertex's number orders as Radiance's vertex ID does (mesh edges are oriented by
//! it), and decodes a position exactly as `getmeshvert` does when asked.

use super::objects::{BinaryObject, read_objects};
use super::portio::{BinaryError, Reader, Result};

/// The format line of a mesh file's header.
pub const MESH_FORMAT: &str = "Radiance_tmesh";
/// `MESHMAGIC`: the magic number less the writer's object size.
pub const MESH_MAGIC: i64 = 8 + 311;
/// `MAXSET`: the most objects (here triangles) an octree leaf holds.
const MAX_SET: i64 = 511;
/// `FTINY`, below which Radiance calls a mesh's cube empty.
const FTINY: f64 = 1e-6;

/// A mesh file, read and checked as readmesh.c and `checkmesh` do.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshFile {
    /// The information header's lines.
    pub header: Vec<String>,
    /// The writer's `sizeof(OBJECT)`.
    pub objsize: usize,
    /// The bounding cube: its lowest corner and its size.
    pub origin: [f64; 3],
    pub size: f64,
    /// `uvlim`: the lowest (u,v), then the highest.
    pub uv_limits: [[f64; 2]; 2],
    /// The materials, as stored (obj2mesh's `-a` files and `usemtl` names).
    pub materials: Vec<BinaryObject>,
    /// Per vertex, its position as fractions of the cube in units of 2^-32.
    pub vertices: Vec<[u32; 3]>,
    /// Per vertex its normal's direction code (0: none); empty when no vertex has one.
    pub normals: Vec<i32>,
    /// Per vertex its (u,v) fractions (`[0, _]`: none); empty when no vertex has one.
    pub uvs: Vec<[u32; 2]>,
    /// Per triangle its three vertices, in the file's order.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle the index of its material in `materials`, -1 for none.
    pub triangle_materials: Vec<i16>,
    /// Whether obj2mesh's octree was empty (Radiance warns "empty mesh octree").
    pub empty_tree: bool,
    /// The file's length and CRC-32: a scene built with `radc build` refers to the
    /// file by name and refuses it when these change.
    pub length: u64,
    pub checksum: u32,
}

/// Marks a vertex reference read as a vertex ID (a joiner's `patch << 8 | index`),
/// resolved to a vertex number once every patch is read; a local vertex is stored as
/// its number. Both fit below it: at most 2^22 patches of 256 vertices.
const UNRESOLVED: u32 = 1 << 31;

impl MeshFile {
    /// Reads a whole mesh file.
    pub fn read(bytes: &[u8]) -> Result<MeshFile> {
        let mut r = Reader::new(bytes, "truncated mesh file");
        let mut mesh = MeshFile::read_head(&mut r)?;
        skip_tree(&mut r, mesh.objsize, "mesh octree", &mut mesh.empty_tree)?;
        let at = r.offset();
        mesh.materials = read_objects(&mut r, mesh.objsize)?;
        for m in &mesh.materials {
            let modifier = crate::schema::lookup(&m.type_name)
                .is_some_and(|s| s.category != crate::schema::Category::Surface);
            if !modifier {
                return r.error(
                    at,
                    format!("non-modifier in mesh ({} \"{}\")", m.type_name, m.name),
                );
            }
        }
        let at = r.offset();
        let npatches = r.int(4)?;
        if !(0..=1 << 22).contains(&npatches) {
            return r.error(at, "bad number of mesh patches");
        }
        let mut patch_start = Vec::with_capacity(npatches as usize + 1);
        for _ in 0..npatches {
            patch_start.push(mesh.vertices.len() as u32);
            mesh.read_patch(&mut r)?;
        }
        patch_start.push(mesh.vertices.len() as u32);
        mesh.resolve(&patch_start)?;
        mesh.length = bytes.len() as u64;
        mesh.checksum = crc32fast::hash(bytes);
        Ok(mesh)
    }

    /// The header, magic number and bounds: all `radc check` needs to say whether a
    /// file is a mesh file, from its first few hundred bytes.
    pub fn read_header(bytes: &[u8]) -> Result<MeshFile> {
        MeshFile::read_head(&mut Reader::new(bytes, "truncated mesh file"))
    }

    fn read_head(r: &mut Reader<'_>) -> Result<MeshFile> {
        let Some((header, format)) = r.header() else {
            return r.error(0, "not a Radiance mesh file (no information header)");
        };
        if let Some(f) = format.filter(|f| f != MESH_FORMAT) {
            return r.error(0, format!("not a Radiance mesh file (its format is '{f}')"));
        }
        let at = r.offset();
        let objsize = r.int(2)? - MESH_MAGIC;
        if !(1..=8).contains(&objsize) {
            return r.error(at, "incompatible mesh format");
        }
        let mut mesh = MeshFile {
            header,
            objsize: objsize as usize,
            ..MeshFile::default()
        };
        for i in 0..3 {
            mesh.origin[i] = crate::c_number::atof(&r.string()?);
        }
        let at = r.offset();
        mesh.size = crate::c_number::atof(&r.string()?);
        for i in 0..2 {
            mesh.uv_limits[0][i] = r.real()?;
            mesh.uv_limits[1][i] = r.real()?;
        }
        if mesh.size.is_nan() || mesh.size <= FTINY {
            return r.error(at, "illegal octree bounds in mesh");
        }
        Ok(mesh)
    }

    fn uv_bounded(&self) -> bool {
        let [lo, hi] = self.uv_limits;
        hi[0] - lo[0] > FTINY && hi[1] - lo[1] > FTINY
    }

    /// One patch (`getpatch`); joiners' vertex IDs are left for [`MeshFile::resolve`].
    fn read_patch(&mut self, r: &mut Reader<'_>) -> Result<()> {
        let at = r.offset();
        let flags = r.int(1)?;
        if flags & 1 == 0 || flags & !7 != 0 {
            return r.error(at, "bad patch flags");
        }
        let at = r.offset();
        let n = r.int(2)?;
        if !(1..=256).contains(&n) {
            return r.error(at, "bad number of patch vertices");
        }
        let first = self.vertices.len();
        for _ in 0..n {
            let x = r.int(4)? as u32;
            let y = r.int(4)? as u32;
            let z = r.int(4)? as u32;
            self.vertices.push([x, y, z]);
        }
        if flags & 2 != 0 {
            self.normals.resize(first, 0);
            for _ in 0..n {
                self.normals.push(r.int(4)? as i32);
            }
        } else if !self.normals.is_empty() {
            self.normals.resize(self.vertices.len(), 0);
        }
        if flags & 4 != 0 {
            if !self.uv_bounded() {
                return r.error(at, "unreferenced uv coordinates");
            }
            self.uvs.resize(first, [0, 0]);
            for _ in 0..n {
                let u = r.int(4)? as u32;
                let v = r.int(4)? as u32;
                self.uvs.push([u, v]);
            }
        } else if !self.uvs.is_empty() {
            self.uvs.resize(self.vertices.len(), [0, 0]);
        }
        // Local triangles use indices into this patch: vertex numbers from its first.
        let local = |i: i64| -> u32 { first as u32 + i as u32 };
        let id = |v: i64| -> u32 { (v as u32 & !UNRESOLVED) | UNRESOLVED };
        let at = r.offset();
        let ntris = r.int(2)?;
        if !(0..=512).contains(&ntris) {
            return r.error(at, "bad number of local triangles");
        }
        let start = self.triangles.len();
        for _ in 0..ntris {
            let a = r.int(1)? & 0xff;
            let b = r.int(1)? & 0xff;
            let c = r.int(1)? & 0xff;
            if a >= n || b >= n || c >= n {
                return r.error(r.offset() - 3, "bad local triangle index");
            }
            self.triangles.push([local(a), local(b), local(c)]);
        }
        let at = r.offset();
        if r.int(2)? > 1 {
            for _ in start..self.triangles.len() {
                self.triangle_materials.push(r.int(2)? as i16);
            }
        } else {
            let sole = r.int(2)? as i16;
            self.triangle_materials.resize(self.triangles.len(), sole);
        }
        if !self.materials.is_empty()
            && self.triangle_materials[start..]
                .iter()
                .any(|&m| m < 0 || m as usize >= self.materials.len())
        {
            return r.error(at, "bad local triangle material");
        }
        let at = r.offset();
        let nj1 = r.int(2)?;
        if !(0..=256).contains(&nj1) {
            return r.error(at, "bad number of joiner triangles");
        }
        for _ in 0..nj1 {
            let v1 = r.int(4)?;
            let b = r.int(1)? & 0xff;
            let c = r.int(1)? & 0xff;
            let m = r.int(2)? as i16;
            if b >= n || c >= n {
                return r.error(r.offset() - 4, "bad j1 triangle local index");
            }
            if !(0..1 << 30).contains(&v1) {
                return r.error(r.offset() - 8, "bad j1 triangle joiner");
            }
            self.check_material(r, m, "bad j1 triangle material")?;
            self.triangles.push([id(v1), local(b), local(c)]);
            self.triangle_materials.push(m);
        }
        let at = r.offset();
        let nj2 = r.int(2)?;
        if !(0..=256).contains(&nj2) {
            return r.error(at, "bad number of double joiner triangles");
        }
        for _ in 0..nj2 {
            let v1 = r.int(4)?;
            let v2 = r.int(4)?;
            let c = r.int(1)? & 0xff;
            let m = r.int(2)? as i16;
            if c >= n {
                return r.error(r.offset() - 3, "bad j2 triangle local index");
            }
            if !(0..1 << 30).contains(&v1) || !(0..1 << 30).contains(&v2) {
                return r.error(r.offset() - 11, "bad j2 triangle joiner");
            }
            self.check_material(r, m, "bad j2 triangle material")?;
            self.triangles.push([id(v1), id(v2), local(c)]);
            self.triangle_materials.push(m);
        }
        Ok(())
    }

    fn check_material(&self, r: &Reader<'_>, m: i16, what: &str) -> Result<()> {
        if !self.materials.is_empty() && (m < 0 || m as usize >= self.materials.len()) {
            return r.error(r.offset() - 2, what);
        }
        Ok(())
    }

    /// Joiners' vertex IDs (patch << 8 | index) to vertex numbers, in place.
    fn resolve(&mut self, patch_start: &[u32]) -> Result<()> {
        for t in &mut self.triangles {
            for v in t.iter_mut().filter(|v| **v & UNRESOLVED != 0) {
                let id = *v & !UNRESOLVED;
                let (patch, index) = ((id >> 8) as usize, id & 0xff);
                *v = match (patch_start.get(patch), patch_start.get(patch + 1)) {
                    (Some(&s), Some(&e)) if s + index < e => s + index,
                    _ => {
                        return Err(BinaryError {
                            offset: 0,
                            message: format!("bad triangle joiner (vertex ID {id})"),
                        });
                    }
                };
            }
        }
        Ok(())
    }

    /// A vertex's position, as `getmeshvert` decodes it.
    #[inline(always)]
    pub fn position(&self, v: u32) -> [f64; 3] {
        let res = (1.0 / 4294967296.0) * self.size;
        let q = self.vertices[v as usize];
        [
            self.origin[0] + (f64::from(q[0]) + 0.5) * res,
            self.origin[1] + (f64::from(q[1]) + 0.5) * res,
            self.origin[2] + (f64::from(q[2]) + 0.5) * res,
        ]
    }

    /// A vertex's normal, when it has one (`decodedir`).
    pub fn normal(&self, v: u32) -> Option<[f64; 3]> {
        let code = *self.normals.get(v as usize)?;
        (code != 0).then(|| decode_direction(code))
    }

    /// A vertex's (u,v), when it has them.
    pub fn uv(&self, v: u32) -> Option<[f64; 2]> {
        let q = *self.uvs.get(v as usize)?;
        if q[0] == 0 {
            return None;
        }
        let [lo, hi] = self.uv_limits;
        Some(
            [0, 1]
                .map(|i| lo[i] + (hi[i] - lo[i]) * (f64::from(q[i]) + 0.5) * (1.0 / 4294967296.0)),
        )
    }
}

/// Skips a pre-ordered octree (`skiptree`) without recursion: damaged files may nest
/// without end. Sets `empty` when the root is an empty node.
pub(super) fn skip_tree(
    r: &mut Reader<'_>,
    objsize: usize,
    what: &str,
    empty: &mut bool,
) -> Result<()> {
    let mut pending: u64 = 1;
    let mut first = true;
    while pending > 0 {
        let at = r.offset();
        match r.byte() {
            Some(0) => {
                *empty |= first;
                pending -= 1;
            }
            Some(1) => {
                let n = r.int(objsize)?;
                if !(0..=MAX_SET).contains(&n) {
                    return r.error(at, format!("bad set in {what}"));
                }
                r.skip(n as usize * objsize)?;
                pending -= 1;
            }
            Some(2) => pending += 7,
            Some(_) => return r.error(at, format!("damaged {what}")),
            None => return r.error(at, format!("truncated {what}")),
        }
        first = false;
    }
    Ok(())
}

/// `decodedir`: a 4-byte direction code back to a unit vector.
pub fn decode_direction(code: i32) -> [f64; 3] {
    const SCALE: f64 = 11584.5;
    const ORDER: [[usize; 3]; 4] = [[1, 0, 2], [0, 1, 2], [1, 2, 0], [0, 2, 1]];
    if code == 0 {
        return [0.0; 3];
    }
    let c = code as u32;
    let ndx = (usize::from(c & 0o20 != 0) << 1) | usize::from(c & 0o10 != 0);
    let d1 = f64::from((c >> 5) & 0x1fff) * (1.0 / SCALE);
    let d2 = f64::from((c >> 18) & 0x1fff) * (1.0 / SCALE);
    let der = (1.0 - d1 * d1 - d2 * d2).sqrt();
    let mut v = [0.0; 3];
    v[ORDER[ndx][0]] = d1;
    v[ORDER[ndx][1]] = d2;
    v[ORDER[ndx][2]] = der;
    for (i, x) in v.iter_mut().enumerate() {
        if c & (1 << i) != 0 {
            *x *= -1.0;
        }
    }
    v
}

/// `encodedir`: a unit vector to its 4-byte code (never 0 for a non-zero vector).
pub fn encode_direction(dv: [f64; 3]) -> i32 {
    const SCALE: f64 = 11584.5;
    let mut dc: i32 = 0;
    let mut cd = [0i32; 3];
    for i in 0..3 {
        if dv[i] < 0.0 {
            cd[i] = (dv[i] * -SCALE + 0.5) as i32;
            dc |= 1 << i;
        } else {
            cd[i] = (dv[i] * SCALE + 0.5) as i32;
        }
    }
    if cd[0] | cd[1] | cd[2] == 0 {
        return 0;
    }
    let cm = if cd[0] <= cd[1] {
        dc |= 0o10 | cd[0] << 5;
        cd[1]
    } else {
        dc |= cd[1] << 5;
        cd[0]
    };
    if cd[2] <= cm {
        dc |= 0o20 | cd[2] << 18;
    } else {
        dc |= cm << 18;
    }
    if dc == 0 { 0o10 } else { dc }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direction_codes_round_trip_within_their_accuracy() {
        for v in [
            [0.0, 0.0, 1.0],
            [0.6, -0.8, 0.0],
            [-0.267, 0.534, -0.802],
            [0.577, 0.577, 0.577],
        ] {
            let n: f64 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            let v = v.map(|x: f64| x / n.sqrt());
            let back = decode_direction(encode_direction(v));
            let dot: f64 = (0..3).map(|i| v[i] * back[i]).sum();
            assert!(dot > (0.006f64).to_radians().cos(), "{v:?} -> {back:?}");
        }
        assert_eq!(decode_direction(0), [0.0; 3]);
    }
}

#[cfg(test)]
mod obj2mesh_files {
    use super::*;

    /// `tests/data/trace/scenes/ball.rtm`: Radiance's obj2mesh of `ball.obj` (a 12 x 24 sphere
    /// with normals, uv and two materials from `ball_materials.rad`).
    #[test]
    fn reads_a_mesh_radiance_wrote() {
        let bytes = std::fs::read(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/data/trace/scenes/ball.rtm"
        ))
        .unwrap();
        let m = MeshFile::read(&bytes).unwrap();
        assert_eq!(m.objsize, 4);
        assert_eq!(m.materials.len(), 2);
        assert_eq!(m.materials[0].name, "red");
        // The poles' triangles are degenerate (two vertices coincide): obj2mesh drops them.
        assert!(m.triangles.len() > 500, "{}", m.triangles.len());
        assert_eq!(m.normals.len(), m.vertices.len());
        for t in 0..m.triangles.len() {
            for &v in &m.triangles[t] {
                let p = m.position(v);
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                assert!((r - 1.0).abs() < 1e-5, "{r}");
                let n = m.normal(v).unwrap();
                let d: f64 = (0..3).map(|i| n[i] * p[i]).sum();
                assert!(d > 0.9999, "{d}");
                let uv = m.uv(v).unwrap();
                assert!(
                    uv.iter().all(|u| (-1e-6..=1.0 + 1e-6).contains(u)),
                    "{uv:?} {:?}",
                    m.uv_limits
                );
            }
        }
        // Every truncation is an error, never a panic.
        for cut in (0..bytes.len()).step_by(97) {
            assert!(MeshFile::read(&bytes[..cut]).is_err());
        }
    }
}
