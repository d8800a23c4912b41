//! `genbox material name xsize ysize zsize [-i] [-b bevel | -r round [-n nsegs][-s]] [-o]`
//!
//! Reproduces Radiance's `src/gen/genbox.c`. A vertex is a 6-bit code: bits 0-2 pick
//! the far (1) or near (0) side on x, y, z; bits 3-5 pull that coordinate in by the
//! bevel. Faces are named by the letters of their vertex codes. `-i` swaps near and far,
//! which turns every face inside out. Rounding finer than one segment per quarter circle
//! (`-n` above 2, or `-r` with `-i`) and `-o` go through Radiance's mesh writer, which
//! radc does not reproduce yet.

use crate::printf::g;
use crate::words::{atof, atoi};
use crate::{GenError, command_comment};

const USAGE: &str =
    "genbox material name xsize ysize zsize [-i] [-b bevel | -r round [-n nsegs][-s]] [-o]";

/// The characters naming vertex codes 0..63 in face names.
const LETTERS: &[u8] = b"0123456789._ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz";

struct Box3 {
    material: String,
    name: String,
    size: [f64; 3],
    bevel: f64,
    reversed: bool,
}

/// The scene genbox prints for `args` (the words after `genbox`).
pub fn genbox(args: &[String]) -> Result<String, GenError> {
    let usage = || GenError::Usage(USAGE.to_string());
    if args.len() < 5 {
        return Err(usage());
    }
    let size = [atof(&args[2]), atof(&args[3]), atof(&args[4])];
    if size.iter().any(|&s| s <= 0.0 || s.is_nan()) {
        return Err(usage());
    }
    let mut b = Box3 {
        material: args[0].clone(),
        name: args[1].clone(),
        size,
        bevel: 0.0,
        reversed: false,
    };
    let (mut rounded, mut nsegs, mut obj_out) = (false, 1_i64, false);
    let mut i = 5;
    while i < args.len() {
        let opt = args[i].as_bytes();
        if opt.first() != Some(&b'-') {
            return Err(usage());
        }
        let mut value = || {
            i += 1;
            args.get(i).ok_or_else(usage)
        };
        match opt.get(1) {
            Some(b'o') => obj_out = true,
            Some(b'i') => b.reversed = true,
            Some(b's') => {}
            Some(c @ (b'r' | b'b')) => {
                rounded |= *c == b'r';
                b.bevel = atof(value()?);
                if b.bevel.is_nan() || b.bevel <= 0.0 {
                    return Err(usage());
                }
            }
            Some(b'n') => {
                nsegs = atoi(value()?);
                if nsegs <= 0 {
                    return Err(usage());
                }
            }
            _ => return Err(usage()),
        }
        i += 1;
    }
    if (obj_out || b.reversed) && nsegs == 1 {
        nsegs = 32;
    }
    let fine_rounding = rounded && nsegs - 1 > 1;
    if fine_rounding || obj_out {
        return Err(GenError::Unsupported(
            "genbox: mesh output (-o, -n above 2, or -r with -i) is not reproduced yet".into(),
        ));
    }
    let mut out = command_comment("genbox", args);
    b.write(&mut out, rounded);
    Ok(out)
}

impl Box3 {
    fn write(&self, out: &mut String, rounded: bool) {
        let bevelled = self.bevel > 0.0;
        if bevelled {
            for f in [
                [0o51, 0o55, 0o54, 0o50],
                [0o64, 0o66, 0o62, 0o60],
                [0o32, 0o33, 0o31, 0o30],
                [0o53, 0o52, 0o56, 0o57],
                [0o65, 0o61, 0o63, 0o67],
                [0o36, 0o34, 0o35, 0o37],
            ] {
                self.polygon(out, &f);
            }
        }
        if bevelled && !rounded {
            for f in [
                [0o31, 0o51, 0o50, 0o30],
                [0o60, 0o62, 0o32, 0o30],
                [0o50, 0o54, 0o64, 0o60],
                [0o34, 0o36, 0o66, 0o64],
                [0o37, 0o57, 0o56, 0o36],
                [0o52, 0o62, 0o66, 0o56],
                [0o52, 0o53, 0o33, 0o32],
                [0o57, 0o67, 0o63, 0o53],
                [0o61, 0o31, 0o33, 0o63],
                [0o65, 0o67, 0o37, 0o35],
                [0o55, 0o51, 0o61, 0o65],
                [0o34, 0o54, 0o55, 0o35],
            ] {
                self.polygon(out, &f);
            }
            for c in [
                [0o30, 0o50, 0o60],
                [0o51, 0o31, 0o61],
                [0o32, 0o62, 0o52],
                [0o64, 0o54, 0o34],
                [0o36, 0o56, 0o66],
                [0o65, 0o35, 0o55],
                [0o53, 0o63, 0o33],
                [0o37, 0o67, 0o57],
            ] {
                self.polygon(out, &c);
            }
        }
        if bevelled && rounded {
            for (a, b) in [
                (0o70, 0o71),
                (0o70, 0o74),
                (0o70, 0o72),
                (0o73, 0o71),
                (0o73, 0o72),
                (0o73, 0o77),
                (0o75, 0o71),
                (0o75, 0o74),
                (0o75, 0o77),
                (0o76, 0o72),
                (0o76, 0o74),
                (0o76, 0o77),
            ] {
                self.header(out, "cylinder", &[a, b]);
                out.push_str("0\n0\n7\n");
                self.vertex(out, a);
                self.vertex(out, b);
                out.push_str(&format!("\t{}\n", g(self.bevel, 18, 12)));
            }
            for v in 0o70..=0o77 {
                self.header(out, "sphere", &[v]);
                out.push_str("0\n0\n4\n");
                self.vertex(out, v);
                out.push_str(&format!("\t{}\n", g(self.bevel, 18, 12)));
            }
        }
        if !bevelled {
            for f in [
                [1, 5, 4, 0],
                [4, 6, 2, 0],
                [2, 3, 1, 0],
                [3, 2, 6, 7],
                [5, 1, 3, 7],
                [6, 4, 5, 7],
            ] {
                self.polygon(out, &f);
            }
        }
    }

    fn header(&self, out: &mut String, kind: &str, codes: &[usize]) {
        let letters: String = codes.iter().map(|&c| LETTERS[c & 0o77] as char).collect();
        out.push_str(&format!(
            "\n{} {kind} {}.{letters}\n",
            self.material, self.name
        ));
    }

    fn polygon(&self, out: &mut String, codes: &[usize]) {
        self.header(out, "polygon", codes);
        out.push_str(&format!("0\n0\n{}\n", 3 * codes.len()));
        for &v in codes {
            self.vertex(out, v);
        }
    }

    fn vertex(&self, out: &mut String, code: usize) {
        for (axis, &size) in self.size.iter().enumerate() {
            let far = ((code >> axis) & 1 == 1) ^ self.reversed;
            let inset = (code >> axis) & 0o10 != 0;
            let x = match (inset, far) {
                (true, true) => size - self.bevel,
                (true, false) => self.bevel,
                (false, true) => size,
                (false, false) => 0.0,
            };
            out.push('\t');
            out.push_str(&g(x, 18, 12));
        }
        out.push('\n');
    }
}
