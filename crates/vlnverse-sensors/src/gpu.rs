//! The wgpu offscreen rasteriser.
//!
//! One render pass writes three targets per view: lit colour (`Rgba8Unorm`), linear depth along
//! the optical axis as `bitcast<u32>(f32)` in an `R32Uint` target (works on Vulkan and GL, which
//! can neither copy `Depth32Float` to a buffer nor render `R32Float`), and the object id
//! (`R32Uint`; the class comes from a lookup table). A batch of views is laid out as tiles of one
//! 2-D atlas (no texture arrays: on GL a square array with 6k layers silently becomes a cube map),
//! rendered and read back in one submission. The scene is uploaded once as one vertex buffer with
//! a contiguous range per object; each view draws only the objects whose box meets its frustum.
//!
//! The device is process-wide and created lazily ([`shared_context`]): on a CPU the software
//! driver (lavapipe) already uses every core, so several devices would only oversubscribe.

use crate::error::{Result, SensorError};
use crate::frame::{Channels, Frame, View};
use crate::renderer::Renderer;
use crate::scene_mesh::SceneMesh;
use crate::shading;
use std::sync::{Arc, OnceLock};
use wgpu::util::DeviceExt;

/// Packages that provide a software Vulkan driver on Debian/Ubuntu.
pub const SOFTWARE_VULKAN_PACKAGES: &str = "mesa-vulkan-drivers libvulkan1";

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const UINT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
const UNIFORM_STRIDE: u64 = 256;

const SHADER: &str = r#"
struct ViewU { view_proj: mat4x4<f32>, cam_pos: vec4<f32>, forward: vec4<f32>, light: vec4<f32> };
@group(0) @binding(0) var<uniform> u: ViewU;

struct VIn {
    @location(0) pos: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) id: u32,
};
struct VOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) rel: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
    @location(3) @interpolate(flat) id: u32,
};
@vertex fn vs(v: VIn) -> VOut {
    var o: VOut;
    o.clip = u.view_proj * vec4<f32>(v.pos, 1.0);
    o.rel = v.pos - u.cam_pos.xyz;
    o.normal = v.normal;
    o.color = v.color.rgb;
    o.id = v.id;
    return o;
}
struct FOut {
    @location(0) color: vec4<f32>,
    @location(1) depth: u32,
    @location(2) id: u32,
};
@fragment fn fs(i: VOut) -> FOut {
    var n = normalize(i.normal);
    if (dot(n, i.rel) > 0.0) { n = -n; }
    let k = u.light.w + u.cam_pos.w * max(dot(n, u.light.xyz), 0.0);
    let c = pow(clamp(i.color * k, vec3<f32>(0.0), vec3<f32>(1.0)), vec3<f32>(1.0 / 2.2));
    var o: FOut;
    o.color = vec4<f32>(c, 1.0);
    o.depth = bitcast<u32>(dot(i.rel, u.forward.xyz));
    o.id = i.id;
    return o;
}
"#;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    pos: [f32; 3],
    normal: [f32; 3],
    color: [u8; 4],
    id: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ViewUniform {
    view_proj: [[f32; 4]; 4],
    /// xyz camera position, w diffuse factor.
    cam_pos: [f32; 4],
    forward: [f32; 4],
    /// xyz towards the light, w ambient factor.
    light: [f32; 4],
}

/// The process-wide wgpu device, queue and pipeline.
pub struct GpuContext {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    max_dim: u32,
}

impl GpuContext {
    /// Adapter name and backend, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) on Vulkan`.
    pub fn adapter_description(&self) -> String {
        format!("{} on {:?}", self.info.name, self.info.backend)
    }

    /// Whether the adapter is a software rasteriser running on the CPU.
    pub fn is_cpu(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

static CONTEXT: OnceLock<std::result::Result<Arc<GpuContext>, String>> = OnceLock::new();

/// The shared device, created on first use. Fails with a message naming the packages of the
/// software driver and the ray-cast fallback when no adapter exists.
pub fn shared_context() -> Result<Arc<GpuContext>> {
    CONTEXT
        .get_or_init(|| create_context().map(Arc::new))
        .clone()
        .map_err(SensorError::NoAdapter)
}

fn request_adapter(backends: wgpu::Backends) -> std::result::Result<wgpu::Adapter, String> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: None,
        ..Default::default()
    }))
    .map_err(|e| e.to_string())
}

fn create_context() -> std::result::Result<GpuContext, String> {
    // WGPU_BACKEND overrides; otherwise native APIs first and GL only when they have no adapter
    // (probing GL on a headless box prints display warnings).
    let adapter = match wgpu::Backends::from_env() {
        Some(b) => request_adapter(b),
        None => request_adapter(wgpu::Backends::PRIMARY)
            .or_else(|_| request_adapter(wgpu::Backends::GL)),
    }
    .map_err(|e| {
        format!(
            "no GPU or software rasteriser found ({e}); install a Vulkan driver (on Debian/Ubuntu: \
             `apt-get install {SOFTWARE_VULKAN_PACKAGES}`, the lavapipe CPU driver) or use the CPU \
             ray-cast backend (`backend = \"raycast\"` in the sensor config)"
        )
    })?;
    let info = adapter.get_info();
    let limits = wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits());
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("vlnverse-sensors"),
        required_limits: limits.clone(),
        ..Default::default()
    }))
    .map_err(|e| format!("adapter {} refused a device: {e}", info.name))?;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("vlnverse-sensors shader"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("view"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<ViewUniform>() as u64),
            },
            count: None,
        }],
    });
    let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("view"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let attrs =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4, 3 => Uint32];
    let target = |format| {
        Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })
    };
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("scene"),
        layout: Some(&pl),
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &attrs,
            })],
        },
        // Two-sided: imported meshes have any winding, and the ray caster is two-sided too.
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &shader,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[
                target(COLOR_FORMAT),
                target(UINT_FORMAT),
                target(UINT_FORMAT),
            ],
        }),
        multiview_mask: None,
        cache: None,
    });
    let max_dim = limits.max_texture_dimension_2d;
    Ok(GpuContext {
        device,
        queue,
        info,
        pipeline,
        layout,
        max_dim,
    })
}

struct Atlas {
    size: (u32, u32),
    color: wgpu::Texture,
    depth: wgpu::Texture,
    id: wgpu::Texture,
    zbuf: wgpu::TextureView,
    readback: [wgpu::Buffer; 3],
    bytes_per_row: u32,
}

struct GpuScene {
    mesh: Arc<SceneMesh>,
    vertices: wgpu::Buffer,
}

/// The wgpu backend of [`Renderer`].
pub struct GpuRenderer {
    ctx: Arc<GpuContext>,
    scene: Option<GpuScene>,
    atlas: Option<Atlas>,
    uniforms: Option<(wgpu::Buffer, wgpu::BindGroup, usize)>,
}

impl GpuRenderer {
    /// A renderer on the shared device ([`shared_context`]).
    pub fn new() -> Result<Self> {
        Ok(GpuRenderer {
            ctx: shared_context()?,
            scene: None,
            atlas: None,
            uniforms: None,
        })
    }

    /// The device this renderer draws with.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    fn ensure_atlas(&mut self, w: u32, h: u32) {
        if self.atlas.as_ref().is_some_and(|a| a.size == (w, h)) {
            return;
        }
        let d = &self.ctx.device;
        let tex = |format, label| {
            d.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let bytes_per_row = (w * 4).div_ceil(256) * 256;
        let buf = |label| {
            d.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes_per_row as u64 * h as u64,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let zbuf = tex(DEPTH_FORMAT, "zbuffer").create_view(&Default::default());
        self.atlas = Some(Atlas {
            size: (w, h),
            color: tex(COLOR_FORMAT, "color"),
            depth: tex(UINT_FORMAT, "linear depth"),
            id: tex(UINT_FORMAT, "instance"),
            zbuf,
            readback: [
                buf("color readback"),
                buf("depth readback"),
                buf("id readback"),
            ],
            bytes_per_row,
        });
    }

    fn ensure_uniforms(&mut self, n: usize) {
        if self.uniforms.as_ref().is_some_and(|u| u.2 >= n) {
            return;
        }
        let n = n.next_power_of_two();
        let d = &self.ctx.device;
        let buf = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("views"),
            size: UNIFORM_STRIDE * n as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bg = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("views"),
            layout: &self.ctx.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &buf,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<ViewUniform>() as u64),
                }),
            }],
        });
        self.uniforms = Some((buf, bg, n));
    }

    /// Render views that fit in one atlas.
    fn render_chunk(&mut self, views: &[View], tile: (u32, u32), cols: u32) -> Result<Vec<Frame>> {
        let rows = (views.len() as u32).div_ceil(cols);
        let cols_used = cols.min(views.len() as u32);
        self.ensure_atlas(cols_used * tile.0, rows * tile.1);
        self.ensure_uniforms(views.len());
        let scene = self.scene.as_ref().ok_or(SensorError::NoScene)?;
        let atlas = self.atlas.as_ref().ok_or(SensorError::NoScene)?;
        let (ubuf, bg, _) = self.uniforms.as_ref().ok_or(SensorError::NoScene)?;
        let ctx = &self.ctx;
        let mut data = vec![0u8; UNIFORM_STRIDE as usize * views.len()];
        let light = shading::light_dir();
        for (i, v) in views.iter().enumerate() {
            let c = &v.camera;
            let u = ViewUniform {
                view_proj: c.view_projection().to_cols_array_2d(),
                cam_pos: [c.position.x, c.position.y, c.position.z, shading::DIFFUSE],
                forward: c.forward().extend(0.0).to_array(),
                light: [light.x, light.y, light.z, shading::AMBIENT],
            };
            let off = i * UNIFORM_STRIDE as usize;
            data[off..off + std::mem::size_of::<ViewUniform>()]
                .copy_from_slice(bytemuck::bytes_of(&u));
        }
        ctx.queue.write_buffer(ubuf, 0, &data);

        let mut enc = ctx.device.create_command_encoder(&Default::default());
        let cv = atlas.color.create_view(&Default::default());
        let dv = atlas.depth.create_view(&Default::default());
        let iv = atlas.id.create_view(&Default::default());
        {
            let att = |view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            };
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("views"),
                color_attachments: &[att(&cv), att(&dv), att(&iv)],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &atlas.zbuf,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&ctx.pipeline);
            pass.set_vertex_buffer(0, scene.vertices.slice(..));
            for (i, v) in views.iter().enumerate() {
                let (x, y) = ((i as u32 % cols) * tile.0, (i as u32 / cols) * tile.1);
                let (w, h) = (v.camera.width, v.camera.height);
                pass.set_viewport(x as f32, y as f32, w as f32, h as f32, 0.0, 1.0);
                pass.set_scissor_rect(x, y, w, h);
                pass.set_bind_group(0, bg, &[(i as u64 * UNIFORM_STRIDE) as u32]);
                let frustum = v.camera.frustum();
                let mut run: Option<(u32, u32)> = None;
                for o in &scene.mesh.objects {
                    if frustum.intersects_aabb(&o.bbox) {
                        run = match run {
                            Some((s, e)) if e == o.first => Some((s, o.first + o.count)),
                            Some((s, e)) => {
                                pass.draw(s * 3..e * 3, 0..1);
                                Some((o.first, o.first + o.count))
                            }
                            None => Some((o.first, o.first + o.count)),
                        };
                    }
                }
                if let Some((s, e)) = run {
                    pass.draw(s * 3..e * 3, 0..1);
                }
            }
        }
        let want = views
            .iter()
            .fold(Channels::default(), |a, v| a.union(v.channels));
        let targets = [
            (&atlas.color, want.rgb),
            (&atlas.depth, want.depth),
            (&atlas.id, want.ids()),
        ];
        for (k, (tex, wanted)) in targets.iter().enumerate() {
            if !wanted {
                continue;
            }
            enc.copy_texture_to_buffer(
                tex.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &atlas.readback[k],
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(atlas.bytes_per_row),
                        rows_per_image: None,
                    },
                },
                wgpu::Extent3d {
                    width: atlas.size.0,
                    height: atlas.size.1,
                    depth_or_array_layers: 1,
                },
            );
        }
        ctx.queue.submit([enc.finish()]);
        let (tx, rx) = std::sync::mpsc::channel();
        for (k, (_, wanted)) in targets.iter().enumerate() {
            if *wanted {
                let tx = tx.clone();
                atlas.readback[k].map_async(wgpu::MapMode::Read, .., move |r| {
                    let _ = tx.send(r);
                });
            }
        }
        drop(tx);
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| SensorError::Gpu(e.to_string()))?;
        for r in rx.iter() {
            r.map_err(|e| SensorError::Gpu(format!("readback failed: {e}")))?;
        }
        let mapped: Vec<Option<wgpu::BufferView>> = targets
            .iter()
            .enumerate()
            .map(|(k, (_, wanted))| {
                wanted
                    .then(|| atlas.readback[k].get_mapped_range(..))
                    .transpose()
                    .map_err(|e| SensorError::Gpu(format!("readback failed: {e:?}")))
            })
            .collect::<Result<_>>()?;
        let bpr = atlas.bytes_per_row as usize;
        let mut frames = Vec::with_capacity(views.len());
        for (i, v) in views.iter().enumerate() {
            let (x0, y0) = (
                ((i as u32 % cols) * tile.0) as usize,
                ((i as u32 / cols) * tile.1) as usize,
            );
            let (w, h) = (v.camera.width as usize, v.camera.height as usize);
            let mut f = Frame {
                width: v.camera.width,
                height: v.camera.height,
                ..Default::default()
            };
            let rows = |k: usize| {
                let m: &[u8] = mapped[k].as_deref().unwrap_or(&[]);
                (0..h).map(move |r| {
                    let s = (y0 + r) * bpr + x0 * 4;
                    &m[s..s + w * 4]
                })
            };
            if v.channels.rgb {
                f.rgb.reserve(w * h * 3);
                for row in rows(0) {
                    for px in row.chunks_exact(4) {
                        f.rgb.extend_from_slice(&px[..3]);
                    }
                }
            }
            if v.channels.depth {
                let far = v.camera.far;
                f.depth.reserve(w * h);
                for row in rows(1) {
                    f.depth.extend(row.chunks_exact(4).map(|b| {
                        let d = f32::from_bits(u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
                        if d > 0.0 && d < far {
                            d
                        } else {
                            far
                        }
                    }));
                }
            }
            if v.channels.ids() {
                let mut ids = Vec::with_capacity(w * h);
                for row in rows(2) {
                    ids.extend(
                        row.chunks_exact(4)
                            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    );
                }
                if v.channels.semantic {
                    f.semantic = ids.iter().map(|&id| scene.mesh.class(id)).collect();
                }
                if v.channels.instance {
                    f.instance = ids;
                }
            }
            frames.push(f);
        }
        drop(mapped);
        for (k, (_, wanted)) in targets.iter().enumerate() {
            if *wanted {
                atlas.readback[k].unmap();
            }
        }
        Ok(frames)
    }
}

impl Renderer for GpuRenderer {
    fn name(&self) -> &'static str {
        "wgpu"
    }

    fn set_scene(&mut self, mesh: Arc<SceneMesh>) -> Result<()> {
        let verts: Vec<Vertex> = (0..mesh.triangle_count())
            .flat_map(|t| {
                let n = mesh.normal(t).to_array();
                let c = mesh.color[t].map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
                let id = mesh.object[t];
                let m = &mesh;
                (0..3).map(move |k| Vertex {
                    pos: m.positions[3 * t + k].to_array(),
                    normal: n,
                    color: [c[0], c[1], c[2], 255],
                    id,
                })
            })
            .collect();
        let vertices = self
            .ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene vertices"),
                contents: bytemuck::cast_slice(&verts),
                usage: wgpu::BufferUsages::VERTEX,
            });
        self.scene = Some(GpuScene { mesh, vertices });
        Ok(())
    }

    fn render(&mut self, views: &[View]) -> Result<Vec<Frame>> {
        if self.scene.is_none() {
            return Err(SensorError::NoScene);
        }
        if views.is_empty() {
            return Ok(Vec::new());
        }
        let tile = views.iter().fold((1, 1), |(w, h), v| {
            (w.max(v.camera.width), h.max(v.camera.height))
        });
        let max = self.ctx.max_dim;
        if tile.0 > max || tile.1 > max {
            return Err(SensorError::invalid(
                "width/height",
                format!("{}x{}", tile.0, tile.1),
                format!("the device allows at most {max} pixels per side"),
            ));
        }
        let cols = (max / tile.0).max(1);
        let per_chunk = (cols * (max / tile.1).max(1)) as usize;
        let mut out = Vec::with_capacity(views.len());
        for chunk in views.chunks(per_chunk) {
            out.extend(self.render_chunk(chunk, tile, cols)?);
        }
        Ok(out)
    }
}
