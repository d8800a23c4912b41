//! No input makes the geometry panic or report a hit it should not: random shapes and
//! rays, including degenerate, huge and non-finite values.

use proptest::prelude::*;
use radc_renderer::bvh::Bvh;
use radc_renderer::math::{FTINY, Vec3};
use radc_renderer::ray::Ray;
use radc_renderer::shapes::{Cone, Polygon, Ring, Shape, Sphere};

fn coord() -> BoxedStrategy<f64> {
    prop_oneof![
        -10.0..10.0f64,
        -1e7..1e7f64,
        Just(0.0),
        Just(1e-300),
        Just(f64::INFINITY),
        Just(f64::NAN),
        Just(-1e300),
    ]
    .boxed()
}

fn vec3() -> BoxedStrategy<Vec3> {
    (coord(), coord(), coord())
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
        .boxed()
}

fn shape() -> BoxedStrategy<Option<Shape>> {
    prop_oneof![
        (vec3(), coord(), any::<bool>()).prop_map(|(center, radius, inward)| Some(Shape::Sphere(
            Sphere {
                center,
                radius: radius.abs(),
                inward
            }
        ))),
        prop::collection::vec(vec3(), 0..8).prop_map(|v| Polygon::new(v).map(Shape::Polygon)),
        (vec3(), vec3(), coord(), coord())
            .prop_map(|(c, n, a, b)| Ring::new(c, n, a, b).map(Shape::Ring)),
        (vec3(), vec3(), coord(), coord(), any::<bool>())
            .prop_map(|(p0, p1, a, b, i)| Cone::new(p0, p1, a, b, i).map(Shape::Cone)),
    ]
    .boxed()
}

proptest! {
    #[test]
    fn shapes_never_panic_and_hits_are_ahead(s in shape(), org in vec3(), dir in vec3()) {
        let Some(s) = s else { return Ok(()) };
        let mut d = dir;
        radc_renderer::math::normalize(&mut d);
        let ray = Ray::new(org, d);
        if let Some(h) = s.intersect(&ray) {
            prop_assert!(h.t > FTINY);
        }
        let _ = s.bounds();
    }

    #[test]
    fn bvh_over_random_shapes_never_panics(shapes in prop::collection::vec(shape(), 0..40), org in vec3(), dir in vec3()) {
        let shapes: Vec<Shape> = shapes.into_iter().flatten().collect();
        let bounds: Vec<_> = shapes.iter().map(|s| s.bounds()).collect();
        let bvh = Bvh::build(&bounds);
        let mut d = dir;
        radc_renderer::math::normalize(&mut d);
        let ray = Ray::new(org, d);
        bvh.traverse(&ray, f64::INFINITY, |slot| {
            let i = bvh.primitive(slot).expect("a slot of the tree");
            let _ = shapes[i as usize].intersect(&ray);
            f64::INFINITY
        });
    }
}

/// Every shape hit by brute force is also found through the BVH.
#[test]
fn bvh_finds_what_brute_force_finds() {
    let mut shapes = Vec::new();
    for i in 0..30 {
        for j in 0..30 {
            let c = Vec3::new(f64::from(i), f64::from(j), f64::from((i * 7 + j * 3) % 5));
            shapes.push(Shape::Sphere(Sphere {
                center: c,
                radius: 0.4,
                inward: false,
            }));
        }
    }
    let bounds: Vec<_> = shapes.iter().map(|s| s.bounds()).collect();
    let bvh = Bvh::build(&bounds);
    for k in 0..200 {
        let a = f64::from(k) * 0.1;
        let ray = Ray::new(
            Vec3::new(-5.0, 14.5, 2.0),
            Vec3::new(a.cos(), a.sin() * 0.3, 0.05).normalize(),
        );
        let brute = shapes
            .iter()
            .filter_map(|s| s.intersect(&ray))
            .map(|h| h.t)
            .fold(f64::INFINITY, f64::min);
        let mut best = f64::INFINITY;
        bvh.traverse(&ray, f64::INFINITY, |slot| {
            let i = bvh.primitive(slot).expect("a slot of the tree");
            if let Some(h) = shapes[i as usize].intersect(&ray) {
                best = best.min(h.t);
            }
            best
        });
        assert_eq!(best, brute, "ray {k}");
    }
}
