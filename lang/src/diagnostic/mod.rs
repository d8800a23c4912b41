//! The one diagnostic type every layer of `lang` produces.
//!
//! A diagnostic is data: a stable [`Code`], a severity, a primary span, secondary
//! labels, a plain-English message and an optional fix hint. The CLI renders it with
//! ariadne or as JSON, the language server converts it to LSP; neither re-words it.

mod codes;

pub use codes::*;

use crate::source::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Warning,
    Error,
}

/// A stable diagnostic code. The table in `codes.rs` is the single list of them: the
/// checker, `radc explain` and the docs all read it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Code {
    /// `E0101`, `W0301`: never reused for a different meaning.
    pub id: &'static str,
    /// A short kebab-case name, e.g. `unknown-type`.
    pub name: &'static str,
    pub severity: Severity,
    /// One sentence saying what the code means, for `radc explain` and docs.
    pub summary: &'static str,
}

/// A secondary location with its own short message ("modifier defined here").
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    pub span: Span,
    pub message: String,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub code: Code,
    pub severity: Severity,
    pub span: Span,
    pub message: String,
    pub labels: Vec<Label>,
    pub hint: Option<String>,
}

impl Diagnostic {
    /// A diagnostic with the code's own severity.
    pub fn new(code: Code, span: Span, message: impl Into<String>) -> Self {
        Diagnostic {
            code,
            severity: code.severity,
            span,
            message: message.into(),
            labels: Vec::new(),
            hint: None,
        }
    }

    pub fn with_hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }

    pub fn with_label(mut self, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: message.into(),
        });
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// The closest candidate by edit distance, for "did you mean ...?" hints. Only
/// suggests names close enough to be a plausible typo.
pub fn suggest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let limit = (word.chars().count() / 3).max(1);
    candidates
        .into_iter()
        .map(|c| (edit_distance(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Levenshtein distance over characters, case-insensitive substitutions cost half
/// (rounded up), so `Plastic` -> `plastic` is always suggested.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=b.len() {
            let sub = usize::from(!a[i - 1].eq_ignore_ascii_case(&b[j - 1]));
            cur[j] = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + sub);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_close_names_only() {
        let types = ["plastic", "metal", "polygon"];
        assert_eq!(suggest("plastc", types), Some("plastic"));
        assert_eq!(suggest("Plastic", types), Some("plastic"));
        assert_eq!(suggest("zzzzzz", types), None);
    }

    #[test]
    fn every_code_is_unique_and_well_formed() {
        let mut seen = std::collections::HashSet::new();
        for c in ALL_CODES {
            assert!(seen.insert(c.id), "duplicate code {}", c.id);
            let prefix = if c.severity == Severity::Error {
                'E'
            } else {
                'W'
            };
            assert!(c.id.starts_with(prefix), "{} has the wrong prefix", c.id);
            assert_eq!(c.id.len(), 5, "{}", c.id);
        }
    }
}
