//! What a material may ask of the renderer while it shades a hit.
//!
//! A material reproduces one of Radiance's shading routines (`m_normal`, `m_glass`,
//! ...), and those routines reach back into the ray tracer: they spawn and trace child
//! rays, ask for the ambient and direct light at the hit, pass the ray through, or hand
//! it to another material. [`ShadingContext`] is that whole reach, so a material can be
//! unit-tested against a scripted context (see the tests of each material) instead of
//! a full scene and [`crate::integrator::Tracer`], which implements it for rendering.
//! Materials are generic over the context: the tracer's calls stay static and inline.

use crate::integrator::{Options, RayKind, RayState};
use crate::materials::MaterialId;
use crate::math::{Color, Vec3};

pub trait ShadingContext {
    /// The rendering options (`-st`, `-bv`, sampling at random or not, ...).
    fn options(&self) -> &Options;

    /// Whether the surface `r` hit is flat (a polygon): reflections off it keep their
    /// distance, highlights widen by the source's size.
    fn hit_is_flat(&self, r: &RayState) -> bool;

    /// For a shadow ray: whether it hit something other than the source it was aimed
    /// at (`None` when it is not aimed at a source).
    fn aimed_at_other_source(&self, r: &RayState) -> Option<bool>;

    /// Whether the source a shadow ray aims at is a glow or illum (`illumblock`).
    fn aimed_source_is_weak(&self, r: &RayState) -> bool;

    /// The source a virtual source images (a mirror relays shadow rays to it).
    fn imaged_source(&self, source: usize) -> Option<usize>;

    /// A child ray from `r`'s hit (`rayorigin`), `None` when too weak or too deep.
    fn spawn(&self, r: &RayState, kind: RayKind, coef: Option<Color>) -> Option<RayState>;

    /// Evaluates a ray (`raytrace`).
    fn trace(&self, r: &mut RayState);

    /// Shades `r`'s hit with another material (an alternate), as if it had it.
    fn shade(&self, r: &mut RayState, material: Option<MaterialId>);

    /// Continues `r` unchanged past its hit (`raytrans`).
    fn transmit(&self, r: &mut RayState);

    /// A function or data material's function (pattern `pattern`) for light from
    /// `dir` of solid angle `omega` at the hit `view` shows; `None` on a compute error.
    fn brdf(
        &self,
        pattern: u32,
        view: &crate::procedural::RayView,
        shade: &crate::procedural::ShadeState,
        dir: Vec3,
        omega: f64,
    ) -> Option<f64>;

    /// A BRTDfunc's colours (pattern `pattern`): its mirror ray's, straight ray's, or
    /// directional part for a light sample; `None` on a compute error.
    fn brtd(
        &self,
        pattern: u32,
        view: &crate::procedural::RayView,
        shade: &crate::procedural::ShadeState,
        part: crate::materials::brtd::BrtdPart,
    ) -> Option<Color>;

    /// An anisotropic material's orientation vector from its expressions (pattern
    /// `pattern`), turned by its transform; `None` on a compute error.
    fn orientation(&self, pattern: u32, view: &crate::procedural::RayView) -> Option<Vec3>;

    /// The coefficient of the mixture whose pattern is `pattern` for `r`'s hit, before
    /// bounding; `None` on a compute error (warned of once).
    fn mixture_coefficient(&self, pattern: u32, r: &RayState) -> Option<f64>;

    /// Indirect light reaching the hit from the hemisphere about `normal`, times
    /// `coef` (`multambient`).
    fn ambient(&self, r: &RayState, coef: Color, normal: Vec3) -> Color;

    /// Adds direct light to `r.color`: for each source sample in direction `dir` of
    /// solid angle `omega`, `coef(dir, omega)` turns its radiance into the hit's.
    fn direct(&self, r: &mut RayState, coef: &dyn Fn(Vec3, f64) -> Color);
}

#[cfg(test)]
pub mod scripted {
    //! A [`ShadingContext`] whose world is a few numbers: every traced ray sees one
    //! radiance, ambient light is one value, and there is one source sample. It records
    //! every ray a material spawns, so a test can check directions and coefficients.

    use super::*;
    use std::cell::RefCell;

    pub struct Scripted {
        pub options: Options,
        /// What every traced child ray sees.
        pub seen: Color,
        /// Ambient radiance: `ambient()` returns `coef * ambient_value`.
        pub ambient_value: Color,
        /// The one source sample: direction, solid angle, radiance.
        pub source: Option<(Vec3, f64, Color)>,
        pub flat: bool,
        /// Rays traced, with their kind, direction and coefficient.
        pub traced: RefCell<Vec<(RayKind, Vec3, Color)>>,
        pub transmitted: RefCell<u32>,
        pub ambient_normals: RefCell<Vec<Vec3>>,
        /// What `mixture_coefficient` answers.
        pub coefficient: Option<f64>,
        /// Materials `shade` was asked for, with the ray's weight and coefficient; each
        /// shades its ray `material + 1` grey and sets both lengths to that.
        pub shaded: RefCell<Vec<(MaterialId, f64, Color)>>,
        /// What `brdf` answers, and the (normal, light direction, solid angle) asked.
        pub brdf_value: Option<f64>,
        pub brdf_calls: RefCell<Vec<(Vec3, Vec3, f64)>>,
        /// What `brtd` answers for every part.
        pub brtd_value: Option<Color>,
        /// What `orientation` answers.
        pub orientation: Option<Vec3>,
    }

    impl Default for Scripted {
        fn default() -> Scripted {
            Scripted {
                options: Options::default(),
                seen: Color::ZERO,
                ambient_value: Color::ZERO,
                source: None,
                flat: true,
                traced: RefCell::new(Vec::new()),
                transmitted: RefCell::new(0),
                ambient_normals: RefCell::new(Vec::new()),
                coefficient: None,
                shaded: RefCell::new(Vec::new()),
                brdf_value: None,
                brdf_calls: RefCell::new(Vec::new()),
                brtd_value: None,
                orientation: None,
            }
        }
    }

    /// A ray arriving at the origin on the plane z = 0 (normal +z) from direction `dir`
    /// (pointing at the surface).
    pub fn hit(dir: Vec3) -> RayState {
        let dir = dir.normalize();
        let mut r = RayState::primary(-dir, dir);
        r.length = 1.0;
        r.point = Vec3::ZERO;
        r.normal = Vec3::Z;
        r.rod = -dir.dot(Vec3::Z);
        r
    }

    impl ShadingContext for Scripted {
        fn options(&self) -> &Options {
            &self.options
        }
        fn hit_is_flat(&self, _: &RayState) -> bool {
            self.flat
        }
        fn aimed_at_other_source(&self, _: &RayState) -> Option<bool> {
            None
        }
        fn aimed_source_is_weak(&self, _: &RayState) -> bool {
            false
        }
        fn imaged_source(&self, _: usize) -> Option<usize> {
            None
        }
        fn spawn(&self, r: &RayState, kind: RayKind, coef: Option<Color>) -> Option<RayState> {
            let mut child = RayState::primary(r.point, r.dir);
            child.kind = r.kind | kind;
            child.coef = coef.unwrap_or(Color::ONE);
            Some(child)
        }
        fn trace(&self, r: &mut RayState) {
            self.traced.borrow_mut().push((r.kind, r.dir, r.coef));
            r.color = self.seen;
            r.length = 1.0;
        }
        fn shade(&self, r: &mut RayState, material: Option<MaterialId>) {
            if let Some(m) = material {
                self.shaded.borrow_mut().push((m, r.weight, r.coef));
                let v = f64::from(m.0 + 1);
                r.color = Color::splat(v);
                r.mirror_length = v;
                r.other_length = v;
            }
        }
        fn brdf(
            &self,
            _: u32,
            _: &crate::procedural::RayView,
            shade: &crate::procedural::ShadeState,
            dir: Vec3,
            omega: f64,
        ) -> Option<f64> {
            self.brdf_calls
                .borrow_mut()
                .push((shade.normal, dir, omega));
            self.brdf_value
        }
        fn brtd(
            &self,
            _: u32,
            _: &crate::procedural::RayView,
            _: &crate::procedural::ShadeState,
            _: crate::materials::brtd::BrtdPart,
        ) -> Option<Color> {
            self.brtd_value
        }
        fn orientation(&self, _: u32, _: &crate::procedural::RayView) -> Option<Vec3> {
            self.orientation
        }
        fn mixture_coefficient(&self, _: u32, _: &RayState) -> Option<f64> {
            self.coefficient
        }
        fn transmit(&self, r: &mut RayState) {
            *self.transmitted.borrow_mut() += 1;
            r.color = self.seen;
        }
        fn ambient(&self, _: &RayState, coef: Color, normal: Vec3) -> Color {
            self.ambient_normals.borrow_mut().push(normal);
            coef * self.ambient_value
        }
        fn direct(&self, r: &mut RayState, coef: &dyn Fn(Vec3, f64) -> Color) {
            if let Some((dir, omega, radiance)) = self.source {
                r.color += coef(dir.normalize(), omega) * radiance;
            }
        }
    }
}
