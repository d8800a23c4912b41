//! Radiance data files: the N-dimensional tables read by `brightdata`, `colordata`,
//! `texdata`, `mixdata`, `plasdata`/`metdata`/`transdata` and `specdata`.
//!
//! Reproduces Radiance's reader (`src/common/data.c`, `getdata`, with words read as by
//! `fgetval.c`) and its interpolator (`data_interp`), including the places where the exact
//! result depends on C details:
//! - values, axis bounds and axis points are stored as `float` (single precision), each
//!   parsed as a double and then rounded, and an axis's extent `end - begin` is computed in
//!   single precision (a zero extent selects an unevenly spaced axis);
//! - interpolation is multilinear, computed as a recursion over the axes in which each level
//!   multiplies the weights handed down by its own two weights, and a branch whose weight is
//!   within `FTINY` (1e-6) of zero contributes nothing;
//! - outside the domain the value is extrapolated linearly for one division, then tapers off
//!   harmonically towards zero (the weights become `1/(i-1-x)` and `-2/(i-1-x)`);
//! - an axis whose bounds overflow single precision to the same infinity has a NaN extent,
//!   which Radiance's optimised build takes for zero (an unevenly spaced axis);
//! - a coordinate that is NaN or at least 2^31 divisions from the origin truncates to
//!   `INT_MIN` on x86-64 (`cvttsd2si`), so Radiance extrapolates it from the first cell.

use std::fmt;

use crate::c_number::{atol, is_c_space, is_int, real_word};

/// Radiance's `MAXDDIM`: the most dimensions a data file may have.
pub const MAX_DIMENSIONS: usize = 6;

/// `FTINY` from `fvect.h`: interpolation weights this close to zero are dropped.
const FTINY: f64 = 1e-6;

/// `fgetval` reads each word into a 64-byte buffer and rejects words that fill it.
const MAX_WORD_LEN: usize = 63;

/// A loaded data file: its axes (slowest-varying first) and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct DataFile {
    axes: Vec<Axis>,
    /// Product of the point counts of the axes after each one.
    strides: Vec<usize>,
    values: Vec<f32>,
}

/// One independent variable of a data file.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The first coordinate.
    pub origin: f32,
    /// `last - first`, in single precision (negative for a decreasing axis).
    pub extent: f32,
    /// Number of points, at least 2.
    pub count: usize,
    /// The points of an unevenly spaced axis; `None` when evenly spaced.
    pub points: Option<Vec<f32>>,
}

/// Why a data file could not be loaded, and where (1-based line and column, counted in
/// characters; `offset` is the byte offset).
#[derive(Debug, Clone, PartialEq)]
pub struct DataFileError {
    pub line: usize,
    pub column: usize,
    pub offset: usize,
    pub kind: DataFileErrorKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum DataFileErrorKind {
    /// The file ended where Radiance expected another word ("unexpected EOF").
    UnexpectedEnd { expected: Expected },
    /// A word is not a number of the kind expected ("bad format").
    BadNumber { expected: Expected, word: String },
    /// A word of 64 or more characters, which Radiance's reader cannot hold.
    WordTooLong,
    /// The dimension count is not between 1 and [`MAX_DIMENSIONS`].
    BadDimensionCount(i32),
    /// An axis has fewer than two points.
    TooFewPoints { axis: usize, count: i32 },
    /// The points of an unevenly spaced axis change direction.
    NotMonotonic { axis: usize },
    /// The axes together need more values than any file could hold.
    TooManyValues,
}

/// The kind of word the reader was looking for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expected {
    DimensionCount,
    AxisBegin { axis: usize },
    AxisEnd { axis: usize },
    PointCount { axis: usize },
    AxisPoint { axis: usize, index: usize },
    Value { index: usize },
}

impl fmt::Display for Expected {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Axes and values are numbered from 1 for people.
        match *self {
            Expected::DimensionCount => write!(f, "the number of dimensions"),
            Expected::AxisBegin { axis } => write!(f, "the first coordinate of axis {}", axis + 1),
            Expected::AxisEnd { axis } => write!(f, "the last coordinate of axis {}", axis + 1),
            Expected::PointCount { axis } => write!(f, "the point count of axis {}", axis + 1),
            Expected::AxisPoint { axis, index } => {
                write!(
                    f,
                    "point {} of unevenly spaced axis {}",
                    index + 1,
                    axis + 1
                )
            }
            Expected::Value { index } => write!(f, "data value {}", index + 1),
        }
    }
}

impl fmt::Display for DataFileErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DataFileErrorKind::UnexpectedEnd { expected } => {
                write!(f, "the file ends where {expected} should be")
            }
            DataFileErrorKind::BadNumber { expected, word } => {
                let kind = match expected {
                    Expected::DimensionCount | Expected::PointCount { .. } => "an integer",
                    _ => "a number",
                };
                write!(f, "expected {expected} ({kind}), found '{word}'")
            }
            DataFileErrorKind::WordTooLong => {
                write!(f, "a word of {} or more characters", MAX_WORD_LEN + 1)
            }
            DataFileErrorKind::BadDimensionCount(n) => {
                write!(f, "{n} dimensions: a data file has 1 to {MAX_DIMENSIONS}")
            }
            DataFileErrorKind::TooFewPoints { axis, count } => {
                write!(
                    f,
                    "axis {} has {count} points; it needs at least 2",
                    axis + 1
                )
            }
            DataFileErrorKind::NotMonotonic { axis } => write!(
                f,
                "the points of axis {} neither only increase nor only decrease",
                axis + 1
            ),
            DataFileErrorKind::TooManyValues => {
                write!(f, "the axes call for more values than a file can hold")
            }
        }
    }
}

impl fmt::Display for DataFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.line, self.column, self.kind)
    }
}

impl std::error::Error for DataFileError {}

impl DataFile {
    /// Reads a data file as Radiance's `getdata` does. Text after the last value is ignored,
    /// as Radiance ignores it.
    pub fn parse(text: &str) -> Result<DataFile, DataFileError> {
        let mut words = Words::new(text);
        let dims = words.integer(Expected::DimensionCount)?;
        if !(1..=MAX_DIMENSIONS as i32).contains(&dims.value) {
            return Err(words.error_at(
                dims.offset,
                DataFileErrorKind::BadDimensionCount(dims.value),
            ));
        }
        let mut axes = Vec::with_capacity(dims.value as usize);
        let mut total: usize = 1;
        for axis in 0..dims.value as usize {
            let begin = words.real(Expected::AxisBegin { axis })?;
            let end = words.real(Expected::AxisEnd { axis })?;
            let count = words.integer(Expected::PointCount { axis })?;
            if count.value < 2 {
                let kind = DataFileErrorKind::TooFewPoints {
                    axis,
                    count: count.value,
                };
                return Err(words.error_at(count.offset, kind));
            }
            let n = count.value as usize;
            total = total
                .checked_mul(n)
                .filter(|&t| t <= i32::MAX as usize)
                .ok_or_else(|| words.error_at(count.offset, DataFileErrorKind::TooManyValues))?;
            let extent = end - begin;
            // The oracle's build (fast-math) compares a NaN extent (from `inf - inf`) as
            // equal to zero, so such an axis also reads its points.
            let parsed = if extent == 0.0 || extent.is_nan() {
                Self::uneven_axis(&mut words, axis, n)?
            } else {
                Axis {
                    origin: begin,
                    extent,
                    count: n,
                    points: None,
                }
            };
            axes.push(parsed);
        }
        let mut values = Vec::new();
        for index in 0..total {
            values.push(words.real(Expected::Value { index })?);
        }
        let mut strides = vec![1; axes.len()];
        for d in (0..axes.len().saturating_sub(1)).rev() {
            strides[d] = strides[d + 1] * axes[d + 1].count;
        }
        Ok(DataFile {
            axes,
            strides,
            values,
        })
    }

    /// An axis given as `0 0 n` followed by its `n` points.
    fn uneven_axis(words: &mut Words, axis: usize, n: usize) -> Result<Axis, DataFileError> {
        let start = words.pos;
        let mut points = Vec::new();
        for index in 0..n {
            points.push(words.real(Expected::AxisPoint { axis, index })?);
        }
        // Radiance compares each step with `<`: a repeated point counts as "not increasing",
        // so it passes in a decreasing axis and is a reversal in an increasing one.
        let reverses = points.windows(3).any(|w| (w[0] < w[1]) != (w[1] < w[2]));
        if reverses {
            return Err(words.error_at(start, DataFileErrorKind::NotMonotonic { axis }));
        }
        let first = points[0];
        let last = points[n - 1];
        Ok(Axis {
            origin: first,
            extent: last - first,
            count: n,
            points: Some(points),
        })
    }

    pub fn dimensions(&self) -> usize {
        self.axes.len()
    }

    pub fn axes(&self) -> &[Axis] {
        &self.axes
    }

    /// The values, last axis varying fastest.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// Interpolates at `coords` (one per axis, slowest-varying axis first) as Radiance's
    /// `datavalue` does. Missing coordinates give NaN; extra ones are ignored.
    pub fn eval(&self, coords: &[f64]) -> f64 {
        if coords.len() < self.axes.len() {
            return f64::NAN;
        }
        self.interpolate(0, 0, coords, 1.0)
    }

    fn interpolate(&self, dim: usize, offset: usize, coords: &[f64], weight: f64) -> f64 {
        if (-FTINY..=FTINY).contains(&weight) {
            return 0.0;
        }
        let (Some(axis), Some(&stride), Some(&coord)) =
            (self.axes.get(dim), self.strides.get(dim), coords.get(dim))
        else {
            return f64::NAN;
        };
        let (cell, x) = axis.locate(coord);
        let (w0, w1) = cell_weights(cell, x);
        let (w0, w1) = (w0 * weight, w1 * weight);
        let lower = offset + cell * stride;
        if dim + 1 < self.axes.len() {
            let y0 = self.interpolate(dim + 1, lower, coords, w0);
            let y1 = self.interpolate(dim + 1, lower + stride, coords, w1);
            y0 + y1
        } else {
            let value = |i: usize| self.values.get(i).map_or(f64::NAN, |&v| f64::from(v));
            value(lower) * w0 + value(lower + 1) * w1
        }
    }
}

impl Axis {
    /// The cell `i` (0 ..= count-2) whose two points interpolate at `coord`, and `coord` in
    /// units of divisions (`i <= x <= i+1` inside the cell).
    fn locate(&self, coord: f64) -> (usize, f64) {
        let last_cell = self.count - 2;
        match &self.points {
            None => {
                let x = (coord - f64::from(self.origin)) / f64::from(self.extent)
                    * (self.count - 1) as f64;
                let i = c_truncate(x);
                let cell = if i < 0 {
                    0
                } else {
                    (i as usize).min(last_cell)
                };
                (cell, x)
            }
            Some(points) => {
                let cell = uneven_search(points, self.extent, coord).min(last_cell);
                let at = |i: usize| points.get(i).copied().unwrap_or(f32::NAN);
                // The spacing is a single-precision difference, as in Radiance.
                let spacing = at(cell + 1) - at(cell);
                let x = cell as f64 + (coord - f64::from(at(cell))) / f64::from(spacing);
                (cell, x)
            }
        }
    }
}

/// Radiance's bisection over unevenly spaced points. For a decreasing axis it starts with
/// the bounds swapped, which makes it settle on the last point not above `coord`, scanning
/// from the high end; the result is reproduced, not corrected.
fn uneven_search(points: &[f32], extent: f32, coord: f64) -> usize {
    let n = points.len();
    let (mut lower, mut upper) = if extent > 0.0 { (0, n) } else { (n, 0) };
    loop {
        let i = (lower + upper) >> 1;
        let point = points.get(i).copied().unwrap_or(f32::NAN);
        if coord >= f64::from(point) {
            lower = i;
        } else {
            upper = i;
        }
        if i == (lower + upper) >> 1 {
            return i;
        }
    }
}

/// The two weights of cell `i` at position `x`: linear inside and for one division beyond,
/// then tapering harmonically to zero (Radiance's `data_interp`, as fixed in Feb 2025).
fn cell_weights(cell: usize, x: f64) -> (f64, f64) {
    let i = cell as f64;
    if x > i + 2.0 {
        let w0 = 1.0 / (i - 1.0 - x);
        (w0, -2.0 * w0)
    } else if x < i - 1.0 {
        let w1 = 1.0 / (x - i);
        (-2.0 * w1, w1)
    } else {
        (i + 1.0 - x, x - i)
    }
}

/// C's `(int)x` as compiled for x86-64: truncation toward zero, with NaN and out-of-range
/// values giving `INT_MIN`.
fn c_truncate(x: f64) -> i64 {
    if x.is_nan() || x >= 2_147_483_648.0 || x <= -2_147_483_649.0 {
        i64::from(i32::MIN)
    } else {
        x.trunc() as i64
    }
}

/// A word and where it starts.
struct Word<'a> {
    text: &'a str,
    offset: usize,
}

/// An integer word's value, as `atoi` gives it, and where it starts.
struct Integer {
    value: i32,
    offset: usize,
}

/// The word reader of Radiance's `fgetval`: words are separated by white space, and `#`
/// starts a comment to the end of the line, also directly after a word.
struct Words<'a> {
    text: &'a str,
    pos: usize,
}

impl<'a> Words<'a> {
    fn new(text: &'a str) -> Self {
        Words { text, pos: 0 }
    }

    fn next_word(&mut self, expected: Expected) -> Result<Word<'a>, DataFileError> {
        let bytes = self.text.as_bytes();
        loop {
            while bytes.get(self.pos).is_some_and(|&b| is_c_space(b)) {
                self.pos += 1;
            }
            if bytes.get(self.pos) != Some(&b'#') {
                break;
            }
            while bytes.get(self.pos).is_some_and(|&b| b != b'\n') {
                self.pos += 1;
            }
        }
        let start = self.pos;
        if start >= bytes.len() {
            return Err(self.error_at(start, DataFileErrorKind::UnexpectedEnd { expected }));
        }
        while bytes
            .get(self.pos)
            .is_some_and(|&b| !is_c_space(b) && b != b'#')
        {
            self.pos += 1;
        }
        if self.pos - start > MAX_WORD_LEN {
            return Err(self.error_at(start, DataFileErrorKind::WordTooLong));
        }
        // Words end at ASCII bytes, so both ends are character boundaries.
        let text = self.text.get(start..self.pos).unwrap_or_default();
        Ok(Word {
            text,
            offset: start,
        })
    }

    fn integer(&mut self, expected: Expected) -> Result<Integer, DataFileError> {
        let word = self.next_word(expected)?;
        match c_atoi(word.text) {
            Some(value) => Ok(Integer {
                value,
                offset: word.offset,
            }),
            None => Err(self.bad_number(&word, expected)),
        }
    }

    fn real(&mut self, expected: Expected) -> Result<f32, DataFileError> {
        let word = self.next_word(expected)?;
        // `isflt`, then `atof` and a cast to float: round to double, then to single
        // precision.
        match real_word(word.text.as_bytes()) {
            Some(v) => Ok(v as f32),
            None => Err(self.bad_number(&word, expected)),
        }
    }

    fn bad_number(&self, word: &Word, expected: Expected) -> DataFileError {
        let kind = DataFileErrorKind::BadNumber {
            expected,
            word: word.text.to_string(),
        };
        self.error_at(word.offset, kind)
    }

    fn error_at(&self, offset: usize, kind: DataFileErrorKind) -> DataFileError {
        let before = self.text.get(..offset).unwrap_or(self.text);
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before.get(line_start..).map_or(0, |s| s.chars().count()) + 1;
        DataFileError {
            line,
            column,
            offset,
            kind,
        }
    }
}

/// Radiance's `isint` followed by `atoi`: glibc saturates to a 64-bit long and the
/// conversion to `int` keeps the low 32 bits.
fn c_atoi(word: &str) -> Option<i32> {
    is_int(word).then(|| atol(word) as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> DataFile {
        match DataFile::parse(text) {
            Ok(d) => d,
            Err(e) => panic!("{e}"),
        }
    }

    fn error(text: &str) -> DataFileError {
        match DataFile::parse(text) {
            Ok(d) => panic!("parsed {d:?}"),
            Err(e) => e,
        }
    }

    #[test]
    fn one_dimension_interpolates_and_extrapolates() {
        // Values checked against rtrace with a brightdata pattern.
        let d = parse("1\n0 4 5\n5 2 4 -8 16\n");
        let cases = [
            (-10.0, 0.800000011920929),
            (-3.0, 2.6666667461395264),
            (-1.5, 5.333333492279053),
            (-1.0, 8.0),
            (0.0, 5.0),
            (0.5, 3.5),
            (2.5, -2.0),
            (3.9, 13.600000381469727),
            (4.0, 16.0),
            (5.0, 40.0),
            (6.0, 10.0),
            (100.0, 0.40816327929496765),
            (3e9, -3.333333331578814e-10),
        ];
        for (x, want) in cases {
            assert_eq!(d.eval(&[x]) as f32, want as f32, "at {x}");
        }
    }

    #[test]
    fn uneven_axes_increasing_and_decreasing() {
        let up = parse("1 0 0 4  0 1 3 7  10 20 30 40");
        assert_eq!(up.eval(&[2.0]), 25.0);
        assert_eq!(up.eval(&[7.0]), 40.0);
        let down = parse("1 0 0 4  7 3 1 0  10 20 30 40");
        assert_eq!(down.axes()[0].extent, -7.0);
        assert!(down.eval(&[2.0]).is_finite());
    }

    #[test]
    fn decreasing_even_axis() {
        let d = parse("1\n90 0 10\n0 .05 .08 .1 .11 .12 .14 .25 1 10\n");
        assert_eq!(d.axes()[0].extent, -90.0);
        assert_eq!(d.eval(&[90.0]), 0.0);
        assert!((d.eval(&[5.0]) - 5.5).abs() < 1e-6);
    }

    #[test]
    fn two_dimensions_are_bilinear_inside() {
        let d = parse("2\n0 1 2\n0 1 2\n1 2\n3 4\n");
        assert_eq!(d.eval(&[0.5, 0.5]), 2.5);
        assert_eq!(d.eval(&[1.0, 0.0]), 3.0);
        assert!(d.eval(&[0.5]).is_nan());
    }

    #[test]
    fn tiny_weights_are_dropped() {
        // The upper row's weight 1e-7 is below FTINY, so only the lower row counts.
        let d = parse("2\n0 1 2\n0 1 2\n0 0\n1e6 1e6\n");
        assert_eq!(d.eval(&[1e-7, 0.0]), 0.0);
        assert!(d.eval(&[1e-5, 0.0]) > 0.0);
    }

    #[test]
    fn nan_and_huge_coordinates_do_not_panic() {
        let d = parse("3 0 1 2 0 1 3 0 0 2 1 5 1 2 3 4 5 6 7 8 9 10 11 12");
        for c in [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            0.0,
        ] {
            let _ = d.eval(&[c, c, c]);
        }
        assert!(d.eval(&[f64::NAN, 0.0, 1.0]).is_nan());
    }

    #[test]
    fn comments_and_word_boundaries() {
        let d = parse("# header\n1 # one axis\n0 1 2#end\n3#x\n4");
        assert_eq!(d.values(), &[3.0, 4.0]);
        assert_eq!(d.eval(&[0.5]), 3.5);
    }

    #[test]
    fn trailing_text_is_ignored() {
        let d = parse("1 0 1 2 5 6 these words are never read");
        assert_eq!(d.values(), &[5.0, 6.0]);
    }

    #[test]
    fn integers_follow_radiance_syntax() {
        assert_eq!(c_atoi("007"), Some(7));
        assert_eq!(c_atoi("2.0"), None);
        assert_eq!(c_atoi("99999999999999999999999"), Some(-1));
    }

    #[test]
    fn values_are_single_precision() {
        let d = parse("1 0 1 2 0.1 1e39");
        assert_eq!(d.values()[0], 0.1f32);
        assert_eq!(d.values()[1], f32::INFINITY);
    }

    #[test]
    fn errors_have_positions() {
        let e = error("2\n0 1 2\n0 1 2\n1 2\n3");
        assert_eq!((e.line, e.column), (5, 2));
        assert!(matches!(
            e.kind,
            DataFileErrorKind::UnexpectedEnd {
                expected: Expected::Value { index: 3 }
            }
        ));
        let e = error("1\n0 1 2\n1 x\n");
        assert_eq!((e.line, e.column), (3, 3));
        assert!(matches!(e.kind, DataFileErrorKind::BadNumber { .. }));
        let e = error("  7");
        assert_eq!(e.kind, DataFileErrorKind::BadDimensionCount(7));
        assert_eq!((e.line, e.column), (1, 3));
        let e = error("1 0 1 1 5");
        assert!(matches!(
            e.kind,
            DataFileErrorKind::TooFewPoints { axis: 0, count: 1 }
        ));
        let e = error("1 0 0 3 1 2 1 5 5 5");
        assert_eq!(e.kind, DataFileErrorKind::NotMonotonic { axis: 0 });
        let e =
            error("1 0 1 2 1 12345678901234567890123456789012345678901234567890123456789012345");
        assert_eq!(e.kind, DataFileErrorKind::WordTooLong);
        let e = error("");
        assert!(matches!(
            e.kind,
            DataFileErrorKind::UnexpectedEnd {
                expected: Expected::DimensionCount
            }
        ));
        let e = error("1.0 0 1 2 3 4");
        assert!(e.to_string().contains("integer"), "{e}");
    }

    #[test]
    fn repeated_uneven_points_pass_only_when_not_increasing() {
        // Radiance compares neighbouring steps with `<`, so a repeat reads as "not
        // increasing": accepted in a decreasing axis, a reversal in an increasing one.
        let d = parse("1 0 0 4 3 2 2 1 10 20 30 40");
        for x in [0.0, 1.5, 2.0, 2.5, 4.0] {
            let _ = d.eval(&[x]);
        }
        let e = error("1 0 0 4 1 2 2 3 10 20 30 40");
        assert_eq!(e.kind, DataFileErrorKind::NotMonotonic { axis: 0 });
    }

    #[test]
    fn infinite_bounds_read_points_like_the_oracle() {
        // 1e39 overflows single precision; inf - inf is NaN, which Radiance's build takes
        // for a zero extent (checked with rtrace: the value at 5.5 is 7.5).
        let d = parse("1\n1e39 1e39 2\n5 6\n7 8\n");
        assert_eq!(d.axes()[0].points.as_deref(), Some(&[5.0f32, 6.0][..]));
        assert_eq!(d.eval(&[5.5]), 7.5);
    }

    #[test]
    fn huge_dimensions_fail_without_allocating() {
        let e = error("6 0 1 2147483647 0 1 2147483647 0 1 2 0 1 2 0 1 2 0 1 2 1");
        assert_eq!(e.kind, DataFileErrorKind::TooManyValues);
        let e = error("2 0 1 40000 0 1 40000 1 2 3");
        assert!(matches!(e.kind, DataFileErrorKind::UnexpectedEnd { .. }));
    }

    #[test]
    fn truncated_files_never_panic() {
        let text =
            "3\n0 1 3\n0 0 3 0 .5 1\n10 -10 2\n1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18\n";
        for end in 0..text.len() {
            let _ = DataFile::parse(&text[..end]);
        }
        assert!(DataFile::parse(text).is_ok());
    }

    #[test]
    fn arbitrary_bytes_never_panic() {
        let alphabet = [
            "1", "2", "0", "-", ".", "e", "#", " ", "\n", "é", "\x0b", "9", "6",
        ];
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..3000 {
            let mut text = String::new();
            for _ in 0..(state % 40) {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                text.push_str(alphabet[(state % alphabet.len() as u64) as usize]);
            }
            if let Ok(d) = DataFile::parse(&text) {
                let _ = d.eval(&[0.5; MAX_DIMENSIONS]);
                let _ = d.eval(&[f64::NAN; MAX_DIMENSIONS]);
            }
        }
    }
}
