//! The primitive schema: every Radiance primitive type as data.
//!
//! This table is the single description of what each type means and takes. The parser's
//! count checks, the typed lowering, the checker's value constraints, hover text, inlay
//! hints, completion snippets and the generated user docs all read it. Adding a type is
//! one entry in `table.rs` (plus its lowering if it needs a typed form).

mod docs;
mod editor;
mod table;

pub use docs::markdown;
pub use editor::{arg_hint, hover, layout, snippet};
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
    /// The smallest accepted count.
    pub const fn min(self) -> u32 {
        match self {
            Count::Exactly(k) | Count::AtLeast(k) | Count::Between(k, _) => k,
            Count::Stepped { min, .. } => min,
            Count::OneOf(ks) => {
                let mut i = 0;
                let mut m = u32::MAX;
                while i < ks.len() {
                    if ks[i] < m {
                        m = ks[i];
                    }
                    i += 1;
                }
                m
            }
        }
    }

    /// The largest accepted count, if there is one.
    pub const fn max(self) -> Option<u32> {
        match self {
            Count::Exactly(k) | Count::Between(_, k) => Some(k),
            Count::AtLeast(_) | Count::Stepped { .. } => None,
            Count::OneOf(ks) => {
                let mut i = 0;
                let mut m = 0;
                while i < ks.len() {
                    if ks[i] > m {
                        m = ks[i];
                    }
                    i += 1;
                }
                Some(m)
            }
        }
    }

    pub fn accepts(self, n: u32) -> bool {
        match self {
            Count::Exactly(k) => n == k,
            Count::AtLeast(k) => n >= k,
            Count::Between(a, b) => (a..=b).contains(&n),
            Count::OneOf(ks) => ks.contains(&n),
            Count::Stepped { min, step } => n >= min && (n - min).is_multiple_of(step.max(1)),
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
    /// Free text (a keyword, a word of colortext's text line, a light source's name in
    /// `mist`, ...). Real arguments also carry this kind.
    Word,
    /// The name of an earlier modifier (mixture foreground/background, illum's alternate
    /// material, antimatter's list), or `void`; WGMDfunc's also accept `inherit`.
    Modifier,
    /// A calcomp expression (a variable name is one), evaluated per ray in the
    /// function file's context: the strings `getfunc` parses (`src/rt/preload.c` masks).
    Function,
    /// The name of a calcomp function that Radiance calls with arguments (plasfunc's
    /// `refl`, colordata's `rfunc`, ...): it must be a name, not an expression. The
    /// argument's meaning says what it is called with.
    FunctionName,
    /// A file name searched in the scene's folder, then along RAYPATH.
    File(FileKind),
    /// A word of the xform-style transform (`-t x y z -rz 30 ...`) that may end a string
    /// list (see [`ArgList::transform`]); the transform runs to the end of the list.
    Transform,
}

impl StringKind {
    /// What the string is, as the docs say it: `expression`, `modifier`, `file (cal)`.
    pub fn describe(self) -> &'static str {
        match self {
            StringKind::Word => "word",
            StringKind::Modifier => "modifier",
            StringKind::Function => "expression",
            StringKind::FunctionName => "function name",
            StringKind::Transform => "transform",
            StringKind::File(kind) => match kind {
                FileKind::Cal => "file (cal)",
                FileKind::Data => "file (data)",
                FileKind::Picture => "file (picture)",
                FileKind::Font => "file (font)",
                FileKind::Octree => "file (octree)",
                FileKind::Mesh => "file (mesh)",
                FileKind::Bsdf => "file (BSDF XML)",
                FileKind::Text => "file (text)",
            },
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
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
    /// A plain text file whose lines colortext, brighttext and mixtext write.
    Text,
}

/// Bounds on a real argument. Violating `valid` is an error (Radiance fails or
/// misbehaves); leaving `plausible` is a warning (physically odd but accepted).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: f64,
    pub max: f64,
    /// Whether `min` itself is allowed (false for "radius > 0").
    pub min_inclusive: bool,
    /// Whether zero is excluded even inside `min..=max`: Radiance flips a negative
    /// sphere, cylinder or tube radius with a warning but rejects a zero one.
    pub nonzero: bool,
}

impl Bounds {
    pub const ANY: Bounds = Bounds::closed(f64::NEG_INFINITY, f64::INFINITY);
    pub const NON_NEGATIVE: Bounds = Bounds::closed(0.0, f64::INFINITY);
    pub const POSITIVE: Bounds = Bounds::above(0.0, f64::INFINITY);
    pub const UNIT: Bounds = Bounds::closed(0.0, 1.0);
    /// Any number but zero.
    pub const NON_ZERO: Bounds = Bounds {
        nonzero: true,
        ..Bounds::ANY
    };

    /// `min <= v <= max`.
    pub const fn closed(min: f64, max: f64) -> Bounds {
        Bounds {
            min,
            max,
            min_inclusive: true,
            nonzero: false,
        }
    }

    /// `min < v <= max`.
    pub const fn above(min: f64, max: f64) -> Bounds {
        Bounds {
            min,
            max,
            min_inclusive: false,
            nonzero: false,
        }
    }

    pub fn contains(&self, v: f64) -> bool {
        let above = if self.min_inclusive {
            v >= self.min
        } else {
            v > self.min
        };
        above && v <= self.max && !(self.nonzero && v == 0.0)
    }

    /// The bounds as a phrase: `between 0 and 1`, `> 0`, `> 0 and <= 360`, `not 0`.
    pub fn describe(&self) -> String {
        let lo = if self.min_inclusive { ">=" } else { ">" };
        let range = match (self.min.is_finite(), self.max.is_finite()) {
            (true, true) if self.min_inclusive => {
                format!("between {} and {}", self.min, self.max)
            }
            (true, true) => format!("> {} and <= {}", self.min, self.max),
            (true, false) => format!("{lo} {}", self.min),
            (false, true) => format!("<= {}", self.max),
            (false, false) if self.nonzero => return "not 0".into(),
            (false, false) => return "any number".into(),
        };
        if self.nonzero && self.contains_ignoring_zero(0.0) {
            format!("{range}, not 0")
        } else {
            range
        }
    }

    fn contains_ignoring_zero(&self, v: f64) -> bool {
        Bounds {
            nonzero: false,
            ..*self
        }
        .contains(v)
    }

    /// Whether these bounds admit every number.
    pub fn is_unbounded(&self) -> bool {
        *self == Bounds::ANY
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
/// that repeats (polygon vertices `x y z`, data coordinates `x1 x2 ..`, extra reals
/// `A5 A6 ..`), then, for string lists that take one, an optional transform.
///
/// `fixed` names every position Radiance gives a meaning; when `count` accepts fewer
/// (glass's optional index, mist's optional groups, text spacing), the trailing fixed
/// arguments are optional.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArgList {
    pub count: Count,
    pub fixed: &'static [Arg],
    pub repeat: &'static [Arg],
    /// Whether the list may end with an xform-style transform. As in Radiance's
    /// `getfunc` and `getinstance`, it begins at the first string after the fixed
    /// arguments (and any repeated ones) that is a transform option
    /// ([`is_transform_option`]) and runs to the end of the list.
    pub transform: bool,
}

impl ArgList {
    pub const NONE: ArgList = ArgList {
        count: Count::Exactly(0),
        fixed: &[],
        repeat: &[],
        transform: false,
    };

    /// The description of every word of a trailing transform.
    pub const TRANSFORM: Arg = Arg {
        name: "transform",
        meaning: "xform-style transform (`-t dx dy dz`, `-rx|-ry|-rz deg`, `-s f`, \
                  `-mx|-my|-mz`, `-i n`) placing the function coordinates, octree or mesh; \
                  it runs to the end of the strings",
        kind: StringKind::Transform,
        valid: Bounds::ANY,
        plausible: Bounds::ANY,
    };

    /// This layout with a trailing transform allowed.
    pub const fn with_transform(self) -> ArgList {
        ArgList {
            transform: true,
            ..self
        }
    }

    /// Where the transform starts in `words` (the string arguments), if it has one.
    pub fn transform_start<S: AsRef<str>>(&self, words: &[S]) -> Option<usize> {
        if !self.transform {
            return None;
        }
        (self.fixed.len()..words.len()).find(|&i| is_transform_option(words[i].as_ref()))
    }

    /// Like [`ArgList::arg_at`], but knowing the strings as written, so that words of
    /// a transform after data coordinates are described as the transform.
    pub fn arg_in<S: AsRef<str>>(&self, i: usize, words: &[S]) -> Option<(Arg, Option<usize>)> {
        match self.transform_start(words) {
            Some(start) if i >= start => Some((ArgList::TRANSFORM, None)),
            _ => self.arg_at(i),
        }
    }

    /// The name shown for position `i`: fixed names as they are, repeated groups
    /// numbered from 1 (`x1 y1 z1 x2 ..`, `src1 src2 ..`), except the extra reals `A`,
    /// numbered by position because function files read them as `A5` / `arg(5)`.
    pub fn label(&self, i: usize) -> Option<String> {
        let (arg, group) = self.arg_at(i)?;
        Some(match group {
            None => arg.name.to_string(),
            Some(_) if arg.name == "A" => format!("A{}", i + 1),
            Some(g) => format!("{}{}", arg.name, g + 1),
        })
    }

    /// The argument description for position `i` (0-based), if the layout names one,
    /// with the 0-based number of its repeated group (see [`ArgList::label`]). Positions
    /// past the fixed arguments of a list with a transform and no repeated group are
    /// described by [`ArgList::TRANSFORM`]; with a repeated group, only the words
    /// themselves tell where the transform starts ([`ArgList::transform_start`]).
    pub fn arg_at(&self, i: usize) -> Option<(Arg, Option<usize>)> {
        if let Some(a) = self.fixed.get(i) {
            return Some((*a, None));
        }
        if self.repeat.is_empty() {
            // Past the fixed arguments of a list without a repeated group, only the
            // transform remains (Radiance skips stray words before its first option).
            return self.transform.then_some((ArgList::TRANSFORM, None));
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
    /// The type of the same surface with its normal reversed (sphere and bubble, cone
    /// and cup, cylinder and tube), which xform writes under `-I` and for mirroring
    /// transforms (`initotypes` in xform.c); `None` where the arguments turn it inside
    /// out instead (a polygon's vertex order, a ring's normal) or nothing does.
    pub inverse: Option<&'static str>,
    /// One line for completion lists.
    pub summary: &'static str,
    /// A paragraph for hover and docs.
    pub doc: &'static str,
    pub strings: ArgList,
    pub reals: ArgList,
}

/// Which argument list of a primitive an index refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArgSide {
    Strings,
    Reals,
}

impl PrimitiveType {
    /// The argument list on one side.
    pub fn args(&self, side: ArgSide) -> &ArgList {
        match side {
            ArgSide::Strings => &self.strings,
            ArgSide::Reals => &self.reals,
        }
    }
}

/// Whether a string argument starts an xform transform, as Radiance's `isxfopt`
/// decides: `-t -s -i` or `-rx -ry -rz -mx -my -mz`, exactly.
pub fn is_transform_option(word: &str) -> bool {
    matches!(
        word,
        "-t" | "-s" | "-i" | "-rx" | "-ry" | "-rz" | "-mx" | "-my" | "-mz"
    )
}

/// Looks a type up by its exact (case-sensitive) keyword.
pub fn lookup(name: &str) -> Option<&'static PrimitiveType> {
    PRIMITIVE_TYPES.iter().find(|t| t.name == name)
}

/// All type keywords, for suggestions and completion.
pub fn type_names() -> impl Iterator<Item = &'static str> {
    PRIMITIVE_TYPES.iter().map(|t| t.name)
}
