//! Feature statistics as LeRobot keeps them (`meta/stats.json`): min, max, mean, std, count
//! and the quantiles q01, q10, q50, q90, q99, per episode and then aggregated over episodes the
//! way LeRobot aggregates them (count-weighted means and quantiles, pooled variance).
//!
//! Per episode, low-dimensional features get exact statistics (quantiles by linear
//! interpolation, as NumPy's default); images get exact per-channel statistics from a
//! 256-bin histogram of their bytes (values / 255); depth gets exact min, max, mean and std and
//! quantiles from a histogram of 1/1000 m-normalised bins.

use serde::{Deserialize, Serialize};

/// The quantiles LeRobot computes.
pub const QUANTILES: [f64; 5] = [0.01, 0.10, 0.50, 0.90, 0.99];
/// Their keys in `stats.json`.
pub const QUANTILE_KEYS: [&str; 5] = ["q01", "q10", "q50", "q90", "q99"];

/// Statistics of one feature, one value per dimension (per channel for images).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Minimum.
    pub min: Vec<f64>,
    /// Maximum.
    pub max: Vec<f64>,
    /// Mean.
    pub mean: Vec<f64>,
    /// Standard deviation (population).
    pub std: Vec<f64>,
    /// Frames counted.
    pub count: u64,
    /// Quantiles, in the order of [`QUANTILES`].
    pub quantiles: Vec<Vec<f64>>,
}

/// Value at fractional rank `pos` of sorted `v` (linear interpolation).
fn interpolate(v: &[f64], pos: f64) -> f64 {
    let lo = pos.floor() as usize;
    let hi = (lo + 1).min(v.len() - 1);
    let t = pos - lo as f64;
    v[lo] + (v[hi] - v[lo]) * t
}

impl Stats {
    /// Exact statistics of `frames` rows of `dims` values each (row-major).
    pub fn exact(values: &[f64], dims: usize) -> Stats {
        let n = values.len().checked_div(dims).unwrap_or(0);
        let mut s = Stats {
            min: vec![f64::INFINITY; dims],
            max: vec![f64::NEG_INFINITY; dims],
            mean: vec![0.0; dims],
            std: vec![0.0; dims],
            count: n as u64,
            quantiles: vec![vec![0.0; dims]; QUANTILES.len()],
        };
        if n == 0 {
            return s;
        }
        let mut col = Vec::with_capacity(n);
        for d in 0..dims {
            col.clear();
            col.extend((0..n).map(|r| values[r * dims + d]));
            let mean = col.iter().sum::<f64>() / n as f64;
            let var = col.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
            col.sort_by(f64::total_cmp);
            s.min[d] = col[0];
            s.max[d] = col[n - 1];
            s.mean[d] = mean;
            s.std[d] = var.sqrt();
            for (k, q) in QUANTILES.iter().enumerate() {
                s.quantiles[k][d] = interpolate(&col, q * (n - 1) as f64);
            }
        }
        s
    }

    /// Statistics of one channel per histogram. `bin_value(b)` is the value bin `b` stands
    /// for; `sum`, `sum_sq`, `min`, `max` are exact per channel over `values` values; `frames`
    /// is the frame count reported.
    pub fn from_histograms(
        hists: &[Vec<u64>],
        bin_value: impl Fn(usize) -> f64,
        sum: &[f64],
        sum_sq: &[f64],
        min: &[f64],
        max: &[f64],
        frames: u64,
    ) -> Stats {
        let c = hists.len();
        let mut s = Stats {
            min: min.to_vec(),
            max: max.to_vec(),
            mean: vec![0.0; c],
            std: vec![0.0; c],
            count: frames,
            quantiles: vec![vec![0.0; c]; QUANTILES.len()],
        };
        for (ch, h) in hists.iter().enumerate() {
            let n: u64 = h.iter().sum();
            if n == 0 {
                continue;
            }
            let mean = sum[ch] / n as f64;
            s.mean[ch] = mean;
            s.std[ch] = (sum_sq[ch] / n as f64 - mean * mean).max(0.0).sqrt();
            // The value of the element of rank r (0-based) in sorted order.
            let at_rank = |r: u64| {
                let mut acc = 0;
                for (b, &k) in h.iter().enumerate() {
                    acc += k;
                    if acc > r {
                        return bin_value(b);
                    }
                }
                bin_value(h.len() - 1)
            };
            for (k, q) in QUANTILES.iter().enumerate() {
                let pos = q * (n - 1) as f64;
                let lo = pos.floor() as u64;
                let t = pos - lo as f64;
                let (a, b) = (at_rank(lo), at_rank((lo + 1).min(n - 1)));
                s.quantiles[k][ch] = a + (b - a) * t;
            }
        }
        s
    }

    /// Statistics over several episodes' statistics, as LeRobot's `aggregate_stats`:
    /// count-weighted mean and quantiles, pooled variance, elementwise min and max.
    pub fn aggregate(list: &[&Stats]) -> Option<Stats> {
        let first = list.first()?;
        let dims = first.mean.len();
        let total: u64 = list.iter().map(|s| s.count).sum();
        let mut out = Stats {
            min: vec![f64::INFINITY; dims],
            max: vec![f64::NEG_INFINITY; dims],
            mean: vec![0.0; dims],
            std: vec![0.0; dims],
            count: total,
            quantiles: vec![vec![0.0; dims]; QUANTILES.len()],
        };
        if total == 0 {
            return Some((*first).clone());
        }
        let w = |s: &Stats| s.count as f64 / total as f64;
        for d in 0..dims {
            let mean: f64 = list.iter().map(|s| s.mean[d] * w(s)).sum();
            let var: f64 = list
                .iter()
                .map(|s| (s.std[d] * s.std[d] + (s.mean[d] - mean).powi(2)) * w(s))
                .sum();
            out.mean[d] = mean;
            out.std[d] = var.max(0.0).sqrt();
            for s in list {
                out.min[d] = out.min[d].min(s.min[d]);
                out.max[d] = out.max[d].max(s.max[d]);
            }
            for k in 0..QUANTILES.len() {
                out.quantiles[k][d] = list.iter().map(|s| s.quantiles[k][d] * w(s)).sum();
            }
        }
        Some(out)
    }

    /// The `stats.json` entry: each statistic as a list (`[[[v]]]` per channel when
    /// `image`, as LeRobot's `(3, 1, 1)` image statistics); integers stay integers for `int`
    /// features' min and max.
    pub fn to_json(&self, image: bool, int: bool) -> serde_json::Value {
        use serde_json::{json, Value};
        let shape = |v: &[f64], int_ok: bool| -> Value {
            let one = |x: f64| -> Value {
                if int && int_ok && x.is_finite() {
                    json!(x as i64)
                } else {
                    json!(x)
                }
            };
            if image {
                Value::Array(v.iter().map(|&x| json!([[one(x)]])).collect())
            } else {
                Value::Array(v.iter().map(|&x| one(x)).collect())
            }
        };
        let mut m = serde_json::Map::new();
        m.insert("min".into(), shape(&self.min, true));
        m.insert("max".into(), shape(&self.max, true));
        m.insert("mean".into(), shape(&self.mean, false));
        m.insert("std".into(), shape(&self.std, false));
        m.insert("count".into(), json!([self.count]));
        for (k, key) in QUANTILE_KEYS.iter().enumerate() {
            m.insert((*key).into(), shape(&self.quantiles[k], false));
        }
        Value::Object(m)
    }
}

/// Per-channel accumulator over interleaved pixels (`channels` values per pixel) quantised
/// into `bins` bins over `[0, 1]`: exact sums, min and max; histogram for the quantiles.
#[derive(Debug, Clone)]
pub struct PixelAccumulator {
    channels: usize,
    bins: usize,
    hist: Vec<Vec<u64>>,
    sum: Vec<f64>,
    sum_sq: Vec<f64>,
    min: Vec<f64>,
    max: Vec<f64>,
    frames: u64,
}

impl PixelAccumulator {
    /// `channels` channels, `bins` bins (bin `b` stands for `b / (bins - 1)`).
    pub fn new(channels: usize, bins: usize) -> Self {
        PixelAccumulator {
            channels,
            bins,
            hist: vec![vec![0; bins]; channels],
            sum: vec![0.0; channels],
            sum_sq: vec![0.0; channels],
            min: vec![f64::INFINITY; channels],
            max: vec![f64::NEG_INFINITY; channels],
            frames: 0,
        }
    }

    /// Add one frame of 8-bit pixels (values / 255; needs 256 bins).
    pub fn add_u8(&mut self, px: &[u8]) {
        debug_assert_eq!(self.bins, 256);
        let c = self.channels;
        let mut sums = vec![0u64; c];
        let mut sq = vec![0u64; c];
        for (i, &v) in px.iter().enumerate() {
            let ch = i % c;
            self.hist[ch][v as usize] += 1;
            sums[ch] += u64::from(v);
            sq[ch] += u64::from(v) * u64::from(v);
        }
        for ch in 0..c {
            self.sum[ch] += sums[ch] as f64 / 255.0;
            self.sum_sq[ch] += sq[ch] as f64 / (255.0 * 255.0);
            let (mut lo, mut hi) = (u8::MAX, u8::MIN);
            for &v in px.iter().skip(ch).step_by(c) {
                lo = lo.min(v);
                hi = hi.max(v);
            }
            if !px.is_empty() {
                self.min[ch] = self.min[ch].min(f64::from(lo) / 255.0);
                self.max[ch] = self.max[ch].max(f64::from(hi) / 255.0);
            }
        }
        self.frames += 1;
    }

    /// Add one frame of values in `[0, 1]`.
    pub fn add_f32(&mut self, px: &[f32]) {
        let c = self.channels;
        let top = (self.bins - 1) as f32;
        for (i, &v) in px.iter().enumerate() {
            let ch = i % c;
            let b = (v.clamp(0.0, 1.0) * top).round() as usize;
            self.hist[ch][b] += 1;
            let x = f64::from(v);
            self.sum[ch] += x;
            self.sum_sq[ch] += x * x;
            self.min[ch] = self.min[ch].min(x);
            self.max[ch] = self.max[ch].max(x);
        }
        self.frames += 1;
    }

    /// The statistics of what was added.
    pub fn stats(&self) -> Stats {
        let top = (self.bins - 1) as f64;
        Stats::from_histograms(
            &self.hist,
            |b| b as f64 / top,
            &self.sum,
            &self.sum_sq,
            &self.min,
            &self.max,
            self.frames,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_matches_numpy_linear_quantiles() {
        // numpy.quantile([1, 2, 3, 4], 0.1) = 1.3; median 2.5.
        let s = Stats::exact(&[1.0, 2.0, 3.0, 4.0], 1);
        assert!((s.quantiles[1][0] - 1.3).abs() < 1e-12);
        assert!((s.quantiles[2][0] - 2.5).abs() < 1e-12);
        assert_eq!((s.min[0], s.max[0], s.count), (1.0, 4.0, 4));
        assert!((s.std[0] - 1.25f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn u8_histogram_equals_exact() {
        let px: Vec<u8> = (0..300u32).map(|i| ((i * 37) % 256) as u8).collect();
        let mut acc = PixelAccumulator::new(1, 256);
        acc.add_u8(&px);
        let h = acc.stats();
        let vals: Vec<f64> = px.iter().map(|&v| f64::from(v) / 255.0).collect();
        let e = Stats::exact(&vals, 1);
        for k in 0..5 {
            assert!(
                (h.quantiles[k][0] - e.quantiles[k][0]).abs() < 1e-12,
                "q{k}"
            );
        }
        assert!((h.mean[0] - e.mean[0]).abs() < 1e-12);
        assert!((h.std[0] - e.std[0]).abs() < 1e-9);
        assert_eq!((h.min[0], h.max[0]), (e.min[0], e.max[0]));
    }

    #[test]
    fn aggregate_pools_mean_and_variance() {
        let a = Stats::exact(&[0.0, 2.0], 1);
        let b = Stats::exact(&[4.0, 6.0, 8.0, 10.0], 1);
        let all = Stats::exact(&[0.0, 2.0, 4.0, 6.0, 8.0, 10.0], 1);
        let g = Stats::aggregate(&[&a, &b]).unwrap();
        assert!((g.mean[0] - all.mean[0]).abs() < 1e-12);
        assert!((g.std[0] - all.std[0]).abs() < 1e-12);
        assert_eq!((g.min[0], g.max[0], g.count), (0.0, 10.0, 6));
    }
}
