//! Light-emitting materials (`m_light` in source.c): `light`, `glow` and `illum`. Seen
//! from the front they have their radiance; the back is black. Shadow rays aimed at
//! another source are blocked by them (so sources are not counted twice); an `illum`
//! seen by any ray not aimed at it shows its alternate material instead.

use super::Alternate;
use crate::integrator::{RayKind, RayState, Tracer};
use crate::math::{Color, FTINY};

#[derive(Clone, Debug, PartialEq)]
pub struct Emitter {
    pub color: Color,
    pub kind: EmitterKind,
}

#[derive(Clone, Debug, PartialEq)]
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

    pub fn shade(&self, t: &Tracer<'_>, r: &mut RayState) {
        let stray = r.kind.any(RayKind::AMBIENT | RayKind::SPECULAR)
            && !(r.kind.any(RayKind::SHADOW) || r.rod < 0.0 || self.distant_glow(r.length));
        if stray {
            r.coef = Color::ZERO;
            return;
        }
        if let Some(true) = r.aimed_at_other_source(t.scene()) {
            let illum_passes = matches!(self.kind, EmitterKind::Illum { .. })
                && !(r.rod > 0.0 && t.aimed_source_is_weak(r));
            if !illum_passes {
                r.coef = Color::ZERO;
                return;
            }
        }
        if let EmitterKind::Illum { alternate } = self.kind
            && r.aimed_at_other_source(t.scene()) != Some(false)
        {
            match alternate {
                Alternate::Material(m) => t.shade(r, Some(m)),
                _ => t.transmit(r),
            }
            return;
        }
        if r.rod < 0.0 {
            if !t.options().backface_visible {
                t.transmit(r);
            }
            return;
        }
        r.color = self.color;
    }

    pub fn is_weak(&self) -> bool {
        self.weak()
    }
}
