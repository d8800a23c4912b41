//! `mirror` (m_mirror.c): a perfect reflector tinted by its colour; the back is black.
//! Mirrors also relay light sources as virtual sources (`-dr`, see `virtuals.rs`).

use super::Alternate;
use super::ShadingContext;
use crate::integrator::{RayKind, RayState};
use crate::math::{Color, FTINY, Vec3, normalize};

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Mirror {
    pub color: Color,
    pub alternate: Alternate,
    /// The normal's perturbation at the hit being shaded (see `Plastic::texture`).
    #[serde(skip)]
    pub texture: Vec3,
}

impl Mirror {
    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        // None: not a shadow ray; Some(false): aimed at this mirror's virtual source.
        let aimed_elsewhere = t.aimed_at_other_source(r);
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
            (Some(false), Some(si)) => t.imaged_source(si),
            _ => None,
        };
        let Some(mut child) = t.spawn(r, RayKind::REFLECTED, Some(self.color)) else {
            return;
        };
        // A texture tips the reflection, except for relayed sources and ambient rays,
        // and never under the surface (m_mirror's `rpure`).
        let mut pure = true;
        if relay.is_none()
            && !r.kind.any(RayKind::AMBIENT)
            && self.texture.dot(self.texture) > FTINY * FTINY
        {
            let (normal, cos) = super::plastic::perturbed_normal(r, self.texture);
            child.dir = r.dir + normal * (2.0 * cos);
            pure = false;
        }
        if pure || child.dir.dot(r.normal) <= FTINY {
            child.dir = r.dir + r.normal * (2.0 * r.rod);
        }
        normalize(&mut child.dir);
        // A shadow ray to a virtual source goes on toward the source it images.
        child.source = relay;
        t.trace(&mut child);
        let c = child.color * child.coef;
        r.mirror_color = c;
        r.color += c;
        r.mirror_length = r.length;
        if pure && t.hit_is_flat(r) {
            r.mirror_length += child.effective_length();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::context::scripted::{Scripted, hit};

    #[test]
    fn a_mirror_reflects_about_the_normal_and_tints_what_it_sees() {
        let t = Scripted {
            seen: Color::splat(2.0),
            ..Scripted::default()
        };
        let m = Mirror {
            color: Color::new(0.9, 0.5, 0.1),
            alternate: Alternate::None,
            texture: Vec3::ZERO,
        };
        let mut r = hit(Vec3::new(0.0, 1.0, -2.0));
        m.shade(&t, &mut r);
        let (kind, d, _) = t.traced.borrow()[0];
        assert!(kind.any(RayKind::REFLECTED));
        assert!((d - Vec3::new(0.0, 1.0, 2.0).normalize()).length() < 1e-12);
        assert!((r.color - Color::new(1.8, 1.0, 0.2)).length() < 1e-12);
        assert_eq!(r.mirror_color, r.color);
        // The back of a mirror is black.
        let mut back = hit(Vec3::new(0.0, 0.0, 1.0));
        m.shade(&t, &mut back);
        assert_eq!(back.color, Color::ZERO);
    }
}
