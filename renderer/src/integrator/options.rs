//! What a ray is (Radiance's ray type flags) and the options that steer evaluation
//! (rtrace's and rpict's `-ab -ad -dj ...`).

use crate::math::Color;

/// Ray types (Radiance's `PRIMARY`, `RSHADOW`, ... flags); a ray's `kind` is its own
/// type or'ed with its ancestors'.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayKind(pub u32);

impl RayKind {
    pub const PRIMARY: RayKind = RayKind(0o1);
    pub const SHADOW: RayKind = RayKind(0o2 | 0o200);
    pub const REFLECTED: RayKind = RayKind(0o4);
    pub const REFRACTED: RayKind = RayKind(0o10);
    pub const TRANS: RayKind = RayKind(0o20);
    pub const AMBIENT: RayKind = RayKind(0o40 | 0o400);
    pub const SPECULAR: RayKind = RayKind(0o100 | 0o1000);

    pub fn any(self, other: RayKind) -> bool {
        self.0 & other.0 != 0
    }

    /// Kinds that start a new reflection level.
    pub(super) fn reflects(self) -> bool {
        self.0 & (0o2 | 0o4 | 0o40 | 0o100) != 0
    }
}

impl std::ops::BitOr for RayKind {
    type Output = RayKind;
    fn bitor(self, o: RayKind) -> RayKind {
        RayKind(self.0 | o.0)
    }
}

/// rtrace/rpict options that change values.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// `-av`: the ambient radiance.
    pub ambient: Color,
    /// `-ds`: source partition size ratio (0 disables partitioning).
    pub source_size_ratio: f64,
    /// `-lr`: reflection limit (negative: a hard limit of its magnitude).
    pub max_depth: i32,
    /// `-lw`: rays of lower weight are not traced.
    pub min_weight: f64,
    /// `-st`: rough highlights at or below this specularity are not sampled.
    pub specular_threshold: f64,
    /// `-bv`: back faces are visible (otherwise rays pass through them).
    pub backface_visible: bool,
    /// `-i`: primary rays report the irradiance at the opaque surfaces they hit.
    pub irradiance_at_hits: bool,
    /// `-dr`: relays of light through mirrors (virtual sources; apply with
    /// `Scene::add_virtual_sources`).
    pub relays: u32,
    /// `-me`: extinction coefficient of the medium filling the scene (absorbing only).
    pub medium: Color,
    /// `-dv`: light sources are seen by rays (otherwise only by shadow rays).
    pub direct_visible: bool,
    /// `-ab`: ambient bounces: diffuse reflections estimated by Monte Carlo hemisphere
    /// sampling before the constant `-av` takes over.
    pub ambient_bounces: u32,
    /// `-ad`: hemisphere samples at full ray weight (0: no sampling).
    pub ambient_divisions: u32,
    /// `-as`: extra samples, at full ray weight, for the strata that differ most from
    /// their neighbours.
    pub ambient_supersamples: u32,
    /// `-dj`: source jitter, 0 (sample points at partition centres) to 1 (anywhere in
    /// the partition).
    pub source_jitter: f64,
    /// `-dx+` (radc's own): sample convex polygon, disk, sphere and distant sources
    /// with each partition's exact solid angle, so that a fully visible source lights a
    /// Lambertian surface exactly (`lights::Source::exact_samples`). Off, samples are
    /// Radiance's partition centres and agree with rtrace.
    pub exact_sources: bool,
    /// Rays below `-lw` play Russian roulette when `-lr` is not positive (Radiance's
    /// `rayorigin`). Off, they are dropped, which keeps `-ab 0 -dj 0` deterministic.
    pub russian_roulette: bool,
}

impl Options {
    /// Whether any option asks for random sampling (then Russian roulette is played as
    /// Radiance plays it).
    pub fn samples_randomly(&self) -> bool {
        (self.ambient_bounces > 0 && self.ambient_divisions > 0) || self.source_jitter > 0.0
    }
}

impl Default for Options {
    /// rtrace's defaults.
    fn default() -> Options {
        Options {
            ambient: Color::ZERO,
            source_size_ratio: 0.2,
            max_depth: -10,
            min_weight: 1e-4,
            specular_threshold: 0.15,
            backface_visible: true,
            irradiance_at_hits: false,
            relays: 2,
            medium: Color::ZERO,
            direct_visible: true,
            ambient_bounces: 0,
            ambient_divisions: 1024,
            ambient_supersamples: 512,
            source_jitter: 0.0,
            exact_sources: false,
            russian_roulette: false,
        }
    }
}
