//! Observations to files (the formats of `cargo xtask render`, see `docs/formats.md`):
//!
//! - RGB camera `NAME`: `NAME.png` (8-bit sRGB, as rendered, noise included);
//! - depth camera: `NAME.png` (16-bit, millimetres along the optical axis; a `normalize`d depth
//!   sensor is written in metres too);
//! - semantic / instance camera: `NAME.png` (ids colourised with [`colorize_ids`]);
//! - panorama: `NAME_K_rgb.png`, `NAME_K_depth.png`, `NAME_K_semantic.png` for view `K`;
//! - LiDAR: `NAME.npy` (little-endian float32, shape `[channels, beams]`, metres) and
//!   `NAME.png` (the scan from above in the sensor frame);
//! - [`write_rig`] adds `camera.json` (intrinsics and world pose of every camera) and
//!   `sensors.json` (agent pose, backend, state readings, LiDAR beam layouts).
//!
//! [`npy`] is the one `.npy` writer of the workspace (format 1.0, little-endian, C order):
//! the header is a dozen lines of a frozen format, which the `.npy` crates would bring with a
//! Python-literal parser (`npyz`, `ndarray-npy`) or only for 1-D arrays (`npy-writer`).

use std::path::{Path, PathBuf};

use glam::Vec3;
use serde_json::{json, Value};
use vlnverse_env::Pose;

use crate::frame::colorize_ids;
use crate::lidar::{beam_azimuth, ring_elevation};
use crate::{
    Camera, Frame, Intrinsics, LidarScan, LidarSpec, Observation, Observations, Result, RigConfig,
    SensorError, SensorSpec,
};

/// An element type of a `.npy` array: its NumPy `descr` and little-endian bytes.
pub trait NpyElement: Copy {
    /// The NumPy type string (`<f4`, `|u1`, `<u2`, `<u4`).
    const DESCR: &'static str;
    /// Append the little-endian bytes of `self`.
    fn put_le(self, out: &mut Vec<u8>);
}

macro_rules! npy_element {
    ($t:ty, $descr:literal) => {
        impl NpyElement for $t {
            const DESCR: &'static str = $descr;
            fn put_le(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    };
}

npy_element!(f32, "<f4");
npy_element!(u8, "|u1");
npy_element!(u16, "<u2");
npy_element!(u32, "<u4");

/// The bytes of a `.npy` file (format 1.0) holding `data` in C order with `shape`; the
/// header is padded so the data starts at a multiple of 64 bytes. Errors when `data` does not
/// have `shape`'s number of elements.
pub fn npy<T: NpyElement>(shape: &[usize], data: &[T]) -> Result<Vec<u8>> {
    let want = shape.iter().try_fold(1usize, |n, &d| n.checked_mul(d));
    if want != Some(data.len()) {
        return Err(SensorError::invalid(
            "npy shape",
            format!("{shape:?}"),
            format!("the array has {} elements", data.len()),
        ));
    }
    let dims: String = shape
        .iter()
        .map(|d| format!("{d},"))
        .collect::<Vec<_>>()
        .join(" ");
    let mut header = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': ({dims}), }}",
        T::DESCR
    );
    // Magic (6) + version (2) + length (2) + header + '\n', padded to a multiple of 64.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = Vec::with_capacity(10 + header.len() + std::mem::size_of_val(data));
    bytes.extend_from_slice(b"\x93NUMPY\x01\x00");
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    for &v in data {
        v.put_le(&mut bytes);
    }
    Ok(bytes)
}

fn encode_error(what: &str, e: impl std::fmt::Display) -> SensorError {
    SensorError::Write {
        path: PathBuf::from(what),
        message: e.to_string(),
    }
}

/// PNG bytes of `width x height` pixels of `color` (8-bit channels, or 16-bit big-endian
/// as the `image` crate takes them natively).
fn png(
    what: &str,
    data: &[u8],
    width: u32,
    height: u32,
    color: image::ColorType,
) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    image::write_buffer_with_format(
        &mut std::io::Cursor::new(&mut out),
        data,
        width,
        height,
        color,
        image::ImageFormat::Png,
    )
    .map_err(|e| encode_error(what, e))?;
    Ok(out)
}

/// PNG bytes of a frame's RGB channel (8-bit sRGB).
pub fn rgb_png(f: &Frame) -> Result<Vec<u8>> {
    png(
        "rgb frame",
        &f.rgb,
        f.width,
        f.height,
        image::ColorType::Rgb8,
    )
}

/// PNG bytes of a frame's depth as 16-bit millimetres of `depth * scale` metres (`scale` is
/// `far` for a normalised depth sensor, else 1), rounded and clipped to `[0, 65535]`.
pub fn depth_png(f: &Frame, scale: f32) -> Result<Vec<u8>> {
    let mm: Vec<u16> = f
        .depth
        .iter()
        .map(|d| (d * scale * 1000.0).round().clamp(0.0, 65535.0) as u16)
        .collect();
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(f.width, f.height, mm)
        .ok_or_else(|| encode_error("depth frame", "fewer depth values than pixels"))?;
    let mut out = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut out), image::ImageFormat::Png)
        .map_err(|e| encode_error("depth frame", e))?;
    Ok(out)
}

/// PNG bytes of per-pixel ids colourised with the fixed palette ([`colorize_ids`]).
pub fn ids_png(f: &Frame, ids: impl IntoIterator<Item = u32>) -> Result<Vec<u8>> {
    let c = colorize_ids(ids);
    png("id frame", &c, f.width, f.height, image::ColorType::Rgb8)
}

/// The scan from above in the sensor frame (forward up, left to the left), 256 x 256 pixels
/// spanning the farthest return around the sensor: returns in black, the sensor as a red dot.
pub fn lidar_png(l: &LidarSpec, scan: &LidarScan) -> Result<Vec<u8>> {
    const SIZE: u32 = 256;
    let mut img = image::RgbImage::from_pixel(SIZE, SIZE, image::Rgb([255, 255, 255]));
    let half = SIZE as f32 / 2.0;
    let mut points = Vec::with_capacity(scan.ranges.len());
    for k in 0..scan.channels {
        let elevation = ring_elevation(l, k);
        for i in 0..scan.beams {
            let Some(&r) = scan.ranges.get((k * scan.beams + i) as usize) else {
                continue;
            };
            if r.is_finite() {
                // Azimuth counter-clockwise from forward (-Z): left is -X.
                let (a, horiz) = (beam_azimuth(l, i), r * elevation.cos());
                points.push((-a.sin() * horiz, -a.cos() * horiz));
            }
        }
    }
    let reach = points
        .iter()
        .map(|(x, z)| x.abs().max(z.abs()))
        .fold(1.0f32, f32::max);
    let scale = (half - 2.0) / reach;
    for (x, z) in points {
        let (px, py) = (half + x * scale, half + z * scale);
        if px >= 0.0 && py >= 0.0 && px < SIZE as f32 && py < SIZE as f32 {
            img.put_pixel(px as u32, py as u32, image::Rgb([0, 0, 0]));
        }
    }
    for dy in -2i32..=2 {
        for dx in -2i32..=2 {
            if dx * dx + dy * dy <= 4 {
                let (x, y) = ((half as i32 + dx) as u32, (half as i32 + dy) as u32);
                img.put_pixel(x, y, image::Rgb([220, 30, 30]));
            }
        }
    }
    png(
        "lidar plot",
        img.as_raw(),
        SIZE,
        SIZE,
        image::ColorType::Rgb8,
    )
}

/// Intrinsics and world pose of a camera, as listed in `camera.json`.
pub fn camera_json(name: &str, c: &Camera) -> Value {
    let i = Intrinsics::from(c);
    json!({
        "sensor": name,
        "width": i.width, "height": i.height,
        "fx": i.fx, "fy": i.fy, "cx": i.cx, "cy": i.cy,
        "hfov_deg": c.hfov.to_degrees(), "near": c.near, "far": c.far,
        "position": c.position.to_array(),
        "rotation": c.rotation.to_array(),
    })
}

/// The beam layout and summary of a LiDAR scan, as listed in `sensors.json`.
pub fn lidar_json(name: &str, l: &LidarSpec, scan: &LidarScan) -> Value {
    let finite = scan.ranges.iter().filter(|r| r.is_finite()).count();
    json!({
        "file": format!("{name}.npy"),
        "shape": [scan.channels, scan.beams],
        "layout": "ranges[ring][beam] in metres, ring 0 highest; inf = no return within range_max, NaN = dropped return",
        "azimuth_deg": (0..scan.beams).map(|i| beam_azimuth(l, i).to_degrees()).collect::<Vec<_>>(),
        "elevation_deg": (0..scan.channels).map(|k| ring_elevation(l, k).to_degrees()).collect::<Vec<_>>(),
        "range_min": l.range_min,
        "range_max": l.range_max,
        "returns": finite,
        "sensor_position": scan.sensor_pose.translation().to_array(),
        "sensor_rotation": scan.sensor_pose.quat().to_array(),
    })
}

/// What [`write_observation`] wrote for one sensor.
#[derive(Debug, Default, Clone)]
pub struct ObservationFiles {
    /// The files written, in order.
    pub files: Vec<PathBuf>,
    /// The cameras behind the images (a panorama's views as `NAME_K`), for `camera.json`.
    pub cameras: Vec<(String, Camera)>,
    /// The reading for `sensors.json` (pose, compass, GPS, collision, LiDAR layout), if any.
    pub reading: Option<Value>,
}

fn write_file(path: PathBuf, bytes: &[u8], files: &mut Vec<PathBuf>) -> Result<()> {
    std::fs::write(&path, bytes).map_err(|e| vlnverse_env::EnvError::io(&path, e))?;
    files.push(path);
    Ok(())
}

/// Write one sensor's reading `obs` into the folder `dir` (which must exist), with files
/// named after `spec`'s sensor name; `base` is the agent base pose the cameras hang from.
/// Errors name the sensor when `obs` is not of `spec`'s kind, or the file that could not be
/// encoded or written.
pub fn write_observation(
    dir: &Path,
    spec: &SensorSpec,
    obs: &Observation,
    base: &Pose,
) -> Result<ObservationFiles> {
    let name = spec.name();
    let mut out = ObservationFiles::default();
    let files = &mut out.files;
    // Encode, then write `dir/file`; an encoding error names the file.
    let mut put = |file: String, bytes: Result<Vec<u8>>| -> Result<()> {
        let path = dir.join(file);
        match bytes {
            Ok(b) => write_file(path, &b, files),
            Err(e) => Err(SensorError::Write {
                path,
                message: e.to_string(),
            }),
        }
    };
    match (spec, obs) {
        (SensorSpec::Rgb(c), Observation::Rgb(f)) => {
            out.cameras.push((name.into(), c.camera(base)));
            put(format!("{name}.png"), rgb_png(f))?;
        }
        (SensorSpec::Depth(c), Observation::Depth(f)) => {
            out.cameras.push((name.into(), c.camera(base)));
            let scale = if c.normalize { c.far } else { 1.0 };
            put(format!("{name}.png"), depth_png(f, scale))?;
        }
        (SensorSpec::Semantic(c), Observation::Semantic(f)) => {
            out.cameras.push((name.into(), c.camera(base)));
            put(
                format!("{name}.png"),
                ids_png(f, f.semantic.iter().map(|&c| c as u32)),
            )?;
        }
        (SensorSpec::Instance(c), Observation::Instance(f)) => {
            out.cameras.push((name.into(), c.camera(base)));
            put(
                format!("{name}.png"),
                ids_png(f, f.instance.iter().copied()),
            )?;
        }
        (SensorSpec::Panorama(p), Observation::Panorama(frames)) => {
            let cam = p.camera.camera(base);
            for (k, f) in frames.iter().enumerate() {
                let view = format!("{name}_{k}");
                let yaw = (k as f32 * p.step_deg).to_radians();
                out.cameras.push((view.clone(), cam.yawed(yaw)));
                if !f.rgb.is_empty() {
                    put(format!("{view}_rgb.png"), rgb_png(f))?;
                }
                if !f.depth.is_empty() {
                    put(format!("{view}_depth.png"), depth_png(f, 1.0))?;
                }
                if !f.semantic.is_empty() {
                    put(
                        format!("{view}_semantic.png"),
                        ids_png(f, f.semantic.iter().map(|&c| c as u32)),
                    )?;
                }
            }
        }
        (SensorSpec::Lidar(l), Observation::Lidar(scan)) => {
            let shape = [scan.channels as usize, scan.beams as usize];
            put(format!("{name}.npy"), npy(&shape, &scan.ranges))?;
            put(format!("{name}.png"), lidar_png(l, scan))?;
            out.reading = Some(lidar_json(name, l, scan));
        }
        (_, Observation::Pose(p)) => {
            out.reading = Some(json!({
                "position": p.translation().to_array(),
                "rotation": p.quat().to_array(),
                "yaw_deg": p.yaw().to_degrees(),
            }));
        }
        (_, Observation::Compass(h)) => out.reading = Some(json!({ "heading_rad": h })),
        (_, Observation::Gps(g)) => out.reading = Some(json!({ "position": g })),
        (_, Observation::Collision(c)) => {
            let v = serde_json::to_value(c).map_err(|e| encode_error(name, e))?;
            out.reading = Some(v);
        }
        (spec, _) => {
            return Err(SensorError::invalid(
                format!("sensor `{name}`"),
                spec.kind(),
                "the observation is not of the sensor's kind",
            ))
        }
    }
    Ok(out)
}

/// One reading of a whole rig, and where it was taken.
#[derive(Debug, Clone, Copy)]
pub struct RigCapture<'a> {
    /// The rig's config (sensor order and names; `seed` goes to `sensors.json`).
    pub config: &'a RigConfig,
    /// The readings, by sensor name (sensors without one are skipped).
    pub observations: &'a Observations,
    /// Agent base position, metres.
    pub position: Vec3,
    /// Agent yaw, degrees counter-clockwise from -Z.
    pub yaw_deg: f32,
    /// The backend that rendered (`SensorRig::backend_name`).
    pub backend: &'a str,
}

/// Write every reading of `capture` into `dir` (created when missing) with
/// [`write_observation`], then `camera.json` (when the rig has cameras) and `sensors.json`.
/// Returns the paths written, in order.
pub fn write_rig(dir: &Path, capture: &RigCapture) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| vlnverse_env::EnvError::io(dir, e))?;
    let base = Pose::from_yaw(capture.position, capture.yaw_deg.to_radians());
    let mut files = Vec::new();
    let mut cameras: Vec<(String, Camera)> = Vec::new();
    let mut readings = serde_json::Map::new();
    for spec in &capture.config.sensors {
        let Some(obs) = capture.observations.get(spec.name()) else {
            continue;
        };
        let o = write_observation(dir, spec, obs, &base)?;
        files.extend(o.files);
        cameras.extend(o.cameras);
        if let Some(r) = o.reading {
            readings.insert(spec.name().to_string(), r);
        }
    }
    let to_json = |v: &Value| serde_json::to_string_pretty(v).map(|s| s + "\n");
    if let Some((name, cam)) = cameras.first() {
        let mut json = camera_json(name, cam);
        json["convention"] = json!("camera looks along -Z, +Y up, +X right; rotation is the camera-to-world quaternion [x, y, z, w]; pixel (u, v) centre at (u + 0.5, v + 0.5), v = 0 top row");
        json["depth_png"] = json!("uint16 millimetres along the optical axis, clipped at far");
        json["agent_position"] = json!(capture.position.to_array());
        json["agent_yaw_deg"] = json!(capture.yaw_deg);
        json["backend"] = json!(capture.backend);
        json["cameras"] = cameras
            .iter()
            .map(|(n, c)| camera_json(n, c))
            .collect::<Vec<_>>()
            .into();
        let text = to_json(&json).map_err(|e| encode_error("camera.json", e))?;
        write_file(dir.join("camera.json"), text.as_bytes(), &mut files)?;
    }
    let sensors = json!({
        "agent_position": capture.position.to_array(),
        "agent_yaw_deg": capture.yaw_deg,
        "backend": capture.backend,
        "seed": capture.config.seed,
        "sensors": capture.config.sensors.iter().map(|s| json!({"name": s.name(), "type": s.kind()})).collect::<Vec<_>>(),
        "readings": readings,
    });
    let text = to_json(&sensors).map_err(|e| encode_error("sensors.json", e))?;
    write_file(dir.join("sensors.json"), text.as_bytes(), &mut files)?;
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn npy_header_is_aligned_and_names_dtype_and_shape() {
        let b = npy(&[2, 3], &[0f32; 6]).unwrap();
        assert_eq!(&b[..8], b"\x93NUMPY\x01\x00");
        let hlen = u16::from_le_bytes([b[8], b[9]]) as usize;
        assert_eq!((10 + hlen) % 64, 0);
        assert_eq!(b.len(), 10 + hlen + 24);
        let header = std::str::from_utf8(&b[10..10 + hlen]).unwrap();
        assert!(
            header.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3,), }"),
            "{header}"
        );
        assert!(header.ends_with('\n'));
        let b = npy(&[2], &[1u16, 0x0203]).unwrap();
        assert!(String::from_utf8_lossy(&b).contains("'<u2'"));
        assert_eq!(&b[b.len() - 4..], &[1, 0, 3, 2]);
        let b = npy(&[], &[7u8]).unwrap();
        assert!(
            String::from_utf8_lossy(&b).contains("'|u1', 'fortran_order': False, 'shape': (), }")
        );
    }

    #[test]
    fn npy_refuses_a_shape_that_does_not_fit_the_data() {
        let e = npy(&[2, 3], &[0u32; 5]).unwrap_err().to_string();
        assert!(e.contains("[2, 3]") && e.contains('5'), "{e}");
    }
}
