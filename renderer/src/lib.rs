//! radc's renderer: a compiled scene (shapes, BVH, materials, light sources) and the
//! ray evaluation that reproduces Radiance's rtrace. It sees typed scenes, never text.
//!
//! Not modelled yet, and refused by name by the scene compiler (never dropped): the
//! text and spectral patterns, `mixtext`, mixtures of materials that modify a material
//! or follow a pattern (Radiance stops at the first), dispersion (`dielectric` with a
//! Hartmann constant), BSDF, WGMDfunc, scattering media (mist with an albedo, `-ma`),
//! instances and meshes. Not reproduced: Radiance's irradiance cache (`-aa > 0`; radc
//! computes every ambient value afresh, Radiance's `-aa 0`), its random sequence
//! (results with `-ab > 0` or `-dj > 0` agree with Radiance's in distribution, not
//! number for number), rough highlights above `-st` when sampling is not random (one
//! fixed sample for plastic/metal reflection, none for rough transmission; the
//! anisotropic materials' and ashik2's are never sampled), probabilistic shadow testing
//! (`-dt > 0`: every shadow is tested) and randomly oriented source partitions (`-u+`).
//! Rays below `-lw` play Russian roulette (when `-lr` is not positive) only when
//! sampling is random, so `-ab 0 -dj 0` stays deterministic.

pub mod ambient;
pub mod bvh;
pub mod camera;
pub mod integrator;
pub mod lights;
pub mod materials;
pub mod math;
pub mod picture;
pub mod procedural;
pub mod random;
pub mod ray;
pub mod ray_order;
pub mod render;
pub mod scene;
pub mod scene_file;
pub mod shapes;
pub mod small_sources;
pub mod solid_angle;
pub mod surfaces;
pub mod trace;
pub mod view_rays;
pub mod virtuals;

pub use integrator::{Options, RayState, Target, Tracer};
pub use scene::{RendererSupport, Scene, Unsupported};
