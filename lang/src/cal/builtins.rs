//! calcomp's function library: the functions every calcomp program sees (calfunc.c's
//! table), the ones rcalc adds, and the renderer's (func.c, noise3.c). A library entry
//! has an arity and a constness: a constant (`:`) library function of constant
//! arguments is folded at parse time, exactly as calexpr.c `isconstfun` allows.

/// The functions built into calcomp itself, available in every program.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Builtin {
    Acos,
    Asin,
    Atan,
    Atan2,
    Ceil,
    Cos,
    Exp,
    Floor,
    If,
    Log,
    Log10,
    Max,
    Min,
    Rand,
    Select,
    Sin,
    Sqrt,
    Tan,
}

impl Builtin {
    pub const ALL: [Builtin; 18] = [
        Builtin::Acos,
        Builtin::Asin,
        Builtin::Atan,
        Builtin::Atan2,
        Builtin::Ceil,
        Builtin::Cos,
        Builtin::Exp,
        Builtin::Floor,
        Builtin::If,
        Builtin::Log,
        Builtin::Log10,
        Builtin::Max,
        Builtin::Min,
        Builtin::Rand,
        Builtin::Select,
        Builtin::Sin,
        Builtin::Sqrt,
        Builtin::Tan,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Builtin::Acos => "acos",
            Builtin::Asin => "asin",
            Builtin::Atan => "atan",
            Builtin::Atan2 => "atan2",
            Builtin::Ceil => "ceil",
            Builtin::Cos => "cos",
            Builtin::Exp => "exp",
            Builtin::Floor => "floor",
            Builtin::If => "if",
            Builtin::Log => "log",
            Builtin::Log10 => "log10",
            Builtin::Max => "max",
            Builtin::Min => "min",
            Builtin::Rand => "rand",
            Builtin::Select => "select",
            Builtin::Sin => "sin",
            Builtin::Sqrt => "sqrt",
            Builtin::Tan => "tan",
        }
    }

    /// Arguments the function needs at least. `select`, `min` and `max` take any
    /// number from one on; `if` needs three.
    pub fn min_args(self) -> usize {
        match self {
            Builtin::Atan2 => 2,
            Builtin::If => 3,
            _ => 1,
        }
    }

    /// Arguments beyond this are ignored (calfunc.c reads only what it needs).
    pub fn max_args(self) -> Option<usize> {
        match self {
            Builtin::Max | Builtin::Min | Builtin::Select => None,
            b => Some(b.min_args()),
        }
    }

    /// The one-argument functions that map straight to the C math library.
    pub fn unary(self, x: f64) -> Option<f64> {
        Some(match self {
            // Outside [-1, 1] the reference rcalc (built with -ffast-math, so calling
            // glibc's `__acos_finite` rather than the `acos` wrapper) gets the x86
            // default NaN, whose sign bit is set: it prints `-nan`. Likewise log10.
            Builtin::Acos | Builtin::Asin if x.abs() > 1.0 => DEFAULT_NAN,
            Builtin::Log10 if x < 0.0 => DEFAULT_NAN,
            Builtin::Acos => x.acos(),
            Builtin::Asin => x.asin(),
            Builtin::Atan => x.atan(),
            // The reference rcalc's floor and ceil (inlined under -ffast-math) never
            // return -0: ceil(-0.5) and floor(-0) print 0. Checked against rcalc.
            Builtin::Ceil => no_negative_zero(x.ceil()),
            Builtin::Cos => x.cos(),
            Builtin::Exp => x.exp(),
            Builtin::Floor => no_negative_zero(x.floor()),
            Builtin::Log => x.ln(),
            Builtin::Log10 => x.log10(),
            Builtin::Rand => rand(x),
            Builtin::Sin => x.sin(),
            Builtin::Sqrt => x.sqrt(),
            Builtin::Tan => x.tan(),
            _ => return None,
        })
    }

    pub fn doc(self) -> &'static str {
        match self {
            Builtin::Acos => "acos(x): arc cosine, radians",
            Builtin::Asin => "asin(x): arc sine, radians",
            Builtin::Atan => "atan(x): arc tangent, radians",
            Builtin::Atan2 => "atan2(y, x): arc tangent of y/x in the right quadrant",
            Builtin::Ceil => "ceil(x): smallest integer not below x",
            Builtin::Cos => "cos(x): cosine of x radians",
            Builtin::Exp => "exp(x): e to the power x",
            Builtin::Floor => "floor(x): largest integer not above x",
            Builtin::If => "if(c, a, b): a when c > 0, else b; only the chosen branch is evaluated",
            Builtin::Log => "log(x): natural logarithm",
            Builtin::Log10 => "log10(x): base-10 logarithm",
            Builtin::Max => "max(a, ...): largest argument",
            Builtin::Min => "min(a, ...): smallest argument",
            Builtin::Rand => "rand(x): a fixed pseudo-random hash of x in [0, 1)",
            Builtin::Select => {
                "select(n, a1, a2, ...): the n-th argument; select(0, ...) is the count"
            }
            Builtin::Sin => "sin(x): sine of x radians",
            Builtin::Sqrt => "sqrt(x): square root",
            Builtin::Tan => "tan(x): tangent of x radians",
        }
    }
}

/// The NaN x86 SSE arithmetic produces for an invalid operation (`0/0`, `sqrt(-1)`):
/// sign bit set, printed `-nan` by glibc.
pub const DEFAULT_NAN: f64 = f64::from_bits(0xfff8_0000_0000_0000);

fn no_negative_zero(x: f64) -> f64 {
    if x == 0.0 { 0.0 } else { x }
}

/// calcomp's `rand`: a deterministic hash, not a generator, so a scene renders the
/// same every time. The constants are calfunc.c's (`e` and `pi/4` to 15 digits); the
/// operation order is kept so every bit matches.
pub fn rand(x: f64) -> f64 {
    let mut x = x;
    // Radiance's 15-digit e, not `std::f64::consts::E`: the last bits matter.
    #[allow(clippy::approx_constant)]
    let e15 = 2.71828182845904;
    x *= 1.0 / (1.0 + x * x) + e15;
    x += 0.785398163397447 - x.floor();
    x = 1e5 / x;
    x - x.floor()
}

/// A library function: one of calcomp's own, or one the host program installs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LibFn {
    Builtin(Builtin),
    /// rcalc's `in(n)`: input column n, `in(0)` the number of columns. Not constant.
    In,
    /// A function the renderer installs (func.c, noise3.c, fprism.c). It can be checked
    /// but not evaluated outside a renderer.
    Renderer(&'static RendererFn),
}

impl LibFn {
    pub fn name(&self) -> &'static str {
        match self {
            LibFn::Builtin(b) => b.name(),
            LibFn::In => "in",
            LibFn::Renderer(r) => r.name,
        }
    }

    pub fn min_args(&self) -> usize {
        match self {
            LibFn::Builtin(b) => b.min_args(),
            LibFn::In => 1,
            LibFn::Renderer(r) => r.arity,
        }
    }

    pub fn max_args(&self) -> Option<usize> {
        match self {
            LibFn::Builtin(b) => b.max_args(),
            LibFn::In => Some(1),
            LibFn::Renderer(r) => Some(r.arity),
        }
    }

    /// Whether calls with constant arguments fold (calfunc.c's `atyp == ':'`).
    pub fn is_constant(&self) -> bool {
        match self {
            LibFn::Builtin(_) => true,
            LibFn::In => false,
            LibFn::Renderer(r) => r.constant,
        }
    }
}

#[derive(Debug, PartialEq, Eq, Hash)]
pub struct RendererFn {
    pub name: &'static str,
    pub arity: usize,
    pub constant: bool,
    pub doc: &'static str,
}

/// Functions the renderer adds to the library (func.c `initfunc`, noise3.c,
/// fprism.c). `arg(0)` is the argument count of the current primitive.
pub static RENDERER_FUNCTIONS: &[RendererFn] = &[
    RendererFn {
        name: "arg",
        arity: 1,
        constant: false,
        doc: "arg(n): the primitive's n-th real argument; arg(0) is their count",
    },
    RendererFn {
        name: "erf",
        arity: 1,
        constant: true,
        doc: "erf(z): the error function",
    },
    RendererFn {
        name: "erfc",
        arity: 1,
        constant: true,
        doc: "erfc(z): the complementary error function",
    },
    RendererFn {
        name: "fnoise3",
        arity: 3,
        constant: true,
        doc: "fnoise3(x, y, z): fractal Perlin noise in [-1, 1]",
    },
    RendererFn {
        name: "fprism_val",
        arity: 3,
        constant: false,
        doc: "fprism_val(...): prism light redirection value",
    },
    RendererFn {
        name: "noise3",
        arity: 3,
        constant: true,
        doc: "noise3(x, y, z): Perlin noise in [-1, 1]",
    },
    RendererFn {
        name: "noise3x",
        arity: 3,
        constant: true,
        doc: "noise3x(x, y, z): x gradient of noise3",
    },
    RendererFn {
        name: "noise3y",
        arity: 3,
        constant: true,
        doc: "noise3y(x, y, z): y gradient of noise3",
    },
    RendererFn {
        name: "noise3z",
        arity: 3,
        constant: true,
        doc: "noise3z(x, y, z): z gradient of noise3",
    },
    RendererFn {
        name: "source_corr",
        arity: 2,
        constant: false,
        doc: "source_corr(...): source correction",
    },
    RendererFn {
        name: "source_phi",
        arity: 1,
        constant: false,
        doc: "source_phi(n): source azimuth",
    },
    RendererFn {
        name: "source_theta",
        arity: 1,
        constant: false,
        doc: "source_theta(n): source altitude",
    },
];

/// Variables the renderer defines per ray (func.c binds them to ray channels) and per
/// shading call (m_brdf.c, m_direct.c, pmapmat.c set them with `varset`).
pub static RENDERER_VARIABLES: &[&str] = &[
    "Dx", "Dy", "Dz", "Nx", "Ny", "Nz", "Px", "Py", "Pz", "T", "Ts", "Rdot", "S", "Tx", "Ty", "Tz",
    "Ix", "Iy", "Iz", "Jx", "Jy", "Jz", "Kx", "Ky", "Kz", "Lu", "Lv", "NxP", "NyP", "NzP", "RdotP",
    "CrP", "CgP", "CbP", "DxA", "DyA", "DzA",
];

/// Names rayinit.cal defines (Radiance loads it before any scene function file), with
/// the parameter count of the functions and whether the definition is a constant `:`.
/// The definitions themselves are radc's built-in rayinit.cal (`crate::library`), which
/// a renderer environment loads; this table serves completion and hover, and a test
/// pins it to that file.
pub static RAYINIT_NAMES: &[(&str, Option<usize>, bool)] = &[
    ("A1", None, false),
    ("A2", None, false),
    ("A3", None, false),
    ("A4", None, false),
    ("A5", None, false),
    ("A6", None, false),
    ("A7", None, false),
    ("A8", None, false),
    ("A9", None, false),
    ("A10", None, false),
    ("AC", None, false),
    ("noise3a", Some(3), true),
    ("noise3b", Some(3), true),
    ("noise3c", Some(3), true),
    ("noise3d", Some(4), true),
    ("D", Some(1), false),
    ("N", Some(1), false),
    ("P", Some(1), false),
    ("bound", Some(3), true),
    ("Acos", Some(1), true),
    ("Asin", Some(1), true),
    ("Atan2", Some(2), true),
    ("Exp", Some(1), true),
    ("Sqrt", Some(1), true),
    ("PI", None, true),
    ("DEGREE", None, true),
    ("FTINY", None, true),
    ("and", Some(2), true),
    ("or", Some(2), true),
    ("not", Some(1), true),
    ("xor", Some(2), true),
    ("abs", Some(1), true),
    ("sgn", Some(1), true),
    ("sq", Some(1), true),
    ("inside", Some(3), true),
    ("frac", Some(1), true),
    ("mod", Some(2), true),
    ("tri", Some(2), true),
    ("linterp", Some(3), true),
    ("noop", Some(1), true),
    ("clip", Some(1), true),
    ("noneg", Some(1), true),
    ("red", Some(3), true),
    ("green", Some(3), true),
    ("blue", Some(3), true),
    ("grey", Some(3), true),
    ("clip_r", Some(3), true),
    ("clip_g", Some(3), true),
    ("clip_b", Some(3), true),
    ("clipgrey", Some(3), true),
    ("dot", Some(2), true),
    ("cross", Some(3), true),
    ("fade", Some(3), true),
    ("hermite", Some(5), true),
    ("bezier", Some(5), true),
    ("bspline", Some(5), true),
    ("turbulence", Some(4), true),
    ("turbulencex", Some(4), true),
    ("turbulencey", Some(4), true),
    ("turbulencez", Some(4), true),
    ("unif2norm", Some(1), true),
    ("nrand", Some(1), false),
    ("U", None, false),
    ("V", None, false),
    ("Ldx", Some(3), false),
    ("Ldy", Some(3), false),
    ("Ldz", Some(3), false),
    ("Idx", None, false),
    ("Idy", None, false),
    ("Idz", None, false),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rand_matches_rcalc() {
        // rcalc -n -e '$1=rand(1)' prints 0.35008306
        assert_eq!(format!("{:.8}", rand(1.0)), "0.35008306");
    }
}
