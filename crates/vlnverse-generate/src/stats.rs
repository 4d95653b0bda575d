//! Dataset statistics as in the paper: navigable area and rooms per scene, path lengths per
//! task, instruction lengths per task and style, landmark vocabulary, and how varied the
//! language is (distinct words; the largest share of a task's instructions that one sentence
//! skeleton covers). Written as PNG charts (drawn here with the env crate's 8x8 font, no
//! plotting crate) and a markdown summary; [`samples_markdown`] draws seeded random
//! instructions per task and style for reading; [`naturalness`] measures the wording against
//! human instructions (`xtask stats --reference`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use image::{Rgb, RgbImage};
use serde::Serialize;
use vlnverse_env::io::json::scene_from_json;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::topdown::{draw_text, text_width};

use vlnverse_score::dataset::{read_split, split_path, write_atomic};
use vlnverse_score::episode::{Role, Split, Task};
use vlnverse_score::{DataError, Result};

mod naturalness;
pub use naturalness::{naturalness, GroupNaturalness, Naturalness};

/// Summary numbers of a list of values.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ValueStats {
    /// Count.
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// Minimum.
    pub min: f64,
    /// Median.
    pub median: f64,
    /// Maximum.
    pub max: f64,
    /// 10th percentile.
    pub p10: f64,
    /// 90th percentile.
    pub p90: f64,
}

impl ValueStats {
    /// Summary of `values` (all zero when empty).
    pub fn of(values: &[f64]) -> ValueStats {
        if values.is_empty() {
            return ValueStats::default();
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        ValueStats {
            n: v.len(),
            mean: v.iter().sum::<f64>() / v.len() as f64,
            min: v[0],
            median: v[v.len() / 2],
            max: v[v.len() - 1],
            p10: v[v.len() / 10],
            p90: v[(v.len() * 9 / 10).min(v.len() - 1)],
        }
    }
}

/// Statistics of a dataset folder.
#[derive(Clone, Debug, Default, Serialize)]
pub struct DatasetStats {
    /// Navigable area per scene (m^2), by scene id.
    pub navigable_m2: BTreeMap<String, f64>,
    /// Rooms per scene, by scene id.
    pub rooms: BTreeMap<String, usize>,
    /// Objects per scene besides structure (walls, floors, ceilings, windows, door frames) and
    /// doors, by scene id.
    pub objects: BTreeMap<String, usize>,
    /// Classes of those objects, over all scenes.
    pub object_classes: BTreeSet<String>,
    /// Episodes per task and split.
    pub episodes: BTreeMap<String, BTreeMap<String, usize>>,
    /// Geodesic path lengths (m) per task.
    pub path_length: BTreeMap<String, Vec<f64>>,
    /// Instruction lengths (words) per task and style (`all` for every style).
    pub instruction_words: BTreeMap<String, BTreeMap<String, Vec<f64>>>,
    /// Classes of the grounded landmark objects, over all tasks.
    pub landmark_classes: BTreeSet<String>,
    /// Classes of all grounded objects (landmarks, targets, references).
    pub grounded_classes: BTreeSet<String>,
    /// Distinct lower-case words over all instructions.
    pub word_vocabulary: usize,
    /// Per task: the largest share (0..1) of its instructions that one sentence skeleton
    /// covers (see [`skeleton`]), and that skeleton.
    pub skeleton_share: BTreeMap<String, (f64, String)>,
    /// Per task: distinct skeletons.
    pub skeletons: BTreeMap<String, usize>,
    /// Perplexity and OOV share against human instructions, when a reference was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub naturalness: Option<Naturalness>,
}

/// Words that [`skeleton`] masks: object class and room names (every name the template
/// generator uses), colour and shade words, and numbers written out.
fn masked_words() -> BTreeSet<String> {
    use vlnverse_env::{RoomType, SemanticClass};
    use vlnverse_instructions::lexicon::{class_names, room_names};
    let mut m = BTreeSet::new();
    let mut add = |phrase: &str| {
        for w in phrase.split(|c: char| !c.is_alphanumeric() && c != '\'') {
            if !w.is_empty() {
                m.insert(w.to_lowercase());
            }
        }
    };
    // Function words inside multi-word names ("chest of drawers") stay visible.
    let mut add = |phrase: &str| {
        for w in phrase.split(' ').filter(|w| !matches!(*w, "of" | "set")) {
            add(w);
        }
    };
    for &c in SemanticClass::ALL {
        add(&c.words());
        for n in class_names(c) {
            add(n);
        }
    }
    for &r in RoomType::ALL {
        add(&r.words());
        for n in room_names(r) {
            add(n);
        }
    }
    for n in 0..100 {
        add(&vlnverse_instructions::lexicon::number_word(n));
    }
    for c in [
        "red", "blue", "green", "yellow", "orange", "pink", "purple", "brown", "black", "white",
        "grey", "gray", "silver", "gold", "beige", "wooden",
    ] {
        add(c);
    }
    m
}

/// The sentence skeleton of an instruction: lower-case words with object and room names,
/// colours and numbers masked (`_`, runs of masks folded into one), punctuation kept as
/// spaces.
pub fn skeleton(text: &str) -> String {
    thread_local! {
        static MASK: BTreeSet<String> = masked_words();
    }
    MASK.with(|mask| {
        let mut out: Vec<&str> = Vec::new();
        let lower = text.to_lowercase();
        for w in lower.split(|c: char| !c.is_alphanumeric() && c != '\'') {
            if w.is_empty() {
                continue;
            }
            let masked = mask.contains(w) || w.chars().all(|c| c.is_ascii_digit());
            if masked {
                if out.last() != Some(&"_") {
                    out.push("_");
                }
            } else {
                out.push(w);
            }
        }
        out.join(" ")
    })
}

/// Read a dataset folder: `DIR/scenes/*` and every split file present.
pub fn collect(dir: &Path) -> Result<DatasetStats> {
    let mut st = DatasetStats::default();
    let scenes = dir.join("scenes");
    if scenes.is_dir() {
        // Dot-entries (an interrupted writer's temporary folders) are not scenes.
        let ids = vlnverse_env::io::list_scene_dirs(&scenes)?;
        for p in ids {
            let id = p
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let json_path = p.join("scene.json");
            let raw = std::fs::read(&json_path).map_err(|e| DataError::io(&json_path, e))?;
            let scene = scene_from_json(&raw, &json_path)?;
            st.rooms.insert(id.clone(), scene.rooms.len());
            let objects: Vec<_> = scene
                .objects
                .iter()
                .filter(|o| !o.class.is_structure() && o.class != vlnverse_env::SemanticClass::Door)
                .collect();
            st.objects.insert(id.clone(), objects.len());
            st.object_classes
                .extend(objects.iter().map(|o| o.class.name().to_string()));
            let yaml = p.join("navigable.yaml");
            if yaml.is_file() {
                let map = GridMap::load_ros(&yaml)?;
                st.navigable_m2.insert(id, map.free_area_m2() as f64);
            }
        }
    }
    let mut words: BTreeSet<String> = BTreeSet::new();
    for task in Task::ALL {
        let mut skel: BTreeMap<String, usize> = BTreeMap::new();
        let mut count = 0usize;
        for split in Split::ALL {
            if !split_path(dir, task, split).is_file() {
                continue;
            }
            let eps = read_split(dir, task, split)?;
            st.episodes
                .entry(task.name().into())
                .or_default()
                .insert(split.name().into(), eps.len());
            for ep in &eps {
                st.path_length
                    .entry(task.name().into())
                    .or_default()
                    .push(ep.info.geodesic_distance as f64);
                let text = &ep.instruction.instruction_text;
                *skel.entry(skeleton(text)).or_default() += 1;
                count += 1;
                let n = text.split_whitespace().count() as f64;
                let per_style = st.instruction_words.entry(task.name().into()).or_default();
                per_style.entry("all".into()).or_default().push(n);
                if let Some(s) = ep.instruction.style {
                    per_style.entry(s.name().into()).or_default().push(n);
                }
                for w in text.split(|c: char| !c.is_alphanumeric() && c != '\'') {
                    if !w.is_empty() {
                        words.insert(w.to_lowercase());
                    }
                }
                for g in &ep.instruction.grounding {
                    st.grounded_classes.insert(g.class.clone());
                    if g.role == Role::Landmark {
                        st.landmark_classes.insert(g.class.clone());
                    }
                }
            }
        }
        if let Some((k, c)) = skel.iter().max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0))) {
            st.skeleton_share.insert(
                task.name().into(),
                (*c as f64 / count.max(1) as f64, k.clone()),
            );
            st.skeletons.insert(task.name().into(), skel.len());
        }
    }
    st.word_vocabulary = words.len();
    Ok(st)
}

/// Histogram of `values` in `bins` equal bins over `[min, max]`: labels and counts.
pub fn histogram(values: &[f64], bins: usize) -> (Vec<String>, Vec<f64>) {
    let bins = bins.max(1);
    if values.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min).floor();
    let hi = values
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil();
    let width = ((hi - lo) / bins as f64).max(1e-9);
    let mut counts = vec![0.0; bins];
    for &v in values {
        let i = (((v - lo) / width) as usize).min(bins - 1);
        counts[i] += 1.0;
    }
    let labels = (0..bins)
        .map(|i| format!("{:.0}", lo + width * i as f64))
        .collect();
    (labels, counts)
}

/// A bar chart: title, one bar per label, value axis from 0, values written over the bars.
pub fn bar_chart(title: &str, x_label: &str, labels: &[String], values: &[f64]) -> RgbImage {
    let n = labels.len().max(1) as u32;
    let bar_w = (560 / n).clamp(8, 60);
    let (left, right, top, bottom) = (60u32, 20u32, 40u32, 60u32);
    let w = (left + right + bar_w * n).max(420);
    let h = 360u32;
    let mut img = RgbImage::from_pixel(w, h, Rgb([255, 255, 255]));
    let ink = [30, 30, 30];
    let title_x = (w.saturating_sub(text_width(title, 2)) / 2) as i64;
    draw_text(&mut img, title_x, 10, title, 2, ink, false);
    let plot_h = h - top - bottom;
    let vmax = values.iter().copied().fold(0.0, f64::max).max(1e-9);
    // Axes.
    for y in top..=top + plot_h {
        img.put_pixel(left - 1, y, Rgb(ink));
    }
    for x in left - 1..w - right {
        img.put_pixel(x, top + plot_h, Rgb(ink));
    }
    draw_text(&mut img, 4, top as i64 - 4, &fmt_value(vmax), 1, ink, false);
    draw_text(&mut img, 4, (top + plot_h - 8) as i64, "0", 1, ink, false);
    let every = (labels.len() as u32 * 8 * 5 / (bar_w * n).max(1)).max(1) as usize;
    for (i, (&v, label)) in values.iter().zip(labels).enumerate() {
        let x0 = left + i as u32 * bar_w + 1;
        let bh = ((v / vmax) * plot_h as f64).round() as u32;
        for x in x0..x0 + bar_w.saturating_sub(2).max(1) {
            for y in top + plot_h - bh..top + plot_h {
                img.put_pixel(x, y, Rgb([70, 120, 190]));
            }
        }
        if bar_w >= 24 || i % every == 0 {
            let t: String = label.chars().take((bar_w / 8).max(5) as usize).collect();
            draw_text(
                &mut img,
                x0 as i64,
                (top + plot_h + 6) as i64,
                &t,
                1,
                ink,
                false,
            );
        }
        if bar_w >= 32 {
            let vt = fmt_value(v);
            let y = (top + plot_h - bh) as i64 - 10;
            draw_text(&mut img, x0 as i64, y.max(top as i64), &vt, 1, ink, false);
        }
    }
    let xl = (w.saturating_sub(text_width(x_label, 1)) / 2) as i64;
    draw_text(&mut img, xl, (h - 20) as i64, x_label, 1, ink, false);
    img
}

fn fmt_value(v: f64) -> String {
    if v >= 100.0 || v.fract() == 0.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

fn save_png(img: &RgbImage, path: &Path) -> Result<()> {
    let png = super::reference_image::encode_png(img.as_raw(), img.width(), img.height())?;
    write_atomic(path, &png)
}

/// Write `DIR/stats/`: `navigable_area.png`, `rooms.png`, `path_length.png`,
/// `instruction_length.png`, `stats.json` and `stats.md`; returns the markdown.
/// A folder without episodes (no split files, or only empty ones) is an error saying so.
pub fn write_stats(dir: &Path) -> Result<String> {
    write_stats_with(dir, None)
}

/// [`write_stats`], with the naturalness figures (from [`naturalness`]) added to `stats.md`
/// and `stats.json` when given.
pub fn write_stats_with(dir: &Path, naturalness: Option<&Naturalness>) -> Result<String> {
    let mut st = collect(dir)?;
    refuse_empty(dir, &st)?;
    st.naturalness = naturalness.cloned();
    let out = dir.join("stats");
    write_plots(&st, &out)?;
    let mut md = stats_markdown(dir, &st);
    if let Some(n) = naturalness {
        md.push_str(&n.markdown());
    }
    write_atomic(&out.join("stats.md"), md.as_bytes())?;
    let json = serde_json::to_vec_pretty(&st)
        .map_err(|e| DataError::invalid("stats", "<stats>", e.to_string()))?;
    write_atomic(&out.join("stats.json"), &json)?;
    Ok(md)
}

/// A dataset without episodes is an error that says why (a shard, an unfinished run, nothing).
fn refuse_empty(dir: &Path, st: &DatasetStats) -> Result<()> {
    let episodes: usize = st.episodes.values().flat_map(|m| m.values()).sum();
    if episodes == 0 {
        let hint = if dir
            .join(super::pipeline::PARTS_DIR)
            .join(super::pipeline::SHARD_FILE)
            .exists()
        {
            "it is one shard of a dataset: join the shards with `cargo xtask merge` first"
        } else if dir.join(super::pipeline::PARTS_DIR).is_dir() {
            "its generation failed or did not finish (see its error; rerunning the same \
             `cargo xtask generate` resumes it)"
        } else {
            "generate one with `cargo xtask generate --out DIR`"
        };
        let found = if st.episodes.is_empty() {
            "no split files (<task>/<split>/<split>.json.gz)"
        } else {
            "only empty split files"
        };
        return Err(DataError::invalid(
            "dataset",
            dir.display(),
            format!(
                "holds no episodes ({found}, {} scene folders); {hint}",
                st.rooms.len()
            ),
        ));
    }
    Ok(())
}

/// The PNG charts under `out`.
fn write_plots(st: &DatasetStats, out: &Path) -> Result<()> {
    let areas: Vec<f64> = st.navigable_m2.values().copied().collect();
    let (l, c) = histogram(&areas, 12);
    save_png(
        &bar_chart("Navigable area per scene", "m^2 (bin start)", &l, &c),
        &out.join("navigable_area.png"),
    )?;
    let mut room_counts: BTreeMap<usize, f64> = BTreeMap::new();
    for &r in st.rooms.values() {
        *room_counts.entry(r).or_default() += 1.0;
    }
    let (l, c): (Vec<String>, Vec<f64>) =
        room_counts.iter().map(|(k, v)| (k.to_string(), *v)).unzip();
    save_png(
        &bar_chart("Rooms per scene", "rooms", &l, &c),
        &out.join("rooms.png"),
    )?;
    let all_len: Vec<f64> = st.path_length.values().flatten().copied().collect();
    let (l, c) = histogram(&all_len, 15);
    save_png(
        &bar_chart("Path length (all tasks)", "metres (bin start)", &l, &c),
        &out.join("path_length.png"),
    )?;
    let mut il_labels = Vec::new();
    let mut il_values = Vec::new();
    for (task, per) in &st.instruction_words {
        for (style, v) in per {
            if style == "all" && per.len() > 1 {
                continue;
            }
            let short = match task.as_str() {
                "coarse" => "co",
                "visual_reference" => "vr",
                "long_horizon" => "lh",
                "dialogue" => "dia",
                other => other,
            };
            let label = if style == "all" {
                short.to_string()
            } else {
                format!("{short}/{}", &style[..1.min(style.len())])
            };
            il_labels.push(label);
            il_values.push(ValueStats::of(v).mean);
        }
    }
    save_png(
        &bar_chart(
            "Mean instruction length (words)",
            "task (co/vr/lh/dia) / style (f/n/c)",
            &il_labels,
            &il_values,
        ),
        &out.join("instruction_length.png"),
    )?;
    if let Some(fine) = st.instruction_words.get("fine").and_then(|m| m.get("all")) {
        let (l, c) = histogram(fine, 20);
        let vs = ValueStats::of(fine);
        save_png(
            &bar_chart(
                &format!(
                    "Fine-grained length: mean {:.0}, p10-p90 {:.0}-{:.0}",
                    vs.mean, vs.p10, vs.p90
                ),
                "words (bin start); R2R mean ~29",
                &l,
                &c,
            ),
            &out.join("instruction_length_fine.png"),
        )?;
    }
    Ok(())
}

/// `stats.md`: the quantities' distributions, episode counts, vocabulary and skeleton shares.
fn stats_markdown(dir: &Path, st: &DatasetStats) -> String {
    let mut md = String::from("# Dataset statistics\n\n");
    md.push_str(&format!("Dataset: `{}`\n\n", dir.display()));
    md.push_str(
        "| quantity | n | mean | min | p10 | median | p90 | max |\n|---|---|---|---|---|---|---|---|\n",
    );
    let row = |md: &mut String, name: &str, s: ValueStats| {
        md.push_str(&format!(
            "| {name} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |\n",
            s.n, s.mean, s.min, s.p10, s.median, s.p90, s.max
        ));
    };
    row(
        &mut md,
        "navigable area per scene (m^2)",
        ValueStats::of(&st.navigable_m2.values().copied().collect::<Vec<f64>>()),
    );
    let rooms: Vec<f64> = st.rooms.values().map(|&r| r as f64).collect();
    row(&mut md, "rooms per scene", ValueStats::of(&rooms));
    let objects: Vec<f64> = st.objects.values().map(|&n| n as f64).collect();
    row(
        &mut md,
        "objects per scene (no structure, doors)",
        ValueStats::of(&objects),
    );
    for (task, v) in &st.path_length {
        row(
            &mut md,
            &format!("path length, {task} (m)"),
            ValueStats::of(v),
        );
    }
    for (task, per) in &st.instruction_words {
        for (style, v) in per {
            row(
                &mut md,
                &format!("instruction words, {task}, {style}"),
                ValueStats::of(v),
            );
        }
    }
    md.push_str("\n| task | train | val_seen | val_unseen | test |\n|---|---|---|---|---|\n");
    for (task, per) in &st.episodes {
        let g = |s: &str| per.get(s).copied().unwrap_or(0);
        md.push_str(&format!(
            "| {task} | {} | {} | {} | {} |\n",
            g("train"),
            g("val_seen"),
            g("val_unseen"),
            g("test")
        ));
    }
    md.push_str(&format!(
        "\nObject classes in the scenes: {}. Landmark vocabulary: {} object classes named as \
         landmarks ({} classes grounded in all); {} distinct words over all instructions.\n",
        st.object_classes.len(),
        st.landmark_classes.len(),
        st.grounded_classes.len(),
        st.word_vocabulary
    ));
    md.push_str(
        "\n| task | distinct skeletons | largest skeleton share | that skeleton |\n|---|---|---|---|\n",
    );
    for (task, (share, sk)) in &st.skeleton_share {
        let shown: String = sk.chars().take(80).collect();
        md.push_str(&format!(
            "| {task} | {} | {:.2}% | `{shown}` |\n",
            st.skeletons.get(task).copied().unwrap_or(0),
            share * 100.0
        ));
    }
    md.push_str(
        "\nA skeleton is the instruction with object and room names, colours and numbers masked.\n",
    );
    md.push_str("\nPlots: `navigable_area.png`, `rooms.png`, `path_length.png`, `instruction_length.png`, `instruction_length_fine.png`.\n");
    md
}

/// Markdown with `per_group` instructions drawn at random (seeded) from the dataset for each
/// task and style (fine-grained: one group), over all splits present.
pub fn samples_markdown(dir: &Path, per_group: usize, seed: u64) -> Result<String> {
    use rand::seq::IndexedRandom;
    use rand::SeedableRng;
    let mut md = String::new();
    for task in Task::ALL {
        let mut groups: BTreeMap<String, Vec<(String, String)>> = BTreeMap::new();
        for split in Split::ALL {
            if !split_path(dir, task, split).is_file() {
                continue;
            }
            for ep in read_split(dir, task, split)? {
                let style = ep
                    .instruction
                    .style
                    .map_or_else(|| "all".to_string(), |s| s.name().to_string());
                groups
                    .entry(style)
                    .or_default()
                    .push((ep.scene_id.clone(), ep.instruction.instruction_text.clone()));
            }
        }
        for (style, eps) in &groups {
            // Each group draws from its own stream (FNV-1a of its name), so adding a group
            // leaves the others' samples unchanged.
            let salt = format!("{}/{style}", task.name())
                .bytes()
                .fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
                    (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
                });
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed ^ salt);
            let picked: Vec<&(String, String)> = eps.choose_multiple(&mut rng, per_group).collect();
            if style == "all" {
                md.push_str(&format!("### {}\n\n", task.name()));
            } else {
                md.push_str(&format!("### {}, {style}\n\n", task.name()));
            }
            for (i, (scene, text)) in picked.iter().enumerate() {
                md.push_str(&format!(
                    "{}. {} *({scene})*\n",
                    i + 1,
                    text.replace('\n', " ")
                ));
            }
            md.push('\n');
        }
    }
    Ok(md)
}
