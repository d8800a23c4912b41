//! A bounding volume hierarchy over the scene's surfaces: binned SAH splits, subtrees
//! built in parallel with rayon, then collapsed into an 8-wide tree, flattened
//! depth-first for traversal.
//!
//! Each node holds its (up to) eight children's boxes in `f32`, rounded outward (a box
//! may only grow), laid out per axis and side as eight lanes: a visit tests all eight
//! children at once in `f32` vector arithmetic whose rounding is bounded and allowed
//! for, so that a box test can only err towards visiting. Eight lanes are one AVX
//! register (two SSE ones): against four they halve the nodes a ray visits (the
//! room of `bench/trace_rays.py`: 7.0 to 3.9 a traversal, BENCHMARKS.md).
//!
//! A node is 256 bytes: its eight children's boxes in `f32`, rounded outward, laid out
//! per axis and side as eight lanes, and their links (unused lanes hold an empty box and
//! `Link::NONE`). Traversal tests all eight children at once (module `lanes`: one AVX
//! register where the processor has AVX2, found once per process by `simd::avx2()`, else
//! two SSE2 ones; both bit-identical to the scalar reference `Slabs::entries`, the walk
//! compiled once per instruction set through `#[target_feature]`; `RADC_NO_AVX2=1` forces
//! the portable one) in `f32`, with the origin rounded towards smaller entry and larger
//! exit distances and an exit slack that covers the rounding, so a box test may only err
//! towards visiting (a test pins this 1e5 units from the origin, where an `f32` origin is
//! off by millimetres); no NaN fix-ups (a NaN leaves a slab unbounded). The walk goes on
//! with the nearest child entered and stacks the others; large trees prefetch every child
//! entered. Scenes of up to 65,536 primitives get single-primitive leaves and an SAH over
//! all axes (`LeafRule`); larger ones leaves of up to four. The tree reports leaf *slots*;
//! `Bvh::primitive(slot)` is the object. `Bvh::validate` checks a loaded tree's indices.

use crate::math::{Bounds, Vec3, prefetch};
use crate::ray::Ray;

const BINS: usize = 16;

/// Which vector instructions traversal may use, decided once per process.
#[cfg(target_arch = "x86_64")]
mod simd {
    use std::sync::atomic::{AtomicU8, Ordering};

    /// 0: not yet known, 1: no AVX2, 2: AVX2.
    static AVX2: AtomicU8 = AtomicU8::new(0);

    /// Whether the processor has AVX2 (and the bit instructions `walk_avx2` uses),
    /// unless `RADC_NO_AVX2` is set: the portable code then runs, for tests and for
    /// comparing the two.
    #[inline(always)]
    pub fn avx2() -> bool {
        match AVX2.load(Ordering::Relaxed) {
            0 => detect(),
            v => v == 2,
        }
    }

    #[cold]
    fn detect() -> bool {
        let yes = std::env::var_os("RADC_NO_AVX2").is_none()
            && is_x86_feature_detected!("avx2")
            && is_x86_feature_detected!("bmi1")
            && is_x86_feature_detected!("bmi2")
            && is_x86_feature_detected!("lzcnt")
            && is_x86_feature_detected!("popcnt");
        AVX2.store(if yes { 2 } else { 1 }, Ordering::Relaxed);
        yes
    }
}

/// How leaves are made. A small scene's tree stays in cache whatever its size, and
/// leaves of one primitive save tests; a large scene's extra nodes cost more memory
/// traffic than the tests they save (measured on `bench/trace_rays.py`'s scenes, see
/// BENCHMARKS.md: the 318-surface room and 20,000 spheres gain 7% and 10% fewer
/// instructions, the 320,000-triangle terrain is slower with them).
#[derive(Clone, Copy)]
struct LeafRule {
    /// At most this many primitives always make a leaf.
    size: usize,
    /// SAH: the cost of a split's node, in primitive tests per unit of its area.
    node_cost: f64,
    /// A leaf SAH prefers to splitting holds at most this many.
    max: usize,
    /// SAH looks at every axis, not only the one the centroids spread most along.
    all_axes: bool,
}

impl LeafRule {
    /// Up to this many primitives a scene is small.
    const SMALL: usize = 1 << 16;

    fn for_scene(primitives: usize) -> LeafRule {
        if primitives <= LeafRule::SMALL {
            LeafRule {
                size: 1,
                node_cost: 0.5,
                max: 8,
                all_axes: true,
            }
        } else {
            LeafRule {
                size: 4,
                node_cost: 0.0,
                max: 16,
                all_axes: false,
            }
        }
    }
}
/// Children per node.
const WIDTH: usize = 8;
/// A lane's index from any bit position: `WIDTH` is a power of two.
const LANE: u32 = WIDTH as u32 - 1;
const _: () = assert!(WIDTH.is_power_of_two() && WIDTH <= 32);
/// Below this many primitives a subtree is built on the current thread.
const PARALLEL_THRESHOLD: usize = 4096;
/// Below this depth SAH chooses splits; deeper, median splits keep the depth logarithmic
/// (and the build's recursion bounded) whatever the distribution of primitives.
const SAH_DEPTH: u32 = 32;
/// Traversal stack entries kept in a fixed array; deeper trees spill to the heap (tests
/// use a short array, so that they reach the spill).
#[cfg(not(test))]
const STACK: usize = 64;
#[cfg(test)]
const STACK: usize = 3;
/// Trees of more nodes than this (512 KiB of them, half a core's L2 cache here) have their
/// nodes prefetched.
const PREFETCH_NODES: usize = 4096;
/// The slab distances are products of two `f32` roundings of exact values and one of
/// an `f32` inverse, each within a relative 2^-24: an exit distance scaled by this
/// (itself rounded) stays above the exact exit whenever the exact entry lies before it.
const EXIT_SLACK: f32 = 1.0 + 1.0 / (1 << 21) as f32;
/// Absolute slack for distances that underflow (a box within 1e-30 of the origin).
const EXIT_TINY: f32 = 1e-30;

#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Bvh {
    /// A node whose only child is the whole tree (its box the tree's): traversal
    /// starts here like anywhere else.
    root: Node,
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

/// An interior node: `planes[axis][side][child]` (side 0 the low corner, 1 the high
/// one) and the children: 256 bytes, four cache lines. Unused lanes hold an empty box
/// and [`Link::NONE`].
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
#[repr(C, align(64))]
struct Node {
    planes: [[[f32; WIDTH]; 2]; 3],
    child: [Link; WIDTH],
}

impl Link {
    /// An unused lane: an interior node no tree has, which traversal skips.
    const NONE: Link = Link {
        first: u32::MAX,
        count: 0,
    };
}

impl Default for Node {
    fn default() -> Node {
        Node {
            planes: [[[f32::INFINITY; WIDTH], [f32::NEG_INFINITY; WIDTH]]; 3],
            child: [Link::NONE; WIDTH],
        }
    }
}

impl Node {
    fn set(&mut self, lane: usize, b: Bounds, link: Link) {
        for a in 0..3 {
            self.planes[a][0][lane] = f32_down(b.min[a]);
            self.planes[a][1][lane] = f32_up(b.max[a]);
        }
        self.child[lane] = link;
    }
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

/// `f` moved by at least one `f32` step (and at least one step of the smallest
/// normal magnitude) up (`sign` 1) or down (-1): `|f| 2^-23` is at least one step of
/// `f`, so the rounded sum lies at or beyond the neighbour. Infinities and NaN stay.
#[inline(always)]
fn widen(f: f32, sign: f32) -> f32 {
    f + sign * (f.abs() * (1.0 / (1u32 << 23) as f32) + f32::MIN_POSITIVE)
}

/// What a ray needs for slab tests, computed once per ray: per axis which side of a
/// box the ray meets first (`1`: the high side, for a negative direction, including
/// -0), the inverse direction, and the origin rounded to `f32` in the direction that
/// makes entry distances smaller (`org_near`) and exit distances larger (`org_far`):
/// with outward boxes and [`EXIT_SLACK`], the `f32` test visits every box the exact
/// ray meets, also far from the origin where an `f32` origin is off by millimetres.
///
/// A zero direction component gives an infinite inverse; a box side through the origin
/// then gives `0 * inf = NaN`, which the comparisons in `entries` ignore: the slab
/// counts as unbounded, an error towards visiting, with no fix-up on the hot path.
#[derive(Clone, Copy)]
struct Slabs {
    org_near: [f32; 3],
    org_far: [f32; 3],
    inv: [f32; 3],
    near: [usize; 3],
}

/// A ray's values for [`Bvh::any_prepared`], computed apart from the walk: a caller
/// with several rays to walk prepares them together, and their divisions overlap
/// instead of each walk waiting for its own.
#[derive(Clone, Copy)]
pub struct Prepared(Slabs);

impl Prepared {
    #[inline(always)]
    pub fn of(ray: &Ray) -> Prepared {
        Prepared(Slabs::new(ray))
    }

    /// `prepared` when the caller has it, else `ray`'s own.
    #[inline(always)]
    pub fn given_or_of(prepared: Option<&Prepared>, ray: &Ray) -> Prepared {
        match prepared {
            Some(p) => *p,
            None => Prepared::of(ray),
        }
    }
}

impl Slabs {
    #[inline(always)]
    fn new(ray: &Ray) -> Slabs {
        let inv = (Vec3::ONE / ray.dir).to_array();
        let near = inv.map(|v| usize::from(v.is_sign_negative()));
        let org = ray.org.to_array();
        // Entry distances shrink with an origin moved along the direction, exits grow
        // with one moved against it: here by at least one `f32` step whether or not
        // the conversion was exact (no branches; a step more errs towards visiting).
        let up = org.map(|v| widen(v as f32, 1.0));
        let down = org.map(|v| widen(v as f32, -1.0));
        Slabs {
            org_near: std::array::from_fn(|a| if near[a] == 0 { up[a] } else { down[a] }),
            org_far: std::array::from_fn(|a| if near[a] == 0 { down[a] } else { up[a] }),
            inv: inv.map(|v| v as f32),
            near,
        }
    }

    /// Node `n`'s planes along axis `a` that the ray meets first (entries) and last
    /// (exits), for all lanes.
    #[inline(always)]
    fn planes<'n>(&self, n: &'n Node, a: usize) -> (&'n [f32; WIDTH], &'n [f32; WIDTH]) {
        let side = self.near[a] & 1;
        (&n.planes[a][side], &n.planes[a][side ^ 1])
    }

    /// The distances at which the ray enters each child's box (0 from inside), and a
    /// bit per child whose box it enters before `limit`: the reference for the vector
    /// versions in [`lanes`], which compute the same operations lane by lane.
    #[allow(clippy::needless_range_loop)] // The axis indexes four arrays at once.
    #[cfg(any(test, not(target_arch = "x86_64")))]
    fn entries(&self, n: &Node, limit: f32) -> ([f32; WIDTH], u32) {
        let (mut t0, mut t1) = ([0.0f32; WIDTH], [limit; WIDTH]);
        for a in 0..3 {
            let (near, far) = self.planes(n, a);
            for c in 0..WIDTH {
                let tn = (near[c] - self.org_near[a]) * self.inv[a];
                let tf = (far[c] - self.org_far[a]) * self.inv[a];
                // Written so that a NaN leaves the bound as it was.
                t0[c] = if tn > t0[c] { tn } else { t0[c] };
                t1[c] = if tf < t1[c] { tf } else { t1[c] };
            }
        }
        let mut hits = 0;
        for c in 0..WIDTH {
            hits |= u32::from(t0[c] <= t1[c] * EXIT_SLACK + EXIT_TINY) << c;
        }
        (t0, hits)
    }
}

/// [`Slabs::entries`] in vector registers: the compiler leaves an eight-lane loop
/// partly scalar, so the lanes are spelled out. `max(tn, t0)` and `min(tf, t1)` are
/// x86's `maxps`/`minps`, which return their second operand when either is NaN: the
/// reference's "a NaN leaves the bound as it was".
mod lanes {
    #[cfg(target_arch = "x86_64")]
    use super::{EXIT_SLACK, EXIT_TINY};
    use super::{Node, Slabs, WIDTH};

    /// How a walk tests a node's children.
    pub(super) trait Lanes {
        fn entries(s: &Slabs, n: &Node, limit: f32) -> ([f32; WIDTH], u32);
    }

    /// Code for any processor of the target (on x86_64, SSE2: two halves of four).
    pub(super) struct Portable;

    #[cfg(not(target_arch = "x86_64"))]
    impl Lanes for Portable {
        #[inline(always)]
        fn entries(s: &Slabs, n: &Node, limit: f32) -> ([f32; WIDTH], u32) {
            s.entries(n, limit)
        }
    }

    #[cfg(target_arch = "x86_64")]
    impl Lanes for Portable {
        #[inline(always)]
        fn entries(s: &Slabs, n: &Node, limit: f32) -> ([f32; WIDTH], u32) {
            // SAFETY: SSE2 is part of every x86_64 target.
            unsafe { entries_sse2(s, n, limit) }
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "sse2")]
    #[inline]
    fn entries_sse2(s: &Slabs, n: &Node, limit: f32) -> ([f32; WIDTH], u32) {
        use std::arch::x86_64::*;
        let mut t0 = [_mm_setzero_ps(); 2];
        let mut t1 = [_mm_set1_ps(limit); 2];
        for a in 0..3 {
            let (near, far) = s.planes(n, a);
            let (on, of, inv) = (
                _mm_set1_ps(s.org_near[a]),
                _mm_set1_ps(s.org_far[a]),
                _mm_set1_ps(s.inv[a]),
            );
            for h in 0..2 {
                // SAFETY: `near` and `far` hold eight `f32`; each half reads four.
                let (pn, pf) = unsafe {
                    (
                        _mm_loadu_ps(near.as_ptr().add(4 * h)),
                        _mm_loadu_ps(far.as_ptr().add(4 * h)),
                    )
                };
                let tn = _mm_mul_ps(_mm_sub_ps(pn, on), inv);
                let tf = _mm_mul_ps(_mm_sub_ps(pf, of), inv);
                t0[h] = _mm_max_ps(tn, t0[h]);
                t1[h] = _mm_min_ps(tf, t1[h]);
            }
        }
        let (slack, tiny) = (_mm_set1_ps(EXIT_SLACK), _mm_set1_ps(EXIT_TINY));
        let mut out = [0.0f32; WIDTH];
        let mut hits = 0;
        for h in 0..2 {
            let exit = _mm_add_ps(_mm_mul_ps(t1[h], slack), tiny);
            hits |= (_mm_movemask_ps(_mm_cmple_ps(t0[h], exit)) as u32) << (4 * h);
            // SAFETY: `out` holds eight `f32`; each half writes four.
            unsafe { _mm_storeu_ps(out.as_mut_ptr().add(4 * h), t0[h]) };
        }
        (out, hits)
    }

    /// Code for processors with AVX2: only [`super::Bvh::walk_avx2`] uses it.
    #[cfg(target_arch = "x86_64")]
    pub(super) struct Avx2;

    #[cfg(target_arch = "x86_64")]
    impl Lanes for Avx2 {
        #[inline(always)]
        fn entries(s: &Slabs, n: &Node, limit: f32) -> ([f32; WIDTH], u32) {
            // SAFETY: `Avx2` walks run only where `simd::avx2()` found the features.
            unsafe { entries_avx(s, n, limit) }
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline]
    fn entries_avx(s: &Slabs, n: &Node, limit: f32) -> ([f32; WIDTH], u32) {
        use std::arch::x86_64::*;
        let (mut t0, mut t1) = (_mm256_setzero_ps(), _mm256_set1_ps(limit));
        for a in 0..3 {
            let (near, far) = s.planes(n, a);
            // SAFETY: `near` and `far` hold eight `f32`.
            let (pn, pf) = unsafe {
                (
                    _mm256_loadu_ps(near.as_ptr()),
                    _mm256_loadu_ps(far.as_ptr()),
                )
            };
            let tn = _mm256_mul_ps(
                _mm256_sub_ps(pn, _mm256_set1_ps(s.org_near[a])),
                _mm256_set1_ps(s.inv[a]),
            );
            let tf = _mm256_mul_ps(
                _mm256_sub_ps(pf, _mm256_set1_ps(s.org_far[a])),
                _mm256_set1_ps(s.inv[a]),
            );
            t0 = _mm256_max_ps(tn, t0);
            t1 = _mm256_min_ps(tf, t1);
        }
        let exit = _mm256_add_ps(
            _mm256_mul_ps(t1, _mm256_set1_ps(EXIT_SLACK)),
            _mm256_set1_ps(EXIT_TINY),
        );
        let hits = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(t0, exit)) as u32;
        let mut out = [0.0f32; WIDTH];
        // SAFETY: `out` holds eight `f32`.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), t0) };
        (out, hits)
    }
}

/// The binary tree the build makes before it is collapsed to eight-wide nodes: a
/// leaf is a range of the build's item array (in its final order).
enum Build {
    Leaf(Bounds, std::ops::Range<usize>),
    Interior(Bounds, Box<Build>, Box<Build>),
}

impl Build {
    fn bounds(&self) -> Bounds {
        match self {
            Build::Leaf(b, _) | Build::Interior(b, _, _) => *b,
        }
    }
}

/// A primitive as the build sorts it (56 bytes: a mesh of millions of triangles is
/// built in one array of these, partitioned in place).
#[derive(Clone, Copy)]
struct Item {
    index: u32,
    bounds: Bounds,
}

impl Item {
    #[inline(always)]
    fn centroid(&self) -> Vec3 {
        self.bounds.centroid()
    }
}

impl Bvh {
    pub fn build(bounds: &[Bounds]) -> Bvh {
        Bvh::build_with(bounds.len(), |i| bounds[i])
    }

    /// [`Bvh::build`] over `n` primitives whose boxes `bounds` gives: no list of boxes
    /// is held beside the build's own items.
    pub fn build_with(n: usize, bounds: impl Fn(usize) -> Bounds) -> Bvh {
        let mut items: Vec<Item> = (0..n)
            .map(|i| (i, bounds(i)))
            .filter(|(_, b)| b.min.is_finite() && b.max.is_finite())
            .map(|(i, b)| Item {
                index: i as u32,
                bounds: b,
            })
            .collect();
        if items.is_empty() {
            return Bvh::default();
        }
        let rule = LeafRule::for_scene(items.len());
        let tree = build(&mut items, 0, 0, rule);
        let mut bvh = Bvh {
            order: Vec::with_capacity(items.len()),
            ..Bvh::default()
        };
        let link = bvh.flatten(&tree, &items);
        bvh.root.set(0, tree.bounds(), link);
        bvh
    }

    /// The box around everything in the tree (its corners rounded out to `f32`), or
    /// `None` for an empty tree.
    pub fn extent(&self) -> Option<Bounds> {
        if self.order.is_empty() {
            return None;
        }
        let p = &self.root.planes;
        let corner = |side: usize| {
            Vec3::new(
                f64::from(p[0][side][0]),
                f64::from(p[1][side][0]),
                f64::from(p[2][side][0]),
            )
        };
        Some(Bounds {
            min: corner(0),
            max: corner(1),
        })
    }

    /// Bytes a traversal reads from: the nodes and the slot order.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.nodes.as_slice()) + std::mem::size_of_val(self.order.as_slice())
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

    /// Checks the indices a loaded BVH (`scene_file`) traverses with: every used child
    /// and primitive range in bounds and non-empty, children after their parent (so
    /// traversal ends), and every primitive index below `objects`.
    pub fn validate(&self, objects: usize) -> Result<(), String> {
        let (n, order) = (self.nodes.len(), self.order.len());
        let node_ok = |at: Option<usize>, node: &Node| {
            node.child.iter().all(|&l| {
                if l == Link::NONE {
                    true
                } else if l.count > 0 {
                    (l.first as usize)
                        .checked_add(l.count as usize)
                        .is_some_and(|end| end <= order)
                } else {
                    (l.first as usize) < n && at.is_none_or(|at| (l.first as usize) > at)
                }
            })
        };
        if !node_ok(None, &self.root) || (order > 0 && self.root.child[0] == Link::NONE) {
            return Err("BVH root is out of range".into());
        }
        for (at, node) in self.nodes.iter().enumerate() {
            if !node_ok(Some(at), node) {
                return Err(format!("BVH node {at} is out of range"));
            }
        }
        match self.order.iter().find(|&&i| i as usize >= objects) {
            Some(i) => Err(format!("BVH refers to surface {i} of {objects}")),
            None => Ok(()),
        }
    }

    /// Flattens `b` depth-first, each binary node's subtree opened (the largest boxes
    /// first) into one node of up to `WIDTH` children.
    fn flatten(&mut self, b: &Build, items: &[Item]) -> Link {
        let (l, r) = match b {
            Build::Leaf(_, range) => {
                let first = self.order.len() as u32;
                self.order
                    .extend(items[range.clone()].iter().map(|i| i.index));
                return Link {
                    first,
                    count: range.len() as u32,
                };
            }
            Build::Interior(_, l, r) => (l, r),
        };
        let mut kids: Vec<&Build> = vec![l, r];
        while kids.len() < WIDTH {
            let widest = kids
                .iter()
                .enumerate()
                .filter(|(_, k)| matches!(k, Build::Interior(..)))
                .max_by(|(_, a), (_, b)| {
                    a.bounds()
                        .surface_area()
                        .total_cmp(&b.bounds().surface_area())
                })
                .map(|(i, _)| i);
            let Some(i) = widest else { break };
            if let Build::Interior(_, l, r) = kids[i] {
                kids[i] = l;
                kids.insert(i + 1, r);
            }
        }
        let at = self.nodes.len();
        self.nodes.push(Node::default());
        let mut node = Node::default();
        for (lane, k) in kids.iter().enumerate() {
            let link = self.flatten(k, items);
            node.set(lane, k.bounds(), link);
        }
        self.nodes[at] = node;
        Link {
            first: at as u32,
            count: 0,
        }
    }

    /// Visits every leaf slot whose box the ray enters before `limit`, going on at
    /// each node with the nearest child entered. `visit` tests the primitive in one slot ([`Bvh::primitive`]) and returns
    /// the new limit (which may only shrink; a negative one ends the traversal).
    ///
    /// All children's boxes are tested at their parent, and only those the ray enters
    /// are pushed (of two the farther; of more all but the nearest, unsorted: sorting
    /// them cost more than the better order saved), with their entry distance: a
    /// popped node whose entry lies beyond the (meanwhile shrunk) limit is skipped
    /// without touching it.
    ///
    /// On a processor with AVX2 the walk (and `visit`, where inlined) runs as code
    /// compiled for it: eight lanes in one vector instead of two. Both are the same
    /// IEEE operations in the same order (no fused multiply-adds: Rust never contracts
    /// them), so they visit the same slots in the same order.
    #[inline(always)]
    pub fn traverse(&self, ray: &Ray, limit: f64, visit: impl FnMut(u32) -> f64) {
        self.traverse_prepared(&Prepared::of(ray), limit, visit)
    }

    /// [`Bvh::traverse`] for a ray prepared beforehand ([`Prepared::of`]).
    #[inline(always)]
    pub fn traverse_prepared(&self, ray: &Prepared, limit: f64, visit: impl FnMut(u32) -> f64) {
        #[cfg(target_arch = "x86_64")]
        if simd::avx2() {
            // SAFETY: the processor has the features `walk_avx2` is compiled for.
            return unsafe { self.walk_avx2(ray, limit, visit) };
        }
        self.walk::<lanes::Portable>(ray, limit, visit)
    }

    /// [`Bvh::walk`] compiled for AVX2 (and the bit instructions that come with it).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,avx2,bmi1,bmi2,lzcnt,popcnt")]
    fn walk_avx2(&self, ray: &Prepared, limit: f64, visit: impl FnMut(u32) -> f64) {
        self.walk::<lanes::Avx2>(ray, limit, visit)
    }

    /// [`Bvh::traverse`]'s walk, for whichever instruction set it is inlined into.
    #[inline(always)]
    fn walk<L: lanes::Lanes>(
        &self,
        ray: &Prepared,
        mut limit: f64,
        mut visit: impl FnMut(u32) -> f64,
    ) {
        if self.order.is_empty() {
            return;
        }
        let s = &ray.0;
        let far = self.nodes.len() > PREFETCH_NODES;
        let mut limit32 = f32_up(limit);
        // An entry computed beyond this cannot be exactly before `limit`.
        let mut cull = limit32 * EXIT_SLACK + EXIT_TINY;
        // Only entries below `sp` are read, each written first: no need to zero it.
        let mut stack = [std::mem::MaybeUninit::<(Link, f32)>::uninit(); STACK];
        let mut spill: Vec<(Link, f32)> = Vec::new();
        let mut sp = 0usize;
        // The root's children's boxes lie inside its own: a tree that starts with a
        // node starts there, without testing the box around everything.
        let top = self.root.child[0];
        let mut node = match self.nodes.get(top.first as usize) {
            Some(n) if top.count == 0 => n,
            _ => &self.root,
        };
        loop {
            let (t0, hits) = L::entries(s, node, limit32);
            // Start fetching every interior child entered at once, so that their
            // misses overlap instead of coming one after another as they are visited
            // (a tree small enough to stay in cache needs no such help).
            let mut bits = if far { hits } else { 0 };
            while bits != 0 {
                let l = node.child[(bits.trailing_zeros() & LANE) as usize];
                bits &= bits - 1;
                if l.count == 0
                    && let Some(n) = self.nodes.get(l.first as usize)
                {
                    prefetch(n);
                }
            }
            let mut push = |e: (Link, f32)| {
                if sp < STACK {
                    stack[sp] = std::mem::MaybeUninit::new(e);
                } else {
                    spill.push(e);
                }
                sp += 1;
            };
            // Lanes are 0..WIDTH, a power of two (the mask spares the bounds checks).
            let child = |c: u32| (node.child[(c & LANE) as usize], t0[(c & LANE) as usize]);
            // The children entered: the nearest next, the others onto the stack.
            let mut next = match hits.count_ones() {
                0 => None,
                1 => Some(child(hits.trailing_zeros())),
                2 => {
                    let (a, b) = (
                        child(hits.trailing_zeros()),
                        child(31 - hits.leading_zeros()),
                    );
                    let (near, far) = if b.1 < a.1 { (b, a) } else { (a, b) };
                    push(far);
                    Some(near)
                }
                _ => {
                    // The nearest of three to eight; the others pushed as they come.
                    let mut bits = hits;
                    let mut best = child(bits.trailing_zeros());
                    bits &= bits - 1;
                    while bits != 0 {
                        let e = child(bits.trailing_zeros());
                        bits &= bits - 1;
                        if e.1 < best.1 {
                            push(best);
                            best = e;
                        } else {
                            push(e);
                        }
                    }
                    Some(best)
                }
            };
            // Straight down to an interior child: no leaf (no call) on this path, so
            // the ray's lanes stay in registers.
            if let Some((link, _)) = next
                && link.count == 0
                && let Some(n) = self.nodes.get(link.first as usize)
            {
                node = n;
                continue;
            }
            node = loop {
                let (link, entry) = match next.take() {
                    Some(e) => e,
                    None if sp == 0 => return,
                    None => {
                        sp -= 1;
                        if sp < STACK {
                            // SAFETY: `stack[sp]` was written when `sp` last counted up
                            // past it (entries at or above STACK go to `spill`).
                            unsafe { stack[sp].assume_init() }
                        } else {
                            match spill.pop() {
                                Some(e) => e,
                                None => return,
                            }
                        }
                    }
                };
                if entry > cull {
                    continue;
                }
                if link.count == 0 {
                    match self.nodes.get(link.first as usize) {
                        Some(n) => break n,
                        None => continue,
                    }
                }
                let before = limit;
                for slot in link.first..link.first.saturating_add(link.count) {
                    limit = limit.min(visit(slot));
                    if limit < 0.0 {
                        return;
                    }
                }
                if limit < before {
                    limit32 = f32_up(limit);
                    cull = limit32 * EXIT_SLACK + EXIT_TINY;
                }
            };
        }
    }

    /// Whether `stop` is true for some leaf slot whose box the ray enters before
    /// `limit`: the walk for questions whose answer does not depend on the order slots
    /// are met in (is anything in the way?). Every slot [`Bvh::traverse`] would visit
    /// with a `limit` that never shrinks is offered, in some order, until `stop` says
    /// yes.
    ///
    /// Cheaper per node than `traverse`: no entry distances kept, no nearest child
    /// chosen, leaves tested where they are met, only interior nodes stacked.
    ///
    /// The slots in `skip` are never offered: a shadow ray's own source, whose box it
    /// always enters, and the surface it starts from cost no call (`u32::MAX` skips
    /// nothing).
    #[inline(always)]
    pub fn any(
        &self,
        ray: &Ray,
        limit: f64,
        skip: [u32; 2],
        stop: impl FnMut(u32) -> bool,
    ) -> bool {
        self.any_prepared(&Prepared::of(ray), limit, skip, stop)
    }

    /// [`Bvh::any`] for a ray prepared beforehand ([`Prepared::of`]).
    #[inline(always)]
    pub fn any_prepared(
        &self,
        ray: &Prepared,
        limit: f64,
        skip: [u32; 2],
        stop: impl FnMut(u32) -> bool,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        if simd::avx2() {
            // SAFETY: the processor has the features `any_avx2` is compiled for.
            return unsafe { self.any_avx2(ray, limit, skip, stop) };
        }
        self.any_walk::<lanes::Portable>(ray, limit, skip, stop)
    }

    /// [`Bvh::any_walk`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,avx2,bmi1,bmi2,lzcnt,popcnt")]
    fn any_avx2(
        &self,
        ray: &Prepared,
        limit: f64,
        skip: [u32; 2],
        stop: impl FnMut(u32) -> bool,
    ) -> bool {
        self.any_walk::<lanes::Avx2>(ray, limit, skip, stop)
    }

    /// [`Bvh::any`]'s walk, for whichever instruction set it is inlined into.
    #[inline(always)]
    fn any_walk<L: lanes::Lanes>(
        &self,
        ray: &Prepared,
        limit: f64,
        skip: [u32; 2],
        mut stop: impl FnMut(u32) -> bool,
    ) -> bool {
        if self.order.is_empty() {
            return false;
        }
        let s = &ray.0;
        let far = self.nodes.len() > PREFETCH_NODES;
        let limit32 = f32_up(limit);
        let mut stack = [std::mem::MaybeUninit::<u32>::uninit(); STACK];
        let mut spill: Vec<u32> = Vec::new();
        let mut sp = 0usize;
        let top = self.root.child[0];
        let mut node = match self.nodes.get(top.first as usize) {
            Some(n) if top.count == 0 => n,
            _ => &self.root,
        };
        loop {
            let (_, hits) = L::entries(s, node, limit32);
            let mut bits = hits;
            while bits != 0 {
                let link = node.child[(bits.trailing_zeros() & LANE) as usize];
                bits &= bits - 1;
                if link.count == 0 {
                    if far && let Some(n) = self.nodes.get(link.first as usize) {
                        prefetch(n);
                    }
                    if sp < STACK {
                        stack[sp] = std::mem::MaybeUninit::new(link.first);
                    } else {
                        spill.push(link.first);
                    }
                    sp += 1;
                } else {
                    for slot in link.first..link.first.saturating_add(link.count) {
                        if slot != skip[0] && slot != skip[1] && stop(slot) {
                            return true;
                        }
                    }
                }
            }
            node = loop {
                if sp == 0 {
                    return false;
                }
                sp -= 1;
                let first = if sp < STACK {
                    // SAFETY: `stack[sp]` was written when `sp` last counted up past it
                    // (entries at or above STACK go to `spill`).
                    unsafe { stack[sp].assume_init() }
                } else {
                    match spill.pop() {
                        Some(f) => f,
                        None => return false,
                    }
                };
                if let Some(n) = self.nodes.get(first as usize) {
                    break n;
                }
            };
        }
    }
}

fn bounds_of(items: &[Item]) -> (Bounds, Bounds) {
    items
        .iter()
        .fold((Bounds::EMPTY, Bounds::EMPTY), |(b, c), it| {
            (b.union(it.bounds), c.union(Bounds::point(it.centroid())))
        })
}

/// Builds the tree over `items` (which start at `at` in the whole array), reordering
/// them in place: each split is a stable partition, so the order, and the tree, are
/// what splitting into separate lists would give.
fn build(items: &mut [Item], at: usize, depth: u32, rule: LeafRule) -> Build {
    let (bounds, cbounds) = bounds_of(items);
    if items.len() <= rule.size {
        return Build::Leaf(bounds, at..at + items.len());
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
        return split_middle(items, at, bounds, axis, depth, rule);
    }
    // A small scene's build can afford to try every axis; a large one's splits the
    // widest.
    let axes: &[usize] = if rule.all_axes {
        &[0, 1, 2]
    } else {
        std::slice::from_ref(&axis)
    };
    let best = axes
        .iter()
        .copied()
        .filter(|&a| extent[a] > 0.0 && extent[a].is_finite())
        .filter_map(|a| sah_split(items, &cbounds, a, bounds, rule).map(|(c, b)| (c, a, b)))
        .min_by(|x, y| x.0.total_cmp(&y.0));
    let Some((_, axis, split)) = best else {
        if items.len() <= rule.max {
            return Build::Leaf(bounds, at..at + items.len());
        }
        return split_middle(items, at, bounds, axis, depth, rule);
    };
    let (lo, span) = (cbounds.min[axis], extent[axis]);
    let bin = |c: Vec3| (((c[axis] - lo) / span * BINS as f64) as usize).min(BINS - 1);
    let left = stable_partition(items, |i| bin(i.centroid()) <= split);
    if left == 0 || left == items.len() {
        return split_middle(items, at, bounds, axis, depth, rule);
    }
    children(items, at, left, bounds, depth, rule)
}

/// Moves the items for which `keep` holds to the front, keeping the order on both
/// sides; the number kept. Only the others are copied out meanwhile.
fn stable_partition(items: &mut [Item], keep: impl Fn(&Item) -> bool) -> usize {
    let mut right = Vec::new();
    let mut n = 0;
    for i in 0..items.len() {
        let it = items[i];
        if keep(&it) {
            items[n] = it;
            n += 1;
        } else {
            right.push(it);
        }
    }
    items[n..].copy_from_slice(&right);
    n
}

fn children(
    items: &mut [Item],
    at: usize,
    mid: usize,
    bounds: Bounds,
    depth: u32,
    rule: LeafRule,
) -> Build {
    let parallel = items.len() > PARALLEL_THRESHOLD;
    let (left, right) = items.split_at_mut(mid);
    let (l, r) = if parallel {
        rayon::join(
            || build(left, at, depth + 1, rule),
            || build(right, at + mid, depth + 1, rule),
        )
    } else {
        (
            build(left, at, depth + 1, rule),
            build(right, at + mid, depth + 1, rule),
        )
    };
    Build::Interior(bounds, Box::new(l), Box::new(r))
}

fn split_middle(
    items: &mut [Item],
    at: usize,
    bounds: Bounds,
    axis: usize,
    depth: u32,
    rule: LeafRule,
) -> Build {
    items.sort_by(|a, b| a.centroid()[axis].total_cmp(&b.centroid()[axis]));
    let mid = items.len() / 2;
    children(items, at, mid, bounds, depth, rule)
}

/// The bin boundary along `axis` minimizing the surface area heuristic and its cost,
/// if splitting beats a leaf.
fn sah_split(
    items: &[Item],
    cb: &Bounds,
    axis: usize,
    bounds: Bounds,
    rule: LeafRule,
) -> Option<(f64, usize)> {
    let (lo, span) = (cb.min[axis], cb.max[axis] - cb.min[axis]);
    let mut bins = [(Bounds::EMPTY, 0usize); BINS];
    for it in items {
        let b = (((it.centroid()[axis] - lo) / span * BINS as f64) as usize).min(BINS - 1);
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
    let split_cost = best.0 + rule.node_cost * bounds.surface_area();
    (best.0.is_finite() && (split_cost < leaf_cost || items.len() > rule.max))
        .then_some((split_cost, best.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slots `bvh` visits along `ray` before `limit`, with `visit`'s limits, by
    /// the portable walk and, where the processor has it, the AVX2 one: both must
    /// visit the same slots in the same order.
    fn walks(bvh: &Bvh, ray: &Ray, limit: f64, visit: impl Fn(u32) -> f64) -> Vec<u32> {
        let mut portable = Vec::new();
        let prepared = Prepared::of(ray);
        bvh.walk::<lanes::Portable>(&prepared, limit, |slot| {
            portable.push(slot);
            visit(slot)
        });
        #[cfg(target_arch = "x86_64")]
        if simd::avx2() {
            let mut avx = Vec::new();
            // SAFETY: the processor has AVX2.
            unsafe {
                bvh.walk_avx2(&prepared, limit, |slot| {
                    avx.push(slot);
                    visit(slot)
                })
            };
            assert_eq!(avx, portable, "the walks differ");
        }
        portable
    }

    /// [`walks`] keeping the limit: every slot whose box the ray enters.
    fn visited(bvh: &Bvh, ray: &Ray, limit: f64) -> Vec<u32> {
        walks(bvh, ray, limit, |_| f64::INFINITY)
    }

    /// The slots [`Bvh::any`] offers, by the portable walk and, where the processor
    /// has it, the AVX2 one (the same slots, in the same order), until `stop` says yes.
    fn offered(
        bvh: &Bvh,
        ray: &Ray,
        limit: f64,
        skip: [u32; 2],
        stop: impl Fn(u32) -> bool,
    ) -> (Vec<u32>, bool) {
        let mut portable = Vec::new();
        let prepared = Prepared::of(ray);
        let stopped = bvh.any_walk::<lanes::Portable>(&prepared, limit, skip, |slot| {
            portable.push(slot);
            stop(slot)
        });
        #[cfg(target_arch = "x86_64")]
        if simd::avx2() {
            let mut avx = Vec::new();
            // SAFETY: the processor has AVX2.
            let avx_stopped = unsafe {
                bvh.any_avx2(&prepared, limit, skip, |slot| {
                    avx.push(slot);
                    stop(slot)
                })
            };
            assert_eq!(
                (&avx, avx_stopped),
                (&portable, stopped),
                "the walks differ"
            );
        }
        (portable, stopped)
    }

    /// `any` offers each slot `traverse` visits with a limit that never shrinks, each
    /// once, and no other (the test's three-entry stack makes deep trees spill); it
    /// ends at the first slot `stop` takes, and says so; a skipped slot is never
    /// offered.
    #[test]
    fn any_offers_what_traverse_visits_and_stops_when_told() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let bounds: Vec<Bounds> = (0..3000)
            .map(|_| {
                let c = Vec3::new(next(), next(), next()) * 20.0;
                let h = Vec3::new(next(), next(), next()) * 0.4 + Vec3::splat(0.01);
                Bounds {
                    min: c - h,
                    max: c + h,
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds);
        let mut stopped_some = 0;
        for k in 0..300 {
            let org = Vec3::new(next(), next(), next()) * 24.0 - Vec3::splat(2.0);
            let dir = (Vec3::new(next(), next(), next()) - Vec3::splat(0.5)).normalize();
            let limit = if k % 3 == 0 {
                f64::INFINITY
            } else {
                next() * 30.0
            };
            let ray = Ray::new(org, dir);
            let mut expect = visited(&bvh, &ray, limit);
            expect.sort();
            let (mut got, stopped) = offered(&bvh, &ray, limit, [u32::MAX; 2], |_| false);
            assert!(!stopped);
            let all = got.clone();
            got.sort();
            let mut unique = got.clone();
            unique.dedup();
            assert_eq!(unique.len(), got.len(), "a slot offered twice");
            assert_eq!(got, expect, "ray {k}");
            // Stopping at the middle slot offered: nothing after it.
            if let Some(&middle) = all.get(all.len() / 2) {
                let (until, stopped) =
                    offered(&bvh, &ray, limit, [u32::MAX; 2], |slot| slot == middle);
                assert!(stopped);
                assert_eq!(until, all[..=all.len() / 2]);
                stopped_some += 1;
                // Skipping it (and the first): every other slot, in the same order, and
                // no stop.
                let skip = [middle, all[0]];
                let (rest, stopped) = offered(&bvh, &ray, limit, skip, |slot| slot == middle);
                assert!(!stopped);
                let others: Vec<u32> = all.iter().copied().filter(|s| !skip.contains(s)).collect();
                assert_eq!(rest, others);
            }
        }
        assert!(stopped_some > 100, "{stopped_some} rays met boxes");
    }

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
        let seen = visited(
            &bvh,
            &Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X),
            f64::INFINITY,
        );
        assert_eq!(seen.len(), 2000);
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
        let mut seen: Vec<u32> = visited(&bvh, &ray, f64::INFINITY)
            .into_iter()
            .filter_map(|slot| bvh.primitive(slot))
            .collect();
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
            let seen: Vec<u32> = visited(&bvh, &Ray::new(org, dir), f64::INFINITY)
                .into_iter()
                .filter_map(|slot| bvh.primitive(slot))
                .collect();
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

    /// The `f32` slab test against an exact one: random millimetre boxes 1e5 units
    /// from the origin (where an `f32` origin is off by 4 mm) and near it, rays from
    /// random points, from box corners and along box faces, with limits that end
    /// inside boxes. Every box the ray meets before the limit is visited.
    #[test]
    fn f32_slabs_miss_no_box_far_from_the_origin() {
        let mut seed = 7u64;
        let mut next = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for centre in [Vec3::ZERO, Vec3::new(1e5, -1e5, 3e4)] {
            let bounds: Vec<Bounds> = (0..300)
                .map(|_| {
                    let c = centre + Vec3::new(next(), next(), next()) * 0.2;
                    let h = Vec3::new(next(), next(), next()) * 1e-3;
                    Bounds {
                        min: c - h,
                        max: c + h,
                    }
                })
                .collect();
            let bvh = Bvh::build(&bounds);
            for k in 0..400 {
                let target = &bounds[k % bounds.len()];
                // Origins: random, on a corner of another box, or a box's low face.
                let org = match k % 3 {
                    0 => centre + Vec3::new(next(), next(), next()) * 0.3 - Vec3::splat(0.05),
                    1 => bounds[(k * 7) % bounds.len()].max,
                    _ => Vec3::new(target.min.x, target.min.y - 0.01, next() * 0.2 + centre.z),
                };
                let aim =
                    target.min + (target.max - target.min) * Vec3::new(next(), next(), next());
                let mut dir = (aim - org).normalize();
                if k % 3 == 2 {
                    dir = Vec3::Y; // along the low x face of `target`
                }
                if !dir.is_finite() {
                    continue;
                }
                let limit = if k % 4 == 0 {
                    (aim - org).length()
                } else {
                    f64::INFINITY
                };
                let ray = Ray::new(org, dir);
                let mut seen = vec![false; bounds.len()];
                for slot in visited(&bvh, &ray, limit) {
                    if let Some(i) = bvh.primitive(slot) {
                        seen[i as usize] = true;
                    }
                }
                for (i, b) in bounds.iter().enumerate() {
                    let (mut t0, mut t1) = (0.0f64, limit);
                    let mut met = true;
                    for a in 0..3 {
                        if dir[a] == 0.0 {
                            met &= b.min[a] <= org[a] && org[a] <= b.max[a];
                            continue;
                        }
                        let (p, q) = ((b.min[a] - org[a]) / dir[a], (b.max[a] - org[a]) / dir[a]);
                        t0 = t0.max(p.min(q));
                        t1 = t1.min(p.max(q));
                    }
                    if met && t0 <= t1 {
                        assert!(seen[i], "box {i} missed by {org} {dir} (limit {limit})");
                    }
                }
            }
        }
    }

    /// The vector lanes compute what the scalar reference does, to the bit: random
    /// boxes and empty lanes (infinite planes), rays with zero direction components
    /// and origins on box planes (`0 * inf = NaN`), finite and infinite limits.
    #[test]
    fn lanes_match_the_scalar_reference() {
        use lanes::Lanes;
        let mut seed = 11u64;
        let mut next = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let grid = |x: f64| (x * 8.0).floor() / 4.0 - 1.0;
        for k in 0..4000 {
            let mut node = Node::default();
            for lane in 0..WIDTH {
                if (k + lane) % 5 == 0 {
                    continue; // an unused lane
                }
                let lo = Vec3::new(grid(next()), grid(next()), grid(next()));
                let b = Bounds {
                    min: lo,
                    max: lo + Vec3::new(next(), next(), next()),
                };
                node.set(lane, b, Link { first: 0, count: 1 });
            }
            let org = Vec3::new(grid(next()), grid(next()), grid(next()));
            let mut dir = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            if k % 3 == 0 {
                dir[k % 9 / 3] = if k % 2 == 0 { 0.0 } else { -0.0 };
            }
            let s = Slabs::new(&Ray::new(org, dir.normalize()));
            let limit = if k % 4 == 0 {
                f32::INFINITY
            } else {
                next() as f32 * 3.0
            };
            let (t0, hits) = s.entries(&node, limit);
            let bits = |t: [f32; WIDTH]| t.map(f32::to_bits);
            let (p0, ph) = lanes::Portable::entries(&s, &node, limit);
            assert_eq!((bits(p0), ph), (bits(t0), hits), "portable, case {k}");
            #[cfg(target_arch = "x86_64")]
            if simd::avx2() {
                let (a0, ah) = lanes::Avx2::entries(&s, &node, limit);
                assert_eq!((bits(a0), ah), (bits(t0), hits), "AVX2, case {k}");
            }
        }
    }

    /// With a limit that shrinks as hits are found (as `nearest` uses it), both walks
    /// still agree, and find the nearest box entry a brute-force search finds.
    #[test]
    fn shrinking_limits_find_the_nearest() {
        let mut seed = 5u64;
        let mut next = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let bounds: Vec<Bounds> = (0..500)
            .map(|_| {
                let c = Vec3::new(next(), next(), next()) * 10.0;
                Bounds {
                    min: c,
                    max: c + Vec3::new(next(), next(), next()) * 0.5,
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds);
        let entry = |b: &Bounds, ray: &Ray| {
            let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
            for a in 0..3 {
                let (p, q) = (
                    (b.min[a] - ray.org[a]) / ray.dir[a],
                    (b.max[a] - ray.org[a]) / ray.dir[a],
                );
                t0 = t0.max(p.min(q));
                t1 = t1.min(p.max(q));
            }
            (t0 <= t1).then_some(t0)
        };
        for _ in 0..300 {
            let org = Vec3::new(next(), next(), next()) * 12.0 - Vec3::ONE;
            let dir = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize();
            let ray = Ray::new(org, dir);
            let best = std::cell::Cell::new(f64::INFINITY);
            let hit = |slot: u32| {
                let b = &bounds[bvh.primitive(slot).unwrap_or(0) as usize];
                if let Some(t) = entry(b, &ray) {
                    best.set(best.get().min(t));
                }
                best.get()
            };
            let _ = walks(&bvh, &ray, f64::INFINITY, hit);
            let expect = bounds
                .iter()
                .filter_map(|b| entry(b, &ray))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(best.get(), expect);
        }
    }

    /// A node is four whole cache lines.
    #[test]
    fn nodes_are_four_cache_lines() {
        assert_eq!(std::mem::size_of::<Node>(), 256);
        assert_eq!(std::mem::align_of::<Node>(), 64);
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
