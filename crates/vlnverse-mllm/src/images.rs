//! Pictures for the request: camera frames and the map, encoded as PNG or JPEG.

use image::codecs::jpeg::JpegEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder, RgbImage};
use vlnverse_eval::{Result, TaskError};
use vlnverse_sensors::Frame;

use crate::config::ImageFormat;

/// An encoded picture.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Encoded {
    /// `image/png` or `image/jpeg`.
    pub mime: &'static str,
    /// The file bytes.
    pub bytes: Vec<u8>,
    /// Width and height in pixels.
    pub size: (u32, u32),
}

fn encode_error(e: impl std::fmt::Display) -> TaskError {
    TaskError::invalid("mllm.image_format", "encode", e.to_string())
}

/// Encode an RGB image.
pub fn encode(img: &RgbImage, format: ImageFormat, jpeg_quality: u8) -> Result<Encoded> {
    let mut bytes = Vec::new();
    let (w, h) = img.dimensions();
    let mime = match format {
        ImageFormat::Png => {
            // Fast compression: the request size matters less than the step time.
            PngEncoder::new_with_quality(&mut bytes, CompressionType::Fast, FilterType::Sub)
                .write_image(img.as_raw(), w, h, ExtendedColorType::Rgb8)
                .map_err(encode_error)?;
            "image/png"
        }
        ImageFormat::Jpeg => {
            JpegEncoder::new_with_quality(&mut bytes, jpeg_quality)
                .write_image(img.as_raw(), w, h, ExtendedColorType::Rgb8)
                .map_err(encode_error)?;
            "image/jpeg"
        }
    };
    Ok(Encoded {
        mime,
        bytes,
        size: (w, h),
    })
}

/// A camera frame's colour as an image (`None` when it has no colour).
pub fn frame_image(f: &Frame) -> Option<RgbImage> {
    if f.rgb.len() != f.pixels() * 3 || f.width == 0 {
        return None;
    }
    RgbImage::from_raw(f.width, f.height, f.rgb.clone())
}

/// Views side by side, left to right in the given order, separated by a 2-pixel white gap.
pub fn strip(views: &[&Frame]) -> Option<RgbImage> {
    let imgs: Vec<RgbImage> = views.iter().filter_map(|f| frame_image(f)).collect();
    if imgs.is_empty() || imgs.len() != views.len() {
        return None;
    }
    let h = imgs.iter().map(|i| i.height()).max()?;
    let gap = 2;
    let w = imgs.iter().map(|i| i.width()).sum::<u32>() + gap * (imgs.len() as u32 - 1);
    let mut out = RgbImage::from_pixel(w, h, image::Rgb([255, 255, 255]));
    let mut x = 0;
    for img in &imgs {
        image::imageops::replace(&mut out, img, x.into(), 0);
        x += img.width() + gap;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_encodings_decode_to_the_same_size() {
        let img = RgbImage::from_fn(40, 30, |x, y| image::Rgb([x as u8 * 6, y as u8 * 8, 90]));
        for (fmt, mime) in [
            (ImageFormat::Png, "image/png"),
            (ImageFormat::Jpeg, "image/jpeg"),
        ] {
            let e = encode(&img, fmt, 80).unwrap();
            assert_eq!(e.mime, mime);
            let back = image::load_from_memory(&e.bytes).unwrap();
            assert_eq!((back.width(), back.height()), (40, 30));
        }
        let png = encode(&img, ImageFormat::Png, 80).unwrap();
        assert_eq!(image::load_from_memory(&png.bytes).unwrap().to_rgb8(), img);
    }

    #[test]
    fn a_strip_puts_views_side_by_side() {
        let f = |v: u8| Frame {
            width: 4,
            height: 3,
            rgb: vec![v; 36],
            ..Default::default()
        };
        let (a, b) = (f(10), f(200));
        let s = strip(&[&a, &b]).unwrap();
        assert_eq!(s.dimensions(), (10, 3));
        assert_eq!(s.get_pixel(0, 0).0, [10; 3]);
        assert_eq!(s.get_pixel(4, 0).0, [255; 3]);
        assert_eq!(s.get_pixel(9, 2).0, [200; 3]);
        assert!(strip(&[&a, &Frame::default()]).is_none());
    }
}
