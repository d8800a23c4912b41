//! Scanlines (`src/common/color.c`: `fwritecolrs`, `freadcolrs`, `oldreadcolrs`).
//!
//! Three encodings exist. Flat: four bytes a pixel. Old-style run-length: a pixel
//! `(1, 1, 1, n)` repeats the one before it `n` times, consecutive markers giving the
//! count's higher bytes. New-style: `(2, 2, hi, lo)` with the length, then each of the
//! four byte planes as chunks: a count byte above 128 repeats the next byte `count - 128`
//! times, a count up to 128 is followed by that many literal bytes. Radiance writes the
//! new style for scanlines 17 to 32767 pixels long and flat ones otherwise; a reader
//! must accept all three.

use crate::color::Colr;

/// Scanline lengths Radiance run-length encodes (`MINELEN`, `MAXELEN`).
pub const MIN_ENCODED: usize = 17;
pub const MAX_ENCODED: usize = 0x7fff;
/// The shortest run `fwritecolrs` writes as a run (`MINRUN`).
const MIN_RUN: usize = 4;

/// Why a scanline could not be read, with the byte offset where it was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScanlineError {
    /// The data ends, or a chunk runs past the end of the scanline.
    Truncated(usize),
    /// A new-style scanline with another length in its first four bytes.
    Length { found: u32, at: usize },
}

/// Reads one scanline of `len` pixels starting at `*pos`, appending them to `out` and
/// moving `*pos` past it, as `freadcolrs` reads one.
pub fn read(
    data: &[u8],
    pos: &mut usize,
    len: usize,
    out: &mut Vec<Colr>,
) -> Result<(), ScanlineError> {
    if len == 0 {
        return Ok(());
    }
    let start = *pos;
    let first = take4(data, pos).ok_or(ScanlineError::Truncated(start))?;
    if first[0] != 2 || first[1] != 2 || first[2] & 0x80 != 0 {
        out.push(first);
        return read_old(data, pos, len - 1, out);
    }
    let found = u32::from(first[2]) << 8 | u32::from(first[3]);
    if found as usize != len {
        return Err(ScanlineError::Length { found, at: start });
    }
    let base = out.len();
    out.resize(base + len, [0; 4]);
    let scan = &mut out[base..];
    for plane in 0..4 {
        let mut j = 0;
        while j < len {
            let at = *pos;
            let code = usize::from(*data.get(at).ok_or(ScanlineError::Truncated(at))?);
            *pos += 1;
            if code > 128 {
                let n = code & 127;
                let v = *data.get(*pos).ok_or(ScanlineError::Truncated(*pos))?;
                *pos += 1;
                let run = scan.get_mut(j..j + n).ok_or(ScanlineError::Truncated(at))?;
                run.iter_mut().for_each(|p| p[plane] = v);
                j += n;
            } else {
                let run = scan
                    .get_mut(j..j + code)
                    .ok_or(ScanlineError::Truncated(at))?;
                let bytes = data
                    .get(*pos..*pos + code)
                    .ok_or(ScanlineError::Truncated(data.len()))?;
                run.iter_mut().zip(bytes).for_each(|(p, &b)| p[plane] = b);
                *pos += code;
                j += code;
            }
        }
    }
    Ok(())
}

/// The rest of an old-style (or flat) scanline: `len` more pixels after the first.
fn read_old(
    data: &[u8],
    pos: &mut usize,
    mut len: usize,
    out: &mut Vec<Colr>,
) -> Result<(), ScanlineError> {
    let mut shift = 0u32;
    while len > 0 {
        let at = *pos;
        let p = take4(data, pos).ok_or(ScanlineError::Truncated(at))?;
        if p[..3] == [1, 1, 1] {
            // A repeat count: its bytes come least significant first. (Radiance's int
            // shift overflows past three bytes; the count is then "the rest".)
            let count = if shift < 32 {
                u64::from(p[3]) << shift
            } else {
                u64::MAX
            };
            let n = count.min(len as u64) as usize;
            // The first pixel of a scanline is never a marker, so there is one before.
            let last = out.last().copied().unwrap_or([0; 4]);
            out.extend(std::iter::repeat_n(last, n));
            len -= n;
            shift += 8;
        } else {
            out.push(p);
            len -= 1;
            shift = 0;
        }
    }
    Ok(())
}

fn take4(data: &[u8], pos: &mut usize) -> Option<Colr> {
    let b = data.get(*pos..*pos + 4)?;
    *pos += 4;
    Some([b[0], b[1], b[2], b[3]])
}

/// Appends one scanline to `out` exactly as `fwritecolrs` writes it: flat outside
/// 17..=32767 pixels, else new-style, each plane split into runs of 4 to 127 equal
/// bytes and literal chunks of up to 128, a gap of 2 or 3 equal bytes before a run
/// written as a short run.
pub fn write(scan: &[Colr], out: &mut Vec<u8>) {
    let len = scan.len();
    if !(MIN_ENCODED..=MAX_ENCODED).contains(&len) {
        scan.iter().for_each(|p| out.extend_from_slice(p));
        return;
    }
    out.extend_from_slice(&[2, 2, (len >> 8) as u8, (len & 0xff) as u8]);
    let mut plane = vec![0u8; len];
    for c in 0..4 {
        for (b, p) in plane.iter_mut().zip(scan) {
            *b = p[c];
        }
        write_plane(&plane, out);
    }
}

fn write_plane(p: &[u8], out: &mut Vec<u8>) {
    let len = p.len();
    let run_at = |beg: usize| {
        let mut cnt = 1;
        while cnt < 127 && beg + cnt < len && p[beg + cnt] == p[beg] {
            cnt += 1;
        }
        cnt
    };
    let mut j = 0;
    while j < len {
        // The next run of at least MIN_RUN, or the end.
        let mut beg = j;
        let mut cnt = 1;
        while beg < len {
            cnt = run_at(beg);
            if cnt >= MIN_RUN {
                break;
            }
            beg += cnt;
        }
        let gap = beg - j;
        if (2..MIN_RUN).contains(&gap) && p[j + 1..beg].iter().all(|&b| b == p[j]) {
            out.push((128 + gap) as u8);
            out.push(p[j]);
            j = beg;
        }
        while j < beg {
            let n = (beg - j).min(128);
            out.push(n as u8);
            out.extend_from_slice(&p[j..j + n]);
            j += n;
        }
        if cnt >= MIN_RUN {
            out.push((128 + cnt) as u8);
            out.push(p[beg]);
            j = beg + cnt;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(scan: &[Colr]) -> Vec<u8> {
        let mut bytes = Vec::new();
        write(scan, &mut bytes);
        let (mut pos, mut back) = (0, Vec::new());
        read(&bytes, &mut pos, scan.len(), &mut back).unwrap();
        assert_eq!(pos, bytes.len());
        assert_eq!(back, scan);
        bytes
    }

    #[test]
    fn short_and_long_scanlines_are_flat() {
        let scan = vec![[9, 8, 7, 130]; 16];
        assert_eq!(round_trip(&scan).len(), 64);
        let scan = vec![[9, 8, 7, 130]; 17];
        assert_eq!(round_trip(&scan)[..4], [2, 2, 0, 17]);
    }

    #[test]
    fn runs_and_literals_as_fwritecolrs() {
        // Plane 0: a run of 5, 2 equal bytes (a short run), a run of 10, 3 literals.
        let mut v: Vec<u8> = vec![7; 5];
        v.extend([4, 4]);
        v.extend([9; 10]);
        v.extend([1, 2, 3]);
        let scan: Vec<Colr> = v.iter().map(|&b| [b, 0, 0, 0]).collect();
        let bytes = round_trip(&scan);
        assert_eq!(
            bytes[4..16],
            [128 + 5, 7, 128 + 2, 4, 128 + 10, 9, 3, 1, 2, 3, 128 + 20, 0]
        );
    }

    #[test]
    fn old_style_runs_are_read() {
        // One pixel, repeated 3 + 256 * 1 times, then a last pixel.
        let mut bytes = vec![5, 6, 7, 128, 1, 1, 1, 3, 1, 1, 1, 1];
        bytes.extend([9, 9, 9, 129]);
        let (mut pos, mut out) = (0, Vec::new());
        read(&bytes, &mut pos, 261, &mut out).unwrap();
        assert_eq!(out.len(), 261);
        assert!(out[..260].iter().all(|p| *p == [5, 6, 7, 128]));
        assert_eq!(out[260], [9, 9, 9, 129]);
    }

    #[test]
    fn damage_is_an_error() {
        let scan = vec![[1, 2, 3, 130]; 40];
        let mut bytes = Vec::new();
        write(&scan, &mut bytes);
        for cut in 0..bytes.len() {
            let (mut pos, mut out) = (0, Vec::new());
            assert!(
                read(&bytes[..cut], &mut pos, 40, &mut out).is_err(),
                "{cut}"
            );
        }
        let (mut pos, mut out) = (0, Vec::new());
        assert_eq!(
            read(&bytes, &mut pos, 41, &mut out),
            Err(ScanlineError::Length { found: 40, at: 0 })
        );
    }
}
