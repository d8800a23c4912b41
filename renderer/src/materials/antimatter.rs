//! `antimatter` (m_clip.c): surfaces that cut away other surfaces. A ray entering an
//! antimatter surface from the front passes through every surface modified by the
//! listed modifiers until it leaves through the back. Where the ray meets the
//! antimatter while inside a clipped object, it sees the antimatter surface shaded with
//! the first listed modifier (the cut face).

use super::MaterialId;
use super::ShadingContext;
use crate::integrator::RayState;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Antimatter {
    /// The clipped modifiers (primitive indices).
    pub modifiers: Vec<i64>,
    /// How the cut face looks: `None` for `void` (never shown), else the first listed
    /// modifier's material.
    pub face: Option<Option<MaterialId>>,
}

impl Antimatter {
    pub fn shade(&self, t: &impl ShadingContext, r: &mut RayState) {
        let entering = r.rod > 0.0;
        let mut set = r.clipset.clone();
        for m in &self.modifiers {
            if entering {
                if !set.contains(m) {
                    set.push(*m);
                }
            } else {
                set.retain(|x| x != m);
            }
        }
        r.new_clipset = Some(set);
        if let Some(face) = self.face {
            // Inside a clipped object: count the clipped surfaces passed on the way here.
            let inside: i32 = r
                .passages
                .iter()
                .filter(|(m, _)| self.modifiers.contains(m))
                .map(|&(_, front)| if front { 1 } else { -1 })
                .sum();
            if inside > 0 {
                r.flip();
                match face {
                    Some(m) => return t.shade(r, Some(m)),
                    None => return t.transmit(r),
                }
            }
        }
        t.transmit(r);
    }
}
