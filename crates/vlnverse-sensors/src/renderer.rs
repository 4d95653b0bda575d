//! The swap point for how images are made: [`Renderer`], and [`create_renderer`] choosing a
//! backend from the config.
//!
//! ```
//! use std::sync::Arc;
//! use vlnverse_sensors::{Frame, Renderer, Result, SceneMesh, View};
//!
//! /// A renderer that sees nothing: every pixel at the far plane, no object.
//! struct Blind;
//!
//! impl Renderer for Blind {
//!     fn name(&self) -> &'static str { "blind" }
//!     fn set_scene(&mut self, _mesh: Arc<SceneMesh>) -> Result<()> { Ok(()) }
//!     fn render(&mut self, views: &[View]) -> Result<Vec<Frame>> {
//!         Ok(views.iter().map(|v| {
//!             let (w, h) = (v.camera.width, v.camera.height);
//!             let n = (w * h) as usize;
//!             Frame {
//!                 width: w,
//!                 height: h,
//!                 rgb: if v.channels.rgb { vec![0; 3 * n] } else { vec![] },
//!                 depth: if v.channels.depth { vec![v.camera.far; n] } else { vec![] },
//!                 semantic: if v.channels.semantic { vec![0; n] } else { vec![] },
//!                 instance: if v.channels.instance { vec![0; n] } else { vec![] },
//!             }
//!         }).collect())
//!     }
//! }
//! ```

use crate::config::Backend;
use crate::error::Result;
use crate::frame::{Frame, View};
use crate::scene_mesh::SceneMesh;
use std::sync::Arc;

/// Makes images of a scene from cameras. Implemented by the wgpu rasteriser
/// ([`crate::GpuRenderer`]) and the CPU ray caster ([`crate::RaycastRenderer`]).
pub trait Renderer: Send {
    /// Short backend name for logs (`"wgpu"`, `"raycast"`).
    fn name(&self) -> &'static str;

    /// Prepare a scene once; later calls to [`Renderer::render`] show it.
    fn set_scene(&mut self, mesh: Arc<SceneMesh>) -> Result<()>;

    /// Render a batch of views of the current scene (one frame per view, in order). Each frame
    /// holds the channels its view asked for, laid out as documented in [`crate::frame`].
    fn render(&mut self, views: &[View]) -> Result<Vec<Frame>>;
}

/// Make the renderer a config asks for. `Auto` takes wgpu when an adapter exists and the
/// ray caster otherwise; either way one `info` line says which backend renders and why.
pub fn create_renderer(backend: Backend) -> Result<Box<dyn Renderer>> {
    match backend {
        Backend::Raycast => {
            tracing::info!("rendering with the CPU ray-cast backend (configured)");
            Ok(Box::new(crate::RaycastRenderer::new()))
        }
        Backend::Wgpu => {
            let r = crate::GpuRenderer::new()?;
            tracing::info!(
                "rendering with wgpu on {} (configured)",
                r.context().adapter_description()
            );
            Ok(Box::new(r))
        }
        Backend::Auto => match crate::GpuRenderer::new() {
            Ok(r) => {
                tracing::info!(
                    "rendering with wgpu on {} (backend = auto)",
                    r.context().adapter_description()
                );
                Ok(Box::new(r))
            }
            Err(e) => {
                tracing::info!("rendering with the CPU ray-cast backend (backend = auto): {e}");
                Ok(Box::new(crate::RaycastRenderer::new()))
            }
        },
    }
}
