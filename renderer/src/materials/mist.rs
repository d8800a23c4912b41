//! `mist` (m_mist.c): the boundary of a volume of participating medium. Rays entering it
//! add its extinction to their medium, rays leaving take it away; the surface itself
//! is invisible. radc models absorbing mist only: scattering (an albedo) needs random
//! sampling of in-scattered light, which it refuses.

use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::Color;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Mist {
    pub extinction: Color,
}

impl Mist {
    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        let Some(mut child) = t.spawn(r, RayKind::TRANS, None) else {
            return;
        };
        child.dir = r.dir;
        child.extinction = if r.rod > 0.0 {
            r.extinction + self.extinction
        } else {
            // Leaving: never below the scene's medium (`-me`).
            (r.extinction - self.extinction).max(t.options().medium)
        };
        t.trace(&mut child);
        r.color = child.color;
        r.mirror_color = child.mirror_color;
        r.mirror_length = r.length + child.mirror_length;
        r.other_length = r.length + child.other_length;
    }
}
