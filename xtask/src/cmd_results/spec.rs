//! `configs/results.toml`: which tables `cargo xtask results` makes, from what, into which
//! block of which docs file.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use serde::Deserialize;

/// What a table holds.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// The reference agents' rows of a results table (learned-model rows kept, checked for
    /// staleness).
    Agents,
    /// Episodes per task and split.
    Episodes,
    /// The dataset statistics of `xtask stats`.
    Stats,
}

/// One table.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableSpec {
    /// Block name: the markers are `<!-- results:NAME -->` and `<!-- /results:NAME -->`.
    pub name: String,
    /// Docs file, relative to the workspace root.
    pub file: PathBuf,
    /// What the table holds.
    pub kind: Kind,
    /// Dataset preset the figures come from.
    pub preset: String,
    /// Checked by CI (`results --check --ci`, run by `cargo xtask test`).
    #[serde(default)]
    pub ci: bool,
    /// `agents`: task.
    pub task: Option<String>,
    /// `agents`: split.
    pub split: Option<String>,
    /// `agents`: settings, in row order.
    #[serde(default)]
    pub settings: Vec<String>,
    /// `agents`: built-in agents, in row order.
    #[serde(default)]
    pub agents: Vec<String>,
    /// `agents`: `--sample N` (default: the whole split).
    pub sample: Option<usize>,
    /// `agents`: `--seed`.
    #[serde(default)]
    pub seed: u64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    table: Vec<TableSpec>,
}

/// The tables of `path`, checked: unique names, the fields each kind needs.
pub fn load(path: &Path) -> anyhow::Result<Vec<TableSpec>> {
    let text = std::fs::read_to_string(path).with_context(|| path.display().to_string())?;
    let file: File =
        toml::from_str(&text).map_err(|e| anyhow::anyhow!("{}: {}", path.display(), e))?;
    let mut names = std::collections::BTreeSet::new();
    for (i, t) in file.table.iter().enumerate() {
        let at = format!("{}: table[{i}] `{}`", path.display(), t.name);
        anyhow::ensure!(names.insert(&t.name), "{at}: the name is used twice");
        anyhow::ensure!(
            !t.name.is_empty()
                && t.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_".contains(c)),
            "{at}: a name is letters, digits, `-` and `_`"
        );
        if t.kind == Kind::Agents {
            anyhow::ensure!(
                t.task.is_some() && t.split.is_some(),
                "{at}: an `agents` table needs `task` and `split`"
            );
            anyhow::ensure!(
                !t.settings.is_empty() && !t.agents.is_empty(),
                "{at}: an `agents` table needs `settings` and `agents`"
            );
            for s in &t.settings {
                anyhow::ensure!(
                    setting_label(s).is_some(),
                    "{at}: setting `{s}`: expected strict, telhop or lenient"
                );
            }
        }
    }
    Ok(file.table)
}

/// How the docs write a setting.
pub fn setting_label(setting: &str) -> Option<&'static str> {
    match setting {
        "strict" => Some("Strict"),
        "telhop" => Some("Tel-Hop"),
        "lenient" => Some("Lenient"),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_spec_loads_and_bad_ones_are_refused() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let tables = load(&root.join("configs/results.toml")).unwrap();
        assert!(tables.iter().any(|t| t.ci), "CI checks at least one table");
        for t in &tables {
            assert!(root.join(&t.file).is_file(), "{}", t.file.display());
        }
        let d = tempfile::tempdir().unwrap();
        let f = d.path().join("results.toml");
        let base =
            "[[table]]\nname = \"a\"\nfile = \"x.md\"\nkind = \"agents\"\npreset = \"tiny\"\n";
        std::fs::write(&f, base).unwrap();
        let err = load(&f).unwrap_err().to_string();
        assert!(err.contains("`a`") && err.contains("task"), "{err}");
        std::fs::write(
            &f,
            format!("{base}task = \"fine\"\nsplit = \"test\"\nagents = [\"random\"]\nsettings = [\"fast\"]\n"),
        )
        .unwrap();
        let err = load(&f).unwrap_err().to_string();
        assert!(err.contains("fast"), "{err}");
        std::fs::write(&f, format!("{base}colour = 1\n")).unwrap();
        let err = load(&f).unwrap_err().to_string();
        assert!(err.contains("colour"), "{err}");
    }
}
