//! Seeded noise models. Each call takes the generator explicitly so that the rig can derive
//! one stream per (step, sensor) and stay deterministic whatever the call order.

use crate::config::Noise;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A standard normal sample (Box-Muller).
pub fn standard_normal(rng: &mut ChaCha8Rng) -> f32 {
    let u1: f32 = rng.random::<f32>().max(f32::MIN_POSITIVE);
    let u2: f32 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (std::f32::consts::TAU * u2).cos()
}

/// Add noise to sRGB bytes (Gaussian in 0..255 units; other models leave colour unchanged).
pub fn apply_rgb(noise: &Noise, rgb: &mut [u8], rng: &mut ChaCha8Rng) {
    if let Noise::Gaussian { stddev } = *noise {
        if stddev > 0.0 {
            for c in rgb {
                *c = (*c as f32 + stddev * standard_normal(rng))
                    .round()
                    .clamp(0.0, 255.0) as u8;
            }
        }
    }
}

/// Add noise to depth in metres; results stay in `[0, far]`. Pixels at `far` (no return) are
/// left alone.
pub fn apply_depth(noise: &Noise, depth: &mut [f32], far: f32, rng: &mut ChaCha8Rng) {
    match *noise {
        Noise::None => {}
        Noise::Gaussian { stddev } => {
            for d in depth.iter_mut().filter(|d| **d < far) {
                *d = (*d + stddev * standard_normal(rng)).clamp(0.0, far);
            }
        }
        Noise::Redwood { a, b, c, quantum } => {
            for d in depth.iter_mut().filter(|d| **d < far) {
                let z = *d;
                let sigma = a + b * (z - c) * (z - c);
                let mut n = z + sigma * standard_normal(rng);
                let q = quantum * z * z;
                if q > 0.0 {
                    n = (n / q).round() * q;
                }
                *d = n.clamp(0.0, far);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn gaussian_depth_noise_has_the_configured_spread_and_is_seeded() {
        let run = |seed| {
            let mut d = vec![2.0f32; 20_000];
            apply_depth(
                &Noise::Gaussian { stddev: 0.05 },
                &mut d,
                10.0,
                &mut ChaCha8Rng::seed_from_u64(seed),
            );
            d
        };
        let d = run(1);
        assert_eq!(d, run(1));
        assert_ne!(d, run(2));
        let mean = d.iter().sum::<f32>() / d.len() as f32;
        let sd = (d.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / d.len() as f32).sqrt();
        assert!((mean - 2.0).abs() < 0.003, "{mean}");
        assert!((sd - 0.05).abs() < 0.003, "{sd}");
    }

    #[test]
    fn redwood_noise_grows_with_distance() {
        let spread = |z: f32| {
            let mut d = vec![z; 20_000];
            apply_depth(
                &Noise::KINECT,
                &mut d,
                10.0,
                &mut ChaCha8Rng::seed_from_u64(3),
            );
            let mean = d.iter().sum::<f32>() / d.len() as f32;
            (d.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / d.len() as f32).sqrt()
        };
        let (near, far) = (spread(1.0), spread(5.0));
        assert!(far > 5.0 * near, "{near} {far}");
    }
}
