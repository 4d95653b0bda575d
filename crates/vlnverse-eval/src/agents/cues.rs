//! Cues the `semantic` agent reads besides its own sensors: the dialogue oracle's answers (as
//! text, the way any agent receives them) and the visual-reference image (as a colour
//! histogram).
//!
//! The answer parsers follow the phrasing of [`crate::oracle::ShortestPathOracle`]: "The red
//! mug on the table in the kitchen is on your left, about 4 metres away." (where is), "Turn
//! left and go about 3 metres into the kitchen, then keep going about 2 metres." (which way) and
//! "You are close, about 2 metres away." (am I close). Anything else parses to `None`.

use std::path::Path;

use glam::Vec2;

use crate::error::{Result, TaskError};

/// Floor direction `(dx, dz)` of a yaw (yaw 0 looks along -Z, counter-clockwise).
pub use vlnverse_env::scene_graph::direction_of_yaw as heading;

/// The first distance in `text`: "about a metre" -> 1, "about 4 metres" -> 4.
fn metres(text: &str) -> Option<f32> {
    if text.contains("about a metre") {
        return Some(1.0);
    }
    let words: Vec<&str> = text.split_whitespace().collect();
    words.windows(2).find_map(|w| {
        (w[1].starts_with("metre") || w[1].starts_with("meter"))
            .then(|| w[0].parse::<f32>().ok())
            .flatten()
    })
}

/// "Where is": the object's bearing relative to the agent's heading (radians, counter-clockwise;
/// the middle of the named side's 90-degree sector) and its distance (m).
pub fn parse_where(answer: &str) -> Option<(f32, f32)> {
    let a = answer.to_lowercase();
    let bearing = if a.contains("ahead of you") {
        0.0
    } else if a.contains("on your left") {
        std::f32::consts::FRAC_PI_2
    } else if a.contains("on your right") {
        -std::f32::consts::FRAC_PI_2
    } else if a.contains("behind you") {
        std::f32::consts::PI
    } else {
        return None;
    };
    Some((bearing, metres(&a)?))
}

/// One leg of a "which way" answer: the turn before it (radians, counter-clockwise) and its
/// length (m).
pub type Leg = (f32, f32);

/// "Which way": the legs described, in order; `Some(vec![])` for "you are already there".
pub fn parse_which_way(answer: &str) -> Option<Vec<Leg>> {
    let a = answer.to_lowercase();
    if a.contains("already there") {
        return Some(Vec::new());
    }
    let legs: Vec<Leg> = a
        .split(", then ")
        .filter_map(|part| {
            let turn = if part.contains("turn around") {
                std::f32::consts::PI
            } else if part.contains("turn left") {
                std::f32::consts::FRAC_PI_2
            } else if part.contains("turn right") {
                -std::f32::consts::FRAC_PI_2
            } else if part.contains("bear left") {
                std::f32::consts::FRAC_PI_4
            } else if part.contains("bear right") {
                -std::f32::consts::FRAC_PI_4
            } else if part.contains("straight") || part.contains("keep going") {
                0.0
            } else {
                return None;
            };
            Some((turn, metres(part)?))
        })
        .collect();
    (!legs.is_empty()).then_some(legs)
}

/// The floor points a "which way" answer leads through, from `pos` facing `yaw`.
pub fn route_points(pos: Vec2, yaw: f32, legs: &[Leg]) -> Vec<Vec2> {
    let (mut p, mut h) = (pos, yaw);
    legs.iter()
        .map(|&(turn, len)| {
            h += turn;
            p += heading(h) * len;
            p
        })
        .collect()
}

/// "Am I close": whether the agent is within `success_m` of the goal as far as the answer's
/// distance bucket tells ("there", "very close" and "close" mean within 3 m); `None` when the
/// answer carries no distance.
pub fn parse_close(answer: &str) -> Option<bool> {
    let a = answer.to_lowercase();
    if a.contains("you are there") || a.contains("very close") || a.contains("you are close") {
        Some(true)
    } else if a.contains("not far") || a.contains("still far") {
        Some(false)
    } else {
        None
    }
}

/// Bins per colour channel of [`ColourHistogram`].
const BINS: usize = 4;

/// A normalised RGB histogram (4 bins per channel).
#[derive(Debug, Clone, PartialEq)]
pub struct ColourHistogram(pub [f32; BINS * BINS * BINS]);

impl Default for ColourHistogram {
    fn default() -> Self {
        ColourHistogram([0.0; BINS * BINS * BINS])
    }
}

impl ColourHistogram {
    fn bin(rgb: &[u8]) -> usize {
        let b = |c: u8| c as usize * BINS / 256;
        (b(rgb[0]) * BINS + b(rgb[1])) * BINS + b(rgb[2])
    }

    /// Add one pixel with weight `w`.
    pub fn add(&mut self, rgb: &[u8], w: f32) {
        self.0[Self::bin(rgb)] += w;
    }

    /// Scale to a total of 1 (no-op when empty).
    pub fn normalised(mut self) -> Self {
        let s: f32 = self.0.iter().sum();
        if s > 0.0 {
            self.0.iter_mut().for_each(|v| *v /= s);
        }
        self
    }

    /// Histogram intersection of two normalised histograms, in [0, 1].
    pub fn similarity(&self, other: &ColourHistogram) -> f32 {
        self.0
            .iter()
            .zip(other.0.iter())
            .map(|(a, b)| a.min(*b))
            .sum()
    }

    /// Centre-weighted histogram of an RGB image (3 bytes per pixel, row-major): the reference
    /// camera is aimed at the target, so the middle of the image is mostly the target (Gaussian
    /// weight, sigma = 1/8 of the width).
    pub fn centre_weighted(rgb: &[u8], width: u32, height: u32) -> Self {
        let mut h = ColourHistogram::default();
        let (cx, cy) = (width as f32 / 2.0, height as f32 / 2.0);
        let s2 = (width as f32 / 8.0).powi(2) * 2.0;
        for v in 0..height {
            for u in 0..width {
                let (dx, dy) = (u as f32 + 0.5 - cx, v as f32 + 0.5 - cy);
                let i = (v * width + u) as usize * 3;
                if let Some(px) = rgb.get(i..i + 3) {
                    h.add(px, (-(dx * dx + dy * dy) / s2).exp());
                }
            }
        }
        h.normalised()
    }

    /// The centre-weighted histogram of a reference image file (PNG).
    pub fn of_reference(path: &Path) -> Result<Self> {
        let img = image::open(path)
            .map_err(|e| {
                TaskError::invalid(
                    "reference_image",
                    path.display(),
                    format!("unreadable: {e}"),
                )
            })?
            .to_rgb8();
        Ok(Self::centre_weighted(
            img.as_raw(),
            img.width(),
            img.height(),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::{FRAC_PI_2, PI};

    #[test]
    fn reads_where_answers() {
        let (b, d) = parse_where(
            "The red mug on the table in the kitchen is on your left, about 4 metres away.",
        )
        .unwrap();
        assert!((b - FRAC_PI_2).abs() < 1e-6 && d == 4.0);
        let (b, d) =
            parse_where("The sofa here in this room is behind you, about a metre away.").unwrap();
        assert!((b - PI).abs() < 1e-6 && d == 1.0);
        assert_eq!(parse_where("I don't know of any mug in this home."), None);
    }

    #[test]
    fn reads_which_way_answers() {
        let legs = parse_which_way(
            "Turn left and go about 3 metres into the kitchen, then keep going about 2 metres, and ask again from there.",
        )
        .unwrap();
        assert_eq!(legs, vec![(FRAC_PI_2, 3.0), (0.0, 2.0)]);
        assert_eq!(
            parse_which_way("You are already there; stop here."),
            Some(vec![])
        );
        assert_eq!(
            parse_which_way("I cannot find a way to the goal from where you are."),
            None
        );
        // Facing -Z, a left turn heads to -X.
        let pts = route_points(Vec2::ZERO, 0.0, &legs);
        assert!(pts[0].distance(Vec2::new(-3.0, 0.0)) < 1e-4);
        assert!(pts[1].distance(Vec2::new(-5.0, 0.0)) < 1e-4);
    }

    #[test]
    fn reads_am_i_close_answers() {
        assert_eq!(
            parse_close("You are close, about 2 metres away."),
            Some(true)
        );
        assert_eq!(parse_close("Yes, you are there. Stop here."), Some(true));
        assert_eq!(
            parse_close("Not far now, about 5 metres away."),
            Some(false)
        );
        assert_eq!(
            parse_close("No, you are still far, about 9 metres away."),
            Some(false)
        );
        assert_eq!(parse_close("You have used all 5 of your questions"), None);
    }

    #[test]
    fn histograms_compare_colours() {
        let red: Vec<u8> = [250u8, 10, 10].repeat(64);
        let blue: Vec<u8> = [10u8, 10, 250].repeat(64);
        let r = ColourHistogram::centre_weighted(&red, 8, 8);
        let b = ColourHistogram::centre_weighted(&blue, 8, 8);
        assert!((r.similarity(&r) - 1.0).abs() < 1e-5);
        assert!(r.similarity(&b) < 1e-6);
    }
}
