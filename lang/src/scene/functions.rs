//! What a scene asks of its function files. A primitive such as `colorfunc` names a
//! `.cal` file and the functions or variables in it that the renderer evaluates. Radiance
//! loads the file (after rayinit.cal) when a ray first needs it, and fails then: on a
//! syntax error in the file, or on a name the evaluation reaches that nothing defines.
//! Here both are found at check time, for exactly the names the scene uses.

use std::collections::HashSet;

use crate::cal::{Env, Module, deps};
use crate::diagnostic::{self as codes, Diagnostic};
use crate::source::{FileId, Span};

/// One function file as the renderer loads it.
pub struct FunctionFile {
    pub module: Module,
    /// Errors in the file itself (syntax, bad constants).
    pub errors: Vec<Diagnostic>,
}

impl FunctionFile {
    /// Loads `text` the way the renderer does: renderer names and rayinit.cal defined,
    /// the file's names qualified by its context (the file name without suffix).
    pub fn load(file: FileId, name: &str, text: &str) -> Self {
        let mut module = Module::new(&Env::renderer());
        module.set_context(context_of(name));
        let errors = module
            .add_source(file, text)
            .into_iter()
            .filter(Diagnostic::is_error)
            .collect();
        FunctionFile { module, errors }
    }

    /// Whether a name the scene gives resolves (in the file, rayinit.cal, the
    /// renderer's names or the function library).
    pub fn defines(&self, name: &str) -> bool {
        self.module.lookup(name).is_some_and(|s| self.is_defined(s))
    }

    fn is_defined(&self, s: crate::cal::ir::SymId) -> bool {
        let sym = self.module.symbol(s);
        !sym.stack.is_empty() || sym.lib.is_some() || self.module.host_name(s).is_some()
    }

    /// Names that evaluating `entry` would reach but that nothing defines, with where
    /// they are used (in the function file).
    pub fn undefined_reached_from(&self, entry: &str) -> Vec<(String, Span)> {
        let needed = deps::needed_by_names(&self.module, &[entry]);
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        for id in needed {
            let def = self.module.def(id);
            let mut refs = Vec::new();
            def.body.symbols(&mut refs);
            for (s, span) in refs {
                if !self.is_defined(s) && seen.insert(s) {
                    out.push((self.module.symbol(s).name.clone(), span));
                }
            }
        }
        out
    }
}

/// Radiance's context for a function file: its name without folders and suffix.
fn context_of(name: &str) -> &str {
    let base = name.rsplit('/').next().unwrap_or(name);
    base.strip_suffix(".cal").unwrap_or(base)
}

/// Whether a string argument is a plain name (rather than an expression).
pub fn is_plain_name(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '`')
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '`'))
}

/// The diagnostic for a name a scene uses that its function file does not define.
pub fn undefined_in_file(name: &str, file: &str, span: Span, known: &[&str]) -> Diagnostic {
    let message = if file == "." {
        format!(
            "'{name}' is not defined by rayinit.cal or the renderer, and no function file is given"
        )
    } else {
        format!("'{name}' is not defined in '{file}' (nor by rayinit.cal or the renderer)")
    };
    let mut d = Diagnostic::new(codes::E0601, span, message);
    // Names defined in a function file are qualified by its context (`name`file`).
    let plain = known.iter().map(|k| k.split('`').next().unwrap_or(k));
    if let Some(s) = codes::suggest(name, plain) {
        d = d.with_hint(format!("did you mean '{s}'?"));
    }
    d
}
