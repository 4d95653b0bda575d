//! `evaluate --agent mllm`: the MLLM agent's config from `--agent-config` and the `--mllm-*`
//! flags, its accounting after the run, and the dry run.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context;
use vlnverse_mllm::dry::{reference_moves, DryRun};
use vlnverse_mllm::{MllmConfig, MllmFactory};
use vlnverse_task::eval::{
    evaluate_with, select_episodes, ActionSpace, EvalConfig, EvalRequest, Layers,
};
use vlnverse_task::sample::Sample;

use super::Args;

/// The config: the file (or the defaults), then the flags; the reply cache defaults to
/// `<out>/.mllm-cache`.
pub fn config(args: &Args, eval: &EvalConfig) -> anyhow::Result<MllmConfig> {
    let mut cfg = match &args.agent_config {
        Some(p) => MllmConfig::load(p)?,
        None => MllmConfig::default(),
    };
    if let Some(e) = &args.mllm_endpoint {
        cfg.endpoint = e.clone();
    }
    if let Some(m) = &args.mllm_model {
        cfg.model = m.clone();
    }
    if cfg.cache && cfg.cache_dir.is_none() {
        cfg.cache_dir = Some(args.out.join(".mllm-cache"));
    }
    if eval.action_space != ActionSpace::Discrete {
        anyhow::bail!(
            "--agent mllm answers with discrete moves; the protocol's action space is {:?} (use --action-space discrete)",
            eval.action_space
        );
    }
    if !eval.render {
        anyhow::bail!("--agent mllm looks at its camera: drop --no-render");
    }
    Ok(cfg)
}

/// The factory for a real run (config, endpoint and key checked).
pub fn factory(args: &Args, eval: &EvalConfig) -> anyhow::Result<MllmFactory> {
    let cfg = config(args, eval)?;
    let what = match &args.agent_config {
        Some(p) => format!("--agent-config {}", p.display()),
        None => "--mllm-endpoint / --mllm-model".into(),
    };
    MllmFactory::new(cfg).with_context(|| what)
}

/// After the run: `mllm.jsonl` and the totals in `summary.json`; prints the traffic.
pub fn finish(factory: &MllmFactory, out: &Path) -> anyhow::Result<()> {
    let (t, traffic) =
        vlnverse_mllm::write_accounting(out, &factory.config().model, &factory.stats(), None)?;
    println!(
        "mllm: {} decisions, {} replies ({} sent, {} from the cache, {} transport retries, {:.0} ms mean latency), {} prompt + {} completion tokens ({:.0} per episode), {} corrective retries, {} fallbacks, {} questions -> {}",
        t.decisions,
        t.calls,
        traffic.requests,
        traffic.cache_hits,
        traffic.transport_retries,
        traffic.mean_latency_ms,
        t.prompt_tokens,
        t.completion_tokens,
        t.tokens_per_episode,
        t.parse_retries,
        t.fallbacks,
        t.asks,
        out.join(vlnverse_mllm::ACCOUNTING_FILE).display()
    );
    Ok(())
}

/// `--mllm-dry-run`: one episode against a backend that prints each request and sends
/// nothing, then the token estimate of a sampled run (`--sample N`, 200 by default).
pub fn dry_run(args: &Args, eval: EvalConfig) -> anyhow::Result<()> {
    let mut cfg = config(args, &eval)?;
    if cfg.endpoint.is_empty() {
        cfg.endpoint = "http://dry-run.invalid/v1".into();
    }
    if cfg.model.is_empty() {
        cfg.model = "dry-run".into();
    }
    cfg.cache = false;
    cfg.validate()?;
    let reply_tokens = if cfg.chain_of_thought { 120 } else { 8 };
    let dry = Arc::new(DryRun::new(Box::new(std::io::stdout()), 6, reply_tokens));
    let factory = MllmFactory::with_backend(cfg, dry);
    let tmp = std::env::temp_dir().join(format!("vlnverse-mllm-dry-run-{}", std::process::id()));
    let req = EvalRequest::new(
        args.data.dataset.clone(),
        args.data.task,
        args.data.split,
        tmp.clone(),
    )
    .episodes(Some(1))
    .threads(Some(1))
    .fresh(true)
    .config(eval.clone());
    let run = evaluate_with(&req, &factory, Layers::default());
    let _ = std::fs::remove_dir_all(&tmp);
    run?;
    let stats = factory.stats();
    let (t, _) = vlnverse_mllm::totals(&factory.config().model, &stats);
    let per_call = (t.prompt_tokens + t.completion_tokens) as f64 / t.calls.max(1) as f64;
    let count = args.sample.unwrap_or(200);
    let episodes =
        vlnverse_task::dataset::read_split(&args.data.dataset, args.data.task, args.data.split)?;
    let sampled = select_episodes(
        &EvalRequest::new(
            args.data.dataset.clone(),
            args.data.task,
            args.data.split,
            tmp,
        )
        .sample(Some(Sample {
            count,
            seed: eval.seed,
        }))
        .config(eval.clone()),
        episodes,
    )?;
    let agent = eval.agent_config()?;
    let moves: u64 = sampled
        .iter()
        .map(|e| {
            reference_moves(e, agent.step_size, agent.turn_angle_deg).min(eval.max_steps.into())
        })
        .sum();
    let cap = sampled.len() as u64 * u64::from(eval.max_steps);
    println!(
        "\ndry run: {} requests, about {per_call:.0} tokens each ({} prompt + {} completion in all)",
        t.calls, t.prompt_tokens, t.completion_tokens
    );
    println!(
        "estimate for --sample {count} ({} episodes): about {moves} decisions if each reply is one primitive along the reference path -> about {:.1} M tokens; at most {cap} decisions (the step limit) -> about {:.1} M tokens",
        sampled.len(),
        moves as f64 * per_call / 1e6,
        cap as f64 * per_call / 1e6
    );
    Ok(())
}

/// `evaluate --agent mllm`: the run, then its accounting.
pub fn run(args: &Args, eval: EvalConfig) -> anyhow::Result<()> {
    if args.mllm_dry_run {
        return dry_run(args, eval);
    }
    let factory = factory(args, &eval)?;
    if args.fresh {
        // --fresh starts the accounting over too (the reply cache stays).
        let f = args.out.join(vlnverse_mllm::ACCOUNTING_FILE);
        if let Err(e) = std::fs::remove_file(&f) {
            if e.kind() != std::io::ErrorKind::NotFound {
                return Err(e).with_context(|| f.display().to_string());
            }
        }
    }
    let boxed: Box<dyn vlnverse_task::eval::AgentFactory> = Box::new(factory.clone());
    let boxed = match &args.agent_version {
        Some(v) => Box::new(vlnverse_task::eval::agents::Versioned::new(boxed, v)),
        None => boxed,
    };
    let n =
        vlnverse_task::dataset::read_split(&args.data.dataset, args.data.task, args.data.split)?
            .len();
    let n = args.episodes.or(args.sample).map_or(n, |k| k.min(n));
    let req = EvalRequest::new(
        args.data.dataset.clone(),
        args.data.task,
        args.data.split,
        args.out.clone(),
    )
    .episodes(args.episodes)
    .sample(args.sample.map(|count| Sample {
        count,
        seed: eval.seed,
    }))
    .threads(args.threads)
    .fresh(args.fresh)
    .config(eval);
    let pb = crate::progress::bar(n as u64, "evaluating");
    let t0 = std::time::Instant::now();
    let out = evaluate_with(&req, &*boxed, Layers::default().on_episode(&|| pb.inc(1)))?;
    pb.finish_and_clear();
    finish(&factory, &args.out)?;
    let s = &out.summary.summary;
    println!(
        "{} on {}/{}: {} episodes ({} resumed), SR {:.2}%  SPL {:.2}%  nDTW {:.2}%; {} steps in {:.1} s -> {}",
        out.summary.method,
        args.data.task,
        args.data.split,
        s.episodes,
        out.resumed,
        100.0 * s.sr,
        100.0 * s.spl,
        100.0 * s.ndtw,
        out.steps_run,
        t0.elapsed().as_secs_f64(),
        args.out.display()
    );
    Ok(())
}
