//! Radiance's `rlam` (src/cal/lam.c): records from several inputs joined side by side,
//! each input's data after its separator (`-tS`; a tab by default, a newline for a bare
//! `-t`), text lines or fixed-size binary records (`-if -id -ii -iw -ib` with a count),
//! `-ia N` for N lines a record; the output stops when the first input runs out, part of
//! its last record already written, as rlam does. `-in N` stops after N records.

use std::io::{self, BufRead, Write};

/// One input: its stream, its separator, and its record size (`> 0`: that many bytes;
/// `0`: one line; `< 0`: that many lines).
pub struct LamInput<'a> {
    pub stream: Box<dyn BufRead + 'a>,
    pub separator: Vec<u8>,
    pub size: i64,
}

/// Laminates `inputs` onto `out`; `count` is `-in` (0: no limit). Returns whether the
/// inputs ended before `count` records (rlam's "premature EOD").
pub fn laminate(
    inputs: &mut [LamInput<'_>],
    out: &mut dyn Write,
    count: i64,
    unbuffered: bool,
) -> io::Result<bool> {
    let text = inputs.iter().any(|i| i.size <= 0);
    let mut left = count;
    let mut line = Vec::new();
    'records: loop {
        for (k, input) in inputs.iter_mut().enumerate() {
            if input.size > 0 {
                let mut record = vec![0u8; input.size as usize];
                if input.stream.read_exact(&mut record).is_err() {
                    break 'records;
                }
                out.write_all(&record)?;
                continue;
            }
            let lines = if input.size < 0 { -input.size } else { 1 };
            for n in 0..lines {
                line.clear();
                if input.stream.read_until(b'\n', &mut line)? == 0 {
                    break 'records;
                }
                if k > 0 || n > 0 {
                    out.write_all(&input.separator)?;
                }
                // lam.c handles the line as a C string: up to its first NUL, less the
                // last character (the newline, or whatever ends it).
                let len = line.iter().position(|&c| c == 0).unwrap_or(line.len());
                out.write_all(&line[..len.saturating_sub(1)])?;
            }
        }
        if text {
            out.write_all(b"\n")?;
        }
        if unbuffered {
            out.flush()?;
        }
        left -= 1;
        if left == 0 {
            break;
        }
    }
    out.flush()?;
    Ok(left > 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(text: &'static [u8], separator: &str, size: i64) -> LamInput<'static> {
        LamInput {
            stream: Box::new(text),
            separator: separator.as_bytes().to_vec(),
            size,
        }
    }

    #[test]
    fn lines_join_until_the_first_input_ends() {
        let mut inputs = [input(b"a\nb\nc\n", "\t", 0), input(b"1\n2\n", ",", 0)];
        let mut out = Vec::new();
        let early = laminate(&mut inputs, &mut out, 0, false).expect("written");
        // The third record starts with "c" before the second input runs out.
        assert_eq!(String::from_utf8_lossy(&out), "a,1\nb,2\nc");
        assert!(!early);
    }

    #[test]
    fn binary_records_and_multiline_inputs() {
        let mut inputs = [input(b"xyzw", "", 2), input(b"p\nq\nr\ns\n", " ", -2)];
        let mut out = Vec::new();
        let early = laminate(&mut inputs, &mut out, 3, false).expect("written");
        assert_eq!(String::from_utf8_lossy(&out), "xy p q\nzw r s\n");
        assert!(early);
    }

    proptest::proptest! {
        /// Any inputs laminated as lines, multi-line records or binary: no panic.
        #[test]
        fn any_inputs_are_laminated(
            a in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..200),
            b in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..200),
            size in -3i64..5,
        ) {
            let a: &'static [u8] = Box::leak(a.into_boxed_slice());
            let b: &'static [u8] = Box::leak(b.into_boxed_slice());
            let mut inputs = [input(a, "\t", 0), input(b, ",", size)];
            let mut out = Vec::new();
            let _ = laminate(&mut inputs, &mut out, 0, false);
        }
    }
}
