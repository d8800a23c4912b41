//! `ColorPicture` against Radiance's colorpict: tests/data/picture/colorpict.json holds
//! what rtrace sees of pictures used as `colorpict` patterns on a glow (the radiance is
//! the pattern's value), at points inside the pictures, on their edges and beyond them
//! (extrapolation and taper), with pixel aspect ratios and other orientations. rtrace
//! keeps colours in single precision and prints six digits, and its path to the value
//! has single-precision steps that the interpolation amplifies where neighbouring pixels
//! differ a lot: values must agree within 1e-5 relative. Where extrapolation goes below
//! zero rtrace reports 0 (no negative radiance); those points are counted apart.

use std::path::Path;

use radc_picture::{ColorPicture, Picture};

#[test]
fn colorpict_values_agree_with_rtrace() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/picture");
    let cases: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(data.join("colorpict.json")).expect("colorpict.json"),
    )
    .expect("JSON");
    let mut compared = 0;
    let mut bad = 0;
    let mut negative = 0;
    for case in cases.as_array().expect("a list") {
        let name = case["picture"].as_str().expect("picture");
        let bytes = std::fs::read(data.join("inputs").join(name)).expect("picture");
        let picture = Picture::read(&bytes).expect("reads");
        let pattern = ColorPicture::new(&picture).expect("an RGBE picture");
        let (u, v) = (
            case["u"].as_f64().expect("u"),
            case["v"].as_f64().expect("v"),
        );
        let got = pattern.value(u, v);
        for (c, want) in case["rgb"].as_array().expect("rgb").iter().enumerate() {
            let want: f64 = want.as_str().expect("a number").parse().expect("a number");
            // In single precision, as rtrace's colour, then to rtrace's six digits.
            let ours = f64::from(got[c] as f32);
            if ours < 0.0 && want == 0.0 {
                // Extrapolation below zero: rtrace reports no negative radiance.
                negative += 1;
                continue;
            }
            if (ours - want).abs() > 1e-5 * want.abs() + 1e-7 {
                eprintln!(
                    "{name} at ({u}, {v}) channel {c}: radc {ours:e}, rtrace {want:e} rel {:e}",
                    (ours - want) / want
                );
                bad += 1;
            }
            compared += 1;
        }
    }
    assert!(compared > 1000, "{compared}");
    assert_eq!(bad, 0, "of {compared}");
    eprintln!("{compared} values agree with rtrace, {negative} extrapolated below zero");
}
