//! The typed form of each primitive type the renderer models ([`PrimKind`]), read
//! from argument lists already checked against the schema; other types keep their
//! arguments as written. Reading stays total so that a schema slip can never turn
//! user input into a panic.

use super::Lowering;
use super::geometry::{norm, real_span};
use crate::scene::ir::{PrimKind, Rgb, Vec3};
use crate::scene::syntax::Primitive;
use crate::schema::PrimitiveType;

impl Lowering<'_> {
    /// The typed form; counts are already known to fit the schema. For a primitive
    /// that is not `kept`, just its checks (the kind returned is then a placeholder).
    pub(super) fn lower_kind(
        &mut self,
        p: &Primitive,
        schema: &PrimitiveType,
        kept: bool,
    ) -> PrimKind {
        // Counts were checked against the schema, but indexing stays total so a schema
        // slip can never become a panic on user input.
        let values = &p.reals.items;
        let r = Reals(values);
        let s: Vec<String> = p.strings.items.iter().map(|w| w.text.clone()).collect();
        let v3 = |i: usize| -> Vec3 { [r[i], r[i + 1], r[i + 2]] };
        let rgb = |i: usize| -> Rgb { [r[i], r[i + 1], r[i + 2]] };
        let first_string = || s.first().cloned();
        match schema.name {
            "source" => {
                if v3(0) == [0.0; 3] {
                    self.zero_direction(p, 0);
                }
                PrimKind::Source {
                    direction: v3(0),
                    angle: r[3],
                }
            }
            "sphere" | "bubble" => {
                self.check_radius(p, r[3], 3);
                let (center, radius) = (v3(0), r[3]);
                if (schema.name == "sphere") == (radius >= 0.0) {
                    PrimKind::Sphere {
                        center,
                        radius: radius.abs(),
                    }
                } else {
                    PrimKind::Bubble {
                        center,
                        radius: radius.abs(),
                    }
                }
            }
            "polygon" => {
                let mut vertices = std::mem::take(&mut self.vertices);
                vertices.clear();
                vertices.extend(
                    values
                        .chunks_exact(3)
                        .map(|c| [c[0].value, c[1].value, c[2].value]),
                );
                self.check_polygon(p, &vertices);
                if kept {
                    PrimKind::Polygon { vertices }
                } else {
                    self.vertices = vertices;
                    PrimKind::Polygon {
                        vertices: Vec::new(),
                    }
                }
            }
            "cone" | "cup" => {
                let (p0, p1, r0, r1) = (v3(0), v3(3), r[6], r[7]);
                self.check_axis(p, p0, p1);
                self.check_cone_radii(p, r0, r1);
                if (schema.name == "cone") == (r0 >= 0.0 && r1 >= 0.0) {
                    PrimKind::Cone {
                        p0,
                        p1,
                        r0: r0.abs(),
                        r1: r1.abs(),
                    }
                } else {
                    PrimKind::Cup {
                        p0,
                        p1,
                        r0: r0.abs(),
                        r1: r1.abs(),
                    }
                }
            }
            "cylinder" | "tube" => {
                let (p0, p1, radius) = (v3(0), v3(3), r[6]);
                self.check_axis(p, p0, p1);
                self.check_radius(p, radius, 6);
                if (schema.name == "cylinder") == (radius >= 0.0) {
                    PrimKind::Cylinder {
                        p0,
                        p1,
                        radius: radius.abs(),
                    }
                } else {
                    PrimKind::Tube {
                        p0,
                        p1,
                        radius: radius.abs(),
                    }
                }
            }
            "ring" => {
                let (center, normal, r0, r1) = (v3(0), v3(3), r[6], r[7]);
                if norm(normal) == 0.0 {
                    self.degenerate(
                        p,
                        real_span(p, 3).to(real_span(p, 5)),
                        "its normal is the zero vector",
                    );
                }
                self.check_ring_radii(p, r0, r1);
                PrimKind::Ring {
                    center,
                    normal,
                    r0: r0.min(r1),
                    r1: r0.max(r1),
                }
            }
            "instance" => PrimKind::Instance {
                octree: first_string().unwrap_or_default(),
                transform: s.iter().skip(1).cloned().collect(),
            },
            "mesh" => PrimKind::Mesh {
                file: first_string().unwrap_or_default(),
                transform: s.iter().skip(1).cloned().collect(),
                materials: Vec::new(),
            },
            "light" => PrimKind::Light { color: rgb(0) },
            "illum" => PrimKind::Illum {
                alternate: first_string(),
                color: rgb(0),
            },
            "glow" => PrimKind::Glow {
                color: rgb(0),
                max_radius: r[3],
            },
            "spotlight" => {
                if v3(4) == [0.0; 3] {
                    self.zero_direction(p, 4);
                }
                PrimKind::Spotlight {
                    color: rgb(0),
                    angle: r[3],
                    direction: v3(4),
                }
            }
            "mirror" => PrimKind::Mirror {
                alternate: first_string(),
                color: rgb(0),
            },
            "plastic" => PrimKind::Plastic {
                color: rgb(0),
                spec: r[3],
                rough: r[4],
            },
            "metal" => PrimKind::Metal {
                color: rgb(0),
                spec: r[3],
                rough: r[4],
            },
            "trans" => PrimKind::Trans {
                color: rgb(0),
                spec: r[3],
                rough: r[4],
                trans: r[5],
                tspec: r[6],
            },
            "glass" => PrimKind::Glass {
                transmission: rgb(0),
                // Radiance's default index of refraction for glass.
                index: values.get(3).map_or(1.52, |r| r.value),
            },
            "dielectric" => PrimKind::Dielectric {
                transmission: rgb(0),
                index: r[3],
                hartmann: r[4],
            },
            "interface" => PrimKind::Interface {
                t1: rgb(0),
                n1: r[3],
                t2: rgb(4),
                n2: r[7],
            },
            "antimatter" => PrimKind::Antimatter { modifiers: s },
            _ => other(p),
        }
    }
}

pub(super) fn other(p: &Primitive) -> PrimKind {
    PrimKind::Other {
        strings: p.strings.items.iter().map(|w| w.text.clone()).collect(),
        reals: p.reals.items.iter().map(|r| r.value).collect(),
    }
}

/// Total indexing into a real list: missing values read as 0.
struct Reals<'a>(&'a [crate::scene::syntax::Real]);

impl std::ops::Index<usize> for Reals<'_> {
    type Output = f64;
    fn index(&self, i: usize) -> &f64 {
        self.0.get(i).map_or(&0.0, |r| &r.value)
    }
}
