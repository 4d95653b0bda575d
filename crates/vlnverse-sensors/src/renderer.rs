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
//!     fn name(&self) -> String { "blind".into() }
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
/// ([`crate::GpuRenderer`]), the CPU ray caster ([`crate::RaycastRenderer`]) and the CPU
/// rasteriser ([`crate::RasterRenderer`]).
pub trait Renderer: Send {
    /// What renders, for logs and a run's `run.json` (`"wgpu"`, `"raycast"`, `"raster"`; a
    /// wrapper says what it wraps: `"blurred(raster)"`). A resume of a run made with another
    /// name is refused.
    fn name(&self) -> String;

    /// Prepare a scene once; later calls to [`Renderer::render`] show it.
    fn set_scene(&mut self, mesh: Arc<SceneMesh>) -> Result<()>;

    /// Render a batch of views of the current scene (one frame per view, in order). Each frame
    /// holds the channels its view asked for, laid out as documented in [`crate::frame`].
    fn render(&mut self, views: &[View]) -> Result<Vec<Frame>>;

    /// A function that prepares a scene ahead of [`Renderer::set_scene`], from any thread,
    /// for backends that keep prepared scenes in a process-wide cache (a training run's
    /// environments prepare their next homes while they step); `None` (the default) when
    /// there is nothing to prepare ahead.
    fn scene_preparer(&self) -> Option<fn(Arc<SceneMesh>)> {
        None
    }
}

/// Log which backend renders and why: at `info` the first time in a process, at `debug` after
/// (evaluation makes one renderer per worker thread).
macro_rules! announce {
    ($($arg:tt)*) => {
        if ANNOUNCED.swap(true, std::sync::atomic::Ordering::Relaxed) {
            tracing::debug!($($arg)*)
        } else {
            tracing::info!($($arg)*)
        }
    };
}

static ANNOUNCED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Make the renderer a config asks for. `Auto` takes wgpu on a hardware GPU and the CPU
/// rasteriser otherwise (it beats wgpu on lavapipe, and needs no graphics stack); either way
/// one `info` line per process says which backend renders and why. On Linux, `Auto` does not
/// even ask the graphics stack when no GPU device node exists (`/dev/dri/renderD*`,
/// `/dev/nvidia*`), so machines without a GPU see no driver messages.
pub fn create_renderer(backend: Backend) -> Result<Box<dyn Renderer>> {
    match backend {
        Backend::Raycast => {
            announce!("rendering with the CPU ray-cast backend (configured)");
            Ok(Box::new(crate::RaycastRenderer::new()))
        }
        Backend::Raster => {
            announce!("rendering with the CPU rasteriser (configured)");
            Ok(Box::new(crate::RasterRenderer::new()))
        }
        #[cfg(not(feature = "wgpu"))]
        Backend::Wgpu => Err(crate::SensorError::NoAdapter(
            "this build has no wgpu backend (the `wgpu` cargo feature of vlnverse-sensors is \
             off); use backend = \"raster\" or \"raycast\", or build with the feature"
                .into(),
        )),
        #[cfg(not(feature = "wgpu"))]
        Backend::Auto => {
            announce!("rendering with the CPU rasteriser (backend = auto; built without wgpu)");
            Ok(Box::new(crate::RasterRenderer::new()))
        }
        #[cfg(feature = "wgpu")]
        Backend::Wgpu => {
            let r = crate::GpuRenderer::new()?;
            announce!(
                "rendering with wgpu on {} (configured)",
                r.context().adapter_description()
            );
            Ok(Box::new(r))
        }
        #[cfg(feature = "wgpu")]
        Backend::Auto => match hardware_gpu() {
            Some(name) => match crate::GpuRenderer::new() {
                Ok(r) => {
                    announce!(
                        "rendering with wgpu on {} (backend = auto, GPU {name} found)",
                        r.context().adapter_description()
                    );
                    Ok(Box::new(r))
                }
                Err(e) => {
                    announce!("rendering with the CPU rasteriser (backend = auto): {e}");
                    Ok(Box::new(crate::RasterRenderer::new()))
                }
            },
            None => {
                announce!(
                    "rendering with the CPU rasteriser (backend = auto: no hardware GPU adapter; \
                     set backend = \"wgpu\" to use a software Vulkan driver instead)"
                );
                Ok(Box::new(crate::RasterRenderer::new()))
            }
        },
    }
}

/// Whether a GPU device node exists. Only Linux is checked (elsewhere: `true`); `WGPU_BACKEND`
/// set means the user asked for a probe, so it is `true` too.
#[cfg(feature = "wgpu")]
fn gpu_device_node_exists() -> bool {
    if !cfg!(target_os = "linux") || std::env::var_os("WGPU_BACKEND").is_some() {
        return true;
    }
    let has = |dir: &str, prefix: &str| {
        std::fs::read_dir(dir).is_ok_and(|d| {
            d.flatten()
                .any(|e| e.file_name().to_string_lossy().starts_with(prefix))
        })
    };
    // renderD*: DRM render nodes (Mesa, AMD, Intel, nouveau); nvidia*: the proprietary driver;
    // dxg: WSL2's GPU paravirtualisation.
    has("/dev/dri", "renderD") || has("/dev", "nvidia") || has("/dev", "dxg")
}

/// Name of a hardware (or virtualised) GPU adapter, if any, without creating a device. Looks at
/// the backends `WGPU_BACKEND` names, else the native ones (Vulkan, Metal, DX12). Without a GPU
/// device node (see [`gpu_device_node_exists`]) it does not create a wgpu instance at all:
/// Mesa's Vulkan WSI layers print errors (`XDG_RUNTIME_DIR is invalid`) when probed headless.
#[cfg(feature = "wgpu")]
fn hardware_gpu() -> Option<String> {
    if !gpu_device_node_exists() {
        return None;
    }
    let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    pollster::block_on(instance.enumerate_adapters(backends))
        .into_iter()
        .map(|a| a.get_info())
        .find(|i| {
            matches!(
                i.device_type,
                wgpu::DeviceType::DiscreteGpu
                    | wgpu::DeviceType::IntegratedGpu
                    | wgpu::DeviceType::VirtualGpu
            )
        })
        .map(|i| i.name)
}
