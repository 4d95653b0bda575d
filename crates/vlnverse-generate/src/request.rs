//! One generation run as plain data: which config (a shipped preset or a TOML file), which
//! scenes (procedural homes or the scene folders under a directory), which tasks and which
//! shard. `cargo xtask generate` and `vlnverse.generate` in Python both build their run here,
//! so they accept and refuse the same inputs with the same messages.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};

use crate::episodes::StageTimes;
use crate::pipeline::{self, check_shard, GenerateSummary, RunOptions};
use crate::presets::{GenerateConfig, GeneratePreset};
use vlnverse_instructions::{InstructionGenerator, TemplateGenerator};
use vlnverse_score::episode::Task;
use vlnverse_score::{DataError, Result};

/// What to generate and where.
#[derive(Clone, Debug)]
pub struct GenerateRequest {
    /// Shipped preset (`tiny`, `vlnverse`), used when `config` is `None`.
    pub preset: String,
    /// A generation TOML config instead of the preset.
    pub config: Option<PathBuf>,
    /// Overrides the config's global seed.
    pub seed: Option<u64>,
    /// Dataset folder.
    pub out: PathBuf,
    /// Tasks to generate; empty = all five.
    pub tasks: Vec<Task>,
    /// `(k, n)`: the scenes with `index % n == k`; `(0, 1)` is the whole dataset.
    pub shard: (usize, usize),
    /// Build episodes on the scene folders under this directory instead of procedural homes
    /// (the config's counts are rescaled to their number).
    pub scenes_from: Option<PathBuf>,
}

impl GenerateRequest {
    /// The whole `preset` into `out`, all tasks.
    pub fn preset(preset: &str, out: impl Into<PathBuf>) -> Self {
        GenerateRequest {
            preset: preset.to_string(),
            config: None,
            seed: None,
            out: out.into(),
            tasks: Vec::new(),
            shard: (0, 1),
            scenes_from: None,
        }
    }

    /// Read and check the config, open the scene source, fix the tasks.
    pub fn prepare(&self) -> Result<PreparedRun> {
        let (k, n) = self.shard;
        check_shard(k, n)?;
        // Where the config came from, named in its errors.
        let (mut config, origin) = match &self.config {
            Some(p) => (GenerateConfig::from_toml_file(p)?, p.clone()),
            None => {
                let preset = GeneratePreset::from_str(&self.preset)?;
                let origin = PathBuf::from(format!("configs/generate/{}.toml", preset.name()));
                (preset.config()?, origin)
            }
        };
        if let Some(seed) = self.seed {
            config.seed = seed;
        }
        let source: Box<dyn SceneSource> = match &self.scenes_from {
            Some(dir) => {
                let s = pipeline::FolderSource::new(dir)?;
                config = config.rescaled(s.len());
                config.validate_in(&origin).map_err(|e| {
                    DataError::invalid(
                        "scenes_from",
                        dir.display(),
                        format!("the config rescaled to its {} scenes: {e}", s.len()),
                    )
                })?;
                Box::new(s)
            }
            None => Box::new(procedural_homes(&config, &origin)?),
        };
        let tasks = if self.tasks.is_empty() {
            Task::ALL.to_vec()
        } else {
            self.tasks.clone()
        };
        Ok(PreparedRun {
            options: RunOptions {
                out: self.out.clone(),
                tasks,
                shard: self.shard,
                occupancy: OccupancyConfig::default(),
            },
            config,
            source,
        })
    }
}

/// The procedural homes of the config's scene preset; their number must match the splits.
fn procedural_homes(config: &GenerateConfig, origin: &Path) -> Result<HomeGenerator> {
    let field = || format!("{}: scene_preset", origin.display());
    let preset = Preset::from_str(&config.scene_preset)
        .map_err(|e| DataError::invalid(field(), &config.scene_preset, e.to_string()))?;
    let source = HomeGenerator::from_preset(preset)?;
    if source.len() != config.splits.total() {
        return Err(DataError::invalid(
            format!("{}: splits", origin.display()),
            format!("{} scenes", config.splits.total()),
            format!(
                "scene preset `{}` makes {} homes; make [splits] add up to {} or build on a \
                 scene folder (--scenes-from)",
                config.scene_preset,
                source.len(),
                source.len()
            ),
        ));
    }
    Ok(source)
}

/// A checked run, ready to go.
pub struct PreparedRun {
    /// The generation config (seed override and rescaling applied).
    pub config: GenerateConfig,
    /// Where the scenes come from.
    pub source: Box<dyn SceneSource>,
    /// Output folder, tasks, shard.
    pub options: RunOptions,
}

impl PreparedRun {
    /// Number of scenes this shard handles.
    pub fn scenes_in_shard(&self) -> usize {
        let (k, n) = self.options.shard;
        (0..self.source.len()).filter(|i| i % n == k).count()
    }

    /// Run the pipeline on the calling thread's rayon pool with the config's instruction stage
    /// (the templates, or the LLM stage of `[instructions.llm]`, whose report goes to
    /// `llm_report.json`); `on_scene` is called after each scene (from worker threads).
    pub fn run(
        &self,
        times: &StageTimes,
        on_scene: &(dyn Fn(&str) + Sync),
    ) -> Result<GenerateSummary> {
        #[cfg(feature = "llm")]
        if let Some(llm) = &self.config.instructions.llm {
            use crate::llm_stage;
            let g = llm_stage::llm_generator(llm, self.config.image, &self.options.out)?;
            let summary = self.run_with(&g, times, on_scene);
            let report = g.report();
            // A failed run leaves no report (what it counted was not kept).
            if report.instructions > 0 && summary.is_ok() {
                llm_stage::write_report(&self.options.out, &report)?;
            }
            return summary;
        }
        self.run_with(&TemplateGenerator::default(), times, on_scene)
    }

    /// Run the pipeline with another instruction generator.
    pub fn run_with(
        &self,
        instructions: &dyn InstructionGenerator,
        times: &StageTimes,
        on_scene: &(dyn Fn(&str) + Sync),
    ) -> Result<GenerateSummary> {
        pipeline::run(
            self.source.as_ref(),
            &self.config,
            &self.options,
            instructions,
            times,
            on_scene,
        )
    }
}
