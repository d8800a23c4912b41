//! Every diagnostic code radc emits. Codes are stable: retire one, never reuse it.
//!
//! Ranges: scene syntax `E01xx`, scene semantics `E02xx`-`E03xx`, scene warnings
//! `W01xx`-`W03xx`; calcomp `E05xx`-`E06xx` / `W05xx`-`W06xx`; calcomp evaluation
//! `E07xx` / `W07xx`; generators and `!` commands `E08xx` / `W08xx`.

use super::{Code, Severity};

macro_rules! codes {
    ($( $konst:ident = $id:literal $name:literal $sev:ident : $summary:literal; )*) => {
        $( pub const $konst: Code = Code {
            id: $id, name: $name, severity: Severity::$sev, summary: $summary,
        }; )*
        /// All codes, in table order.
        pub const ALL_CODES: &[Code] = &[$($konst),*];
    };
}

codes! {
    // --- scene syntax -------------------------------------------------------------
    E0102 = "E0102" "unexpected-end" Error: "The file ends in the middle of a primitive.";
    E0103 = "E0103" "bad-count" Error: "An argument count is not a non-negative integer.";
    E0104 = "E0104" "bad-real" Error: "A real argument is not a number Radiance can read.";
    E0105 = "E0105" "nonzero-int-args" Error: "The integer-argument count must be 0.";
    E0106 = "E0106" "unterminated-quote" Error: "A quoted string is not closed before the end of the file.";
    E0107 = "E0107" "misplaced-comment" Error: "A '#' comment inside a primitive's arguments.";
    E0108 = "E0108" "nul-byte" Error: "The file contains a NUL byte.";
    E0109 = "E0109" "bad-alias" Error: "An alias line is malformed.";
    E0110 = "E0110" "count-too-large" Error: "An argument count is larger than the rest of the file could hold.";
    // --- scene semantics ----------------------------------------------------------
    E0201 = "E0201" "unknown-type" Error: "The primitive type is not one Radiance knows.";
    E0202 = "E0202" "wrong-arg-count" Error: "The number of string or real arguments does not fit the type.";
    E0203 = "E0203" "bad-arg-value" Error: "An argument's value violates the type's constraint.";
    E0204 = "E0204" "reserved-name" Error: "A modifier is named 'void' or 'inherit'.";
    E0206 = "E0206" "inherit-misuse" Error: "The 'inherit' modifier is used by something other than an alias.";
    E0205 = "E0205" "bad-transform" Error: "A transform argument list cannot be parsed.";
    E0301 = "E0301" "undefined-modifier" Error: "The modifier is not defined earlier in the scene.";
    E0302 = "E0302" "wrong-modifier-kind" Error: "The modifier is of a kind that cannot modify this primitive.";
    E0303 = "E0303" "undefined-alias-target" Error: "An alias refers to a name not defined earlier.";
    E0304 = "E0304" "alias-of-surface" Error: "An alias refers to a surface; only modifiers can be aliased.";
    E0305 = "E0305" "missing-file" Error: "A file named by an argument is not found in the scene's folder or RAYPATH.";
    E0307 = "E0307" "command-failed" Error: "A '!' command could not be expanded: a generator rejected its arguments, or commands nest too deep.";
    // --- scene warnings -----------------------------------------------------------
    W0101 = "W0101" "invalid-utf8" Warning: "The file is not valid UTF-8; invalid bytes were read as '?'.";
    W0102 = "W0102" "long-word" Warning: "A word is longer than the 511 characters Radiance reads; Radiance splits it.";
    W0201 = "W0201" "value-out-of-range" Warning: "An argument is outside its physically plausible range.";
    W0202 = "W0202" "negative-radius" Warning: "A negative radius flips the surface's orientation (Radiance changes its type).";
    W0203 = "W0203" "nonplanar-polygon" Warning: "A polygon's vertices do not lie in one plane.";
    W0204 = "W0204" "degenerate-polygon" Warning: "A polygon has zero area or collinear vertices.";
    W0206 = "W0206" "degenerate-geometry" Warning: "The geometry has no extent (zero radius, equal cone ends, zero normal); Radiance drops it.";
    W0205 = "W0205" "cone-equal-radii" Warning: "A cone or cup with equal radii is a cylinder or tube.";
    W0301 = "W0301" "unused-modifier" Warning: "A modifier is defined but nothing uses it.";
    W0302 = "W0302" "redefined-modifier" Warning: "A modifier name is defined again; later uses see the new one.";
    W0303 = "W0303" "command-not-expanded" Warning: "A '!' command line was not expanded, so what it makes was not checked.";
}
