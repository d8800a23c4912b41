//! Transform words (`-t x y z -rx a -ry a -rz a -s f -mx -my -mz -i N`) as a matrix.
//!
//! The same words follow the octree of an `instance`/`mesh`, and are `xform`'s command
//! line. This module reproduces Radiance's `xf()` (`src/common/xf.c`) to the last bit:
//! each option is a 4x4 matrix acting on row vectors (`p' = p M`), options compose left
//! to right, `-i N` repeats everything since the previous `-i` (or the start) `N` times,
//! and the scale factor is the product of `-s` factors and `-1` for each mirror, so a
//! negative scale means the transform mirrors (xform then reverses surfaces).
//!
//! Pure: no IO. Arguments are validated as strictly as `badarg()` does, so a word that
//! Radiance would stop at is an error here, pointing at that word.

// Every layer of `lang` reports a `Diagnostic` by value; boxing it here alone would make
// this module the odd one out.
#![allow(clippy::result_large_err)]

use crate::diagnostic::{self, Diagnostic};
use crate::source::Span;

/// A 4x4 matrix in Radiance's layout: rows are images of the axes, row 3 the translation.
pub type Mat4 = [[f64; 4]; 4];

pub const IDENTITY: Mat4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// More repetitions than this are refused: Radiance multiplies once per repetition
/// (so results depend on doing exactly that), and a huge count would hang.
pub const MAX_REPEAT: i64 = 1_000_000;

/// Which of xf.c's two readers of a transform: `xf` or `invxf`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Direction {
    Forward,
    Inverse,
}

/// A parsed transform: the matrix and its uniform scale factor (negative if mirrored).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub matrix: Mat4,
    pub scale: f64,
}

impl Default for Transform {
    fn default() -> Self {
        Transform::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        matrix: IDENTITY,
        scale: 1.0,
    };

    /// Parses a whole transform: every word must belong to it.
    pub fn parse(words: &[(&str, Span)]) -> Result<Transform, Diagnostic> {
        Transform::parse_whole(words, Direction::Forward)
    }

    /// Every word must belong to the transform read in `direction`.
    fn parse_whole(words: &[(&str, Span)], direction: Direction) -> Result<Transform, Diagnostic> {
        let (xf, used) = Transform::parse_prefix_as(words, direction)?;
        match words.get(used) {
            None => Ok(xf),
            Some((w, span)) => Err(Diagnostic::new(
                diagnostic::E0801,
                *span,
                format!("'{w}' is not a transform option"),
            )
            .with_hint(OPTIONS_HINT)),
        }
    }

    /// Parses the transform words at the start of `words`, stopping before the first
    /// word that does not begin with `-` (a file name on xform's command line). Returns
    /// the transform and how many words it used. A word beginning with `-` that is not a
    /// valid option is an error, as it is for xform.
    pub fn parse_prefix(words: &[(&str, Span)]) -> Result<(Transform, usize), Diagnostic> {
        Transform::parse_prefix_as(words, Direction::Forward)
    }

    /// The inverse of the transform `words` give, built as xf.c's `invxf` builds it
    /// (each step inverted and multiplied on the left), not by inverting the matrix:
    /// the renderer maps hit points into a function's coordinates with it, and the
    /// last bits must be Radiance's. `scale` is its factor, negative if mirrored.
    pub fn parse_inverse(words: &[(&str, Span)]) -> Result<Transform, Diagnostic> {
        Transform::parse_whole(words, Direction::Inverse)
    }

    fn parse_prefix_as(
        words: &[(&str, Span)],
        direction: Direction,
    ) -> Result<(Transform, usize), Diagnostic> {
        let inverse = direction == Direction::Inverse;
        let sign = if inverse { -1.0 } else { 1.0 };
        let mut total = Transform::IDENTITY;
        let mut group = Transform::IDENTITY;
        let mut repeat: i64 = 1;
        let mut i = 0;
        while let Some(&(word, span)) = words.get(i) {
            if !word.starts_with('-') {
                break;
            }
            let option = Op::parse(word, span)?;
            let args = option.arguments(words, i)?;
            i += 1 + args.len();
            let step = match option {
                Op::Translate => {
                    let t = [
                        sign * real(args[0])?,
                        sign * real(args[1])?,
                        sign * real(args[2])?,
                    ];
                    let mut m = IDENTITY;
                    m[3][..3].copy_from_slice(&t);
                    Transform {
                        matrix: m,
                        scale: 1.0,
                    }
                }
                Op::Rotate(axis) => rotation(axis, sign * real(args[0])?),
                Op::Scale => {
                    let s = real(args[0])?;
                    if s == 0.0 {
                        return Err(Diagnostic::new(
                            diagnostic::E0803,
                            args[0].1,
                            "a scale factor of 0 collapses everything to a point",
                        )
                        .with_label(span, "in this -s option")
                        .with_hint(
                            "give a non-zero factor (a negative one also mirrors), or drop the -s",
                        ));
                    }
                    let s = if inverse { 1.0 / s } else { s };
                    let mut m = IDENTITY;
                    for (k, row) in m.iter_mut().take(3).enumerate() {
                        row[k] = s;
                    }
                    Transform {
                        matrix: m,
                        scale: s,
                    }
                }
                Op::Mirror(axis) => {
                    let mut m = IDENTITY;
                    m[axis][axis] = -1.0;
                    Transform {
                        matrix: m,
                        scale: -1.0,
                    }
                }
                Op::Iterate => {
                    total = total.repeated_as(group, repeat, direction);
                    repeat = count(args[0])?;
                    group = Transform::IDENTITY;
                    continue;
                }
            };
            group = match direction {
                Direction::Forward => group.then(&step),
                // invxf multiplies each inverted step on the left.
                Direction::Inverse => step.then(&group),
            };
        }
        Ok((total.repeated_as(group, repeat, direction), i))
    }

    /// `self` followed by `next` (Radiance's `multmat4(a, self, next)`).
    pub fn then(&self, next: &Transform) -> Transform {
        Transform {
            matrix: multiply(&self.matrix, &next.matrix),
            scale: self.scale * next.scale,
        }
    }

    /// `self` followed by `n` copies of `group`, multiplied one at a time as xf.c does
    /// (on the right for `xf`, on the left for `invxf`).
    fn repeated_as(self, group: Transform, n: i64, direction: Direction) -> Transform {
        (0..n.max(0)).fold(self, |acc, _| match direction {
            Direction::Forward => acc.then(&group),
            Direction::Inverse => group.then(&acc),
        })
    }

    /// Whether the transform mirrors space (an odd number of `-m` options, or a negative
    /// `-s`): xform then reverses surface orientation.
    pub fn is_mirror(&self) -> bool {
        self.scale < 0.0
    }

    /// A point: rotated, scaled and translated (`multp3`).
    pub fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let v = self.vector(p);
        let m = &self.matrix;
        [v[0] + m[3][0], v[1] + m[3][1], v[2] + m[3][2]]
    }

    /// A direction: rotated and scaled, not translated (`multv3`).
    pub fn vector(&self, v: [f64; 3]) -> [f64; 3] {
        let m = &self.matrix;
        let mut out = [0.0; 3];
        for (j, o) in out.iter_mut().enumerate() {
            *o = v[0] * m[0][j] + v[1] * m[1][j] + v[2] * m[2][j];
        }
        out
    }
}

const OPTIONS_HINT: &str =
    "transform options are -t x y z, -rx/-ry/-rz degrees, -s factor, -mx/-my/-mz and -i count";

#[derive(Clone, Copy, Debug)]
enum Op {
    Translate,
    Rotate(usize),
    Scale,
    Mirror(usize),
    Iterate,
}

/// What an option's arguments must look like (`badarg()`'s format letters).
#[derive(Clone, Copy)]
enum ArgKind {
    Real,
    Integer,
}

impl Op {
    fn parse(word: &str, span: Span) -> Result<Op, Diagnostic> {
        let axis = |c: &str| match c {
            "x" => Some(0),
            "y" => Some(1),
            "z" => Some(2),
            _ => None,
        };
        let option = match word.get(1..).unwrap_or("") {
            "t" => Some(Op::Translate),
            "s" => Some(Op::Scale),
            "i" => Some(Op::Iterate),
            w if w.len() == 2 && w.starts_with('r') => axis(&w[1..]).map(Op::Rotate),
            w if w.len() == 2 && w.starts_with('m') => axis(&w[1..]).map(Op::Mirror),
            _ => None,
        };
        option.ok_or_else(|| {
            let mut d = Diagnostic::new(
                diagnostic::E0801,
                span,
                format!("'{word}' is not a transform option"),
            );
            let known = ["-t", "-rx", "-ry", "-rz", "-s", "-mx", "-my", "-mz", "-i"];
            d = if word.starts_with("-r") {
                d.with_hint("rotations are -rx, -ry and -rz, each followed by degrees")
            } else if word.starts_with("-m") {
                d.with_hint("mirrors are -mx, -my and -mz")
            } else if let Some(s) = diagnostic::suggest(word, known) {
                d.with_hint(format!("did you mean '{s}'?"))
            } else {
                d.with_hint(OPTIONS_HINT)
            };
            d
        })
    }

    fn signature(self) -> &'static [ArgKind] {
        match self {
            Op::Translate => &[ArgKind::Real; 3],
            Op::Rotate(_) | Op::Scale => &[ArgKind::Real],
            Op::Mirror(_) => &[],
            Op::Iterate => &[ArgKind::Integer],
        }
    }

    /// The words after the option at `at`, checked against its signature.
    fn arguments<'w, 'a>(
        self,
        words: &'w [(&'a str, Span)],
        at: usize,
    ) -> Result<&'w [(&'a str, Span)], Diagnostic> {
        let kinds = self.signature();
        let (word, span) = words[at];
        let rest = &words[at + 1..];
        if rest.len() < kinds.len() {
            let what = describe(kinds);
            let follow = match rest.len() {
                0 => "nothing follows it".to_string(),
                1 => "only 1 word follows it".to_string(),
                n => format!("only {n} words follow it"),
            };
            return Err(Diagnostic::new(
                diagnostic::E0802,
                span,
                format!("'{word}' needs {what}, but {follow}"),
            ));
        }
        let args = &rest[..kinds.len()];
        for (&(arg, arg_span), kind) in args.iter().zip(kinds) {
            let ok = match kind {
                ArgKind::Real => is_real(arg),
                ArgKind::Integer => is_integer(arg),
            };
            if !ok {
                let what = match kind {
                    ArgKind::Real => "a number",
                    ArgKind::Integer => "a whole number",
                };
                return Err(Diagnostic::new(
                    diagnostic::E0802,
                    arg_span,
                    format!("'{arg}' is not {what}, as '{word}' needs"),
                )
                .with_label(span, "the option"));
            }
        }
        Ok(args)
    }
}

fn describe(kinds: &[ArgKind]) -> String {
    match kinds {
        [ArgKind::Integer] => "a repeat count".into(),
        [ArgKind::Real] => "a number".into(),
        k => format!("{} numbers", k.len()),
    }
}

/// A rotation by `degrees` about an axis, built entry by entry as xf.c builds it.
fn rotation(axis: usize, degrees: f64) -> Transform {
    let a = (std::f64::consts::PI / 180.0) * degrees;
    let (s, c) = (a.sin(), a.cos());
    // The two axes other than `axis`, in the cyclic order that makes the angle positive.
    let (u, v) = match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let mut m = IDENTITY;
    m[u][u] = c;
    m[v][v] = c;
    m[u][v] = s;
    m[v][u] = -s;
    Transform {
        matrix: m,
        scale: 1.0,
    }
}

/// `a * b` summed as the reference build's `multmat4` sums it, so results match to
/// the bit: the oracle (pyradiance) compiles Radiance with `-ffast-math`, and its
/// `multmat4` adds the four products in pairs, `(t0 + t1) + (t2 + t3)`.
pub fn multiply(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, o) in row.iter_mut().enumerate() {
            *o = (a[i][0] * b[0][j] + a[i][1] * b[1][j]) + (a[i][2] * b[2][j] + a[i][3] * b[3][j]);
        }
    }
    out
}

fn real(arg: (&str, Span)) -> Result<f64, Diagnostic> {
    arg.0.trim().parse::<f64>().map_err(|_| {
        Diagnostic::new(
            diagnostic::E0802,
            arg.1,
            format!("'{}' is not a number", arg.0),
        )
    })
}

fn count(arg: (&str, Span)) -> Result<i64, Diagnostic> {
    let n = arg.0.trim().parse::<i64>().unwrap_or(i64::MAX);
    if n > MAX_REPEAT {
        return Err(Diagnostic::new(
            diagnostic::E0804,
            arg.1,
            format!("repeat count {} is too large", arg.0.trim()),
        )
        .with_hint(format!("radc allows at most {MAX_REPEAT} repetitions")));
    }
    Ok(n)
}

/// Radiance's integer syntax (`iskip()`): optional spaces, sign, digits.
pub fn is_integer(s: &str) -> bool {
    let s = s.trim_matches(|c: char| c.is_ascii_whitespace());
    let digits = s.strip_prefix(['+', '-']).unwrap_or(s);
    !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())
}

/// Radiance's real syntax (`fskip()`): `[+-](digits[.digits]|.digits)[(e|E)[+-]digits]`,
/// also `5.`; no `inf`, `nan` or hex.
pub fn is_real(s: &str) -> bool {
    let s = s.trim_matches(|c: char| c.is_ascii_whitespace());
    let s = s.strip_prefix(['+', '-']).unwrap_or(s);
    let mantissa_end = s.find(['e', 'E']).unwrap_or(s.len());
    let (mantissa, exponent) = s.split_at(mantissa_end);
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all_digits = |t: &str| t.bytes().all(|b| b.is_ascii_digit());
    let mantissa_ok = all_digits(int) && all_digits(frac) && !(int.is_empty() && frac.is_empty());
    mantissa_ok && (exponent.is_empty() || is_integer_strict(&exponent[1..]))
}

fn is_integer_strict(s: &str) -> bool {
    let digits = s.strip_prefix(['+', '-']).unwrap_or(s);
    !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// invxf's inverse undoes xf's transform (to rounding), repetitions included.
    #[test]
    fn inverse_undoes_the_transform() {
        let words = [
            "-rz", "30", "-t", ".2", "1", "-3", "-s", "2.5", "-i", "3", "-rx", "10", "-my",
        ];
        let spanned: Vec<(&str, Span)> = words.iter().map(|w| (*w, Span::default())).collect();
        let (f, i) = (
            Transform::parse(&spanned).expect("valid"),
            Transform::parse_inverse(&spanned).expect("valid"),
        );
        let p = [0.3, -1.7, 2.2];
        let back = i.point(f.point(p));
        for (a, b) in back.iter().zip(p) {
            assert!((a - b).abs() < 1e-12, "{back:?} vs {p:?}");
        }
        assert!((f.scale * i.scale - 1.0).abs() < 1e-15);
    }
    use crate::source::FileId;

    /// Words with spans as if the words were joined by single spaces.
    fn words(text: &str) -> Vec<(&str, Span)> {
        let mut out = Vec::new();
        let mut at = 0;
        for w in text.split(' ').filter(|w| !w.is_empty()) {
            let start = text[at..].find(w).map(|o| o + at).unwrap_or(at);
            out.push((w, Span::new(FileId(0), start..start + w.len())));
            at = start + w.len();
        }
        out
    }

    fn xf(text: &str) -> Transform {
        match Transform::parse(&words(text)) {
            Ok(t) => t,
            Err(d) => panic!("{text}: {d:?}"),
        }
    }

    fn err(text: &str) -> Diagnostic {
        match Transform::parse(&words(text)) {
            Ok(t) => panic!("{text} parsed: {t:?}"),
            Err(d) => d,
        }
    }

    fn close(a: [f64; 3], b: [f64; 3]) {
        for k in 0..3 {
            assert!(
                (a[k] - b[k]).abs() <= 1e-11 * (1.0 + b[k].abs()),
                "{a:?} != {b:?}"
            );
        }
    }

    // Expected numbers below come from real xform (Radiance 6, pyradiance) applied to
    // `void sphere s 0 0 4 1 2 3 0.5`, e.g. `xform -rz 30 -t 1 0 0` prints the centre
    // 0.866025403784 2.23205080757 3 and radius 0.5.
    #[test]
    fn rotate_then_translate_matches_xform() {
        let t = xf("-rz 30 -t 1 0 0");
        close(
            t.point([1.0, 2.0, 3.0]),
            [0.866025403784, 2.23205080757, 3.0],
        );
        assert_eq!(t.scale, 1.0);
    }

    #[test]
    fn composition_order_matches_xform() {
        // xform -t 1 0 0 -rz 90 sphere -> -2 2 3
        close(
            xf("-t 1 0 0 -rz 90").point([1.0, 2.0, 3.0]),
            [-2.0, 2.0, 3.0],
        );
        // xform -rx 45 -ry 60 -s 2 -> 7.12372435696 -1.41421356237 1.80348309836
        let t = xf("-rx 45 -ry 60 -s 2");
        close(
            t.point([1.0, 2.0, 3.0]),
            [7.12372435696, -std::f64::consts::SQRT_2, 1.80348309836],
        );
        assert_eq!(t.scale, 2.0);
    }

    #[test]
    fn mirror_negates_scale() {
        let t = xf("-mx -s 3");
        assert!(t.is_mirror());
        assert_eq!(t.scale, -3.0);
        close(t.point([1.0, 2.0, 3.0]), [-3.0, 6.0, 9.0]);
        assert!(!xf("-mx -my").is_mirror());
    }

    #[test]
    fn iterate_repeats_the_group_before_it() {
        // xform -t 1 0 0 -i 3 -rz 90 -> (1,2,3)+(1,0,0) rotated 90 three times: 2 -2 3
        close(
            xf("-t 1 0 0 -i 3 -rz 90").point([1.0, 2.0, 3.0]),
            [2.0, -2.0, 3.0],
        );
        // -i 0 drops the group after it.
        close(xf("-i 0 -t 5 5 5").point([1.0, 2.0, 3.0]), [1.0, 2.0, 3.0]);
        // xform -i 2 -t 1 0 0 -s 2 -> x = ((1+1)*2+1)*2 = 10, y 8, z 12
        let t = xf("-i 2 -t 1 0 0 -s 2");
        close(t.point([1.0, 2.0, 3.0]), [10.0, 8.0, 12.0]);
        assert_eq!(t.scale, 4.0);
    }

    #[test]
    fn vectors_ignore_translation() {
        let t = xf("-t 5 5 5 -ry 90");
        close(t.vector([1.0, 0.0, 0.0]), [0.0, 0.0, -1.0]);
    }

    #[test]
    fn empty_is_identity() {
        assert_eq!(xf(""), Transform::IDENTITY);
    }

    #[test]
    fn errors_point_at_the_word() {
        let d = err("-t 1 x 3");
        assert_eq!(d.code, diagnostic::E0802);
        assert_eq!(d.span.range(), 5..6);
        let d = err("-rz 10 -rw 5");
        assert_eq!(d.code, diagnostic::E0801);
        assert_eq!(d.span.range(), 7..10);
        let d = err("-s 0");
        assert_eq!(d.code, diagnostic::E0803);
        assert_eq!(d.span.range(), 3..4);
        let d = err("-t 1 2");
        assert_eq!(d.code, diagnostic::E0802);
        assert_eq!(d.span.range(), 0..2);
        assert_eq!(err("-i 2.5").code, diagnostic::E0802);
        assert_eq!(err("-i 99999999999999999999").code, diagnostic::E0804);
        assert_eq!(err("-rz 10 file.rad").code, diagnostic::E0801);
        assert_eq!(err("-sx 2").code, diagnostic::E0801);
    }

    #[test]
    fn prefix_stops_at_a_file_name() {
        let w = words("-s 2 scene.rad -t 1 1 1");
        let (t, used) = Transform::parse_prefix(&w).expect("prefix");
        assert_eq!(used, 2);
        assert_eq!(t.scale, 2.0);
    }

    #[test]
    fn number_syntax_is_radiances() {
        for ok in ["1", "-1.5", "+.5", "5.", "1e3", "1.5E-2", "-0"] {
            assert!(is_real(ok), "{ok}");
        }
        for bad in [
            "", ".", "e1", "1e", "1.5.2", "inf", "nan", "0x10", "1,5", "--1",
        ] {
            assert!(!is_real(bad), "{bad}");
        }
        assert!(is_integer("-3") && !is_integer("3.0") && !is_integer("+"));
    }

    /// What a user sees for each kind of mistake: code, the word pointed at, message, hint.
    #[test]
    fn diagnostics_read_well() {
        let cases = [
            "-rz 10 -rw 5",
            "-rot 90",
            "-tt 1 2 3",
            "-t 1 x 3",
            "-t 1 2",
            "-s 0",
            "-i 2.5 -rz 10",
            "-i 99999999999",
            "-mx extra.oct",
        ];
        let mut report = String::new();
        for text in cases {
            let d = err(text);
            let word = &text[d.span.range()];
            report.push_str(&format!(
                "{text}\n  {} at '{word}': {}\n",
                d.code.id, d.message
            ));
            if let Some(h) = &d.hint {
                report.push_str(&format!("  hint: {h}\n"));
            }
            for l in &d.labels {
                report.push_str(&format!(
                    "  label '{}': {}\n",
                    &text[l.span.range()],
                    l.message
                ));
            }
        }
        insta::assert_snapshot!(report);
    }

    #[test]
    fn never_panics_on_odd_words() {
        for text in [
            "-",
            "--",
            "-r",
            "-m",
            "-rxx 1",
            "-é 1",
            "-t",
            "-i",
            "-i -3 -t 1 1 1",
        ] {
            let _ = Transform::parse(&words(text));
        }
    }
}
