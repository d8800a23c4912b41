//! The primitive schema: every Radiance primitive type as data.
//!
//! This table is the single description of what each type means and takes. The parser's
//! count checks, the typed lowering, the checker's value constraints, hover text, inlay
//! hints, completion snippets and the generated user docs all read it. Adding a type is
//! one entry in `table.rs` (plus its lowering if it needs a typed form).

mod table;

pub use table::PRIMITIVE_TYPES;

/// What a primitive is for; decides what may modify what.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Category {
    /// Geometry: polygon, sphere, ..., plus `instance` and `mesh`.
    Surface,
    /// Reflecting/transmitting materials, including `antimatter`.
    Material,
    /// Light-emitting materials: light, illum, glow, spotlight.
    Light,
    /// Perturb the surface normal: texfunc, texdata.
    Texture,
    /// Modulate the colour: colorfunc, brightdata, colorpict, ...
    Pattern,
    /// Blend two modifiers: mixfunc, mixdata, mixpict, mixtext.
    Mixture,
    /// `alias`: a new name for an earlier modifier.
    Alias,
}

impl Category {
    /// Whether a primitive of this category may be used as another's modifier.
    pub fn is_modifier(self) -> bool {
        !matches!(self, Category::Surface)
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Category::Surface => "surface",
            Category::Material => "material",
            Category::Light => "light source material",
            Category::Texture => "texture",
            Category::Pattern => "pattern",
            Category::Mixture => "mixture",
            Category::Alias => "alias",
        }
    }
}

/// How many arguments of one kind (strings or reals) a type accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Count {
    Exactly(u32),
    AtLeast(u32),
    /// Inclusive bounds.
    Between(u32, u32),
    OneOf(&'static [u32]),
    /// `min`, `min + step`, `min + 2 step`, ...: polygon vertices (9, 12, 15, ...).
    Stepped {
        min: u32,
        step: u32,
    },
}

impl Count {
    pub fn accepts(self, n: u32) -> bool {
        match self {
            Count::Exactly(k) => n == k,
            Count::AtLeast(k) => n >= k,
            Count::Between(a, b) => (a..=b).contains(&n),
            Count::OneOf(ks) => ks.contains(&n),
            Count::Stepped { min, step } => n >= min && (n - min) % step.max(1) == 0,
        }
    }

    /// The count as the docs write it: `5`, `4+`, `0..7`, `0|3|6|9`, `9+3N`.
    pub fn describe(self) -> String {
        match self {
            Count::Exactly(k) => k.to_string(),
            Count::AtLeast(k) => format!("{k}+"),
            Count::Between(a, b) => format!("{a}..{b}"),
            Count::OneOf(ks) => ks.iter().map(u32::to_string).collect::<Vec<_>>().join("|"),
            Count::Stepped { min, step } => format!("{min}+{step}N"),
        }
    }
}

/// What a string argument names; drives file lookup, go-to-definition and checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StringKind {
    /// Free text (a keyword, a text line of colortext, ...).
    Word,
    /// The name of an earlier modifier (mixture foreground/background), or `void`.
    Modifier,
    /// A calcomp variable or function name, or an expression.
    Function,
    /// A file name searched in the scene's folder, then along RAYPATH.
    File(FileKind),
    /// The start of an xform-style transform (`-t x y z -rz 30 ...`) running to the end.
    Transform,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FileKind {
    /// A calcomp function file; `.` means none.
    Cal,
    /// A data file (Radiance manual section 2.2.2).
    Data,
    /// A Radiance picture.
    Picture,
    /// A font file for colortext/brighttext/mixtext.
    Font,
    /// An octree for `instance`.
    Octree,
    /// A compiled mesh for `mesh`.
    Mesh,
    /// A BSDF XML file.
    Bsdf,
}

/// Bounds on a real argument. Violating `valid` is an error (Radiance fails or
/// misbehaves); leaving `plausible` is a warning (physically odd but accepted).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: f64,
    pub max: f64,
    /// Whether `min` itself is allowed (false for "radius > 0").
    pub min_inclusive: bool,
}

impl Bounds {
    pub const ANY: Bounds = Bounds::closed(f64::NEG_INFINITY, f64::INFINITY);
    pub const NON_NEGATIVE: Bounds = Bounds::closed(0.0, f64::INFINITY);
    pub const POSITIVE: Bounds = Bounds {
        min: 0.0,
        max: f64::INFINITY,
        min_inclusive: false,
    };
    pub const UNIT: Bounds = Bounds::closed(0.0, 1.0);

    pub const fn closed(min: f64, max: f64) -> Bounds {
        Bounds {
            min,
            max,
            min_inclusive: true,
        }
    }

    pub fn contains(&self, v: f64) -> bool {
        let above = if self.min_inclusive {
            v >= self.min
        } else {
            v > self.min
        };
        above && v <= self.max
    }

    pub fn describe(&self) -> String {
        let lo = if self.min_inclusive { ">=" } else { ">" };
        match (self.min.is_finite(), self.max.is_finite()) {
            (true, true) => format!("between {} and {}", self.min, self.max),
            (true, false) => format!("{lo} {}", self.min),
            (false, true) => format!("<= {}", self.max),
            (false, false) => "any number".into(),
        }
    }
}

/// One positional argument.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arg {
    /// Short name shown in inlay hints (`spec`, `rough`, `x0`).
    pub name: &'static str,
    /// What it means, with units and typical values, for hover text.
    pub meaning: &'static str,
    /// For string arguments: what the string names. `Word` for reals.
    pub kind: StringKind,
    /// For real arguments: the hard limits (an error outside).
    pub valid: Bounds,
    /// For real arguments: the physically plausible range (a warning outside).
    pub plausible: Bounds,
}

/// The layout of one argument list: fixed leading arguments, then an optional group
/// that repeats (polygon vertices `x y z`, pattern transform words, extra reals `A1..`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArgList {
    pub count: Count,
    pub fixed: &'static [Arg],
    pub repeat: &'static [Arg],
}

impl ArgList {
    pub const NONE: ArgList = ArgList {
        count: Count::Exactly(0),
        fixed: &[],
        repeat: &[],
    };

    /// The argument description for position `i` (0-based), if the layout names one.
    /// Repeated groups get their name suffixed with the group number (`x2`).
    pub fn arg_at(&self, i: usize) -> Option<(Arg, Option<usize>)> {
        if let Some(a) = self.fixed.get(i) {
            return Some((*a, None));
        }
        if self.repeat.is_empty() {
            return None;
        }
        let k = i - self.fixed.len();
        Some((
            self.repeat[k % self.repeat.len()],
            Some(k / self.repeat.len()),
        ))
    }
}

/// One primitive type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimitiveType {
    /// The keyword as written in scenes (case-sensitive).
    pub name: &'static str,
    pub category: Category,
    /// One line for completion lists.
    pub summary: &'static str,
    /// A paragraph for hover and docs.
    pub doc: &'static str,
    pub strings: ArgList,
    pub reals: ArgList,
}

/// Looks a type up by its exact (case-sensitive) keyword.
pub fn lookup(name: &str) -> Option<&'static PrimitiveType> {
    PRIMITIVE_TYPES.iter().find(|t| t.name == name)
}

/// All type keywords, for suggestions and completion.
pub fn type_names() -> impl Iterator<Item = &'static str> {
    PRIMITIVE_TYPES.iter().map(|t| t.name)
}
