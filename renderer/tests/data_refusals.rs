//! Data and picture patterns the renderer cannot evaluate as p_data.c would are
//! refused by name, never rendered approximately.

use std::collections::HashMap;

use radc_lang::FileId;
use radc_lang::scene::{FileLookup, LowerInput};
use radc_lang::schema::FileKind;
use radc_renderer::Scene;

/// Files held in memory.
struct Files(HashMap<&'static str, Vec<u8>>);

impl FileLookup for Files {
    fn exists(&self, name: &str, _: FileKind, _: FileId) -> bool {
        self.0.contains_key(name)
    }
    fn read(&self, name: &str, _: FileKind, _: FileId) -> Option<String> {
        Some(String::from_utf8_lossy(self.0.get(name)?).into_owned())
    }
    fn load(&self, name: &str, kind: FileKind, from: FileId) -> Option<(FileId, String)> {
        Some((FileId(1000), self.read(name, kind, from)?))
    }
    fn read_head(&self, name: &str, _: FileKind, _: FileId, max: usize) -> Option<Vec<u8>> {
        let bytes = self.0.get(name)?;
        Some(bytes[..bytes.len().min(max)].to_vec())
    }
}

fn files() -> Files {
    let mut pic = b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n".to_vec();
    pic.extend_from_slice(&[128, 128, 128, 129]);
    Files(HashMap::from([
        (
            "f.cal",
            b"u = Px;\nf(x) = x;\nsneaky(x) = $28;\nv = 1;\n".to_vec(),
        ),
        ("one.dat", b"1\n0 1 2\n.5 .5\n".to_vec()),
        ("two.dat", b"2\n0 1 2\n0 1 2\n.5 .5 .5 .5\n".to_vec()),
        ("xyz.hdr", pic),
    ]))
}

/// The refusal of the pattern named `p` in a scene with it on a plastic floor.
fn refusal(pattern: &str) -> String {
    let text = format!(
        "{pattern}\np plastic m 0 0 5 .5 .5 .5 0 0\n\
         m polygon floor 0 0 12 -5 -5 0 5 -5 0 5 5 0 -5 5 0\n"
    );
    let (syntax, diags) = radc_lang::scene::parse(FileId(0), &text);
    assert!(diags.is_empty(), "{diags:?}");
    let input = LowerInput {
        file: FileId(0),
        syntax: &syntax,
        warn_unused: true,
    };
    let (ir, _) = radc_lang::scene::lower(&[input], &files());
    let refusals = Scene::refusals(&ir);
    let found = refusals
        .iter()
        .find(|r| r.name == "p")
        .unwrap_or_else(|| panic!("{pattern}: refused ({refusals:?})"));
    found.why.clone()
}

#[test]
fn a_function_file_reading_the_data_channels_is_refused() {
    let why = refusal("void brightdata p 4 sneaky one.dat f.cal u 0 0");
    assert!(why.contains("channel 28"), "{why}");
}

#[test]
fn a_variable_or_variadic_function_is_refused() {
    for f in ["v", "max", "nosuch"] {
        let why = refusal(&format!("void brightdata p 4 {f} one.dat f.cal u 0 0"));
        assert!(why.contains(f), "{f}: {why}");
    }
}

#[test]
fn colordata_files_of_different_dimensions_are_refused() {
    let why = refusal("void colordata p 9 f f f one.dat two.dat one.dat f.cal u u 0 0");
    assert!(why.contains("dimension"), "{why}");
}

#[test]
fn a_missing_data_file_or_a_bad_picture_is_refused() {
    let why = refusal("void brightdata p 4 f gone.dat f.cal u 0 0");
    assert!(why.contains("gone.dat"), "{why}");
    let why = refusal("void colorpict p 7 f f f xyz.hdr f.cal u u 0 0");
    assert!(why.contains("xyz.hdr"), "{why}");
}

#[test]
fn too_few_coordinates_are_refused() {
    let why = refusal("void brightdata p 4 f two.dat f.cal u 0 0");
    assert!(why.contains("too few"), "{why}");
}
