//! The compiled scene file (`.rsc`, written by `radc build`): oconv's role, an octree
//! file's replacement. It holds a compiled [`Scene`] (reachable surfaces, materials,
//! light sources and the BVH), so rendering skips parsing, checking and BVH building.
//!
//! Layout, all integers little-endian:
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `RADCSCN\x1a` (`\x1a` stops `type`/`more` on a text terminal, as PNG's does) |
//! | 4 | format version ([`FORMAT_VERSION`]) |
//! | 1 + n | radc version that wrote it (length, then UTF-8) |
//! | 8 | payload length |
//! | 4 | CRC-32 of the payload |
//! | rest | payload: the scene in postcard's serde encoding |
//!
//! The payload is the serde encoding of the scene types themselves, so a field added to
//! a material or a light is stored without touching this module. postcard's encoding is
//! not self-describing: a file written by a build whose types differ would decode into
//! nonsense or fail, so a reader accepts only files of its own format version *and*
//! radc version. Bump [`FORMAT_VERSION`] whenever the compiled scene's types change
//! within one radc version.

use std::fmt;

use crate::scene::Scene;

/// The first bytes of every compiled scene file.
pub const MAGIC: &[u8; 8] = b"RADCSCN\x1a";
/// The layout of the header and of the scene types. See the module's documentation.
pub const FORMAT_VERSION: u32 = 5;
/// The radc version stamped into files this build writes.
pub const RADC_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Why bytes are not a compiled scene this build can load.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SceneFileError {
    /// Not a compiled scene at all; `what` says what it looks like instead.
    Foreign { what: &'static str },
    /// Fewer bytes than the header or the payload length promises.
    Truncated { expected: u64, found: u64 },
    /// The payload's checksum does not match the header's.
    Corrupt { expected: u32, found: u32 },
    /// Written by another format version or another radc version.
    Version { format: u32, radc: String },
    /// The checksum matched but the payload does not decode (or has bytes left over):
    /// written by an incompatible build with the same version stamp.
    Undecodable { why: String },
    /// The scene could not be encoded (never expected: every type is plain data).
    Encode { why: String },
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneFileError::Foreign { what } => write!(
                f,
                "not a radc compiled scene ({what}); give the scene's .rad files, or compile \
                 them with 'radc build'"
            ),
            SceneFileError::Truncated { expected, found } => write!(
                f,
                "truncated compiled scene: {found} bytes where {expected} were expected; \
                 rebuild it with 'radc build'"
            ),
            SceneFileError::Corrupt { expected, found } => write!(
                f,
                "corrupt compiled scene: the payload's checksum is {found:08x}, the header \
                 says {expected:08x}; rebuild it with 'radc build'"
            ),
            SceneFileError::Version { format, radc } => write!(
                f,
                "compiled scene of format {format} written by radc {radc}; this radc \
                 {RADC_VERSION} reads format {FORMAT_VERSION} from its own version only: \
                 rebuild it with 'radc build'"
            ),
            SceneFileError::Undecodable { why } => write!(
                f,
                "compiled scene does not decode ({why}): written by an incompatible build \
                 of radc; rebuild it with 'radc build'"
            ),
            SceneFileError::Encode { why } => write!(f, "cannot encode the scene: {why}"),
        }
    }
}

impl std::error::Error for SceneFileError {}

/// True when `head` (a file's first bytes) starts like a compiled scene.
pub fn looks_compiled(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// The whole file for `scene`: header and payload.
pub fn encode(scene: &Scene) -> Result<Vec<u8>, SceneFileError> {
    let payload =
        postcard::to_stdvec(scene).map_err(|e| SceneFileError::Encode { why: e.to_string() })?;
    frame(&payload)
}

/// A file around an already encoded `payload`: this build's header, its length and
/// checksum. Public so that the fuzzer can reach the decoder past the checksum.
pub fn frame(payload: &[u8]) -> Result<Vec<u8>, SceneFileError> {
    let version = RADC_VERSION.as_bytes();
    let version_len = u8::try_from(version.len()).map_err(|_| SceneFileError::Encode {
        why: "version string too long".into(),
    })?;
    let mut out = Vec::with_capacity(payload.len() + 32 + version.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.push(version_len);
    out.extend_from_slice(version);
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(payload).to_le_bytes());
    out.extend_from_slice(payload);
    Ok(out)
}

/// A scene from a whole file's bytes. Checks, in order: magic, versions, length,
/// checksum, then decodes; never panics on any input.
pub fn decode(bytes: &[u8]) -> Result<Scene, SceneFileError> {
    if !looks_compiled(bytes) {
        if MAGIC.starts_with(bytes) && !bytes.is_empty() {
            return Err(SceneFileError::Truncated {
                expected: MAGIC.len() as u64,
                found: bytes.len() as u64,
            });
        }
        return Err(SceneFileError::Foreign {
            what: describe_foreign(bytes),
        });
    }
    let mut r = Reader {
        bytes,
        at: MAGIC.len(),
    };
    let format = r.u32()?;
    let version_len = r.take(1)?[0] as usize;
    let radc = String::from_utf8_lossy(r.take(version_len)?).into_owned();
    if format != FORMAT_VERSION || radc != RADC_VERSION {
        return Err(SceneFileError::Version { format, radc });
    }
    let length = r.u64()?;
    let checksum = r.u32()?;
    let rest = &bytes[r.at..];
    if (rest.len() as u64) < length {
        return Err(SceneFileError::Truncated {
            expected: r.at as u64 + length,
            found: bytes.len() as u64,
        });
    }
    if rest.len() as u64 > length {
        return Err(SceneFileError::Undecodable {
            why: format!("{} bytes after the payload", rest.len() as u64 - length),
        });
    }
    let found = crc32fast::hash(rest);
    if found != checksum {
        return Err(SceneFileError::Corrupt {
            expected: checksum,
            found,
        });
    }
    let (scene, left) = postcard::take_from_bytes::<Scene>(rest)
        .map_err(|e| SceneFileError::Undecodable { why: e.to_string() })?;
    if !left.is_empty() {
        return Err(SceneFileError::Undecodable {
            why: format!("{} bytes left after the scene", left.len()),
        });
    }
    let mut scene = scene;
    scene
        .validate()
        .map_err(|why| SceneFileError::Undecodable { why })?;
    scene.pack_surfaces();
    Ok(scene)
}

/// What a file that is not a compiled scene looks like, for the error message.
fn describe_foreign(bytes: &[u8]) -> &'static str {
    let head = &bytes[..bytes.len().min(4096)];
    let text = String::from_utf8_lossy(head);
    if bytes.is_empty() {
        "the file is empty"
    } else if text.starts_with("#?RADIANCE") && text.contains("FORMAT=Radiance_octree") {
        "it is a Radiance octree, made by oconv"
    } else if text.starts_with("#?RADIANCE") || text.starts_with("#?RGBE") {
        "it is a Radiance file (a picture or other data with a Radiance header)"
    } else if head
        .iter()
        .all(|b| b.is_ascii_graphic() || b.is_ascii_whitespace())
    {
        "it is a text file: a scene description is given as .rad files"
    } else {
        "its first bytes are not radc's"
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], SceneFileError> {
        let end = self.at.checked_add(n).filter(|e| *e <= self.bytes.len());
        let Some(end) = end else {
            return Err(SceneFileError::Truncated {
                expected: (self.at + n) as u64,
                found: self.bytes.len() as u64,
            });
        };
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn u32(&mut self) -> Result<u32, SceneFileError> {
        let mut b = [0; 4];
        b.copy_from_slice(self.take(4)?);
        Ok(u32::from_le_bytes(b))
    }

    fn u64(&mut self) -> Result<u64, SceneFileError> {
        let mut b = [0; 8];
        b.copy_from_slice(self.take(8)?);
        Ok(u64::from_le_bytes(b))
    }
}

/// `ir::PrimId` lives in `radc-lang`, which has no serde derives on it: stored as its
/// number.
pub(crate) mod prim_id {
    use radc_lang::scene::ir::PrimId;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(id: &PrimId, s: S) -> Result<S::Ok, S::Error> {
        id.0.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<PrimId, D::Error> {
        u32::deserialize(d).map(PrimId)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::{Options, Tracer};
    use crate::math::Vec3;
    use crate::scene::tests::IrBuilder;
    use radc_lang::scene::ir::PrimKind;

    fn scene() -> Scene {
        let mut b = IrBuilder::default();
        let lamp = b.add("light", "lamp", None, PrimKind::Light { color: [10.0; 3] });
        b.add(
            "sphere",
            "bulb",
            Some(lamp),
            PrimKind::Sphere {
                center: [0.0, 0.0, 3.0],
                radius: 0.5,
            },
        );
        let grey = b.plastic("grey", 0.5);
        for i in 0..40 {
            b.square(&format!("floor{i}"), grey, -f64::from(i) * 0.1, true);
        }
        Scene::compile(&b.scene).expect("compiles")
    }

    #[test]
    fn round_trip_renders_identically() {
        let original = scene();
        let bytes = encode(&original).expect("encodes");
        let loaded = decode(&bytes).expect("decodes");
        assert_eq!(loaded.objects.len(), original.objects.len());
        assert_eq!(loaded.materials, original.materials);
        assert_eq!(loaded.sources, original.sources);
        // What is derived at load, not stored, is derived again.
        assert_eq!(loaded.surfaces, original.surfaces);
        for i in 0..original.objects.len() as u32 {
            assert_eq!(loaded.hit_info(i), original.hit_info(i));
            assert!(loaded.hit_info(i).is_some());
        }
        let (a, b) = (
            Tracer::new(&original, Options::default()),
            Tracer::new(&loaded, Options::default()),
        );
        for i in 0..50 {
            let x = f64::from(i) * 0.04 - 1.0;
            let org = Vec3::new(x, 0.3, 2.0);
            let dir = Vec3::new(0.1, -0.2, -1.0).normalize();
            let (ra, rb) = (a.radiance(org, dir), b.radiance(org, dir));
            assert_eq!(ra.color, rb.color);
            assert_eq!(ra.length, rb.length);
            assert_eq!(ra.hit, rb.hit);
        }
    }

    /// Found by the `rsc_payload` fuzzer: a mirror that names itself as its alternate
    /// sent shading round in a loop until the stack overflowed. A compiled scene
    /// cannot hold one; a damaged file that does is refused.
    #[test]
    fn alternates_in_a_loop_are_refused() {
        use crate::materials::{Alternate, Material, MaterialId, mirror::Mirror};
        let mut looped = scene();
        let last = MaterialId(looped.materials.len() as u32);
        looped.materials.push(Material::Mirror(Mirror {
            color: Vec3::ONE,
            alternate: Alternate::Material(last),
            texture: Vec3::ZERO,
        }));
        assert!(looped.validate().is_err());
        let e = decode(&encode(&looped).expect("encodes")).expect_err("a loop");
        assert!(e.to_string().contains("alternates in a loop"), "{e}");
        // A chain that ends is fine.
        let mut chained = scene();
        let first = MaterialId(0);
        chained.materials.push(Material::Mirror(Mirror {
            color: Vec3::ONE,
            alternate: Alternate::Material(first),
            texture: Vec3::ZERO,
        }));
        assert!(chained.validate().is_ok());
    }

    #[test]
    fn every_truncation_is_an_error() {
        let bytes = encode(&scene()).expect("encodes");
        for n in 0..bytes.len() {
            let e = decode(&bytes[..n]).expect_err("a truncated file");
            assert!(
                matches!(
                    e,
                    SceneFileError::Truncated { .. } | SceneFileError::Foreign { .. }
                ),
                "{n}: {e}"
            );
        }
    }

    #[test]
    fn flipped_payload_bytes_fail_the_checksum() {
        let bytes = encode(&scene()).expect("encodes");
        let header = MAGIC.len() + 4 + 1 + RADC_VERSION.len() + 8 + 4;
        for at in (header..bytes.len()).step_by(7) {
            let mut b = bytes.clone();
            b[at] ^= 0x20;
            assert!(
                matches!(decode(&b), Err(SceneFileError::Corrupt { .. })),
                "byte {at}"
            );
        }
    }

    #[test]
    fn other_versions_are_refused() {
        let mut bytes = encode(&scene()).expect("encodes");
        bytes[MAGIC.len()] = bytes[MAGIC.len()].wrapping_add(1);
        let e = decode(&bytes).expect_err("another format");
        assert!(
            matches!(e, SceneFileError::Version { format, .. } if format == FORMAT_VERSION + 1)
        );
        let mut bytes = encode(&scene()).expect("encodes");
        let v = MAGIC.len() + 5;
        bytes[v] = b'9';
        let e = decode(&bytes).expect_err("another radc");
        assert!(e.to_string().contains("rebuild"), "{e}");
    }

    #[test]
    fn foreign_files_say_what_they_are() {
        let octree = b"#?RADIANCE\noconv scene.rad\nFORMAT=Radiance_octree\n\n\x01\x02";
        let e = decode(octree).expect_err("an octree");
        assert!(e.to_string().contains("octree"), "{e}");
        let e = decode(b"void plastic red 0 0 5 1 0 0 0 0\n").expect_err("text");
        assert!(e.to_string().contains("text"), "{e}");
        let e = decode(&[0xff; 100]).expect_err("random bytes");
        assert!(matches!(e, SceneFileError::Foreign { .. }));
        assert!(decode(&[]).is_err());
    }

    /// Payloads that pass the checksum but were made by a different build: decoding
    /// must fail cleanly (or give a scene whose indices are checked), never panic.
    #[test]
    fn garbage_with_a_valid_checksum_never_panics() {
        let bytes = encode(&scene()).expect("encodes");
        let header = MAGIC.len() + 4 + 1 + RADC_VERSION.len() + 8 + 4;
        let payload = &bytes[header..];
        for at in 0..payload.len().min(600) {
            let mut p = payload.to_vec();
            p[at] = p[at].wrapping_add(0x41);
            let file = frame(&p).expect("frames");
            if let Ok(s) = decode(&file) {
                // Decoded: tracing it must still be safe.
                let t = Tracer::new(&s, Options::default());
                t.radiance(Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 0.0, -1.0));
            }
        }
    }
}
