//! `cargo xtask bench`: a quick, fixed suite over the hot paths (scene generation, geodesic
//! queries, simulator steps, rendering, metrics, episode generation). Each case runs a fixed
//! amount of work several times and the table shows the median with the range; `--json` keeps
//! the figures for comparing runs. The criterion benches (`cargo bench -p CRATE`) remain the
//! place for careful measurements; this is the one-command overview.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use serde::Serialize;

mod cases;

/// Arguments of `cargo xtask bench`.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct Args {
    /// Smaller workloads and 3 repetitions (a second or two instead of five to ten).
    #[arg(long)]
    pub quick: bool,
    /// Run only the cases whose name contains one of these words (comma-separated), e.g.
    /// `geodesic,raster`; `--list` names the cases.
    #[arg(long, value_delimiter = ',')]
    pub filter: Vec<String>,
    /// Write the figures (medians, ranges, every repetition) as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Repetitions of each case (default 5, or 3 with `--quick`); the median is reported.
    #[arg(long)]
    pub reps: Option<usize>,
    /// List the cases and exit.
    #[arg(long)]
    pub list: bool,
}

/// How a figure reads: a time per item (lower is better) or a rate (higher is better).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Seconds per `item`.
    Time {
        /// What one measured item is (`home`, `field`, ...).
        per: &'static str,
    },
    /// `unit` per second (`steps`, `frames`, ...).
    Rate {
        /// What is counted.
        unit: &'static str,
    },
    /// Bytes per `item` (memory held; lower is better).
    Size {
        /// What one measured item is (`home`, ...).
        per: &'static str,
    },
    /// A plain ratio of two figures of the same repetition (see the detail).
    Ratio,
}

/// One figure from one repetition of a case.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Figure name, `case/what`.
    pub name: String,
    /// Seconds per item, or items per second (see `kind`).
    pub value: f64,
    /// How `value` reads.
    pub kind: Kind,
    /// The work of one repetition, for people.
    pub detail: String,
}

impl Sample {
    /// Seconds per item: `seconds` spent on `items` items.
    pub fn time(name: &str, seconds: f64, items: usize, per: &'static str, detail: String) -> Self {
        Sample {
            name: name.into(),
            value: seconds / items.max(1) as f64,
            kind: Kind::Time { per },
            detail,
        }
    }

    /// Bytes per item: `bytes` held by `items` items.
    pub fn size(name: &str, bytes: usize, items: usize, per: &'static str, detail: String) -> Self {
        Sample {
            name: name.into(),
            value: bytes as f64 / items.max(1) as f64,
            kind: Kind::Size { per },
            detail,
        }
    }

    /// A ratio of two figures measured in the same repetition.
    pub fn ratio(name: &str, ratio: f64, detail: String) -> Self {
        Sample {
            name: name.into(),
            value: ratio,
            kind: Kind::Ratio,
            detail,
        }
    }

    /// Items per second: `items` done in `seconds`.
    pub fn rate(name: &str, items: f64, seconds: f64, unit: &'static str, detail: String) -> Self {
        Sample {
            name: name.into(),
            value: items / seconds.max(1e-12),
            kind: Kind::Rate { unit },
            detail,
        }
    }
}

/// Workload size of the suite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Scale {
    /// `--quick`: smaller workloads.
    pub quick: bool,
}

impl Scale {
    /// `full` items normally, `quick` items with `--quick`.
    pub fn pick(&self, full: usize, quick: usize) -> usize {
        if self.quick {
            quick
        } else {
            full
        }
    }
}

/// One repetition of a case: runs its fixed work and returns its figures.
pub type Repetition = Box<dyn FnMut() -> anyhow::Result<Vec<Sample>>>;

/// A case of the suite.
pub struct Case {
    /// Name matched by `--filter`; prefix of its figure names.
    pub name: &'static str,
    /// What it measures, for `--list`.
    pub what: &'static str,
    /// At most this many repetitions (for the slow cases).
    pub max_reps: usize,
    /// Build the fixtures (not timed) and return one repetition.
    pub setup: fn(Scale) -> anyhow::Result<Repetition>,
}

/// A figure summarised over the repetitions (what the table and the JSON file show).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Figure {
    /// `case/what`.
    pub name: String,
    /// Median over the repetitions.
    pub median: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Every repetition, in order.
    pub samples: Vec<f64>,
    /// How the values read (seconds per item, or items per second).
    pub kind: Kind,
    /// The work of one repetition.
    pub detail: String,
}

/// What `--json` writes.
#[derive(Debug, Serialize)]
struct Report<'a> {
    /// Format version of this file.
    format_version: u32,
    quick: bool,
    reps: usize,
    /// Hardware threads of the machine.
    threads: usize,
    /// Threads of rayon's global pool (what the parallel cases use).
    rayon_threads: usize,
    /// The rasteriser's copy of its fill and resolve (`avx2` or `baseline`).
    raster_copy: &'static str,
    seconds: f64,
    figures: &'a [Figure],
}

/// The cases selected by `filter` (every case when it is empty); a word matching no case is an
/// error that lists the names.
pub fn select<'a>(cases: &'a [Case], filter: &[String]) -> anyhow::Result<Vec<&'a Case>> {
    let words: Vec<&str> = filter
        .iter()
        .map(|w| w.trim())
        .filter(|w| !w.is_empty())
        .collect();
    if words.is_empty() {
        return Ok(cases.iter().collect());
    }
    let names = || cases.iter().map(|c| c.name).collect::<Vec<_>>().join(", ");
    for w in &words {
        anyhow::ensure!(
            cases.iter().any(|c| c.name.contains(w)),
            "--filter `{w}` matches no case (cases: {})",
            names()
        );
    }
    Ok(cases
        .iter()
        .filter(|c| words.iter().any(|w| c.name.contains(w)))
        .collect())
}

/// Median of the values (mean of the two middle ones for an even count); NaN when empty.
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// Group the samples of all repetitions by figure name (first-seen order) and summarise them.
pub fn summarise(reps: &[Vec<Sample>]) -> Vec<Figure> {
    let mut out: Vec<Figure> = Vec::new();
    for s in reps.iter().flatten() {
        match out.iter_mut().find(|f| f.name == s.name) {
            Some(f) => f.samples.push(s.value),
            None => out.push(Figure {
                name: s.name.clone(),
                median: 0.0,
                min: 0.0,
                max: 0.0,
                samples: vec![s.value],
                kind: s.kind,
                detail: s.detail.clone(),
            }),
        }
    }
    for f in &mut out {
        f.median = median(&f.samples);
        f.min = f.samples.iter().copied().fold(f64::INFINITY, f64::min);
        f.max = f.samples.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    }
    out
}

/// Three significant digits with a k/M/G suffix: `1.23 M`, `456`, `0.0123`.
pub fn si(v: f64) -> String {
    let (x, suffix) = match v.abs() {
        a if a >= 1e9 => (v / 1e9, " G"),
        a if a >= 1e6 => (v / 1e6, " M"),
        a if a >= 1e4 => (v / 1e3, " k"),
        _ => (v, " "),
    };
    let digits = match x.abs() {
        a if a >= 100.0 => 0,
        a if a >= 10.0 => 1,
        a if a >= 1.0 => 2,
        _ => 3,
    };
    format!("{x:.digits$}{suffix}")
}

/// A duration in s, ms or µs with three significant digits.
pub fn duration(seconds: f64) -> String {
    let (x, unit) = match seconds.abs() {
        a if a >= 1.0 => (seconds, "s"),
        a if a >= 1e-3 => (seconds * 1e3, "ms"),
        _ => (seconds * 1e6, "µs"),
    };
    format!("{}{unit}", si(x))
}

/// A value of a figure with its unit.
pub fn format_value(v: f64, kind: Kind) -> String {
    match kind {
        Kind::Time { per } => format!("{}/{per}", duration(v)),
        Kind::Rate { unit } => format!("{} {unit}/s", si(v).trim_end()),
        Kind::Size { per } => format!("{}B/{per}", si(v)),
        Kind::Ratio => format!("{v:.3}x"),
    }
}

fn print_row(f: &Figure) {
    let range = match f.kind {
        Kind::Time { .. } => format!("{} .. {}", duration(f.min), duration(f.max)),
        Kind::Ratio => format!("{:.3} .. {:.3}", f.min, f.max),
        Kind::Rate { .. } | Kind::Size { .. } => {
            format!("{} .. {}", si(f.min).trim_end(), si(f.max).trim_end())
        }
    };
    println!(
        "{:<27} {:>20}  {:>22}  {}",
        f.name,
        format_value(f.median, f.kind),
        range,
        f.detail
    );
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let all = cases::all();
    if args.list {
        for c in &all {
            println!("{:<10} {}", c.name, c.what);
        }
        return Ok(());
    }
    let selected = select(&all, &args.filter)?;
    let scale = Scale { quick: args.quick };
    let reps = args.reps.unwrap_or(if args.quick { 3 } else { 5 });
    anyhow::ensure!(
        (1..=100).contains(&reps),
        "--reps {reps}: expected 1 to 100"
    );
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let rayon_threads = rayon::current_num_threads();
    let raster_copy = vlnverse_sensors::raster::copy_in_use();
    println!(
        "bench: {} case(s), median of {reps} repetitions{} on {threads} hardware threads \
         (rayon pool {rayon_threads}, rasteriser copy {raster_copy}); figures vary with \
         machine load, compare runs on the same idle machine",
        selected.len(),
        if args.quick { " (quick)" } else { "" },
    );
    println!(
        "{:<27} {:>20}  {:>22}  work per repetition",
        "figure", "median", "range"
    );
    let start = Instant::now();
    let mut figures = Vec::new();
    for case in selected {
        tracing::debug!("bench case {}", case.name);
        let mut rep = (case.setup)(scale).with_context(|| format!("case `{}`", case.name))?;
        let n = reps.min(case.max_reps).max(1);
        let samples = (0..n)
            .map(|_| rep())
            .collect::<anyhow::Result<Vec<_>>>()
            .with_context(|| format!("case `{}`", case.name))?;
        for f in summarise(&samples) {
            print_row(&f);
            figures.push(f);
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    println!("bench: done in {seconds:.1} s");
    if let Some(path) = &args.json {
        let report = Report {
            format_version: 1,
            quick: args.quick,
            reps,
            threads,
            rayon_threads,
            raster_copy,
            seconds,
            figures: &figures,
        };
        let text = serde_json::to_string_pretty(&report)?;
        std::fs::write(path, text + "\n")
            .with_context(|| format!("cannot write --json {}", path.display()))?;
        println!("bench: figures -> {}", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(name: &'static str) -> Case {
        Case {
            name,
            what: "",
            max_reps: 1,
            setup: |_| Ok(Box::new(|| Ok(vec![]))),
        }
    }

    #[test]
    fn filter_selects_by_substring_and_names_unknown_words() {
        let cases = [
            case("scene"),
            case("geodesic"),
            case("raster"),
            case("raycast"),
        ];
        let names = |f: &[&str]| {
            let f: Vec<String> = f.iter().map(|s| s.to_string()).collect();
            select(&cases, &f).map(|v| v.iter().map(|c| c.name).collect::<Vec<_>>())
        };
        assert_eq!(names(&[]).unwrap().len(), 4);
        assert_eq!(names(&[" "]).unwrap().len(), 4);
        assert_eq!(names(&["ra"]).unwrap(), ["raster", "raycast"]);
        assert_eq!(names(&["raycast", "scene"]).unwrap(), ["scene", "raycast"]);
        let err = names(&["geo", "physics"]).unwrap_err().to_string();
        assert!(
            err.contains("`physics`") && err.contains("scene, geodesic"),
            "{err}"
        );
    }

    #[test]
    fn args_parse_filter_list_and_flags() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            args: Args,
        }
        let a = Cli::parse_from([
            "x",
            "--quick",
            "--filter",
            "sim,metrics",
            "--json",
            "f.json",
        ]);
        assert!(a.args.quick && !a.args.list);
        assert_eq!(a.args.filter, ["sim", "metrics"]);
        assert_eq!(a.args.json, Some(PathBuf::from("f.json")));
        assert!(Cli::try_parse_from(["x", "--reps", "many"]).is_err());
    }

    #[test]
    fn every_shipped_case_has_a_distinct_name() {
        let all = cases::all();
        for (i, c) in all.iter().enumerate() {
            assert!(all[..i].iter().all(|d| d.name != c.name), "{}", c.name);
            assert!(!c.what.is_empty() && c.max_reps >= 1, "{}", c.name);
        }
    }

    #[test]
    fn summary_is_the_median_and_range_per_figure() {
        let s = |name: &str, v: f64| Sample::rate(name, v, 1.0, "q", String::new());
        let reps = vec![
            vec![s("a", 3.0), s("b", 10.0)],
            vec![s("a", 1.0), s("b", 30.0)],
            vec![s("a", 2.0), s("b", 20.0)],
            vec![s("a", 8.0), s("b", 40.0)],
        ];
        let f = summarise(&reps);
        assert_eq!(f.len(), 2);
        assert_eq!((f[0].name.as_str(), f[0].median), ("a", 2.5));
        assert_eq!((f[0].min, f[0].max), (1.0, 8.0));
        assert_eq!(f[1].median, 25.0);
        assert_eq!(f[1].samples, [10.0, 30.0, 20.0, 40.0]);
        assert!(median(&[]).is_nan());
        assert_eq!(median(&[5.0]), 5.0);
    }

    #[test]
    fn values_print_with_units() {
        assert_eq!(si(1_234_567.0), "1.23 M");
        assert_eq!(si(45_600.0), "45.6 k");
        assert_eq!(si(987.0), "987 ");
        assert_eq!(duration(0.000_812), "812 µs");
        assert_eq!(duration(0.0123), "12.3 ms");
        assert_eq!(
            format_value(0.0123, Kind::Time { per: "home" }),
            "12.3 ms/home"
        );
        assert_eq!(
            format_value(2.0e6, Kind::Rate { unit: "rays" }),
            "2.00 M rays/s"
        );
    }
}
