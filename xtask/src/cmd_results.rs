//! `cargo xtask results [--check]`: every deterministic figure the docs quote, regenerated at
//! HEAD into the docs' marked blocks (`<!-- results:NAME -->` ... `<!-- /results:NAME -->`).
//! `configs/results.toml` lists the tables: the reference agents' rows of a results table
//! (evaluated again, fresh), the episodes per task and split, the dataset statistics. Each
//! table's preset is generated anew under `target/results/` unless `--dataset PRESET=DIR`
//! names one already generated at HEAD.
//!
//! Learned-model rows cannot be remade here: they stay as written, with the commit, checkpoint
//! and benchmark version they were made with, and a row of another
//! [`vlnverse_score::BENCHMARK_VERSION`] is marked stale. `--check` writes nothing and fails
//! naming every block, row and figure that differs (`old -> new`); `--ci` keeps to the tables
//! marked `ci = true`, which `cargo xtask test` checks.

mod blocks;
mod spec;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use clap::Parser as _;

use blocks::Table;
use spec::{Kind, TableSpec};
use vlnverse_score::report::RunSummary;
use vlnverse_task::generate::stats::{collect, DatasetStats, ValueStats};
use vlnverse_task::Task;

/// Arguments of `cargo xtask results`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Write nothing: fail when a table in the docs differs from what HEAD produces, naming the
    /// block, the row and the figures.
    #[arg(long)]
    pub check: bool,
    /// Only the tables CI checks (`ci = true`).
    #[arg(long)]
    pub ci: bool,
    /// Only these tables (comma-separated block names).
    #[arg(long, value_delimiter = ',')]
    pub only: Vec<String>,
    /// Use this dataset for a preset instead of generating it (`PRESET=DIR`; it must be what
    /// HEAD generates for the preset). Repeatable.
    #[arg(long, value_parser = parse_dataset)]
    pub dataset: Vec<(String, PathBuf)>,
    /// The table list.
    #[arg(long, default_value = "configs/results.toml")]
    pub spec: PathBuf,
    /// Work folder for the generated datasets and the evaluation runs.
    #[arg(long, default_value = "target/results")]
    pub work: PathBuf,
    /// Worker threads of generation and evaluation (default: all cores; the figures do not
    /// depend on it).
    #[arg(long)]
    pub threads: Option<usize>,
}

fn parse_dataset(s: &str) -> Result<(String, PathBuf), String> {
    match s.split_once('=') {
        Some((p, d)) if !p.is_empty() && !d.is_empty() => Ok((p.to_string(), d.into())),
        _ => Err(format!(
            "`{s}`: expected PRESET=DIR, e.g. vlnverse=datasets/vlnverse"
        )),
    }
}

/// The workspace root: relative paths of the command and the spec are read from it.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let t0 = Instant::now();
    let root = root();
    let at_root = |p: &Path| {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            root.join(p)
        }
    };
    let all = spec::load(&at_root(&args.spec))?;
    for name in &args.only {
        anyhow::ensure!(
            all.iter().any(|t| &t.name == name),
            "--only {name}: no such table in {} (there are: {})",
            args.spec.display(),
            all.iter()
                .map(|t| t.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let tables: Vec<&TableSpec> = all
        .iter()
        .filter(|t| !args.ci || t.ci)
        .filter(|t| args.only.is_empty() || args.only.contains(&t.name))
        .collect();
    let work = at_root(&args.work);
    let mut datasets: BTreeMap<String, PathBuf> = args.dataset.iter().cloned().collect();
    let mut stats: BTreeMap<String, DatasetStats> = BTreeMap::new();
    let mut contents: Vec<(&TableSpec, Table)> = Vec::new();
    for t in &tables {
        let dir = match datasets.get(&t.preset) {
            Some(d) => d.clone(),
            None => {
                let d = generate(&work, &t.preset, args.threads)?;
                datasets.insert(t.preset.clone(), d.clone());
                d
            }
        };
        let t1 = Instant::now();
        let page = read_page(&root, t)?;
        let old = blocks::find(&page, &t.name)
            .map(|r| page[r].to_string())
            .map_err(|e| anyhow::anyhow!("{}: {e}", t.file.display()))?;
        let table = match t.kind {
            Kind::Agents => agents_table(&root, &work, &dir, t, &old, args.threads)?,
            Kind::Episodes | Kind::Stats => {
                if !stats.contains_key(&t.preset) {
                    stats.insert(t.preset.clone(), collect(&dir)?);
                }
                let st = &stats[&t.preset];
                if t.kind == Kind::Episodes {
                    episodes_table(st)
                } else {
                    stats_table(st)
                }
            }
        };
        eprintln!("== {}: made in {:.1} s", t.name, t1.elapsed().as_secs_f64());
        contents.push((t, table));
    }
    let mut failures = Vec::new();
    let mut pages: BTreeMap<PathBuf, String> = BTreeMap::new();
    for (t, table) in &contents {
        let page = match pages.get(&t.file) {
            Some(p) => p.clone(),
            None => read_page(&root, t)?,
        };
        let diff = differences(&t.file, &t.name, &page, table)?;
        if diff.is_empty() {
            println!("{}: `{}` is up to date", t.file.display(), t.name);
            pages.insert(t.file.clone(), page);
            continue;
        }
        if args.check {
            failures.extend(diff);
        } else {
            for d in &diff {
                println!("{d}");
            }
        }
        let new = table.markdown();
        let updated = blocks::replace(&page, &t.name, &new).map_err(|e| anyhow::anyhow!("{e}"))?;
        pages.insert(t.file.clone(), updated);
    }
    if args.check {
        anyhow::ensure!(
            failures.is_empty(),
            "{} figure(s) in the docs differ from what HEAD produces (regenerate with `cargo \
             xtask results`):\n  {}",
            failures.len(),
            failures.join("\n  ")
        );
    } else {
        for (file, page) in &pages {
            let path = root.join(file);
            let before = std::fs::read_to_string(&path).unwrap_or_default();
            if &before != page {
                vlnverse_score::dataset::write_atomic(&path, page.as_bytes())?;
                println!("wrote {}", file.display());
            }
        }
    }
    println!(
        "{} table(s) {} in {:.0} s",
        contents.len(),
        if args.check { "checked" } else { "made" },
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}

/// What differs between block `name` of `page` (the docs file `file`) and `new`, one line per
/// row naming the file, the block, the row and the figures; empty when the block is `new`.
fn differences(file: &Path, name: &str, page: &str, new: &Table) -> anyhow::Result<Vec<String>> {
    let r = blocks::find(page, name).map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
    if page[r.clone()].trim() == new.markdown().trim() {
        return Ok(Vec::new());
    }
    let mut diff = blocks::differences(&Table::parse(&page[r], new.key_columns), new);
    if diff.is_empty() {
        diff.push("the block's text differs (layout)".into());
    }
    Ok(diff
        .into_iter()
        .map(|d| format!("{}, block `{name}`: {d}", file.display()))
        .collect())
}

fn read_page(root: &Path, t: &TableSpec) -> anyhow::Result<String> {
    let path = root.join(&t.file);
    std::fs::read_to_string(&path)
        .with_context(|| format!("table `{}`: {}", t.name, path.display()))
}

/// Generate `preset` afresh under `work/datasets/` (a leftover of an older HEAD is removed, not
/// resumed).
fn generate(work: &Path, preset: &str, threads: Option<usize>) -> anyhow::Result<PathBuf> {
    let out = work.join("datasets").join(preset);
    if out.exists() {
        std::fs::remove_dir_all(&out).with_context(|| format!("removing {}", out.display()))?;
    }
    eprintln!("== generating the `{preset}` preset into {}", out.display());
    let mut argv = vec![
        "generate".to_string(),
        "--preset".into(),
        preset.into(),
        "--out".into(),
    ];
    argv.push(out.display().to_string());
    if let Some(n) = threads {
        argv.extend(["--threads".into(), n.to_string()]);
    }
    crate::cmd_generate::run(parse::<crate::cmd_generate::Args>(&argv)?)?;
    Ok(out)
}

/// A subcommand's arguments parsed as its command line would be (so its defaults apply).
fn parse<A: clap::Args>(argv: &[String]) -> anyhow::Result<A> {
    #[derive(clap::Parser)]
    struct Cmd<A: clap::Args> {
        #[command(flatten)]
        args: A,
    }
    Ok(Cmd::<A>::try_parse_from(argv)
        .map_err(|e| anyhow::anyhow!("{}: {e}", argv.join(" ")))?
        .args)
}

const AGENT_HEADER: [&str; 15] = [
    "method",
    "training",
    "setting",
    "TL",
    "NE",
    "SR",
    "OSR",
    "SPL",
    "nDTW",
    "CR",
    "train wall time",
    "parameters",
    "commit",
    "checkpoint",
    "benchmark",
];

/// How the table names a built-in agent.
fn agent_label(agent: &str) -> String {
    match agent {
        "oracle" => "oracle (teacher)".into(),
        a => a.into(),
    }
}

/// The row of an evaluation's summary.
fn agent_row(agent: &str, setting: &str, run: &RunSummary) -> Vec<String> {
    let s = &run.summary;
    let pct = |v: f64| format!("{:.1}", 100.0 * v);
    vec![
        agent_label(agent),
        "-".into(),
        setting.into(),
        format!("{:.2}", s.tl),
        s.ne.map_or_else(|| "-".into(), |v| format!("{v:.2}")),
        pct(s.sr),
        pct(s.osr),
        pct(s.spl),
        pct(s.ndtw),
        format!("{:.3}", s.cr),
        "-".into(),
        "-".into(),
        "-".into(),
        "-".into(),
        vlnverse_score::BENCHMARK_VERSION.into(),
    ]
}

/// A learned-model row as the docs hold it, mapped onto the table's columns by name, its
/// benchmark cell marked stale when it is not this version.
fn recorded_row(old: &Table, row: &[String]) -> Vec<String> {
    let now = vlnverse_score::BENCHMARK_VERSION;
    AGENT_HEADER
        .iter()
        .map(|h| {
            let cell = old
                .header
                .iter()
                .position(|o| o == h)
                .and_then(|i| row.get(i))
                .cloned()
                .unwrap_or_else(|| "-".into());
            if *h != "benchmark" {
                return cell;
            }
            let v = cell.split_whitespace().next().unwrap_or("-");
            if v == now {
                v.to_string()
            } else {
                format!("{v} (**stale**: the benchmark is now {now})")
            }
        })
        .collect()
}

/// The reference agents evaluated afresh (one run per agent and setting), and the learned
/// rows of the docs' block after them, per setting.
fn agents_table(
    root: &Path,
    work: &Path,
    dataset: &Path,
    t: &TableSpec,
    old_block: &str,
    threads: Option<usize>,
) -> anyhow::Result<Table> {
    let old = Table::parse(old_block, 3);
    let builtin: Vec<String> = t.agents.iter().map(|a| agent_label(a)).collect();
    let learned: Vec<&Vec<String>> = old
        .rows
        .iter()
        .filter(|r| r.first().is_some_and(|m| !builtin.contains(m)))
        .collect();
    let setting_col = old.header.iter().position(|h| h == "setting");
    let mut table = Table::new(&AGENT_HEADER, 3);
    let (task, split) = (
        t.task.as_deref().unwrap_or(""),
        t.split.as_deref().unwrap_or(""),
    );
    let mut placed = vec![false; learned.len()];
    for setting in &t.settings {
        let label = spec::setting_label(setting).unwrap_or("?");
        for agent in &t.agents {
            let out = work
                .join("runs")
                .join(&t.name)
                .join(format!("{agent}-{setting}"));
            let mut argv: Vec<String> = ["evaluate", "--dataset"]
                .iter()
                .map(|s| s.to_string())
                .collect();
            argv.push(dataset.display().to_string());
            for (k, v) in [
                ("--task", task.to_string()),
                ("--split", split.to_string()),
                ("--agent", agent.clone()),
                ("--setting", setting.clone()),
                (
                    "--config",
                    root.join("configs/eval")
                        .join(format!("{setting}.toml"))
                        .display()
                        .to_string(),
                ),
                // The CPU rasteriser on every machine (`auto` picks it where there is no
                // hardware GPU), so the semantic agent sees the same pixels everywhere.
                ("--backend", "raster".into()),
                ("--seed", t.seed.to_string()),
                ("--out", out.display().to_string()),
            ] {
                argv.extend([k.to_string(), v]);
            }
            if let Some(n) = t.sample {
                argv.extend(["--sample".into(), n.to_string()]);
            }
            if let Some(n) = threads {
                argv.extend(["--threads".into(), n.to_string()]);
            }
            argv.push("--fresh".into());
            crate::cmd_evaluate::run(parse::<crate::cmd_evaluate::Args>(&argv)?)
                .with_context(|| format!("table `{}`: {}", t.name, argv.join(" ")))?;
            let path = out.join("summary.json");
            let bytes = std::fs::read(&path).with_context(|| path.display().to_string())?;
            let run: RunSummary = serde_json::from_slice(&bytes)
                .with_context(|| format!("{}: not a summary", path.display()))?;
            table.push(agent_row(agent, label, &run));
        }
        for (i, r) in learned.iter().enumerate() {
            if !placed[i] && setting_col.and_then(|c| r.get(c)).map(String::as_str) == Some(label) {
                table.push(recorded_row(&old, r));
                placed[i] = true;
            }
        }
    }
    for (i, r) in learned.iter().enumerate() {
        if !placed[i] {
            table.push(recorded_row(&old, r));
        }
    }
    Ok(table)
}

/// `1,234`.
fn thousands(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

fn episodes_table(st: &DatasetStats) -> Table {
    let splits = ["train", "val_seen", "val_unseen", "test"];
    let mut header = vec!["task"];
    header.extend(splits);
    header.push("all");
    let mut table = Table::new(&header, 1);
    for task in Task::ALL {
        let Some(per) = st.episodes.get(task.name()) else {
            continue;
        };
        let mut row = vec![task.name().to_string()];
        row.extend(
            splits
                .iter()
                .map(|s| thousands(per.get(*s).copied().unwrap_or(0))),
        );
        row.push(thousands(per.values().sum()));
        table.push(row);
    }
    table
}

fn stats_table(st: &DatasetStats) -> Table {
    let mut table = Table::new(&["figure", "value"], 1);
    let mut add = |k: String, v: String| table.push(vec![k, v]);
    let spread = |v: &ValueStats| {
        format!(
            "{:.1} / {:.1} ({:.1}-{:.1})",
            v.mean, v.median, v.p10, v.p90
        )
    };
    add("scenes".into(), thousands(st.rooms.len()));
    let area: Vec<f64> = st.navigable_m2.values().copied().collect();
    add(
        "navigable area per scene (m^2), mean / median (p10-p90)".into(),
        spread(&ValueStats::of(&area)),
    );
    let rooms: Vec<f64> = st.rooms.values().map(|&r| r as f64).collect();
    add(
        "rooms per scene, mean / median (p10-p90)".into(),
        spread(&ValueStats::of(&rooms)),
    );
    for task in Task::ALL {
        if let Some(v) = st.path_length.get(task.name()) {
            add(
                format!("path length, {} (m), mean / median (p10-p90)", task.name()),
                spread(&ValueStats::of(v)),
            );
        }
    }
    for task in Task::ALL {
        for (style, v) in st.instruction_words.get(task.name()).into_iter().flatten() {
            let name = if style == "all" {
                task.name().to_string()
            } else {
                format!("{}, {style}", task.name())
            };
            add(
                format!("instruction words, {name}, mean / median (p10-p90)"),
                spread(&ValueStats::of(v)),
            );
        }
    }
    add(
        "distinct words, all instructions".into(),
        thousands(st.word_vocabulary),
    );
    add(
        "object classes named as landmarks (grounded in all)".into(),
        format!(
            "{} ({})",
            st.landmark_classes.len(),
            st.grounded_classes.len()
        ),
    );
    for task in Task::ALL {
        if let Some((share, _)) = st.skeleton_share.get(task.name()) {
            add(
                format!("largest skeleton share, {}", task.name()),
                format!(
                    "{:.2}% ({} distinct skeletons)",
                    100.0 * share,
                    thousands(st.skeletons.get(task.name()).copied().unwrap_or(0))
                ),
            );
        }
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    fn summary(sr: f64) -> RunSummary {
        let mut s = vlnverse_score::Summary {
            episodes: 50,
            tl: 3.55,
            ne: Some(8.17),
            sr,
            osr: 0.1,
            spl: 0.071,
            ndtw: 0.382,
            cr: 0.021,
            ..Default::default()
        };
        s.sdtw = 0.05;
        RunSummary::with_summary(
            "semantic",
            Some("telhop"),
            Task::Fine,
            vlnverse_task::Split::ValUnseen,
            s,
            &[],
        )
    }

    #[test]
    fn learned_rows_of_another_benchmark_are_marked_stale() {
        let now = vlnverse_score::BENCHMARK_VERSION;
        let old = Table::parse(
            "| method | training | setting | SR | commit | benchmark |\n|---|---|---|---|---|---|\n\
             | CMA | offline | Tel-Hop | 10.0 | abc1234 | 0 |\n",
            3,
        );
        let row = recorded_row(&old, &old.rows[0]);
        assert_eq!(row[0], "CMA");
        assert_eq!(row[5], "10.0");
        assert_eq!(row[12], "abc1234");
        assert_eq!(row[10], "-", "a column the docs lack is empty");
        assert_eq!(
            row[14],
            format!("0 (**stale**: the benchmark is now {now})")
        );
        // Marking is idempotent, and a row of this version stays as it is.
        let mut again = Table::new(&AGENT_HEADER, 3);
        again.push(row.clone());
        assert_eq!(recorded_row(&again, &row), row);
        let mut current = row.clone();
        current[14] = now.into();
        assert_eq!(recorded_row(&again, &current)[14], now);
    }

    /// The real docs block, one reference-agent figure edited by hand: `--check`'s comparison
    /// names the block's row and the old and new numbers.
    #[test]
    fn check_names_a_deliberately_edited_row() {
        let root = root();
        let page = std::fs::read_to_string(root.join("docs/baselines.md")).unwrap();
        let name = "baselines-fine-val_unseen";
        let r = blocks::find(&page, name).unwrap();
        let head = Table::parse(&page[r.clone()], 3);
        let key = "semantic / - / Tel-Hop";
        let row = head
            .row(key)
            .expect("the table has the semantic Tel-Hop row")
            .clone();
        let sr_col = head.header.iter().position(|h| h == "SR").unwrap();
        let mut edited_row = row.clone();
        edited_row[sr_col] = "99.9".into();
        let edited_page = page.replacen(
            &format!("| {} |", row.join(" | ")),
            &format!("| {} |", edited_row.join(" | ")),
            1,
        );
        assert_ne!(edited_page, page);
        let file = Path::new("docs/baselines.md");
        assert!(differences(file, name, &page, &head).unwrap().is_empty());
        let diff = differences(file, name, &edited_page, &head).unwrap();
        assert_eq!(
            diff,
            vec![format!(
                "docs/baselines.md, block `{name}`: row `{key}`: SR 99.9 -> {}",
                row[sr_col]
            )]
        );
        // A row made from a summary has the table's layout and figures.
        let made = agent_row("semantic", "Tel-Hop", &summary(0.08));
        assert_eq!(made.len(), head.header.len());
        assert_eq!(
            &made[..10],
            &["semantic", "-", "Tel-Hop", "3.55", "8.17", "8.0", "10.0", "7.1", "38.2", "0.021"]
        );
    }

    #[test]
    fn counts_have_thousands_separators() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(825), "825");
        assert_eq!(thousands(3963), "3,963");
        assert_eq!(thousands(1234567), "1,234,567");
    }
}
