//! `radc trace -I` against closed-form illuminance. Each test states its formula.

mod common;

use std::f64::consts::PI;

use std::path::Path;

fn trace(dir: &Path, scene: &str, options: &[&str], rays: &str) -> Vec<Vec<f64>> {
    std::fs::write(dir.join("scene.rad"), scene).expect("write scene");
    let mut cmd = common::radc(["trace", "-h"]);
    cmd.args(options).arg(dir.join("scene.rad"));
    let out = common::run(cmd, rays.as_bytes());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| {
            l.split_whitespace()
                .map(|w| w.parse().expect("number"))
                .collect()
        })
        .collect()
}

fn assert_close(got: f64, want: f64, rel: f64, what: &str) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "{what}: got {got}, want {want} (relative error {:.2e})",
        (got - want).abs() / want.abs()
    );
}

/// A sphere of radiance L and radius r at distance d from a point subtends a cone of
/// half-angle alpha with sin(alpha) = r/d; the illuminance on a surface whose normal is
/// theta away from the sphere's centre (and sees all of it) is
///     E = pi L sin^2(alpha) cos(theta).
/// Like rtrace, `-I` measures 1e-4 in front of the given point, along the normal.
#[test]
fn sphere_source_illuminance() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r, d) = (100.0, 0.5, 5.0);
    let scene = format!("void light lamp 0 0 3 {l} {l} {l}\nlamp sphere bulb 0 0 4 0 0 {d} {r}\n");
    let theta: f64 = 60f64.to_radians();
    let rays = format!("0 0 0 0 0 1\n0 0 0 {} 0 {}\n", theta.sin(), theta.cos());
    let out = trace(dir.path(), &scene, &["-I", "-ab", "0"], &rays);
    for (row, n) in out
        .iter()
        .zip([[0.0, 0.0, 1.0], [theta.sin(), 0.0, theta.cos()]])
    {
        let v = [-n[0] * 1e-4, -n[1] * 1e-4, d - n[2] * 1e-4];
        let dist = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let cos = (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) / dist;
        let sin2 = (r / dist) * (r / dist);
        for &e in row {
            assert_close(e, PI * l * sin2 * cos, 1e-6, "sphere source");
        }
    }
}

/// A square of radiance L and half-side a, facing a point on its axis at distance h
/// (X = a / h), gives (four corner rectangles of the rectangle view factor)
///     E = 4 L X / sqrt(1 + X^2) * atan(X / sqrt(1 + X^2)).
/// Far away one sample suffices (`-ds 0`); near by, the partitioned source (`-ds .2`)
/// must still agree to a percent.
#[test]
fn square_source_on_axis() {
    let dir = tempfile::tempdir().unwrap();
    let (l, a) = (50.0, 0.5);
    let scene = format!(
        "void light panel 0 0 3 {l} {l} {l}\n\
         panel polygon square 0 0 12 -{a} -{a} 0 -{a} {a} 0 {a} {a} 0 {a} -{a} 0\n"
    );
    let exact = |h: f64| {
        let x: f64 = a / h;
        let s = (1.0 + x * x).sqrt();
        4.0 * l * x / s * (x / s).atan()
    };
    let far = trace(dir.path(), &scene, &["-I", "-ds", "0"], "0 0 -20 0 0 1\n");
    assert_close(far[0][0], exact(20.0), 1e-3, "far square, one sample");
    let near = trace(dir.path(), &scene, &["-I", "-ds", ".2"], "0 0 -1.5 0 0 1\n");
    assert_close(near[0][0], exact(1.5), 1e-2, "near square, partitioned");
}

/// In a uniform environment of radiance L every surface receives E = pi L, and a
/// Lambertian surface of reflectance rho reflects rho L (the "white furnace"). With no
/// ambient bounces the environment is the ambient value `-av`.
#[test]
fn uniform_environment() {
    let dir = tempfile::tempdir().unwrap();
    let l = 0.75;
    let scene = "void plastic white 0 0 5 .6 .6 .6 0 0\nwhite sphere ball 0 0 4 0 0 0 1\n";
    let av = ["-av", "0.75", "0.75", "0.75"];
    let irr = trace(
        dir.path(),
        scene,
        &[&["-I"], &av[..]].concat(),
        "0 0 5 0 0 1\n3 1 2 -.3 .5 .8\n",
    );
    for row in &irr {
        for &e in row {
            assert_close(e, PI * l, 1e-6, "irradiance");
        }
    }
    let rad = trace(dir.path(), scene, &av, "0 0 5 0 0 -1\n");
    for &v in &rad[0] {
        assert_close(v, 0.6 * l, 1e-6, "reflected radiance");
    }
}

/// A distant source of radiance L and solid angle omega = 2 pi (1 - cos(angle/2)) at
/// angle theta from the normal gives E = L omega cos(theta).
#[test]
fn distant_source() {
    let dir = tempfile::tempdir().unwrap();
    let l = 1000.0;
    let scene = format!("void light sun 0 0 3 {l} {l} {l}\nsun source disc 0 0 4 0 0 1 .5\n");
    let omega = 2.0 * PI * (1.0 - (0.25f64.to_radians()).cos());
    let theta: f64 = 30f64.to_radians();
    let out = trace(
        dir.path(),
        &scene,
        &["-I"],
        &format!("0 0 0 0 0 1\n0 0 0 0 {} {}\n", theta.sin(), theta.cos()),
    );
    assert_close(out[0][0], l * omega, 1e-6, "normal incidence");
    assert_close(out[1][0], l * omega * theta.cos(), 1e-6, "oblique");
}
