//! Property tests: any picture radc writes reads back to the same header, resolution
//! and pixels, in every orientation and at every width (flat and run-length encoded),
//! and any bytes at all are read without a panic.

use proptest::prelude::*;
use radc_picture::{Format, Header, Orientation, Picture, Resolution};

fn pixels(max: usize) -> impl Strategy<Value = Vec<[u8; 4]>> {
    // Few distinct values, so runs of every length appear.
    prop::collection::vec(
        prop_oneof![
            Just([0u8, 0, 0, 0]),
            Just([128, 64, 2, 130]),
            any::<[u8; 4]>()
        ],
        1..max,
    )
}

proptest! {
    #[test]
    fn pictures_round_trip(px in pixels(400), width in 1u32..60, o in 0u8..8, xyz in any::<bool>()) {
        let height = (px.len() as u32 / width).max(1);
        let mut px = px;
        px.resize((width * height) as usize, [7, 7, 7, 135]);
        let format = if xyz { Format::XYZE } else { Format::RGBE };
        let header = Header::new_picture(&["EXPOSURE=2".into(), "VIEW= -vtv".into()], format);
        let mut picture = Picture::new(header, width, height, px);
        picture.resolution = Resolution { orientation: Orientation(o), ..picture.resolution };
        let mut bytes = Vec::new();
        picture.write(&mut bytes).unwrap();
        let back = Picture::read(&bytes).unwrap();
        prop_assert_eq!(&back, &picture);
        let mut again = Vec::new();
        back.write(&mut again).unwrap();
        prop_assert_eq!(again, bytes);
    }

    #[test]
    fn any_bytes_read_without_panic(data in prop::collection::vec(any::<u8>(), 0..600)) {
        let _ = Picture::read_with_limit(&data, 1 << 16);
        let mut framed = b"#?RADIANCE\n\n-Y 3 +X 20\n".to_vec();
        framed.extend_from_slice(&data);
        let _ = Picture::read_with_limit(&framed, 1 << 16);
    }
}
