//! One output record per ray, as rtrace writes it: the `-o` values in `%e` text with a
//! tab after each, binary floats or doubles, or RGBE pixels, formatted in place into a
//! buffer (no zeroing, no copy per number).

use super::ray_text::c_exp_into;
use super::{Output, RayEncoding, TraceSpec};
use crate::math::Vec3;
use crate::{RayState, Scene, Target, picture};

/// Output bytes: a zero-filled buffer and how much of it is used, so a record is
/// formatted in place, with neither zeroing nor a copy per number.
#[derive(Default)]
pub(super) struct OutBuf {
    buf: Vec<u8>,
    len: usize,
}

impl OutBuf {
    pub(super) fn clear(&mut self) {
        self.len = 0;
    }

    pub(super) fn bytes(&self) -> &[u8] {
        &self.buf[..self.len]
    }

    /// Room for `n` more bytes (at least), from the end of what is used.
    pub(super) fn room(&mut self, n: usize) -> &mut [u8] {
        if self.len + n > self.buf.len() {
            let size = (self.len + n).max(2 * self.buf.len()).max(4096);
            self.buf.resize(size, 0);
        }
        &mut self.buf[self.len..]
    }

    pub(super) fn push(&mut self, bytes: &[u8]) {
        let n = bytes.len();
        self.room(n)[..n].copy_from_slice(bytes);
        self.len += n;
    }

    pub(super) fn push_byte(&mut self, b: u8) {
        self.room(1)[0] = b;
        self.len += 1;
    }

    /// Each of `v` in C's `%e` and a tab.
    pub(super) fn push_numbers(&mut self, v: &[f64]) {
        let room = self.room(17 * v.len());
        let mut at = 0;
        for x in v {
            if let Ok(text) = <&mut [u8; 16]>::try_from(&mut room[at..at + 16]) {
                let n = c_exp_into(*x, text);
                text[n] = b'\t';
                at += n + 1;
            }
        }
        self.len += at;
    }
}

pub(super) fn write_ray(out: &mut OutBuf, r: &RayState, scene: &Scene, a: &TraceSpec) {
    // The usual record (`-ov`, text) without the general loop.
    if a.output == RayEncoding::Ascii && a.outputs == [Output::Value] {
        out.push_numbers(&r.color.to_array());
        out.push_byte(b'\n');
        return;
    }
    let no_hit = matches!(r.hit, Target::None);
    for o in &a.outputs {
        match o {
            Output::Value => put(out, a.output, &r.color.to_array()),
            Output::Origin => put(out, a.output, &r.org.to_array()),
            Output::Direction => put(out, a.output, &r.dir.to_array()),
            Output::Point => put(out, a.output, &r.point.to_array()),
            Output::Normal => put(
                out,
                a.output,
                &if no_hit {
                    [0.0; 3]
                } else {
                    r.perturbed_normal().to_array()
                },
            ),
            Output::SurfaceNormal => put(
                out,
                a.output,
                &if no_hit {
                    [0.0; 3]
                } else {
                    r.surface_normal().to_array()
                },
            ),
            Output::EffectiveLength => put(out, a.output, &[r.effective_length()]),
            Output::Length => put(out, a.output, &[r.length]),
            Output::Mirrored => put(out, a.output, &r.mirror_color.to_array()),
            Output::MirroredLength => put(out, a.output, &[r.mirror_length]),
            Output::Unmirrored => put(out, a.output, &(r.color - r.mirror_color).to_array()),
            Output::UnmirroredLength => put(out, a.output, &[r.other_length]),
            Output::Surface | Output::Modifier | Output::Material => {
                out.push(names(r, scene, *o).as_bytes());
                out.push(b"\t");
            }
            Output::Tilde => out.push(b"~\t"),
            Output::Weight => put(out, a.output, &[r.weight]),
            // Local (u, v) coordinates: zero for every surface but meshes in Radiance.
            Output::LocalCoordinates => put(out, a.output, &r.uv),
        }
    }
    if a.output == RayEncoding::Ascii {
        out.push_byte(b'\n');
    }
}

fn names<'s>(r: &RayState, scene: &'s Scene, o: Output) -> &'s str {
    let (name, modifier, material) = match r.hit {
        Target::None => return "*",
        Target::Object(id) => match scene.object(id.0) {
            Some(x) => match r
                .triangle
                .and_then(|t| x.triangle_materials.get(usize::from(t)))
            {
                // Radiance's stand-in face for a mesh triangle with its own material.
                Some(t) => ("M-Tri", &t.modifier_name, &t.material_name),
                None => (x.name.as_str(), &x.modifier_name, &x.material_name),
            },
            None => return "*",
        },
        Target::Distant(i) => match scene.distant.get(i as usize) {
            Some(x) => (x.name.as_str(), &x.modifier_name, &x.material_name),
            None => return "*",
        },
    };
    match o {
        Output::Surface => name,
        Output::Modifier => modifier,
        _ => material,
    }
}

fn put(out: &mut OutBuf, f: RayEncoding, v: &[f64]) {
    match f {
        RayEncoding::Ascii => out.push_numbers(v),
        RayEncoding::Float => v.iter().for_each(|x| out.push(&(*x as f32).to_ne_bytes())),
        RayEncoding::Double => v.iter().for_each(|x| out.push(&x.to_ne_bytes())),
        RayEncoding::Color => {
            if let [r, g, b] = v {
                out.push(&picture::rgbe(Vec3::new(*r, *g, *b)));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records formatted in place: numbers, names and binary values, buffer growth.
    #[test]
    fn out_buf_grows_and_keeps_records() {
        let mut out = OutBuf::default();
        let mut want = Vec::new();
        for k in 0..2000 {
            let x = k as f64 * 0.37 - 100.0;
            out.push_numbers(&[x, 0.0, 1e300]);
            out.push(b"name\t");
            out.push_byte(b'\n');
            for v in [x, 0.0, 1e300] {
                let mut b = [0u8; 16];
                let n = c_exp_into(v, &mut b);
                want.extend_from_slice(&b[..n]);
                want.push(b'\t');
            }
            want.extend_from_slice(b"name\t\n");
        }
        assert_eq!(out.bytes(), &want[..]);
        out.clear();
        assert!(out.bytes().is_empty());
    }
}
