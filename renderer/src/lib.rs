//! radc's renderer: a compiled scene (shapes, BVH, materials, light sources) and the
//! ray evaluation that reproduces Radiance's rtrace. It sees typed scenes, never text.

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
pub mod virtuals;

pub use integrator::{Options, RayState, Target, Tracer};
pub use scene::{RendererSupport, Scene, Unsupported};
