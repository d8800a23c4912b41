//! Light-emitting materials (`m_light` in source.c): `light`, `glow` and `illum`. Seen
//! from the front they have their radiance; the back is black. Shadow rays aimed at
//! another source are blocked by them (so sources are not counted twice); an `illum`
//! seen by any ray not aimed at it shows its alternate material instead.

use super::Alternate;
use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Emitter {
    pub color: Color,
    pub kind: EmitterKind,
}

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum EmitterKind {
    Light,
    /// Lights points within `max_radius` directly; 0 never, negative never and never
    /// seen by indirect rays.
    Glow {
        max_radius: f64,
    },
    Illum {
        alternate: Alternate,
    },
    /// `spotlight`: light only within a cone around `aim`.
    Spot(Spot),
}

/// A spotlight's cone (srcsupp.c's `makespot`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Spot {
    /// Solid angle of the cone.
    pub size: f64,
    /// Unit direction of the cone's axis.
    pub aim: Vec3,
    /// Length of the given direction vector: a virtual focus this far behind the light.
    pub focus: f64,
}

impl Spot {
    /// `None` for a zero angle or direction (Radiance: "zero angle", "zero focus").
    pub fn new(angle_deg: f64, mut direction: Vec3) -> Option<Spot> {
        if angle_deg <= FTINY {
            return None;
        }
        let focus = normalize(&mut direction);
        if focus == 0.0 {
            return None;
        }
        let half = std::f64::consts::PI / 180.0 / 2.0 * angle_deg;
        Some(Spot {
            size: 2.0 * std::f64::consts::PI * (1.0 - half.cos()),
            aim: direction,
            focus,
        })
    }

    /// Whether a ray travelling along `dir` toward the light is outside the cone
    /// (`spotout`).
    pub fn excludes(&self, dir: Vec3) -> bool {
        self.size < 2.0 * std::f64::consts::PI * (1.0 + self.aim.dot(dir))
    }

    /// A flat spotlight must aim in front of its surface (`checkspot`).
    pub fn faces(&self, normal: Vec3) -> bool {
        let d = self.aim.dot(normal);
        if d > FTINY {
            return true;
        }
        let d1 = 1.0 - self.size / (2.0 * std::f64::consts::PI);
        1.0 - FTINY - d * d < d1 * d1
    }
}

impl Emitter {
    /// Whether this material makes its surfaces direct sources (`marksources`).
    pub fn is_source(&self) -> bool {
        if self.color.max_element() <= FTINY {
            return false;
        }
        !matches!(self.kind, EmitterKind::Glow { max_radius } if max_radius <= FTINY)
    }

    /// A glow too far away to count as a source along this path.
    fn distant_glow(&self, dist: f64) -> bool {
        matches!(self.kind, EmitterKind::Glow { max_radius } if max_radius >= -FTINY && dist > max_radius)
    }

    fn weak(&self) -> bool {
        matches!(
            self.kind,
            EmitterKind::Glow { .. } | EmitterKind::Illum { .. }
        )
    }

    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        let stray = r.kind.any(RayKind::AMBIENT | RayKind::SPECULAR)
            && !(r.kind.any(RayKind::SHADOW) || r.rod < 0.0 || self.distant_glow(r.length));
        if stray {
            r.coef = Color::ZERO;
            return;
        }
        if let Some(true) = t.aimed_at_other_source(r) {
            let illum_passes = matches!(self.kind, EmitterKind::Illum { .. })
                && !(r.rod > 0.0 && t.aimed_source_is_weak(r));
            if !illum_passes {
                r.coef = Color::ZERO;
                return;
            }
        }
        if let EmitterKind::Illum { alternate } = self.kind
            && t.aimed_at_other_source(r) != Some(false)
        {
            match alternate {
                Alternate::Material(m) => t.shade(r, Some(m)),
                _ => t.transmit(r),
            }
            return;
        }
        // `-dv-`: sources are invisible except to shadow rays (and glows too far away to
        // light anything are seen as usual).
        if !t.options().direct_visible
            && !r.kind.any(RayKind::SHADOW)
            && !self.distant_glow(r.path_length + r.length)
        {
            r.coef = Color::ZERO;
            return;
        }
        if r.rod < 0.0 {
            if !t.options().backface_visible {
                t.transmit(r);
            }
            return;
        }
        if let Some(c) = self.front_radiance(r.dir) {
            r.color = c;
        }
    }

    /// The radiance a ray along `dir` sees on the front of the surface: the colour,
    /// unless the ray is outside a spotlight's cone (then `None`: the ray keeps its
    /// colour).
    fn front_radiance(&self, dir: Vec3) -> Option<Color> {
        if let EmitterKind::Spot(spot) = &self.kind
            && spot.excludes(dir)
        {
            return None;
        }
        Some(self.color)
    }

    /// What [`Emitter::shade`] leaves in a fresh shadow ray along `dir` that meets this
    /// source, the one it is aimed at, with `rod` (the ray's colour before the medium
    /// along it): `None` where that is no value of the emitter alone (an `illum`, which
    /// shows its alternate, or the back seen with `-bv-`, which passes the ray on).
    #[inline]
    pub fn aimed_shadow_radiance(
        &self,
        rod: f64,
        dir: Vec3,
        backface_visible: bool,
    ) -> Option<Color> {
        if matches!(self.kind, EmitterKind::Illum { .. }) {
            return None;
        }
        if rod < 0.0 {
            return backface_visible.then_some(Color::ZERO);
        }
        Some(self.front_radiance(dir).unwrap_or(Color::ZERO))
    }

    pub fn is_weak(&self) -> bool {
        self.weak()
    }
}
