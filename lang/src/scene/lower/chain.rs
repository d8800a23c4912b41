//! Modifier chains: what a surface is made of, read as Radiance reads it (the
//! first material shades, the rest of the chain applies as patterns and textures,
//! aliases stand for their targets). Sources need a light-emitting first
//! material; a second material further down is fatal in Radiance.

use super::Lowering;
use crate::diagnostic::{self as codes, Diagnostic};
use crate::scene::ir::{ModRef, PrimId, PrimKind};
use crate::schema::Category;

impl Lowering<'_> {
    /// Whether the first material in a primitive's modifier chain emits light.
    pub(super) fn emits_light(&self, id: PrimId) -> bool {
        let Some(p) = self.scene.get(id) else {
            return false;
        };
        let mut next = p.modifier;
        for _ in 0..256 {
            let ModRef::Prim(m) = next else { return false };
            let Some((category, modifier)) = self.chain_link(m) else {
                return false;
            };
            match category {
                Category::Light => return true,
                Category::Material => return false,
                _ => next = modifier,
            }
        }
        false
    }

    /// What an element of a modifier chain really is: aliases are followed to their
    /// target's type, and take either their own modifier or (with `inherit`) the
    /// target's. Returns the category and the next link of the chain.
    fn chain_link(&self, id: PrimId) -> Option<(Category, ModRef)> {
        let mut cur = self.scene.get(id)?;
        let mut modifier = cur.modifier;
        for _ in 0..64 {
            match cur.kind {
                PrimKind::Alias { target } => {
                    cur = self.scene.get(target)?;
                    if modifier == ModRef::Inherit {
                        modifier = cur.modifier;
                    }
                }
                _ => return Some((cur.category(), modifier)),
            }
        }
        None
    }

    /// Radiance shades a hit with the first material in the surface's modifier chain
    /// and then applies the rest of the chain as patterns and textures; a second
    /// material there is fatal ("conflicting material", `raytexture` in raytrace.c)
    /// as soon as a ray hits it.
    pub(super) fn report_conflicting_materials(&mut self) {
        let is_material = |c: Category| matches!(c, Category::Material | Category::Light);
        let mut found = Vec::new();
        for (i, p) in self.scene.prims.iter().enumerate() {
            if !is_material(p.category()) || matches!(p.kind, PrimKind::Alias { .. }) {
                continue;
            }
            let mut next = p.modifier;
            for _ in 0..256 {
                let ModRef::Prim(id) = next else { break };
                let Some((category, modifier)) = self.chain_link(id) else {
                    break;
                };
                if is_material(category) {
                    found.push((PrimId(i as u32), id));
                    break;
                }
                next = modifier;
            }
        }
        for (user, material) in found {
            let (Some(u), Some(m)) = (self.scene.get(user), self.scene.get(material)) else {
                continue;
            };
            self.diags.push(
                Diagnostic::new(
                    codes::E0302,
                    u.modifier_span,
                    format!(
                        "{} '{}' is modified by {} '{}': a material's modifiers may only be patterns, textures or mixtures of them",
                        u.schema.name, u.name, m.schema.name, m.name
                    ),
                )
                .with_label(m.name_span, "this material is further down the chain")
                .with_hint("Radiance stops with \"conflicting material\" when a ray hits this; give the material the modifier 'void' or a pattern"),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::lower::tests::{PAINT, check};

    #[test]
    fn a_material_modified_by_a_material_conflicts() {
        let text =
            format!("{PAINT}paint plastic p2 0 0 5 .5 .5 .5 0 0\np2 sphere s 0 0 4 0 0 0 1\n");
        assert_eq!(check(&text).1, vec!["E0302"]);
    }
}
