//! A bounding volume hierarchy over the scene's surfaces: binned SAH splits, subtrees
//! built in parallel with rayon, flattened depth-first for traversal.

use crate::math::{Bounds, Vec3};
use crate::ray::Ray;

const BINS: usize = 16;
const LEAF_SIZE: usize = 4;
/// Below this many primitives a subtree is built on the current thread.
const PARALLEL_THRESHOLD: usize = 4096;
/// Below this depth SAH chooses splits; deeper, median splits keep the depth logarithmic
/// (and the build's recursion bounded) whatever the distribution of primitives.
const SAH_DEPTH: u32 = 32;

#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Primitive indices, leaves refer to ranges of this.
    order: Vec<u32>,
}

#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
struct Node {
    bounds: Bounds,
    /// Leaf: `count > 0`, primitives `order[first..first + count]`. Interior: `count == 0`,
    /// left child is the next node, right child at `first`.
    first: u32,
    count: u32,
    axis: u8,
}

enum Build {
    Leaf(Bounds, Vec<u32>),
    Interior(Bounds, u8, Box<Build>, Box<Build>),
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
        let mut bvh = Bvh::default();
        bvh.flatten(tree);
        bvh
    }

    /// Checks the indices a loaded BVH (`scene_file`) traverses with: every child and
    /// primitive range in bounds, children after their parent (so traversal ends), and
    /// every primitive index below `objects`.
    pub fn validate(&self, objects: usize) -> Result<(), String> {
        let (n, order) = (self.nodes.len(), self.order.len());
        for (at, node) in self.nodes.iter().enumerate() {
            let ok = if node.count > 0 {
                (node.first as usize)
                    .checked_add(node.count as usize)
                    .is_some_and(|end| end <= order)
            } else {
                at + 1 < n && (node.first as usize) > at && (node.first as usize) < n
            };
            if !ok || node.axis > 2 {
                return Err(format!("BVH node {at} is out of range"));
            }
        }
        match self.order.iter().find(|&&i| i as usize >= objects) {
            Some(i) => Err(format!("BVH refers to surface {i} of {objects}")),
            None => Ok(()),
        }
    }

    fn flatten(&mut self, b: Build) -> usize {
        let at = self.nodes.len();
        match b {
            Build::Leaf(bounds, idx) => {
                self.nodes.push(Node {
                    bounds,
                    first: self.order.len() as u32,
                    count: idx.len() as u32,
                    axis: 0,
                });
                self.order.extend(idx);
            }
            Build::Interior(bounds, axis, l, r) => {
                self.nodes.push(Node {
                    bounds,
                    first: 0,
                    count: 0,
                    axis,
                });
                self.flatten(*l);
                let right = self.flatten(*r);
                self.nodes[at].first = right as u32;
            }
        }
        at
    }

    /// Visits every primitive whose box the ray enters before `limit`, nearer boxes
    /// first. `visit` tests one primitive and returns the new limit (which may only
    /// shrink).
    ///
    /// Both children's boxes are tested at their parent, and only those the ray enters
    /// are pushed, the farther first, with their entry distance: a popped node whose
    /// entry lies beyond the (meanwhile shrunk) limit is skipped without touching it.
    /// This visits the same primitives as testing each box when it is popped.
    pub fn traverse(&self, ray: &Ray, mut limit: f64, mut visit: impl FnMut(u32) -> f64) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let inv = Vec3::ONE / ray.dir;
        let Some(t_root) = root.bounds.entry(ray.org, inv, limit) else {
            return;
        };
        let mut stack = [(0u32, 0f64); 128];
        stack[0] = (0, t_root);
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let (at, entry) = stack[sp];
            if entry > limit {
                continue;
            }
            let node = &self.nodes[at as usize];
            if node.count > 0 {
                let range = node.first as usize..(node.first + node.count) as usize;
                for &i in &self.order[range] {
                    limit = limit.min(visit(i));
                }
                continue;
            }
            let (left, right) = (at + 1, node.first);
            let tl = self.nodes[left as usize].bounds.entry(ray.org, inv, limit);
            let tr = self.nodes[right as usize].bounds.entry(ray.org, inv, limit);
            if sp + 2 > stack.len() {
                // Deeper than any balanced build of this size reaches; visit in order.
                for i in 0..self.order.len() {
                    limit = limit.min(visit(self.order[i]));
                }
                return;
            }
            match (tl, tr) {
                (Some(l), Some(r)) => {
                    let (near, far) = if r < l {
                        ((right, r), (left, l))
                    } else {
                        ((left, l), (right, r))
                    };
                    stack[sp] = far;
                    stack[sp + 1] = near;
                    sp += 2;
                }
                (Some(l), None) => {
                    stack[sp] = (left, l);
                    sp += 1;
                }
                (None, Some(r)) => {
                    stack[sp] = (right, r);
                    sp += 1;
                }
                (None, None) => {}
            }
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
    children(items, right, bounds, axis, depth)
}

fn children(left: Vec<Item>, right: Vec<Item>, bounds: Bounds, axis: usize, depth: u32) -> Build {
    let (l, r) = if left.len() + right.len() > PARALLEL_THRESHOLD {
        rayon::join(|| build(left, depth + 1), || build(right, depth + 1))
    } else {
        (build(left, depth + 1), build(right, depth + 1))
    };
    Build::Interior(bounds, axis as u8, Box::new(l), Box::new(r))
}

fn split_middle(mut items: Vec<Item>, bounds: Bounds, axis: usize, depth: u32) -> Build {
    items.sort_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    let right = items.split_off(items.len() / 2);
    children(items, right, bounds, axis, depth)
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
        bvh.traverse(&ray, f64::INFINITY, |i| {
            seen.push(i);
            f64::INFINITY
        });
        let expect: Vec<u32> = (0..1000).filter(|i| i % 7 == 3).collect();
        seen.sort();
        seen.retain(|i| expect.contains(i));
        assert_eq!(seen, expect);
    }
}
