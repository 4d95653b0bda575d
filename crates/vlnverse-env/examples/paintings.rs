//! A contact sheet of every painting subject (`vlnverse_env::material::FEATURE_SURFACES` that
//! cover a canvas): each picture's texture as the renderers draw it (the display-encoded grey
//! times a canvas colour of `vlnverse-procgen`, cycling through them), twice its texel size,
//! labelled with the feature the generator records.
//!
//! `cargo run -p vlnverse-env --release --example paintings [OUT.png [SUBJECT ...]]` (only the
//! subjects named, when any are)
//! (the gallery's sheet: `docs/img/gallery/paintings.png`)

use std::path::PathBuf;

use image::{Rgb, RgbImage};
use vlnverse_env::material::{Covers, Surface, FEATURE_SURFACES, TEX_SIZE};
use vlnverse_env::topdown::draw_text;

/// The canvas colours of `vlnverse-procgen` (`decor.rs`), linear RGB.
const CANVASES: [[f32; 3]; 6] = [
    [0.8, 0.72, 0.6],
    [0.35, 0.5, 0.72],
    [0.45, 0.62, 0.42],
    [0.85, 0.55, 0.3],
    [0.7, 0.3, 0.28],
    [0.85, 0.75, 0.4],
];

/// Texels are drawn `SCALE` pixels wide.
const SCALE: usize = 2;
/// Columns of the sheet.
const COLS: usize = 6;
/// Height of the label strip under each picture (pixels).
const LABEL: usize = 22;
/// Gap between tiles (pixels).
const GAP: usize = 6;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .first()
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("paintings.png"));
    let only = args.get(1..).unwrap_or_default();
    let subjects: Vec<_> = FEATURE_SURFACES
        .iter()
        .filter(|(f, _, c)| {
            *c == Covers::Canvas && (only.is_empty() || only.iter().any(|o| o == f))
        })
        .collect();
    // Every surface's texture is built on first use, once per process.
    let start = std::time::Instant::now();
    let texels: usize = Surface::ALL.iter().map(|s| s.luma_encoded().len()).sum();
    println!(
        "{} surface textures ({texels} texels) built in {:.1} ms",
        Surface::ALL.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    let side = TEX_SIZE * SCALE;
    let (cw, ch) = (side + GAP, side + LABEL + GAP);
    let rows = subjects.len().div_ceil(COLS);
    let mut img = RgbImage::from_pixel(
        (COLS * cw + GAP) as u32,
        (rows * ch + GAP) as u32,
        Rgb([40, 40, 40]),
    );
    for (k, (name, surface, _)) in subjects.iter().enumerate() {
        let tint = CANVASES[k % CANVASES.len()].map(|c| c.powf(1.0 / 2.2));
        let (x0, y0) = (GAP + (k % COLS) * cw, GAP + (k / COLS) * ch);
        let luma = surface.luma_encoded();
        for y in 0..side {
            for x in 0..side {
                let g = luma[(y / SCALE) * TEX_SIZE + x / SCALE] as f32;
                let px = tint.map(|t| (g * t).round().min(255.0) as u8);
                img.put_pixel((x0 + x) as u32, (y0 + y) as u32, Rgb(px));
            }
        }
        draw_text(
            &mut img,
            x0 as i64,
            (y0 + side + 7) as i64,
            name,
            1,
            [255, 255, 255],
            false,
        );
    }
    img.save(&out)?;
    println!("{} subjects -> {}", subjects.len(), out.display());
    Ok(())
}
