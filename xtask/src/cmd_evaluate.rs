//! `cargo xtask evaluate`: run an agent on a dataset split under an evaluation protocol and
//! write `summary.json`, `episodes.csv`, `trajectories.jsonl`, `report.md` and top-down plots.
//! An interrupted run resumes from `RUN/progress.jsonl`.

use std::path::PathBuf;

use anyhow::Context;
use std::time::Instant;

use crate::split_args::SplitArgs;
use vlnverse_sensors::Backend;
use vlnverse_task::eval::agents::{builtin, Versioned};
use vlnverse_task::eval::{evaluate_with, ActionSpace, EvalConfig, EvalRequest, Layers, Setting};
use vlnverse_task::sample::Sample;

#[path = "cmd_evaluate_mllm.rs"]
mod mllm;

/// Arguments of `cargo xtask evaluate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dataset, task and split.
    #[command(flatten)]
    pub data: SplitArgs,
    /// Agent: oracle, random, forward, stop, semantic, external, http or mllm.
    #[arg(long)]
    pub agent: String,
    /// Setting: strict, telhop or lenient (picks `configs/eval/<setting>.toml` unless --config).
    #[arg(long, default_value = "strict")]
    pub setting: Setting,
    /// Protocol file (overrides the setting's default file; its `setting` must agree).
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Only the first N episodes of the split (at least 1).
    #[arg(long, value_parser = at_least_one, conflicts_with = "sample")]
    pub episodes: Option<usize>,
    /// A seeded random sample of N episodes spread over the split's scenes (the paper's
    /// zero-shot protocol samples 200); the draw follows --seed.
    #[arg(long, value_parser = at_least_one)]
    pub sample: Option<usize>,
    /// The run's seed (episode seeds, sensor noise, the --sample draw); default: the
    /// protocol file's `seed`.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Dialogue oracle: `rule` (the shortest-path oracle's plain answers) or `llm` (rephrased
    /// through the OpenAI-compatible endpoint of --oracle-config); default: the protocol's.
    #[arg(long)]
    pub oracle: Option<String>,
    /// TOML file with the LLM endpoint of `--oracle llm` (the fields of `[instructions.llm]`:
    /// base_url, model, api_key_env, ...).
    #[arg(long)]
    pub oracle_config: Option<PathBuf>,
    /// Worker threads (default: one per core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Shell command of the external agent.
    #[arg(long)]
    pub agent_cmd: Option<String>,
    /// `--agent mllm`: base URL of the OpenAI-compatible endpoint (overrides the config's).
    #[arg(long)]
    pub mllm_endpoint: Option<String>,
    /// `--agent mllm`: model name sent with each request (overrides the config's).
    #[arg(long)]
    pub mllm_model: Option<String>,
    /// `--agent mllm`: the agent's TOML config (docs/mllm.md).
    #[arg(long)]
    pub agent_config: Option<PathBuf>,
    /// `--agent mllm`: print the requests of one episode and the token estimate of a
    /// `--sample` run (200 episodes by default); sends nothing.
    #[arg(long)]
    pub mllm_dry_run: bool,
    /// `--agent http`: base URL of the agent server (the original VLNVerse agent-server
    /// protocol: /agent/init, /agent/NAME/reset, /agent/NAME/step).
    #[arg(long)]
    pub agent_url: Option<String>,
    /// `--agent http`: the agent's name on the server (`model_name` of init).
    #[arg(long, default_value = "default")]
    pub agent_name: String,
    /// `--agent http`: JSON file with more `agent_config` fields for init (`ckpt_path`,
    /// `model_settings`, ...).
    #[arg(long)]
    pub agent_init: Option<PathBuf>,
    /// `--agent http`: seconds to wait for one step's reply before the run stops.
    #[arg(long, default_value_t = 60.0)]
    pub agent_timeout: f64,
    /// Action space override: discrete, continuous (velocity commands) or waypoint.
    #[arg(long)]
    pub action_space: Option<ActionSpace>,
    /// Renderer backend override: auto, wgpu, raster or raycast.
    #[arg(long)]
    pub backend: Option<String>,
    /// Do not render observations (agents that do not look, e.g. timing the oracle).
    #[arg(long)]
    pub no_render: bool,
    /// What the agent is beyond its name (a version, a checkpoint hash), recorded in
    /// `run.json`: resuming the run with another value is refused.
    #[arg(long)]
    pub agent_version: Option<String>,
    /// Start over: delete an earlier run's results in --out instead of resuming it.
    #[arg(long)]
    pub fresh: bool,
    /// Output folder of the run.
    #[arg(long)]
    pub out: PathBuf,
}

/// `--episodes`: a positive count.
fn at_least_one(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(0) => Err("must be at least 1 (leave --episodes out to run the whole split)".into()),
        Ok(n) => Ok(n),
        Err(e) => Err(format!("expected a positive number of episodes: {e}")),
    }
}

fn config(args: &Args) -> anyhow::Result<EvalConfig> {
    let default_file = PathBuf::from("configs/eval").join(format!("{}.toml", args.setting));
    let mut cfg = match &args.config {
        Some(p) => EvalConfig::load(p)?,
        None if default_file.is_file() => EvalConfig::load(&default_file)?,
        None => EvalConfig::for_setting(args.setting),
    };
    if args.config.is_some() && cfg.setting != args.setting {
        anyhow::bail!(
            "--setting {} disagrees with `setting = \"{}\"` in {}",
            args.setting,
            cfg.setting,
            args.config
                .as_ref()
                .map(|p| p.display().to_string())
                .unwrap_or_default()
        );
    }
    cfg.setting = args.setting;
    if let Some(a) = args.action_space {
        cfg.action_space = a;
    }
    if let Some(b) = &args.backend {
        cfg.backend = Some(b.parse::<Backend>()?);
    }
    if args.no_render {
        cfg.render = false;
    }
    if let Some(seed) = args.seed {
        cfg.seed = seed;
    }
    match (args.oracle.as_deref(), &args.oracle_config) {
        (Some("rule"), None) => cfg.oracle_llm = None,
        (Some("llm") | None, Some(file)) => {
            let text = std::fs::read_to_string(file)
                .with_context(|| format!("--oracle-config {}", file.display()))?;
            let llm: vlnverse_task::instructions::llm::LlmConfig = toml::from_str(&text)
                .map_err(|e| anyhow::anyhow!("{}: {}", file.display(), e.message()))?;
            llm.validate()
                .with_context(|| format!("--oracle-config {}", file.display()))?;
            cfg.oracle_llm = Some(llm);
        }
        (Some("llm"), None) if cfg.oracle_llm.is_some() => {}
        (Some("llm"), None) => anyhow::bail!(
            "--oracle llm needs an endpoint: --oracle-config FILE (base_url, model,              api_key_env) or `[oracle_llm]` in the protocol file"
        ),
        (Some("rule"), Some(_)) => {
            anyhow::bail!("--oracle rule takes no --oracle-config (it is for --oracle llm)")
        }
        (Some(other), _) => anyhow::bail!("--oracle `{other}`: expected rule or llm"),
        (None, None) => {}
    }
    Ok(cfg)
}

/// The `--agent http` factory from its flags.
fn http_factory(args: &Args) -> anyhow::Result<Box<dyn vlnverse_task::eval::AgentFactory>> {
    let Some(url) = &args.agent_url else {
        anyhow::bail!("--agent http needs --agent-url http://HOST:PORT (the agent server)");
    };
    let mut cfg = vlnverse_agent_http::HttpAgentConfig::new(url.as_str(), args.agent_name.as_str());
    if let Some(file) = &args.agent_init {
        let text = std::fs::read_to_string(file)
            .with_context(|| format!("--agent-init {}", file.display()))?;
        match serde_json::from_str(&text) {
            Ok(serde_json::Value::Object(m)) => cfg.agent_config = m,
            Ok(_) => anyhow::bail!("--agent-init {}: expected a JSON object", file.display()),
            Err(e) => anyhow::bail!("--agent-init {}: {e}", file.display()),
        }
    }
    let t = args.agent_timeout;
    anyhow::ensure!(
        t.is_finite() && t > 0.0 && t <= 3600.0,
        "--agent-timeout {t}: expected seconds in (0, 3600]"
    );
    cfg.step_timeout = std::time::Duration::from_secs_f64(t);
    Ok(Box::new(vlnverse_agent_http::HttpFactory::new(cfg)?))
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let cfg = config(&args)?;
    if args.agent == "mllm" {
        return mllm::run(&args, cfg);
    }
    let mut threads = args.threads;
    let mut factory = if args.agent == "http" {
        // The server keeps one agent per name: one worker.
        anyhow::ensure!(
            threads.is_none_or(|t| t == 1),
            "--agent http runs on one worker thread (the agent server keeps one agent per name); drop --threads or pass --threads 1"
        );
        threads = Some(1);
        http_factory(&args)?
    } else {
        builtin(&args.agent, args.agent_cmd.as_deref(), &cfg)?
    };
    if let Some(v) = &args.agent_version {
        factory = Box::new(Versioned::new(factory, v));
    }
    let n =
        vlnverse_task::dataset::read_split(&args.data.dataset, args.data.task, args.data.split)?
            .len();
    let n = args.episodes.or(args.sample).map_or(n, |k| k.min(n));
    let sample = args.sample.map(|count| Sample {
        count,
        seed: cfg.seed,
    });
    let req = EvalRequest::new(
        args.data.dataset.clone(),
        args.data.task,
        args.data.split,
        args.out.clone(),
    )
    .episodes(args.episodes)
    .sample(sample)
    .threads(threads)
    .fresh(args.fresh)
    .config(cfg);
    let pb = crate::progress::bar(n as u64, "evaluating");
    let t0 = Instant::now();
    let trimmer = crate::malloc_arena::Trimmer::start(crate::malloc_arena::TRIM_PERIOD);
    let out = evaluate_with(&req, &*factory, Layers::default().on_episode(&|| pb.inc(1)))?;
    drop(trimmer);
    pb.finish_and_clear();
    let secs = t0.elapsed().as_secs_f64();
    let s = &out.summary.summary;
    println!(
        "{} on {}/{} ({}): {} episodes ({} resumed), SR {:.2}%  SPL {:.2}%  NE {}  nDTW {:.2}%  CR {:.2}%; {} steps in {:.1} s ({:.0} steps/s) -> {}",
        out.summary.method,
        args.data.task,
        args.data.split,
        args.setting,
        s.episodes,
        out.resumed,
        100.0 * s.sr,
        100.0 * s.spl,
        s.ne.map_or_else(|| "-".into(), |v| format!("{v:.2} m")),
        100.0 * s.ndtw,
        100.0 * s.cr,
        out.steps_run,
        secs,
        out.steps_run as f64 / secs.max(1e-9),
        args.out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_task::{Split, Task};

    fn args(config: Option<PathBuf>, setting: Setting) -> Args {
        Args {
            data: SplitArgs {
                dataset: PathBuf::from("unused"),
                task: Task::Fine,
                split: Split::Test,
            },
            agent: "oracle".into(),
            setting,
            config,
            episodes: None,
            sample: None,
            seed: None,
            oracle: None,
            oracle_config: None,
            threads: None,
            agent_cmd: None,
            mllm_endpoint: None,
            mllm_model: None,
            agent_config: None,
            mllm_dry_run: false,
            agent_url: None,
            agent_name: "default".into(),
            agent_init: None,
            agent_timeout: 60.0,
            action_space: Some(ActionSpace::Continuous),
            backend: Some("raster".into()),
            no_render: true,
            agent_version: None,
            fresh: false,
            out: PathBuf::from("unused"),
        }
    }

    #[test]
    fn zero_episodes_is_refused_by_the_flag_parser() {
        let err = at_least_one("0").unwrap_err();
        assert!(err.contains("at least 1"), "{err}");
        assert_eq!(at_least_one("3"), Ok(3));
        assert!(at_least_one("-1").is_err());
    }

    #[test]
    fn http_agent_flags_are_checked_before_anything_runs() {
        let http = |url: Option<&str>, threads: Option<usize>, timeout: f64| Args {
            agent: "http".into(),
            agent_url: url.map(str::to_string),
            threads,
            agent_timeout: timeout,
            ..args(None, Setting::Lenient)
        };
        let err = format!("{:#}", run(http(None, None, 60.0)).unwrap_err());
        assert!(err.contains("--agent-url"), "{err}");
        let url = Some("http://127.0.0.1:9");
        let err = format!("{:#}", run(http(url, Some(2), 60.0)).unwrap_err());
        assert!(err.contains("--threads 1"), "{err}");
        let err = format!("{:#}", run(http(url, None, 0.0)).unwrap_err());
        assert!(err.contains("--agent-timeout"), "{err}");
        let err = format!(
            "{:#}",
            run(http(Some("ftp://x:1"), None, 60.0)).unwrap_err()
        );
        assert!(
            err.contains("agent_url") && err.contains("ftp://x:1"),
            "{err}"
        );
    }

    #[test]
    fn protocol_file_and_flags_combine() {
        let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../configs/eval");
        let cfg = config(&args(Some(root.join("telhop.toml")), Setting::Telhop)).unwrap();
        assert_eq!(cfg.setting, Setting::Telhop);
        assert_eq!(cfg.backend, Some(Backend::Raster));
        assert_eq!(cfg.action_space, ActionSpace::Continuous);
        assert!(!cfg.render);
        let err = config(&args(Some(root.join("telhop.toml")), Setting::Strict)).unwrap_err();
        assert!(err.to_string().contains("telhop.toml"), "{err}");
        let err = run(Args {
            agent: "nope".into(),
            ..args(None, Setting::Lenient)
        })
        .unwrap_err();
        assert!(format!("{err:#}").contains("nope"), "{err:#}");
        // The LLM oracle needs an endpoint; a file names itself in its errors.
        let llm = |oracle: &str, file: Option<PathBuf>| Args {
            oracle: Some(oracle.into()),
            oracle_config: file,
            ..args(None, Setting::Lenient)
        };
        let err = config(&llm("llm", None)).unwrap_err();
        assert!(err.to_string().contains("--oracle-config"), "{err}");
        let err = config(&llm("oracle", None)).unwrap_err();
        assert!(err.to_string().contains("rule or llm"), "{err}");
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("llm.toml");
        std::fs::write(
            &file,
            "base_url = \"http://127.0.0.1:9/v1\"\nmodel = \"m\"\n",
        )
        .unwrap();
        let cfg = config(&llm("llm", Some(file.clone()))).unwrap();
        assert_eq!(cfg.oracle_llm.unwrap().model, "m");
        std::fs::write(&file, "base_url = \"http://x/v1\"\nmodl = \"m\"\n").unwrap();
        let err = config(&llm("llm", Some(file))).unwrap_err();
        assert!(format!("{err:#}").contains("llm.toml") && format!("{err:#}").contains("modl"));
    }
}
