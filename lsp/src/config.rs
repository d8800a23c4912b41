//! The settings a client may send, in `initializationOptions` or in
//! `workspace/didChangeConfiguration` (either bare or under a `radc` key):
//!
//! ```json
//! { "inlayHints": { "enabled": true }, "raypath": ["/usr/local/lib/ray"],
//!   "generators": { "enabled": true } }
//! ```
//!
//! `generators` lets `!` lines that call radc's built-in generators (genbox, xform,
//! ...) expand in-process, as `radc check` does; no process is ever started.
//!
//! `raypath` may also be one string separated like the `RAYPATH` variable. Unknown
//! keys and wrong types are ignored: a bad setting must not stop the server.

use std::path::PathBuf;

use serde_json::Value;

#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    pub inlay_hints: bool,
    /// Folders searched for auxiliary files after the scene's own; `None` means the
    /// server's `RAYPATH` environment variable.
    pub raypath: Option<Vec<PathBuf>>,
    /// Whether `!` lines naming a built-in generator are expanded (in-process).
    pub generators: bool,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            inlay_hints: true,
            raypath: None,
            generators: true,
        }
    }
}

impl Config {
    /// Applies whatever settings `value` holds on top of the current ones.
    pub fn update(&mut self, value: &Value) {
        let value = value.get("radc").unwrap_or(value);
        let hints = value.get("inlayHints");
        let enabled = hints.and_then(|h| h.get("enabled").or(Some(h)));
        if let Some(on) = enabled.and_then(Value::as_bool) {
            self.inlay_hints = on;
        }
        let generators = value.get("generators");
        let enabled = generators.and_then(|g| g.get("enabled").or(Some(g)));
        if let Some(on) = enabled.and_then(Value::as_bool) {
            self.generators = on;
        }
        match value.get("raypath") {
            Some(Value::String(s)) if s.is_empty() => self.raypath = None,
            Some(Value::String(s)) => self.raypath = Some(std::env::split_paths(s).collect()),
            Some(Value::Array(items)) => {
                let dirs = items.iter().filter_map(Value::as_str).map(PathBuf::from);
                self.raypath = Some(dirs.collect());
            }
            Some(Value::Null) => self.raypath = None,
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn reads_bare_nested_and_bad_settings() {
        let mut c = Config::default();
        c.update(&json!({"radc": {"inlayHints": {"enabled": false}, "raypath": ["/a", "/b"]}}));
        assert!(!c.inlay_hints);
        assert_eq!(
            c.raypath,
            Some(vec![PathBuf::from("/a"), PathBuf::from("/b")])
        );
        c.update(&json!({"inlayHints": true, "raypath": 7}));
        assert!(c.inlay_hints);
        assert_eq!(c.raypath.as_ref().map(Vec::len), Some(2));
        c.update(&json!(null));
        assert!(c.inlay_hints);
        assert!(c.generators);
        c.update(&json!({"generators": {"enabled": false}}));
        assert!(!c.generators);
    }
}
