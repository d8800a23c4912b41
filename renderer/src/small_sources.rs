//! rpict's drawing of light sources smaller than a pixel (srcdraw.c): a source whose
//! image is narrower than the pixel sampling would be hit or missed by luck, so after
//! rendering, every pixel its image overlaps is blended with the source's value by the
//! fraction of the pixel it covers (or, where the pixel's own ray already saw the
//! source, scaled by that fraction).

use crate::camera::{Camera, Projection};
use crate::integrator::{RayKind, RayState, Tracer};
use crate::lights::{Source, SourceShape};
use crate::materials::Material;
use crate::materials::light::EmitterKind;
use crate::math::{Color, FHUGE, FTINY, Vec3, intensity};

type Poly = Vec<[f64; 2]>;

/// Vertex order of the cube's silhouette seen from each octant (srcdraw.c's table).
const CUBE_ORDER: [[usize; 6]; 8] = [
    [1, 3, 2, 6, 4, 5],
    [0, 4, 5, 7, 3, 2],
    [0, 1, 3, 7, 6, 4],
    [0, 1, 5, 7, 6, 2],
    [0, 2, 6, 7, 5, 1],
    [0, 4, 6, 7, 3, 1],
    [0, 2, 3, 7, 5, 4],
    [1, 5, 4, 6, 2, 3],
];

/// Blends the sources smaller than `sample` pixels into `pixels` (`width` by `height`,
/// top row first), as rpict's `drawsources` does.
pub fn draw(
    tracer: &Tracer<'_>,
    camera: &Camera,
    width: u32,
    height: u32,
    sample: f64,
    pixels: &mut [Color],
) {
    let scene = tracer.scene();
    let (hres, vres) = (f64::from(width), f64::from(height));
    let ar2 = camera.aspect().powi(2);
    for (si, s) in scene.sources.iter().enumerate() {
        if is_illum(tracer, s) {
            continue;
        }
        let Some(poly) = source_poly(s, camera) else {
            continue;
        };
        let poly = clip_box(&poly, 0.0, 1.0, 0.0, 1.0);
        if poly.len() < 3 || min_width2(&poly, ar2) > sample * sample / (hres * hres) {
            continue;
        }
        // Pixels in the polygon's box (integer truncation as srcdraw.c does it).
        let (mut xmin, mut xmax, mut ymin, mut ymax) = (width as i64, 0i64, height as i64, 0i64);
        for v in &poly {
            if (xmin as f64) / hres > v[0] {
                xmin = (v[0] * hres + FTINY) as i64;
            }
            if (xmax as f64) / hres < v[0] {
                xmax = (v[0] * hres - FTINY) as i64;
            }
            if (ymin as f64) / vres > v[1] {
                ymin = (v[1] * vres + FTINY) as i64;
            }
            if (ymax as f64) / vres < v[1] {
                ymax = (v[1] * vres - FTINY) as i64;
            }
        }
        for y in ymin.max(0)..=ymax.min(height as i64 - 1) {
            for x in xmin.max(0)..=xmax.min(width as i64 - 1) {
                let (xf, yf) = (x as f64, y as f64);
                let part = clip_box(
                    &poly,
                    xf / hres,
                    (xf + 1.0) / hres,
                    yf / vres,
                    (yf + 1.0) / vres,
                );
                if part.is_empty() {
                    continue;
                }
                let n = part.len() as f64;
                let cx = part.iter().map(|p| p[0]).sum::<f64>() / n;
                let cy = part.iter().map(|p| p[1]).sum::<f64>() / n;
                let Some((org, dir, max)) = camera.ray(cx, cy) else {
                    continue; // not in view
                };
                if outside_aperture(s, org, dir) {
                    continue;
                }
                let mut sr = RayState::primary(org, dir);
                sr.max_distance = max;
                sr.kind = RayKind::SHADOW;
                sr.source = Some(si);
                tracer.trace(&mut sr);
                if intensity(sr.color) <= FTINY {
                    continue; // missed or blocked
                }
                let w = area(&part) * hres * vres;
                let row = (height as i64 - 1 - y) as usize;
                let Some(p) = pixels.get_mut(row * width as usize + x as usize) else {
                    continue;
                };
                if !big_difference(sr.color, *p, 0.07) {
                    *p *= w;
                } else {
                    *p = *p * (1.0 - w) + sr.color * w;
                }
            }
        }
    }
}

fn is_illum(tracer: &Tracer<'_>, s: &Source) -> bool {
    let crate::lights::SourceTarget::Object(o) = s.target else {
        return false;
    };
    let material = tracer.scene().object(o).and_then(|o| o.material);
    matches!(
        material.and_then(|m| tracer.scene().material(m)),
        Some(Material::Emitter(e)) if matches!(e.kind, EmitterKind::Illum { .. })
    )
}

/// A spotlight's cone or a mirror image's aperture that the ray is outside of.
fn outside_aperture(s: &Source, org: Vec3, dir: Vec3) -> bool {
    if let Some((center, area)) = s.beam {
        let to = center - org;
        let along = dir.dot(to);
        return std::f64::consts::PI * (to.length_squared() - along * along) > area;
    }
    match &s.spot {
        Some(spot) if !matches!(s.shape, SourceShape::Distant { .. }) => spot.excludes(dir),
        _ => false,
    }
}

/// `bigdiff`: whether any component differs by more than `md` relative.
fn big_difference(a: Color, b: Color, md: f64) -> bool {
    (0..3).any(|i| a[i] - b[i] > md * b[i] || b[i] - a[i] > md * a[i])
}

/// The outline of a source in the image (`sourcepoly`): its quadrilateral for flat and
/// distant sources, the silhouette of the box its sampling vectors span otherwise.
fn source_poly(s: &Source, camera: &Camera) -> Option<Poly> {
    let [su, sv, sw] = s.axes;
    let vp = camera.position();
    let (loc, flat, distant) = match &s.shape {
        SourceShape::Flat { center, .. } => (*center, true, false),
        SourceShape::Distant {
            direction,
            solid_angle,
        } => {
            if camera.projection() == Projection::Parallel
                || (solid_angle / std::f64::consts::PI).sqrt() >= 0.05
            {
                return None;
            }
            (*direction, false, true)
        }
        SourceShape::Sphere { center, .. } | SourceShape::Cylinder { center, .. } => {
            (*center, false, false)
        }
    };
    if flat || distant {
        if flat && (loc - vp).dot(sw) >= 0.0 {
            return None; // facing away
        }
        let mut out = Vec::with_capacity(4);
        for j in 0..4 {
            let su_sign = if j == 1 || j == 2 { 1.0 } else { -1.0 };
            let sv_sign = if j == 2 || j == 3 { 1.0 } else { -1.0 };
            let mut p = loc + su * su_sign + sv * sv_sign;
            if distant {
                // Just beyond the fore plane, as Radiance puts it.
                p = p * (1.0 + camera.fore()) + vp;
            }
            let (x, y) = camera.project(p)?;
            out.push([x, y]);
        }
        return Some(out);
    }
    let ap = loc - vp;
    let dir = usize::from(ap.dot(su) > 0.0)
        | usize::from(ap.dot(sv) > 0.0) << 1
        | usize::from(ap.dot(sw) > 0.0) << 2;
    let mut pts = Vec::with_capacity(6);
    for &c in &CUBE_ORDER[dir] {
        let sign = |bit: usize| if c & bit != 0 { 1.0 } else { -1.0 };
        let p = loc + su * sign(1) + sv * sign(2) + sw * sign(4);
        let (x, y) = camera.project(p)?;
        pts.push([x, y]);
    }
    Some(convex_hull(pts))
}

/// Drops vertices while that does not shrink the polygon (`convex_hull`).
fn convex_hull(mut v: Poly) -> Poly {
    let mut a = area(&v);
    let mut i = 0;
    while i < v.len() {
        let mut t = v.clone();
        t.remove(i);
        let ta = area(&t);
        if ta >= a {
            // Keep the simpler polygon and look at the vertex now at `i`.
            a = ta;
            v = t;
        } else {
            i += 1;
        }
    }
    v
}

fn area(v: &[[f64; 2]]) -> f64 {
    if v.len() < 3 {
        return 0.0;
    }
    let mut a = 0.0;
    let mut e0 = [v[1][0] - v[0][0], v[1][1] - v[0][1]];
    for p in &v[2..] {
        let e1 = [p[0] - v[0][0], p[1] - v[0][1]];
        a += e0[0] * e1[1] - e0[1] * e1[0];
        e0 = e1;
    }
    0.5 * a.abs()
}

/// Square of the polygon's smallest width, `y` stretched by the view's aspect (`minw2`):
/// for each edge the farthest vertex from it, and the least of those.
fn min_width2(v: &[[f64; 2]], ar2: f64) -> f64 {
    let n = v.len();
    let mut w2min = FHUGE;
    for i in 0..n {
        let (p0, p1) = (v[(i + n - 1) % n], v[i]);
        let d2 = (p1[0] - p0[0]).powi(2) + (p1[1] - p0[1]).powi(2) * ar2;
        let mut w2max: f64 = 0.0;
        for j in 1..n - 1 {
            let p2 = v[(i + j) % n];
            let w = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
            w2max = w2max.max(w * w * ar2 / d2);
        }
        w2min = w2min.min(w2max);
    }
    w2min
}

#[derive(Clone, Copy)]
enum Edge {
    Above(f64),
    Below(f64),
    Right(f64),
    Left(f64),
}

impl Edge {
    fn inside(self, p: [f64; 2]) -> bool {
        match self {
            Edge::Above(c) => p[1] < c,
            Edge::Below(c) => p[1] >= c,
            Edge::Right(c) => p[0] < c,
            Edge::Left(c) => p[0] >= c,
        }
    }

    fn cross(self, a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        match self {
            Edge::Above(c) | Edge::Below(c) => {
                [a[0] + (c - a[1]) / (b[1] - a[1]) * (b[0] - a[0]), c]
            }
            Edge::Right(c) | Edge::Left(c) => {
                [c, a[1] + (c - a[0]) / (b[0] - a[0]) * (b[1] - a[1])]
            }
        }
    }
}

/// Sutherland-Hodgman clipping to one half-plane (`hp_clip_poly`).
fn clip_edge(v: &[[f64; 2]], e: Edge) -> Poly {
    let mut out = Vec::with_capacity(v.len() + 2);
    let Some(&last) = v.last() else { return out };
    let mut s = last;
    for &p in v {
        if e.inside(p) {
            if !e.inside(s) {
                out.push(e.cross(s, p));
            }
            out.push(p);
        } else if e.inside(s) {
            out.push(e.cross(s, p));
        }
        s = p;
    }
    out
}

/// `box_clip_poly`.
fn clip_box(v: &[[f64; 2]], xl: f64, xr: f64, yb: f64, ya: f64) -> Poly {
    let v = clip_edge(v, Edge::Below(yb));
    let v = clip_edge(&v, Edge::Above(ya));
    let v = clip_edge(&v, Edge::Left(xl));
    clip_edge(&v, Edge::Right(xr))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_a_square_to_a_corner() {
        let sq = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let c = clip_box(&sq, 1.0, 3.0, 1.0, 3.0);
        assert!((area(&c) - 1.0).abs() < 1e-12);
        assert!(clip_box(&sq, 5.0, 6.0, 5.0, 6.0).is_empty());
    }

    #[test]
    fn hull_drops_the_inner_vertex() {
        let v = vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [2.0, 2.0], [0.0, 2.0]];
        let h = convex_hull(v);
        assert_eq!(h.len(), 4);
        assert!((area(&h) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn width_of_a_thin_rectangle() {
        let r = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.1], [0.0, 0.1]];
        assert!((min_width2(&r, 1.0) - 0.01).abs() < 1e-12);
    }
}
