//! The table of primitive types. Meanings follow the Radiance reference manual
//! (`ray.html`, section 2.1) and the argument checks in `src/rt/*.c`.

use super::{Arg, ArgList, Bounds, Category, Count, PrimitiveType, StringKind};

/// A real argument with hard limits `valid` and a plausible range.
const fn real(name: &'static str, meaning: &'static str, valid: Bounds, plausible: Bounds) -> Arg {
    Arg {
        name,
        meaning,
        kind: StringKind::Word,
        valid,
        plausible,
    }
}

/// A real argument with no limits.
const fn any(name: &'static str, meaning: &'static str) -> Arg {
    real(name, meaning, Bounds::ANY, Bounds::ANY)
}

/// A string argument.
const fn string(name: &'static str, meaning: &'static str, kind: StringKind) -> Arg {
    Arg {
        name,
        meaning,
        kind,
        valid: Bounds::ANY,
        plausible: Bounds::ANY,
    }
}

const fn list(count: Count, fixed: &'static [Arg]) -> ArgList {
    ArgList {
        count,
        fixed,
        repeat: &[],
    }
}

const REFLECTANCE: Bounds = Bounds::UNIT;

pub static PRIMITIVE_TYPES: &[PrimitiveType] = &[
    PrimitiveType {
        name: "polygon",
        category: Category::Surface,
        summary: "A flat polygon given by its vertices",
        doc: "A polygon with N >= 3 vertices listed in order; the surface normal follows the \
              right-hand rule (counter-clockwise seen from the front). Concave polygons and \
              holes joined by seams are allowed.",
        strings: ArgList::NONE,
        reals: ArgList {
            count: Count::Stepped { min: 9, step: 3 },
            fixed: &[],
            repeat: &[
                any("x", "vertex x coordinate"),
                any("y", "vertex y coordinate"),
                any("z", "vertex z coordinate"),
            ],
        },
    },
    PrimitiveType {
        name: "sphere",
        category: Category::Surface,
        summary: "A sphere with outward normals",
        doc: "A sphere given by its centre and radius. Its surface normal points outward; a \
              negative radius makes it a bubble.",
        strings: ArgList::NONE,
        reals: list(
            Count::Exactly(4),
            &[
                any("xc", "centre x"),
                any("yc", "centre y"),
                any("zc", "centre z"),
                real("radius", "radius (> 0)", Bounds::POSITIVE, Bounds::ANY),
            ],
        ),
    },
    PrimitiveType {
        name: "plastic",
        category: Category::Material,
        summary: "Uncoloured specular highlights over a coloured diffuse base",
        doc: "A material with a coloured diffuse component and an uncoloured (white) \
              specular highlight, like paint or plastic.",
        strings: ArgList::NONE,
        reals: list(
            Count::Exactly(5),
            &[
                real(
                    "red",
                    "red diffuse reflectance (0..1)",
                    Bounds::ANY,
                    REFLECTANCE,
                ),
                real(
                    "green",
                    "green diffuse reflectance (0..1)",
                    Bounds::ANY,
                    REFLECTANCE,
                ),
                real(
                    "blue",
                    "blue diffuse reflectance (0..1)",
                    Bounds::ANY,
                    REFLECTANCE,
                ),
                real(
                    "spec",
                    "specularity, fraction of light reflected specularly (0 .. 0.07 typical)",
                    Bounds::ANY,
                    REFLECTANCE,
                ),
                real(
                    "rough",
                    "roughness, rms facet slope (0 smooth .. 0.2 very rough)",
                    Bounds::ANY,
                    Bounds::closed(0.0, 1.0),
                ),
            ],
        ),
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let mut seen = std::collections::HashSet::new();
        for t in PRIMITIVE_TYPES {
            assert!(seen.insert(t.name), "duplicate type {}", t.name);
        }
    }

    #[test]
    fn fixed_args_fit_exact_counts() {
        for t in PRIMITIVE_TYPES {
            for l in [t.strings, t.reals] {
                if let Count::Exactly(n) = l.count {
                    if l.repeat.is_empty() {
                        assert_eq!(l.fixed.len(), n as usize, "{}", t.name);
                    }
                }
            }
        }
    }
}
