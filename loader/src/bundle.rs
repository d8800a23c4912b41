//! The scene file `radc build` (and radc as `oconv`) writes for a scene whose functions
//! are compiled at render time (patterns, textures: every `gensky` sky): the scene's own
//! texts and what its `!` commands printed, in the order they were read, so rendering it
//! reads, checks and compiles exactly the scene that was built, without running any
//! command again. Auxiliary files (function files, data files, pictures) are found along
//! the search path when the scene is loaded, as rtrace finds them for an octree.
//!
//! Layout, all integers little-endian: magic `RADCSRC\x1a` (8 bytes), format version
//! (4), radc version (1 + n), payload length (8), CRC-32 of the payload (4), payload
//! ([`SceneBundle`] in postcard's serde encoding). Like a compiled scene, a bundle is
//! read only by the radc version that wrote it; every damage is an error, never a panic.

use serde::{Deserialize, Serialize};

/// The first bytes of a bundle.
pub const MAGIC: &[u8; 8] = b"RADCSRC\x1a";
/// The layout of the header and of [`SceneBundle`].
pub const FORMAT_VERSION: u32 = 2;
const RADC_VERSION: &str = env!("CARGO_PKG_VERSION");

/// A scene as it was read: its files and its commands' outputs.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SceneBundle {
    pub files: Vec<BundledFile>,
    /// Every command expansion, in the order the reading asked for them.
    pub expansions: Vec<RecordedExpansion>,
    /// The mesh files the scene places, as they were when it was built: they are read
    /// again by name when it is loaded (the bundle holds no copy), and refused if they
    /// changed.
    pub meshes: Vec<MeshStamp>,
}

/// A mesh file by name as written, with its length and CRC-32 when built.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshStamp {
    pub name: String,
    pub length: u64,
    pub checksum: u32,
}

impl SceneBundle {
    /// Records the mesh files of a lowered scene.
    pub fn stamp_meshes(&mut self, ir: &radc_lang::scene::ir::Scene) {
        self.meshes = ir
            .data
            .meshes
            .iter()
            .map(|(name, m)| MeshStamp {
                name: name.clone(),
                length: m.length,
                checksum: m.checksum,
            })
            .collect();
    }

    /// The first mesh file of a lowered scene that differs from the one built with.
    pub fn changed_mesh(&self, ir: &radc_lang::scene::ir::Scene) -> Option<String> {
        self.meshes.iter().find_map(|stamp| {
            let now = ir.data.meshes.get(&stamp.name);
            let same = now.is_some_and(|m| m.length == stamp.length && m.checksum == stamp.checksum);
            (!same).then(|| {
                format!(
                    "mesh file '{}' changed since the scene was built (CRC-32 {:08x} then, {}                      now); rebuild the scene with 'radc build'",
                    stamp.name,
                    stamp.checksum,
                    now.map_or("missing or unreadable".to_string(), |m| format!("{:08x}", m.checksum))
                )
            })
        })
    }
}

/// A scene file named on the command line (or standard input).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BundledFile {
    /// As the user named it, for messages.
    pub name: String,
    /// Its folder, made absolute when built: auxiliary files and commands resolve from it.
    pub dir: String,
    pub text: String,
    /// Report unused modifiers (not for `.mat` files).
    pub warn_unused: bool,
}

/// What one `!` line produced when the scene was built.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RecordedExpansion {
    pub command: String,
    /// The folder it ran in.
    pub dir: String,
    pub outcome: RecordedOutcome,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum RecordedOutcome {
    Text(String),
    /// Wrote `text`, then failed (a warning).
    Partial {
        text: String,
        message: String,
        hint: Option<String>,
    },
    /// Failed without output (a warning).
    Failed {
        message: String,
        hint: Option<String>,
    },
}

/// True when `head` (a file's first bytes) starts like a bundle.
pub fn looks_bundled(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

impl SceneBundle {
    pub fn encode(&self) -> Result<Vec<u8>, String> {
        let payload = postcard::to_stdvec(self).map_err(|e| e.to_string())?;
        let version = RADC_VERSION.as_bytes();
        let version_len = u8::try_from(version.len()).map_err(|_| "version too long")?;
        let mut out = Vec::with_capacity(payload.len() + 32);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.push(version_len);
        out.extend_from_slice(version);
        out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        out.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
        out.extend_from_slice(&payload);
        Ok(out)
    }

    /// A bundle from a whole file's bytes: magic, versions, length, checksum, then the
    /// payload, each checked; never panics.
    pub fn decode(bytes: &[u8]) -> Result<SceneBundle, String> {
        let rebuild = "rebuild it with 'radc build'";
        if !looks_bundled(bytes) {
            return Err("not a radc scene bundle".into());
        }
        let mut at = MAGIC.len();
        let mut take = |n: usize| -> Result<&[u8], String> {
            let end = at
                .checked_add(n)
                .filter(|e| *e <= bytes.len())
                .ok_or_else(|| {
                    format!(
                        "truncated scene file: it ends at byte {}; {rebuild}",
                        bytes.len()
                    )
                })?;
            let piece = &bytes[at..end];
            at = end;
            Ok(piece)
        };
        let format = u32::from_le_bytes(take(4)?.try_into().map_err(|_| "bad header")?);
        let version_len = take(1)?[0] as usize;
        let radc = String::from_utf8_lossy(take(version_len)?).into_owned();
        if format != FORMAT_VERSION || radc != RADC_VERSION {
            return Err(format!(
                "scene file of format {format} written by radc {radc}; this radc \
                 {RADC_VERSION} reads format {FORMAT_VERSION} from its own version only: {rebuild}"
            ));
        }
        let length = u64::from_le_bytes(take(8)?.try_into().map_err(|_| "bad header")?);
        let checksum = u32::from_le_bytes(take(4)?.try_into().map_err(|_| "bad header")?);
        let length = usize::try_from(length).map_err(|_| "impossible payload length")?;
        let payload = take(length)?;
        if at != bytes.len() {
            return Err(format!(
                "{} bytes after the scene file's payload; {rebuild}",
                bytes.len() - at
            ));
        }
        let found = crc32fast::hash(payload);
        if found != checksum {
            return Err(format!(
                "corrupt scene file: the payload's checksum is {found:08x}, the header says \
                 {checksum:08x}; {rebuild}"
            ));
        }
        let (bundle, left) = postcard::take_from_bytes::<SceneBundle>(payload)
            .map_err(|e| format!("scene file does not decode ({e}); {rebuild}"))?;
        if !left.is_empty() {
            return Err(format!(
                "{} bytes left after the scene; {rebuild}",
                left.len()
            ));
        }
        Ok(bundle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bundle() -> SceneBundle {
        SceneBundle {
            files: vec![BundledFile {
                name: "room.rad".into(),
                dir: "/tmp".into(),
                text: "void plastic m 0 0 5 .5 .5 .5 0 0\n!gensky 3 21 12\n".into(),
                warn_unused: true,
            }],
            expansions: vec![RecordedExpansion {
                command: "gensky 3 21 12".into(),
                dir: "/tmp".into(),
                outcome: RecordedOutcome::Text("void brightfunc skyfunc ...".into()),
            }],
            meshes: vec![MeshStamp {
                name: "ball.rtm".into(),
                length: 30893,
                checksum: 0x1234_5678,
            }],
        }
    }

    #[test]
    fn a_bundle_round_trips() {
        let b = bundle();
        let bytes = b.encode().expect("encodes");
        assert!(looks_bundled(&bytes));
        assert_eq!(SceneBundle::decode(&bytes).expect("decodes"), b);
    }

    #[test]
    fn every_truncation_and_every_flipped_byte_is_an_error_not_a_panic() {
        let bytes = bundle().encode().expect("encodes");
        for n in 0..bytes.len() {
            assert!(SceneBundle::decode(&bytes[..n]).is_err(), "prefix {n}");
        }
        for i in 0..bytes.len() {
            let mut damaged = bytes.clone();
            damaged[i] ^= 0x5a;
            // A flip in the version string may still decode only if it is the same
            // string; anything else must be refused.
            if let Ok(b) = SceneBundle::decode(&damaged) {
                assert_eq!(b, bundle(), "byte {i}");
            }
        }
    }
}
