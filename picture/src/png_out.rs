//! Tone-mapped 8-bit sRGB PNGs of a picture's colours (`radc render -o x.png`), through
//! the `png` crate.

use std::io::{self, Write};

use crate::tonemap;

/// Writes `width` by `height` linear colours (top row first) as an 8-bit sRGB PNG,
/// tone-mapped with the automatic exposure of [`tonemap`].
pub fn write_png(out: impl Write, width: u32, height: u32, pixels: &[[f64; 3]]) -> io::Result<()> {
    let exposure = tonemap::auto_exposure(pixels);
    let data = tonemap::to_srgb8(pixels, exposure);
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let png_error = |e: png::EncodingError| io::Error::other(e.to_string());
    let mut writer = encoder.write_header().map_err(png_error)?;
    writer.write_image_data(&data).map_err(png_error)?;
    writer.finish().map_err(png_error)
}
