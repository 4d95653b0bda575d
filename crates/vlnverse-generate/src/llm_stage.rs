//! The LLM stage of `generate` (`[instructions.llm]`): the template instructions rewritten
//! through an OpenAI-compatible endpoint, the describer seeing views rendered along the path
//! (or the goal view of a coarse episode) with the same CPU rasteriser as the reference images.

use std::path::Path;
use std::sync::{Arc, Mutex};

use glam::{Vec2, Vec3};
use vlnverse_env::ObjectId;

use super::presets::ImageConfig;
use super::reference_image::{encode_png, ReferenceRenderer};
use vlnverse_instructions::llm::{LlmConfig, LlmGenerator, LlmReport};
use vlnverse_instructions::{PathContext, TemplateGenerator};
use vlnverse_score::Result;

/// File the stage's report is written to, in the dataset folder.
pub const LLM_REPORT_FILE: &str = "llm_report.json";
/// Default folder of the reply cache, in the dataset folder.
pub const LLM_CACHE_DIR: &str = ".llm-cache";
/// Scenes whose renderers the frame source keeps.
const RENDERERS_KEPT: usize = 8;

/// The template generator behind the LLM stage of `config`, caching replies under `out`
/// unless the config names a cache folder.
pub fn llm_generator(
    config: &LlmConfig,
    image: ImageConfig,
    out: &Path,
) -> Result<LlmGenerator<TemplateGenerator>> {
    let mut config = config.clone();
    if config.cache_dir.is_none() {
        config.cache_dir = Some(out.join(LLM_CACHE_DIR));
    }
    // Preparing a scene for rendering bakes its light: keep the last few scenes' renderers
    // (workers handle one scene at a time, so a handful covers every worker).
    let cache: Mutex<Vec<(String, Arc<ReferenceRenderer>)>> = Mutex::new(Vec::new());
    let frames = move |ctx: &PathContext<'_>, target: Option<ObjectId>, n: u32| {
        if n == 0 {
            return Ok(Vec::new());
        }
        let renderer = {
            let mut c = cache.lock().unwrap_or_else(|p| p.into_inner());
            match c.iter().find(|(id, _)| *id == ctx.scene.id) {
                Some((_, r)) => r.clone(),
                None => {
                    let r = Arc::new(ReferenceRenderer::new(ctx.scene, &image)?);
                    if c.len() >= RENDERERS_KEPT {
                        c.remove(0);
                    }
                    c.push((ctx.scene.id.clone(), r.clone()));
                    r
                }
            }
        };
        frames(ctx, &renderer, target, n, &image)
    };
    Ok(LlmGenerator::new(TemplateGenerator::default(), config)?.with_frames(Box::new(frames)))
}

/// PNG views for the describer: the goal view facing `target` (coarse), or `n` views spread
/// from the start to the end of the path, each facing along the path.
pub fn frames(
    ctx: &PathContext<'_>,
    r: &ReferenceRenderer,
    target: Option<ObjectId>,
    n: u32,
    image: &ImageConfig,
) -> Result<Vec<Vec<u8>>> {
    let points: Vec<Vec2> = ctx.path.iter().map(|p| Vec2::new(p[0], p[2])).collect();
    let Some(&last) = points.last() else {
        return Ok(Vec::new());
    };
    if n == 0 {
        return Ok(Vec::new());
    }
    if let Some(id) = target {
        let centre = ctx
            .scene
            .object(id)
            .map(|o| o.bbox.center())
            .unwrap_or(Vec3::new(last.x, ctx.scene.floor_height, last.y));
        return Ok(vec![r.render_png(last, centre)?]);
    }
    let mut out = Vec::with_capacity(n as usize);
    for k in 0..n {
        // Fraction of the path's points: 0 = start, 1 = end.
        let f = if n == 1 {
            0.0
        } else {
            k as f32 / (n - 1) as f32
        };
        let i = ((points.len() - 1) as f32 * f).round() as usize;
        let at = points[i];
        let ahead = points
            .get(i + 1)
            .map(|p| *p - at)
            .or_else(|| i.checked_sub(1).map(|j| at - points[j]))
            .unwrap_or(Vec2::ZERO);
        let yaw = if ahead.length_squared() > 1e-8 {
            vlnverse_env::scene_graph::yaw_from_direction(ahead)
        } else {
            ctx.start_yaw
        };
        let rgb = r.render_rgb(at, yaw, 0.0);
        out.push(encode_png(&rgb, image.width, image.height)?);
    }
    Ok(out)
}

/// Write the stage's report (atomically) into `out`.
pub fn write_report(out: &Path, report: &LlmReport) -> Result<()> {
    let mut bytes = serde_json::to_vec_pretty(report).map_err(|e| {
        vlnverse_score::DataError::invalid("llm report", LLM_REPORT_FILE, e.to_string())
    })?;
    bytes.push(b'\n');
    vlnverse_score::dataset::write_atomic(&out.join(LLM_REPORT_FILE), &bytes)
}
