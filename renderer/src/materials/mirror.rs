//! `mirror` (m_mirror.c): a perfect reflector tinted by its colour; the back is black.
//! Mirrors also relay light sources as virtual sources (`-dr`, see `virtuals.rs`).

use super::Alternate;
use crate::integrator::{RayKind, RayState, Tracer};
use crate::math::{Color, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Mirror {
    pub color: Color,
    pub alternate: Alternate,
}

impl Mirror {
    pub fn shade(&self, t: &Tracer<'_>, r: &mut RayState) {
        // None: not a shadow ray; Some(false): aimed at this mirror's virtual source.
        let aimed_elsewhere = r.aimed_at_other_source(t.scene());
        if self.alternate != Alternate::None && aimed_elsewhere != Some(false) {
            let pass_ok = r.rod < 0.0 || !r.kind.any(RayKind::AMBIENT | RayKind::SPECULAR);
            if pass_ok {
                match self.alternate {
                    Alternate::Material(m) => return t.shade(r, Some(m)),
                    _ => return t.transmit(r),
                }
            }
        }
        if aimed_elsewhere == Some(true) {
            return;
        }
        if r.rod < 0.0 {
            if !t.options().backface_visible {
                t.transmit(r);
            }
            return;
        }
        let relay = match (aimed_elsewhere, r.source) {
            (Some(false), Some(si)) => t.scene().sources.get(si).and_then(|s| s.parent),
            _ => None,
        };
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(self.color)) else {
            return;
        };
        child.dir = r.dir + r.normal * (2.0 * r.rod);
        normalize(&mut child.dir);
        // A shadow ray to a virtual source goes on toward the source it images.
        child.source = relay;
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        r.mirror_length = r.length;
        if r.hit_is_flat(t.scene()) {
            r.mirror_length += child.effective_length();
        }
    }
}
