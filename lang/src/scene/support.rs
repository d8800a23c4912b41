//! What the renderer would refuse, as `radc check` and the language server report it
//! (W0307). `lang` does not know what the renderer models: the renderer judges
//! (`radc_renderer::RendererSupport`), and the front ends hand its judgement in through
//! [`RenderSupport`], so check, the server and render never disagree silently.

use super::ir::{PrimId, Scene};
use crate::diagnostic::{self as codes, Diagnostic};

/// The renderer's judgement of a lowered scene.
pub trait RenderSupport: Send + Sync {
    /// Each primitive the renderer would refuse, with why (its type, name, reason and
    /// the modifier chain that reaches it, in one line).
    fn refusals(&self, scene: &Scene) -> Vec<(PrimId, String)>;
}

/// W0307 for each primitive `support` refuses, once each. A scene with errors is
/// refused for them first (and its IR lacks what failed), so it gets none: `diags`
/// are the scene's other diagnostics.
pub fn refusal_diagnostics(
    scene: &Scene,
    diags: &[Diagnostic],
    support: &dyn RenderSupport,
) -> Vec<Diagnostic> {
    if diags.iter().any(Diagnostic::is_error) {
        return Vec::new();
    }
    let mut seen = std::collections::HashSet::new();
    support
        .refusals(scene)
        .into_iter()
        .filter(|(id, _)| seen.insert(*id))
        .filter_map(|(id, why)| {
            let prim = scene.get(id)?;
            Some(
                Diagnostic::new(
                    codes::W0307,
                    prim.name_span,
                    format!("radc trace and radc render cannot render {why}"),
                )
                .with_hint(
                    "Radiance's rtrace and rpict render it; radc refuses the scene rather \
                     than render it without this",
                ),
            )
        })
        .collect()
}
