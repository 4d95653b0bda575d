//! Result files of a run (`cargo xtask score` and `cargo xtask evaluate` write the same ones):
//! - `summary.json`: [`RunSummary`], the [`Summary`] keys at top level (`episodes, tl, ne, sr,
//!   osr, spl, ndtw, sdtw, cr`, `sr_1..sr_3, sr_all` for long-horizon) plus method, setting,
//!   task, split and a per-style breakdown;
//! - `episodes.csv`: one row per episode, every metric ([`episodes_csv`]);
//! - `report.md`: a markdown table laid out like the paper's tables ([`markdown_table`]).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::dataset::write_atomic;
use crate::episode::{Split, Task};
use crate::error::{DataError, Result};
use crate::metrics::{aggregate, aggregate_by, EpisodeMetrics, Summary};

/// Content of `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Agent or method name (a row label of the table).
    pub method: String,
    /// Evaluation setting (`strict`, `telhop`, `lenient`), when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub setting: Option<String>,
    /// Task of the split.
    pub task: Task,
    /// Split.
    pub split: Split,
    /// The metrics over all episodes (keys at top level).
    #[serde(flatten)]
    pub summary: Summary,
    /// The same per instruction style (coarse-grained tasks).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub by_style: BTreeMap<String, Summary>,
    /// [`crate::BENCHMARK_VERSION`] of the code that scored the run (absent in runs scored
    /// before it existed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub benchmark_version: Option<String>,
}

impl RunSummary {
    /// Aggregate episode metrics of one task and split.
    pub fn new(
        method: &str,
        setting: Option<&str>,
        task: Task,
        split: Split,
        ms: &[EpisodeMetrics],
    ) -> Self {
        Self::with_summary(method, setting, task, split, aggregate(ms), ms)
    }

    /// [`RunSummary::new`] with the metrics' summary already aggregated (as
    /// [`crate::Scored`] holds it).
    pub fn with_summary(
        method: &str,
        setting: Option<&str>,
        task: Task,
        split: Split,
        summary: Summary,
        ms: &[EpisodeMetrics],
    ) -> Self {
        RunSummary {
            method: method.to_string(),
            setting: setting.map(str::to_string),
            task,
            split,
            summary,
            by_style: aggregate_by(ms, |m| m.style.map(|s| s.to_string())),
            benchmark_version: Some(crate::BENCHMARK_VERSION.to_string()),
        }
    }
}

/// One row of a results table.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportRow {
    /// Method / agent name.
    pub method: String,
    /// Setting (Strict, Tel-Hop, ...); `-` when empty.
    pub setting: Option<String>,
    /// The metrics.
    pub summary: Summary,
}

/// Header of `episodes.csv`.
pub const CSV_HEADER: &str = "episode_id,trajectory_id,scene_id,task,split,style,geodesic_distance,tl,ne,oracle_ne,success,oracle_success,spl,ndtw,sdtw,collisions,steps,cr,stuck,unreachable,sub_goals,sub_goals_reached";

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn opt<T: ToString>(v: Option<T>) -> String {
    v.map(|v| v.to_string()).unwrap_or_default()
}

/// `episodes.csv`: the header and one row per episode (empty cell = not available, e.g. NE of
/// an unreachable goal; booleans as 0/1).
pub fn episodes_csv(ms: &[EpisodeMetrics]) -> String {
    let mut s = String::with_capacity(128 * (ms.len() + 1));
    s.push_str(CSV_HEADER);
    s.push('\n');
    let b = |x: bool| if x { "1" } else { "0" };
    for m in ms {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            m.episode_id,
            m.trajectory_id,
            csv_field(&m.scene_id),
            m.task,
            opt(m.split),
            opt(m.style),
            m.geodesic_distance,
            m.tl,
            opt(m.ne),
            opt(m.oracle_ne),
            b(m.success),
            b(m.oracle_success),
            m.spl,
            m.ndtw,
            m.sdtw,
            m.collisions,
            m.steps,
            m.cr,
            opt(m.stuck.map(b)),
            b(m.unreachable),
            m.sub_goals,
            m.sub_goals_reached,
        );
    }
    s
}

/// A markdown table laid out like the paper's: rows = method / setting, columns TL NE SR OSR SPL
/// nDTW CR (and SR1 SR2 SR3 SR-All when a row has long-horizon numbers); rates, CR included, in
/// percent (the header says `CR (%)`).
pub fn markdown_table(rows: &[ReportRow]) -> String {
    let lh = rows.iter().any(|r| r.summary.sr_1.is_some());
    let mut s =
        String::from("| Method | Setting | TL | NE↓ | SR↑ | OSR↑ | SPL↑ | nDTW↑ | CR (%)↓ |");
    let mut rule = String::from("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    if lh {
        s.push_str(" SR1↑ | SR2↑ | SR3↑ | SR-All↑ |");
        rule.push_str("---:|---:|---:|---:|");
    }
    s.push('\n');
    s.push_str(&rule);
    s.push('\n');
    let pct = |v: f64| format!("{:.2}", 100.0 * v);
    let pct_opt = |v: Option<f64>| v.map_or_else(|| "-".to_string(), pct);
    for r in rows {
        let m = &r.summary;
        let _ = write!(
            s,
            "| {} | {} | {:.2} | {} | {} | {} | {} | {} | {} |",
            r.method.replace('|', "\\|"),
            r.setting.as_deref().unwrap_or("-").replace('|', "\\|"),
            m.tl,
            m.ne.map_or_else(|| "-".to_string(), |v| format!("{v:.2}")),
            pct(m.sr),
            pct(m.osr),
            pct(m.spl),
            pct(m.ndtw),
            pct(m.cr),
        );
        if lh {
            let _ = write!(
                s,
                " {} | {} | {} | {} |",
                pct_opt(m.sr_1),
                pct_opt(m.sr_2),
                pct_opt(m.sr_3),
                pct_opt(m.sr_all)
            );
        }
        s.push('\n');
    }
    s
}

/// `report.md` of one run: the main table, a per-style table when there are styles, and the
/// counts a reader needs to trust the means.
pub fn markdown_report(run: &RunSummary) -> String {
    let mut s = format!("# {} on {} / {}\n\n", run.method, run.task, run.split);
    s.push_str(&markdown_table(&[ReportRow {
        method: run.method.clone(),
        setting: run.setting.clone(),
        summary: run.summary.clone(),
    }]));
    if !run.by_style.is_empty() {
        s.push_str("\nPer instruction style:\n\n");
        let rows: Vec<ReportRow> = run
            .by_style
            .iter()
            .map(|(style, sum)| ReportRow {
                method: run.method.clone(),
                setting: Some(style.clone()),
                summary: sum.clone(),
            })
            .collect();
        s.push_str(&markdown_table(&rows));
    }
    let m = &run.summary;
    let _ = write!(
        s,
        "\n{} episodes; {} with the goal unreachable from the final position (left out of NE); \
         mean steps {:.1}; SDTW {:.2}%; oracle NE {}.\n\
         SR, OSR, SPL, nDTW, SDTW and CR in percent (summary.json and episodes.csv hold \
         fractions); TL and NE in metres; CR (%) = noticeable collisions per 100 actions over \
         all episodes (the paper's definition); per-episode mean CR {:.2}%.\n",
        m.episodes,
        m.unreachable,
        m.steps,
        100.0 * m.sdtw,
        m.oracle_ne
            .map_or_else(|| "-".to_string(), |v| format!("{v:.2} m")),
        100.0 * m.cr_episode_mean,
    );
    s
}

/// Write `summary.json`, `episodes.csv` and `report.md` into `dir` (created if needed), each
/// atomically.
pub fn write_run(dir: &Path, run: &RunSummary, ms: &[EpisodeMetrics]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| DataError::io(dir, e))?;
    let mut json = serde_json::to_string_pretty(run)
        .map_err(|e| DataError::invalid("summary", &run.method, e.to_string()))?;
    json.push('\n');
    write_atomic(&dir.join("summary.json"), json.as_bytes())?;
    write_atomic(&dir.join("episodes.csv"), episodes_csv(ms).as_bytes())?;
    write_atomic(&dir.join("report.md"), markdown_report(run).as_bytes())?;
    Ok(())
}

/// The benchmark version a run folder records (`run.json`, else `summary.json`): `None` when it
/// holds neither file or neither can be read, `Some(None)` for a run made before the version
/// was recorded.
pub fn recorded_version(dir: &Path) -> Option<Option<String>> {
    ["run.json", "summary.json"].iter().find_map(|f| {
        let bytes = std::fs::read(dir.join(f)).ok()?;
        let v: serde_json::Value = serde_json::from_slice(&bytes).ok()?;
        Some(
            v.get("benchmark_version")
                .and_then(|b| b.as_str())
                .map(str::to_string),
        )
    })
}

/// A warning when the run in `dir` was made at another benchmark version than this code's
/// [`crate::BENCHMARK_VERSION`] (its figures are not comparable with a run of this version).
pub fn version_warning(dir: &Path) -> Option<String> {
    let now = crate::BENCHMARK_VERSION;
    match recorded_version(dir)? {
        Some(v) if v == now => None,
        Some(v) => Some(format!(
            "{}: the run was made at benchmark version {v}, this is version {now}: its results \
             are not comparable with runs of this version",
            dir.display()
        )),
        None => Some(format!(
            "{}: the run records no benchmark version (made before version 1), this is version \
             {now}: its results are not comparable with runs of this version",
            dir.display()
        )),
    }
}

#[cfg(test)]
mod version_tests {
    use super::*;

    #[test]
    fn runs_of_another_or_no_version_are_flagged() {
        let d = tempfile::tempdir().unwrap();
        assert_eq!(version_warning(d.path()), None);
        let write = |json: &str| std::fs::write(d.path().join("summary.json"), json).unwrap();
        write(&format!(
            r#"{{"benchmark_version": "{}"}}"#,
            crate::BENCHMARK_VERSION
        ));
        assert_eq!(version_warning(d.path()), None);
        write(r#"{"benchmark_version": "0.9"}"#);
        let w = version_warning(d.path()).unwrap();
        assert!(w.contains("version 0.9"), "{w}");
        write(r#"{"method": "cma"}"#);
        let w = version_warning(d.path()).unwrap();
        assert!(w.contains("no benchmark version"), "{w}");
        // run.json is read first.
        std::fs::write(
            d.path().join("run.json"),
            format!(r#"{{"benchmark_version": "{}"}}"#, crate::BENCHMARK_VERSION),
        )
        .unwrap();
        assert_eq!(version_warning(d.path()), None);
    }
}
