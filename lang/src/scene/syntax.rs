//! The scene syntax tree: what was written, with byte spans, before any meaning is
//! attached. Every word keeps its unquoted value and the span of its original text.

use crate::source::Span;

#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    /// The value as Radiance reads it (quotes removed).
    pub text: String,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Real {
    pub value: f64,
    pub span: Span,
}

/// One count-prefixed argument list.
#[derive(Clone, Debug, PartialEq)]
pub struct ArgGroup<T> {
    /// The span of the count word.
    pub count_span: Span,
    pub items: Vec<T>,
}

impl<T> ArgGroup<T> {
    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
}

/// `modifier type identifier` followed by string, integer and real arguments.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    pub modifier: Word,
    pub kind: Word,
    pub name: Word,
    pub strings: ArgGroup<Word>,
    /// Always empty in a valid scene (Radiance requires an integer count of 0).
    pub ints: ArgGroup<Word>,
    pub reals: ArgGroup<Real>,
    pub span: Span,
}

/// `modifier alias identifier reference`.
#[derive(Clone, Debug, PartialEq)]
pub struct Alias {
    pub modifier: Word,
    pub keyword: Span,
    pub name: Word,
    pub target: Word,
    pub span: Span,
}

/// A `!command` line; `text` is the command without the `!`, continuation
/// backslash-newlines joined with a space as the shell would see them.
#[derive(Clone, Debug, PartialEq)]
pub struct Command {
    pub text: String,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Primitive(Primitive),
    Alias(Alias),
    Command(Command),
    Comment(Span),
    /// A statement that could not be parsed; its diagnostics were reported.
    Error(Span),
}

impl Item {
    pub fn span(&self) -> Span {
        match self {
            Item::Primitive(p) => p.span,
            Item::Alias(a) => a.span,
            Item::Command(c) => c.span,
            Item::Comment(s) | Item::Error(s) => *s,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct SceneFile {
    pub items: Vec<Item>,
}

impl SceneFile {
    pub fn primitives(&self) -> impl Iterator<Item = &Primitive> {
        self.items.iter().filter_map(|i| match i {
            Item::Primitive(p) => Some(p),
            _ => None,
        })
    }
}
