//! The observation layout: which arrays a rig gives (keys, dtypes, shapes) and how one
//! environment's readings are copied into its row of the batched buffers.

use std::path::{Path, PathBuf};

use glam::{Quat, Vec3};
use vlnverse_sensors::{Frame, Observation, RigConfig, SensorSpec};
use vlnverse_task::eval::agents::wrap_angle;
use vlnverse_task::eval::EnvStep;

/// Element type of a buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DType {
    U8,
    U16,
    U32,
    F32,
    I64,
}

impl DType {
    /// NumPy's name.
    pub fn numpy(self) -> &'static str {
        match self {
            DType::U8 => "uint8",
            DType::U16 => "uint16",
            DType::U32 => "uint32",
            DType::F32 => "float32",
            DType::I64 => "int64",
        }
    }
}

/// Where a field's values come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// Colour image of sensor `name`.
    Rgb(String),
    /// Depth image of sensor `name`, times a factor (to or from `[0, 1]`).
    Depth(String, f32),
    /// Class-id image.
    Semantic(String),
    /// Object-id image.
    Instance(String),
    /// LiDAR ranges.
    Lidar(String),
    /// Panorama colour views.
    PanoRgb(String),
    /// Panorama depth views, times a factor (to or from `[0, 1]`).
    PanoDepth(String, f32),
    /// Base pose: x, y, z, yaw.
    Pose,
    /// Heading relative to the start (radians).
    Compass,
    /// Position relative to the start in the start frame: forward, right (habitat's order).
    Gps,
    /// Instruction token ids.
    Tokens,
    /// Long-horizon: index of the sub-instruction being followed.
    SubGoal,
    /// Visual reference: the episode's goal image (PNGs under this folder), read at reset.
    Reference(PathBuf),
}

/// One observation array.
#[derive(Debug, Clone)]
pub struct Field {
    /// Key in the observation dict.
    pub key: String,
    /// Element type.
    pub dtype: DType,
    /// Shape of one environment's value.
    pub shape: Vec<usize>,
    /// What fills it.
    pub source: Source,
}

impl Field {
    fn new(key: impl Into<String>, dtype: DType, shape: Vec<usize>, source: Source) -> Self {
        Field {
            key: key.into(),
            dtype,
            shape,
            source,
        }
    }

    /// Elements of one environment's value.
    pub fn len(&self) -> usize {
        self.shape.iter().product()
    }
}

/// The reference images of a visual-reference split: their folder and size.
#[derive(Debug, Clone)]
pub struct ReferenceImages {
    /// Folder the episodes' `reference_image` paths are relative to.
    pub dir: PathBuf,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// The fields of a rig (when rendering) plus pose, compass, GPS, tokens, sub-goal and (for
/// visual-reference episodes) the reference image.
///
/// The first colour camera is `rgb` and the first depth camera `depth` (VLN-CE's keys);
/// further cameras keep their configured names.
pub fn fields(
    rig: Option<&RigConfig>,
    normalize_depth: bool,
    tokens: usize,
    reference: Option<&ReferenceImages>,
) -> Vec<Field> {
    let mut out = Vec::new();
    // Factor from the rig's depth values to the layout's: metres or [0, 1] whatever the rig
    // gives (a rig that normalises is scaled back to metres when asked for metres).
    let far = |f: f32, own: bool| match (normalize_depth, own) {
        (true, false) => 1.0 / f,
        (false, true) => f,
        _ => 1.0,
    };
    for spec in rig.map(|r| r.sensors.as_slice()).unwrap_or_default() {
        let name = spec.name().to_string();
        let key = |default: &str, out: &[Field]| {
            if name == default || !out.iter().any(|f| f.key == default) {
                default.to_string()
            } else {
                name.clone()
            }
        };
        match spec {
            SensorSpec::Rgb(c) => {
                let k = key("rgb", &out);
                let shape = vec![c.height as usize, c.width as usize, 3];
                out.push(Field::new(k, DType::U8, shape, Source::Rgb(name.clone())));
            }
            SensorSpec::Depth(c) => {
                let k = key("depth", &out);
                let shape = vec![c.height as usize, c.width as usize, 1];
                let src = Source::Depth(name.clone(), far(c.far, c.normalize));
                out.push(Field::new(k, DType::F32, shape, src));
            }
            SensorSpec::Semantic(c) => {
                let k = key("semantic", &out);
                let shape = vec![c.height as usize, c.width as usize, 1];
                out.push(Field::new(
                    k,
                    DType::U16,
                    shape,
                    Source::Semantic(name.clone()),
                ));
            }
            SensorSpec::Instance(c) => {
                let k = key("instance", &out);
                let shape = vec![c.height as usize, c.width as usize, 1];
                out.push(Field::new(
                    k,
                    DType::U32,
                    shape,
                    Source::Instance(name.clone()),
                ));
            }
            SensorSpec::Lidar(l) => {
                let k = key("lidar", &out);
                let shape = vec![l.channels as usize, l.beams as usize];
                out.push(Field::new(
                    k,
                    DType::F32,
                    shape,
                    Source::Lidar(name.clone()),
                ));
            }
            SensorSpec::Panorama(p) => {
                let (v, h, w) = (
                    p.views as usize,
                    p.camera.height as usize,
                    p.camera.width as usize,
                );
                if p.rgb {
                    let src = Source::PanoRgb(name.clone());
                    out.push(Field::new(
                        format!("{name}_rgb"),
                        DType::U8,
                        vec![v, h, w, 3],
                        src,
                    ));
                }
                if p.depth {
                    let src =
                        Source::PanoDepth(name.clone(), far(p.camera.far, p.camera.normalize));
                    out.push(Field::new(
                        format!("{name}_depth"),
                        DType::F32,
                        vec![v, h, w, 1],
                        src,
                    ));
                }
            }
            // Pose, compass and GPS come from the episode state below; collisions are in info.
            SensorSpec::Pose(_)
            | SensorSpec::Compass(_)
            | SensorSpec::Gps(_)
            | SensorSpec::Collision(_) => {}
        }
    }
    out.push(Field::new("pose", DType::F32, vec![4], Source::Pose));
    out.push(Field::new("compass", DType::F32, vec![1], Source::Compass));
    out.push(Field::new("gps", DType::F32, vec![2], Source::Gps));
    out.push(Field::new(
        "instruction_tokens",
        DType::I64,
        vec![tokens],
        Source::Tokens,
    ));
    out.push(Field::new(
        "sub_instruction_index",
        DType::I64,
        vec![1],
        Source::SubGoal,
    ));
    if let Some(r) = reference {
        out.push(Field::new(
            "reference_image",
            DType::U8,
            vec![r.height as usize, r.width as usize, 3],
            Source::Reference(r.dir.clone()),
        ));
    }
    out
}

/// Decode a reference PNG as RGB bytes with its size; errors name the file.
pub fn read_reference(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let img = image::open(path)
        .map_err(|e| format!("reference image {}: {e}", path.display()))?
        .to_rgb8();
    Ok((img.width(), img.height(), img.into_raw()))
}

/// One environment's row of a buffer.
pub enum Row<'a> {
    U8(&'a mut [u8]),
    U16(&'a mut [u16]),
    U32(&'a mut [u32]),
    F32(&'a mut [f32]),
    I64(&'a mut [i64]),
}

fn frame<'o>(step: &'o EnvStep, name: &str) -> Option<&'o Frame> {
    match step.observations.get(name)? {
        Observation::Rgb(f)
        | Observation::Depth(f)
        | Observation::Semantic(f)
        | Observation::Instance(f) => Some(f),
        _ => None,
    }
}

fn copy_scaled(dst: &mut [f32], src: &[f32], factor: f32) {
    if factor == 1.0 {
        dst.copy_from_slice(src);
    } else {
        for (d, s) in dst.iter_mut().zip(src) {
            *d = s * factor;
        }
    }
}

/// Copy one environment's value of `field` into `row`. A sensor not due at this step (its
/// rate) leaves the row as it was; a size mismatch is an error naming the key.
pub fn write(
    field: &Field,
    step: &EnvStep,
    tokens: Option<&[u32]>,
    row: Row<'_>,
) -> Result<(), String> {
    let size = |n: usize| {
        if n == field.len() {
            Ok(())
        } else {
            Err(format!(
                "observation `{}`: the sensor gave {n} values, the layout expects {}",
                field.key,
                field.len()
            ))
        }
    };
    match (&field.source, row) {
        (Source::Rgb(n), Row::U8(d)) => {
            if let Some(f) = frame(step, n) {
                size(f.rgb.len())?;
                d.copy_from_slice(&f.rgb);
            }
        }
        (Source::Depth(n, far), Row::F32(d)) => {
            if let Some(f) = frame(step, n) {
                size(f.depth.len())?;
                copy_scaled(d, &f.depth, *far);
            }
        }
        (Source::Semantic(n), Row::U16(d)) => {
            if let Some(f) = frame(step, n) {
                size(f.semantic.len())?;
                d.copy_from_slice(&f.semantic);
            }
        }
        (Source::Instance(n), Row::U32(d)) => {
            if let Some(f) = frame(step, n) {
                size(f.instance.len())?;
                d.copy_from_slice(&f.instance);
            }
        }
        (Source::Lidar(n), Row::F32(d)) => {
            if let Some(Observation::Lidar(s)) = step.observations.get(n) {
                size(s.ranges.len())?;
                d.copy_from_slice(&s.ranges);
            }
        }
        (Source::PanoRgb(n), Row::U8(d)) => {
            if let Some(Observation::Panorama(views)) = step.observations.get(n) {
                size(views.iter().map(|v| v.rgb.len()).sum())?;
                // Views share one camera, so they are equal in size.
                for (dst, v) in d.chunks_mut(d.len() / views.len()).zip(views) {
                    dst.copy_from_slice(&v.rgb);
                }
            }
        }
        (Source::PanoDepth(n, far), Row::F32(d)) => {
            if let Some(Observation::Panorama(views)) = step.observations.get(n) {
                size(views.iter().map(|v| v.depth.len()).sum())?;
                for (dst, v) in d.chunks_mut(d.len() / views.len()).zip(views) {
                    copy_scaled(dst, &v.depth, *far);
                }
            }
        }
        (Source::Pose, Row::F32(d)) => {
            let p = step.pose.position;
            d.copy_from_slice(&[p[0], p[1], p[2], step.pose.yaw()]);
        }
        (Source::Compass, Row::F32(d)) => d[0] = wrap_angle(step.pose.yaw() - step.start.yaw()),
        (Source::Gps, Row::F32(d)) => {
            let rel = Quat::from_array(step.start.rotation).inverse()
                * (Vec3::from_array(step.pose.position) - Vec3::from_array(step.start.position));
            d[0] = -rel.z;
            d[1] = rel.x;
        }
        (Source::Tokens, Row::I64(d)) => {
            if let Some(tokens) = tokens {
                for (o, t) in d.iter_mut().zip(tokens) {
                    *o = i64::from(*t);
                }
            }
        }
        (Source::SubGoal, Row::I64(d)) => d[0] = i64::from(step.info.sub_goal),
        (Source::Reference(dir), Row::U8(d)) => {
            // The image belongs to the episode: read it when the episode starts.
            if step.info.steps == 0 {
                match &step.episode.reference_image {
                    Some(r) => {
                        let (w, h, rgb) = read_reference(&dir.join(r))?;
                        if rgb.len() != d.len() {
                            return Err(format!(
                                "reference image {}: {w}x{h}, but the split's images are \
                                 {}x{} (the size of its first episode's image)",
                                dir.join(r).display(),
                                field.shape[1],
                                field.shape[0]
                            ));
                        }
                        d.copy_from_slice(&rgb);
                    }
                    None => d.fill(0),
                }
            }
        }
        _ => return Err(format!("observation `{}`: wrong buffer type", field.key)),
    }
    Ok(())
}
