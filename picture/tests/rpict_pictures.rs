//! Pictures rpict wrote (the goldens under tests/data/render/) read and written back
//! byte for byte: header lines, resolution line and every scanline's encoding.

use std::path::Path;

use radc_picture::Picture;

#[test]
fn rpict_pictures_round_trip_byte_for_byte() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/render");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).expect("render goldens") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "hdr") {
            continue;
        }
        let bytes = std::fs::read(&path).expect("read");
        let picture = Picture::read(&bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            picture
                .header
                .software()
                .is_some_and(|s| s.contains("RADIANCE"))
        );
        let mut out = Vec::new();
        picture.write(&mut out).expect("write");
        assert!(
            out == bytes,
            "{}: not written back byte for byte",
            path.display()
        );
        seen += 1;
    }
    assert!(seen >= 5, "only {seen} pictures");
}
