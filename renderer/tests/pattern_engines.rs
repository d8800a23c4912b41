//! The scene's functions give the same pixels, bit for bit, whether the JIT or the
//! reference interpreter evaluates them.

use radc_lang::FileId;
use radc_lang::scene::{FileLookup, LowerInput};
use radc_lang::schema::FileKind;
use radc_renderer::procedural::Engine;
use radc_renderer::{Options, Scene, Tracer};

const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/trace/scenes");

/// Files beside the test scenes.
struct Beside;

impl FileLookup for Beside {
    fn exists(&self, name: &str, _: FileKind, _: FileId) -> bool {
        std::path::Path::new(SCENES).join(name).exists()
    }
    fn read(&self, name: &str, _: FileKind, _: FileId) -> Option<String> {
        std::fs::read_to_string(std::path::Path::new(SCENES).join(name)).ok()
    }
    fn load(&self, name: &str, kind: FileKind, from: FileId) -> Option<(FileId, String)> {
        Some((FileId(1000), self.read(name, kind, from)?))
    }
    fn read_head(&self, name: &str, _: FileKind, _: FileId, max: usize) -> Option<Vec<u8>> {
        let mut bytes = std::fs::read(std::path::Path::new(SCENES).join(name)).ok()?;
        bytes.truncate(max);
        Some(bytes)
    }
}

fn compiled(scene: &str, engine: Engine) -> Scene {
    let text = std::fs::read_to_string(format!("{SCENES}/{scene}")).expect("scene");
    let (syntax, diags) = radc_lang::scene::parse(FileId(0), &text);
    assert!(diags.is_empty(), "{diags:?}");
    let input = LowerInput {
        file: FileId(0),
        syntax: &syntax,
        warn_unused: true,
    };
    let (ir, diags) = radc_lang::scene::lower(&[input], &Beside);
    assert!(!diags.iter().any(|d| d.is_error()), "{diags:?}");
    Scene::compile_with(&ir, engine).expect("the patterns compile")
}

#[test]
fn jit_and_interpreter_shade_alike() {
    for scene in ["patterns.rad", "textures.rad"] {
        same_pixels(scene, 1000);
    }
}

/// The data and picture patterns: coordinates and the functions applied to the
/// values found run on both engines too.
#[test]
fn jit_and_interpreter_shade_data_patterns_alike() {
    same_pixels("data_patterns.rad", 800);
}

/// Texture data, mixtures (between materials, patterns and textures, from
/// functions, data and a picture) and the function and data materials.
#[test]
fn jit_and_interpreter_shade_mixtures_and_texture_data_alike() {
    same_pixels("texture_data.rad", 800);
    same_pixels("mixtures.rad", 800);
    same_pixels("functions.rad", 800);
    same_pixels("brtd.rad", 800);
    same_pixels("aniso_functions.rad", 400);
    same_pixels("aniso_patterns.rad", 400);
    same_pixels("mirror_patterns.rad", 400);
    same_pixels("glass_patterns.rad", 400);
    same_pixels("trans_textures.rad", 400);
    same_pixels("dielectric_patterns.rad", 400);
    same_pixels("ashik.rad", 400);
}

fn same_pixels(scene: &str, min_seen: usize) {
    let (jit, interp) = (
        compiled(scene, Engine::Jit),
        compiled(scene, Engine::Interpreter),
    );
    assert!(jit.functions.is_some(), "the scene has patterns");
    let options = Options {
        ambient: radc_renderer::math::Color::splat(0.05),
        ..Options::default()
    };
    let (a, b) = (
        Tracer::new(&jit, options.clone()),
        Tracer::new(&interp, options),
    );
    let mut compared = 0;
    for i in 0..40 {
        for j in 0..30 {
            let org = glam::DVec3::new(0.0, -4.5, 2.5);
            let dir = glam::DVec3::new(-1.0 + i as f64 / 20.0, 1.0, -0.9 + j as f64 / 25.0);
            let dir = dir.normalize();
            let (ca, cb) = (a.radiance(org, dir).color, b.radiance(org, dir).color);
            assert_eq!(
                ca.to_array().map(f64::to_bits),
                cb.to_array().map(f64::to_bits)
            );
            compared += usize::from(ca.max_element() > 0.0);
        }
    }
    assert!(
        compared > min_seen,
        "{scene}: {compared} rays saw something"
    );
}

/// Only what the patterns reach is compiled: patterns.cal and rayinit.cal define far
/// more than the scene's expressions use.
#[test]
fn only_reachable_definitions_are_compiled() {
    let scene = compiled("patterns.rad", Engine::Jit);
    let f = scene.functions.as_deref().expect("functions");
    let (compiled, loaded) = (f.compiled_definitions(), f.loaded_definitions());
    assert!(compiled > 0, "something is compiled");
    assert!(
        compiled * 4 < loaded,
        "{compiled} of {loaded} definitions compiled"
    );
}
