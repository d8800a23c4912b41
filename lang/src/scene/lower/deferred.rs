//! Errors Radiance raises only when a primitive is used: a material when a ray
//! first hits it, a `source` when it is set up as a light. They are recorded as
//! the primitive is lowered and judged once the whole scene is known: an error
//! whose condition does not hold becomes a W0304 warning.

use super::Lowering;
use crate::diagnostic as codes;
use crate::scene::ir::PrimId;

#[derive(Clone, Copy)]
pub(super) enum Deferred {
    /// Only an error if the modifier is reachable from a surface.
    IfUsed(PrimId),
    /// Only an error if this `source` is made of a light-emitting material.
    IfLightSource(PrimId),
}

impl Lowering<'_> {
    /// Keeps deferred errors whose condition holds and turns the rest into W0304
    /// warnings, keeping the original code in the message.
    pub(super) fn settle_deferred(&mut self) {
        let reachable = self.scene.reachable_from(&self.roots);
        for (condition, index) in std::mem::take(&mut self.deferred) {
            let (id, why) = match condition {
                Deferred::IfUsed(id) => {
                    let users = std::iter::once(id)
                        .chain(self.more_users.get(&index).into_iter().flatten().copied());
                    if users
                        .into_iter()
                        .any(|u| reachable.get(u.0 as usize).copied().unwrap_or(true))
                    {
                        continue;
                    }
                    (id, "nothing uses it, so Radiance never reads it")
                }
                Deferred::IfLightSource(id) => {
                    if self.emits_light(id) {
                        continue;
                    }
                    (
                        id,
                        "its material emits no light, so Radiance never reads it",
                    )
                }
            };
            let name = self
                .scene
                .get(id)
                .map(|p| p.name.clone())
                .unwrap_or_default();
            if let Some(d) = self.diags.get_mut(index) {
                d.message = format!("[{}] {} ('{name}': {why})", d.code.id, d.message);
                d.code = codes::W0304;
                d.severity = codes::W0304.severity;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::lower::tests::{PAINT, check};

    #[test]
    fn a_modifier_error_counts_only_when_the_modifier_is_used() {
        let bad = "void plastic bad 0 0 5 1e999 .5 .5 0 0\n";
        assert_eq!(check(bad).1, vec!["W0304", "W0301"]);
        assert_eq!(
            check(&format!("{bad}bad sphere s 0 0 4 0 0 0 1\n")).1,
            vec!["E0203"]
        );
    }

    #[test]
    fn a_source_error_counts_only_when_its_material_emits_light() {
        // A zero direction: Radiance stops only when it sets the source up as a light.
        let source = "source s 0 0 4 0 0 0 .5\n";
        assert_eq!(check(&format!("{PAINT}paint {source}")).1, vec!["W0304"]);
        assert_eq!(
            check(&format!("void light l 0 0 3 1 1 1\nl {source}")).1,
            vec!["E0203"]
        );
    }
}
