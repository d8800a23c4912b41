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
    E0307 = "E0307" "command-cycle" Error: "'!' commands nest too deep: a file probably includes itself.";
    E0308 = "E0308" "bad-data-file" Error: "A data file named by a primitive is malformed, or has the wrong number of dimensions.";
    E0309 = "E0309" "bad-picture-file" Error: "A file named as a picture is not a Radiance picture.";
    E0310 = "E0310" "bad-mesh-file" Error: "A file named by a mesh is not a Radiance mesh file, or is damaged.";
    // --- scene warnings -----------------------------------------------------------
    W0101 = "W0101" "invalid-utf8" Warning: "The file is not valid UTF-8; invalid bytes were read as '?'.";
    W0103 = "W0103" "nul-byte" Warning: "A word contains a NUL byte; Radiance ignores the rest of that word.";
    W0102 = "W0102" "long-word" Warning: "A word is longer than the 511 characters Radiance reads; Radiance splits it.";
    W0201 = "W0201" "value-out-of-range" Warning: "An argument is outside its physically plausible range.";
    W0202 = "W0202" "negative-radius" Warning: "A negative radius flips the surface's orientation (Radiance changes its type).";
    W0203 = "W0203" "nonplanar-polygon" Warning: "A polygon's vertices do not lie in one plane.";
    W0204 = "W0204" "degenerate-polygon" Warning: "A polygon has zero area or collinear vertices.";
    W0206 = "W0206" "degenerate-geometry" Warning: "The geometry has no extent (zero radius, equal cone ends, zero normal); Radiance drops it.";
    W0205 = "W0205" "cone-equal-radii" Warning: "A cone or cup with equal radii is a cylinder or tube.";
    W0207 = "W0207" "ignored-strings" Warning: "String arguments given to a type that takes none; Radiance ignores them.";
    W0304 = "W0304" "error-in-unused" Warning: "A problem Radiance only reports when the primitive is used; nothing uses it.";
    W0305 = "W0305" "unknown-named-modifier" Warning: "An antimatter or illum names a modifier that is not defined before it; Radiance only warns.";
    W0306 = "W0306" "command-failed" Warning: "A '!' command failed (bad generator arguments, a missing file); Radiance warns and keeps what it wrote before failing.";
    W0301 = "W0301" "unused-modifier" Warning: "A modifier is defined but nothing uses it.";
    W0302 = "W0302" "redefined-modifier" Warning: "A modifier is defined again before its earlier definition was ever used.";
    W0303 = "W0303" "command-not-expanded" Warning: "A '!' command line was not expanded, so what it makes was not checked.";
    W0307 = "W0307" "not-rendered" Warning: "The scene uses something radc's renderer does not model yet: radc trace and radc render refuse the scene (Radiance renders it).";
    // --- calcomp ---------------------------------------------------------------------
    E0501 = "E0501" "cal-syntax" Error: "The calcomp text does not follow the grammar Radiance's parser accepts.";
    E0502 = "E0502" "cal-bad-parameter" Error: "A function parameter name is not allowed (it holds a context mark).";
    E0601 = "E0601" "cal-undefined-name" Error: "A variable or function is used but defined nowhere Radiance would look.";
    E0602 = "E0602" "cal-wrong-arity" Error: "A function is called with fewer arguments than its definition uses.";
    E0603 = "E0603" "cal-not-a-function" Error: "A variable is called like a function, or a function is used as a variable.";
    E0604 = "E0604" "cal-bad-constant" Error: "A constant expression divides by zero or leaves a function's domain (Radiance: 'bad constant expression').";
    W0601 = "W0601" "cal-redefined" Warning: "A name is defined again; the later definition replaces the earlier one.";
    W0602 = "W0602" "cal-nonconstant-constant" Warning: "A ':' definition depends on a value that changes per record or ray.";
    W0603 = "W0603" "cal-unused" Warning: "A definition is never used by any output or other definition.";
    W0604 = "W0604" "cal-hides-library" Warning: "A definition replaces a built-in library function.";
    W0606 = "W0606" "cal-free-name" Warning: "A name is used but not defined in this file; whatever loads the file must define it.";
    W0605 = "W0605" "cal-extra-arguments" Warning: "A call passes more arguments than the function uses; Radiance ignores the extra ones.";
    E0701 = "E0701" "cal-undefined-at-run-time" Error: "Evaluation reached a name that is not defined.";
    E0702 = "E0702" "cal-missing-argument" Error: "Evaluation used a function argument the call did not pass.";
    E0703 = "E0703" "cal-no-input" Error: "An input column was read where there is no input (rcalc -n).";
    E0704 = "E0704" "cal-argument-not-function" Error: "A function parameter used as a function was passed a value, not a function name.";
    W0701 = "W0701" "cal-division-by-zero" Warning: "A division by zero was evaluated; Radiance yields 0.";
    W0702 = "W0702" "cal-domain-error" Warning: "A library function or power was evaluated outside its domain or range; Radiance yields 0.";
    // --- transforms, generators and '!' commands -----------------------------------
    E0801 = "E0801" "unknown-transform-option" Error: "A word in a transform is not one of -t -rx -ry -rz -s -mx -my -mz -i.";
    E0802 = "E0802" "bad-transform-argument" Error: "A transform option is missing an argument, or an argument is not a number.";
    E0803 = "E0803" "zero-scale" Error: "A transform scales by 0, which Radiance refuses.";
    E0804 = "E0804" "repeat-too-large" Error: "A transform's -i repeat count is too large to apply.";
}
