//! A bounding volume hierarchy over the scene's surfaces: binned SAH splits, subtrees
//! built in parallel with rayon, flattened depth-first for traversal.
//!
//! Each interior node holds both children's boxes in `f32`, rounded outward (a box may
//! only grow, so a box test can only err towards visiting), in one 64-byte record: a
//! visit reads one cache line and tests both children together.

use crate::math::{Bounds, Vec3};
use crate::ray::Ray;

const BINS: usize = 16;
const LEAF_SIZE: usize = 4;
/// Below this many primitives a subtree is built on the current thread.
const PARALLEL_THRESHOLD: usize = 4096;
/// Below this depth SAH chooses splits; deeper, median splits keep the depth logarithmic
/// (and the build's recursion bounded) whatever the distribution of primitives.
const SAH_DEPTH: u32 = 32;
/// Traversal stack entries kept in a fixed array; deeper trees spill to the heap (tests
/// use a short array, so that they reach the spill).
#[cfg(not(test))]
const STACK: usize = 32;
#[cfg(test)]
const STACK: usize = 3;

#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Bvh {
    /// The root's box (rounded outward), laid out as a node's with both children the
    /// same, and the root itself.
    root_box: [[[f32; 2]; 3]; 2],
    root: Link,
    nodes: Vec<Node>,
    /// Primitive indices, leaves refer to ranges of this. A leaf slot (a position in
    /// this list) is what traversal reports.
    order: Vec<u32>,
}

/// A child: a leaf (`count > 0`, slots `first..first + count`) or an interior node
/// (`count == 0`, `nodes[first]`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
struct Link {
    first: u32,
    count: u32,
}

/// An interior node: `bounds[side][axis][child]` (side 0 the low corner, 1 the high
/// one) and the two children.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
#[repr(C, align(64))]
struct Node {
    bounds: [[[f32; 2]; 3]; 2],
    child: [Link; 2],
}

/// `x` rounded down to an `f32` (never above `x`).
fn f32_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// `x` rounded up to an `f32` (never below `x`).
fn f32_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

/// What a ray needs for slab tests, computed once per ray: origin, inverse direction,
/// and per axis which side of a box the ray meets first (`1`: the high side, for a
/// negative direction, including -0).
///
/// A zero direction component gives an infinite inverse; a box side through the origin
/// then gives `0 * inf = NaN`, which the comparisons in `entry` ignore: the slab counts
/// as unbounded, an error towards visiting, with no fix-up on the hot path.
struct Slabs {
    org: [f64; 3],
    inv: [f64; 3],
    near: [usize; 3],
}

impl Slabs {
    fn new(ray: &Ray) -> Slabs {
        let inv = (Vec3::ONE / ray.dir).to_array();
        Slabs {
            org: ray.org.to_array(),
            inv,
            near: inv.map(|v| usize::from(v.is_sign_negative())),
        }
    }

    /// The distances at which the ray enters each child's box (0 from inside), and
    /// whether it does before `limit`. Both children in lockstep, so that the compiler
    /// can keep them in the two lanes of one vector.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // The axis indexes four arrays at once.
    fn entries(&self, b: &[[[f32; 2]; 3]; 2], limit: f64) -> ([f64; 2], [bool; 2]) {
        let (mut t0, mut t1) = ([0.0f64; 2], [limit; 2]);
        for a in 0..3 {
            let n = self.near[a];
            let (near, far) = (b[n][a], b[1 - n][a]);
            for c in 0..2 {
                let tn = (f64::from(near[c]) - self.org[a]) * self.inv[a];
                let tf = (f64::from(far[c]) - self.org[a]) * self.inv[a];
                // Written so that a NaN leaves the bound as it was.
                t0[c] = if tn > t0[c] { tn } else { t0[c] };
                t1[c] = if tf < t1[c] { tf } else { t1[c] };
            }
        }
        (t0, [t0[0] <= t1[0], t0[1] <= t1[1]])
    }
}

enum Build {
    Leaf(Bounds, Vec<u32>),
    Interior(Bounds, Box<Build>, Box<Build>),
}

impl Build {
    fn bounds(&self) -> Bounds {
        match self {
            Build::Leaf(b, _) | Build::Interior(b, _, _) => *b,
        }
    }
}

#[derive(Clone, Copy)]
struct Item {
    index: u32,
    bounds: Bounds,
    centroid: Vec3,
}

impl Bvh {
    pub fn build(bounds: &[Bounds]) -> Bvh {
        let items: Vec<Item> = bounds
            .iter()
            .enumerate()
            .filter(|(_, b)| b.min.is_finite() && b.max.is_finite())
            .map(|(i, b)| Item {
                index: i as u32,
                bounds: *b,
                centroid: b.centroid(),
            })
            .collect();
        if items.is_empty() {
            return Bvh::default();
        }
        let tree = build(items, 0);
        let b = tree.bounds();
        let mut bvh = Bvh {
            root_box: [
                b.min.to_array().map(|v| [f32_down(v); 2]),
                b.max.to_array().map(|v| [f32_up(v); 2]),
            ],
            ..Bvh::default()
        };
        bvh.root = bvh.flatten(&tree);
        bvh
    }

    /// Number of leaf slots (primitives in the tree).
    pub fn len(&self) -> usize {
        self.order.len()
    }

    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// The primitive index in leaf slot `slot`.
    pub fn primitive(&self, slot: u32) -> Option<u32> {
        self.order.get(slot as usize).copied()
    }

    /// The primitive indices in slot order.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// Checks the indices a loaded BVH (`scene_file`) traverses with: every child and
    /// primitive range in bounds and non-empty, children after their parent (so
    /// traversal ends), and every primitive index below `objects`.
    pub fn validate(&self, objects: usize) -> Result<(), String> {
        let (n, order) = (self.nodes.len(), self.order.len());
        let link_ok = |at: Option<usize>, l: Link| {
            if l.count > 0 {
                (l.first as usize)
                    .checked_add(l.count as usize)
                    .is_some_and(|end| end <= order)
            } else {
                (l.first as usize) < n && at.is_none_or(|at| (l.first as usize) > at)
            }
        };
        if order > 0 && !link_ok(None, self.root) {
            return Err("BVH root is out of range".into());
        }
        for (at, node) in self.nodes.iter().enumerate() {
            if !node.child.iter().all(|l| link_ok(Some(at), *l)) {
                return Err(format!("BVH node {at} is out of range"));
            }
        }
        match self.order.iter().find(|&&i| i as usize >= objects) {
            Some(i) => Err(format!("BVH refers to surface {i} of {objects}")),
            None => Ok(()),
        }
    }

    fn flatten(&mut self, b: &Build) -> Link {
        match b {
            Build::Leaf(_, idx) => {
                let first = self.order.len() as u32;
                self.order.extend(idx);
                Link {
                    first,
                    count: idx.len() as u32,
                }
            }
            Build::Interior(_, l, r) => {
                let at = self.nodes.len();
                self.nodes.push(Node::default());
                let child = [self.flatten(l), self.flatten(r)];
                let (lb, rb) = (l.bounds(), r.bounds());
                let bounds = [
                    std::array::from_fn(|a| [f32_down(lb.min[a]), f32_down(rb.min[a])]),
                    std::array::from_fn(|a| [f32_up(lb.max[a]), f32_up(rb.max[a])]),
                ];
                self.nodes[at] = Node { bounds, child };
                Link {
                    first: at as u32,
                    count: 0,
                }
            }
        }
    }

    /// Visits every leaf slot whose box the ray enters before `limit`, nearer boxes
    /// first. `visit` tests the primitive in one slot ([`Bvh::primitive`]) and returns
    /// the new limit (which may only shrink; a negative one ends the traversal).
    ///
    /// Both children's boxes are tested at their parent, and only those the ray enters
    /// are pushed, the farther first, with their entry distance: a popped node whose
    /// entry lies beyond the (meanwhile shrunk) limit is skipped without touching it.
    pub fn traverse(&self, ray: &Ray, mut limit: f64, mut visit: impl FnMut(u32) -> f64) {
        if self.order.is_empty() {
            return;
        }
        let s = Slabs::new(ray);
        let (t_root, [hit, _]) = s.entries(&self.root_box, limit);
        if !hit {
            return;
        }
        let mut stack = [(Link::default(), 0f64); STACK];
        let mut spill: Vec<(Link, f64)> = Vec::new();
        let mut sp = 0usize;
        // The nearer child is visited next without going through the stack.
        let mut next = Some((self.root, t_root[0]));
        loop {
            let (link, entry) = match next.take() {
                Some(e) => e,
                None if sp == 0 => return,
                None => {
                    sp -= 1;
                    if sp < STACK {
                        stack[sp]
                    } else {
                        match spill.pop() {
                            Some(e) => e,
                            None => return,
                        }
                    }
                }
            };
            if entry > limit {
                continue;
            }
            if link.count > 0 {
                for slot in link.first..link.first + link.count {
                    limit = limit.min(visit(slot));
                    if limit < 0.0 {
                        return;
                    }
                }
                continue;
            }
            let Some(node) = self.nodes.get(link.first as usize) else {
                continue;
            };
            let ([tl, tr], hits) = s.entries(&node.bounds, limit);
            let [left, right] = node.child;
            let (near, far) = if tr < tl {
                ((right, tr), (left, tl))
            } else {
                ((left, tl), (right, tr))
            };
            next = match hits {
                [true, true] => {
                    if sp < STACK {
                        stack[sp] = far;
                    } else {
                        spill.push(far);
                    }
                    sp += 1;
                    Some(near)
                }
                [true, false] => Some((left, tl)),
                [false, true] => Some((right, tr)),
                [false, false] => None,
            };
        }
    }
}

fn bounds_of(items: &[Item]) -> (Bounds, Bounds) {
    items
        .iter()
        .fold((Bounds::EMPTY, Bounds::EMPTY), |(b, c), it| {
            (b.union(it.bounds), c.union(Bounds::point(it.centroid)))
        })
}

fn build(mut items: Vec<Item>, depth: u32) -> Build {
    let (bounds, cbounds) = bounds_of(&items);
    if items.len() <= LEAF_SIZE {
        return Build::Leaf(bounds, items.iter().map(|i| i.index).collect());
    }
    let extent = cbounds.max - cbounds.min;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    if extent[axis] <= 0.0 || !extent[axis].is_finite() || depth >= SAH_DEPTH {
        return split_middle(items, bounds, axis, depth);
    }
    let Some(split) = sah_split(&items, &cbounds, axis, bounds) else {
        if items.len() <= 4 * LEAF_SIZE {
            return Build::Leaf(bounds, items.iter().map(|i| i.index).collect());
        }
        return split_middle(items, bounds, axis, depth);
    };
    let (lo, span) = (cbounds.min[axis], extent[axis]);
    let bin = |c: Vec3| (((c[axis] - lo) / span * BINS as f64) as usize).min(BINS - 1);
    let right: Vec<Item> = items
        .iter()
        .filter(|i| bin(i.centroid) > split)
        .copied()
        .collect();
    items.retain(|i| bin(i.centroid) <= split);
    if items.is_empty() || right.is_empty() {
        items.extend(right);
        return split_middle(items, bounds, axis, depth);
    }
    children(items, right, bounds, depth)
}

fn children(left: Vec<Item>, right: Vec<Item>, bounds: Bounds, depth: u32) -> Build {
    let (l, r) = if left.len() + right.len() > PARALLEL_THRESHOLD {
        rayon::join(|| build(left, depth + 1), || build(right, depth + 1))
    } else {
        (build(left, depth + 1), build(right, depth + 1))
    };
    Build::Interior(bounds, Box::new(l), Box::new(r))
}

fn split_middle(mut items: Vec<Item>, bounds: Bounds, axis: usize, depth: u32) -> Build {
    items.sort_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    let right = items.split_off(items.len() / 2);
    children(items, right, bounds, depth)
}

/// The bin boundary minimizing the surface area heuristic, if splitting beats a leaf.
fn sah_split(items: &[Item], cb: &Bounds, axis: usize, bounds: Bounds) -> Option<usize> {
    let (lo, span) = (cb.min[axis], cb.max[axis] - cb.min[axis]);
    let mut bins = [(Bounds::EMPTY, 0usize); BINS];
    for it in items {
        let b = (((it.centroid[axis] - lo) / span * BINS as f64) as usize).min(BINS - 1);
        bins[b].0 = bins[b].0.union(it.bounds);
        bins[b].1 += 1;
    }
    let mut right_area = [0.0; BINS];
    let mut acc = (Bounds::EMPTY, 0usize);
    for i in (1..BINS).rev() {
        acc = (acc.0.union(bins[i].0), acc.1 + bins[i].1);
        right_area[i] = if acc.1 > 0 {
            acc.0.surface_area() * acc.1 as f64
        } else {
            0.0
        };
    }
    let mut best = (f64::INFINITY, 0);
    let mut left = (Bounds::EMPTY, 0usize);
    for (i, bin) in bins.iter().enumerate().take(BINS - 1) {
        left = (left.0.union(bin.0), left.1 + bin.1);
        if left.1 == 0 || left.1 == items.len() {
            continue;
        }
        let cost = left.0.surface_area() * left.1 as f64 + right_area[i + 1];
        if cost < best.0 {
            best = (cost, i);
        }
    }
    let leaf_cost = bounds.surface_area() * items.len() as f64;
    (best.0.is_finite() && (best.0 < leaf_cost || items.len() > LEAF_SIZE * 4)).then_some(best.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skewed_scenes_stay_shallow() {
        // Boxes at exponentially growing distances: SAH would peel them off one by one.
        let bounds: Vec<Bounds> = (0..2000)
            .map(|i| {
                let c = Vec3::new(1.01f64.powi(i), 0.0, 0.0);
                Bounds {
                    min: c - Vec3::splat(1e-3),
                    max: c + Vec3::splat(1e-3),
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds);
        let mut seen = 0;
        bvh.traverse(
            &Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X),
            f64::INFINITY,
            |_| {
                seen += 1;
                f64::INFINITY
            },
        );
        assert_eq!(seen, 2000);
    }

    #[test]
    fn finds_every_box_on_the_ray() {
        let bounds: Vec<Bounds> = (0..1000)
            .map(|i| {
                let c = Vec3::new(i as f64, (i % 7) as f64, 0.0);
                Bounds {
                    min: c - Vec3::splat(0.25),
                    max: c + Vec3::splat(0.25),
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds);
        let ray = Ray::new(Vec3::new(-5.0, 3.0, 0.0), Vec3::X);
        let mut seen = Vec::new();
        bvh.traverse(&ray, f64::INFINITY, |slot| {
            seen.extend(bvh.primitive(slot));
            f64::INFINITY
        });
        let expect: Vec<u32> = (0..1000).filter(|i| i % 7 == 3).collect();
        seen.sort();
        seen.retain(|i| expect.contains(i));
        assert_eq!(seen, expect);
    }

    /// Every box the ray meets (by an exact slab test in f64 on the boxes as given) is
    /// visited, also for rays along the axes whose origin lies in a box's side plane
    /// (the `0 * inf` case), and each slot at most once.
    #[test]
    fn visits_every_box_met_also_along_axes() {
        let mut bounds = Vec::new();
        for i in 0..12 {
            for j in 0..12 {
                let (x, y) = (i as f64 * 0.5, j as f64 * 0.5);
                bounds.push(Bounds {
                    min: Vec3::new(x, y, 0.0),
                    max: Vec3::new(x + 0.5, y + 0.5, 0.1 + 0.01 * i as f64),
                });
            }
        }
        let bvh = Bvh::build(&bounds);
        let met = |b: &Bounds, org: Vec3, dir: Vec3| {
            (0..3).all(|a| dir[a] != 0.0 || (b.min[a] <= org[a] && org[a] <= b.max[a])) && {
                let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
                for a in (0..3).filter(|&a| dir[a] != 0.0) {
                    let (p, q) = ((b.min[a] - org[a]) / dir[a], (b.max[a] - org[a]) / dir[a]);
                    t0 = t0.max(p.min(q));
                    t1 = t1.min(p.max(q));
                }
                t0 <= t1
            }
        };
        let rays = [
            (Vec3::new(-1.0, 1.0, 0.05), Vec3::X),
            (Vec3::new(-1.0, 1.5, 0.1), Vec3::X),
            (Vec3::new(7.0, 0.0, 0.0), -Vec3::X),
            (Vec3::new(1.0, -1.0, 0.0), Vec3::Y),
            (Vec3::new(2.5, 2.5, 1.0), -Vec3::Z),
            (Vec3::new(-0.0, 3.0, 0.2), Vec3::new(0.0, -0.6, -0.8)),
            (
                Vec3::new(-1.0, -1.0, 0.5),
                Vec3::new(0.7, 0.7, -0.14).normalize(),
            ),
        ];
        for (org, dir) in rays {
            let mut seen = Vec::new();
            bvh.traverse(&Ray::new(org, dir), f64::INFINITY, |slot| {
                seen.extend(bvh.primitive(slot));
                f64::INFINITY
            });
            let mut unique = seen.clone();
            unique.sort();
            unique.dedup();
            assert_eq!(unique.len(), seen.len(), "a slot visited twice");
            for (i, b) in bounds.iter().enumerate() {
                if met(b, org, dir) {
                    assert!(seen.contains(&(i as u32)), "box {i} missed by {org} {dir}");
                }
            }
        }
    }

    #[test]
    fn boxes_round_outward() {
        for x in [0.1, -0.1, 1e-30, 3.0, -7.3e12, 1e39, -1e39, 1e-46] {
            assert!(f64::from(f32_down(x)) <= x, "{x}");
            assert!(f64::from(f32_up(x)) >= x, "{x}");
        }
    }

    /// A loaded BVH with a child pointing backwards (a loop) is refused.
    #[test]
    fn validate_refuses_loops() {
        let bounds: Vec<Bounds> = (0..40)
            .map(|i| Bounds::point(Vec3::splat(i as f64)).padded())
            .collect();
        let mut bvh = Bvh::build(&bounds);
        assert!(bvh.validate(40).is_ok());
        assert!(bvh.validate(39).is_err());
        bvh.nodes[1].child[0] = Link { first: 0, count: 0 };
        assert!(bvh.validate(40).is_err());
    }
}
