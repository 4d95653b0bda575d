//! ROS `map_server` files: binary PGM (P5) + YAML metadata.

use super::{CellState, GridMap};
use crate::error::{EnvError, Result};
use glam::Vec2;
use std::path::{Path, PathBuf};

/// `occupied_thresh` written to the YAML.
pub const OCCUPIED_THRESH: f64 = 0.65;
/// `free_thresh` written to the YAML.
pub const FREE_THRESH: f64 = 0.196;

impl GridMap {
    /// Binary PGM (P5, maxval 255): free 254, occupied 0, unknown 205. Row 0 of the image is grid
    /// row 0 (smallest world z = largest map y), column i is grid column i.
    pub fn to_pgm_bytes(&self) -> Vec<u8> {
        let header = format!("P5\n{} {}\n255\n", self.width, self.height);
        let mut out = Vec::with_capacity(header.len() + self.len());
        out.extend_from_slice(header.as_bytes());
        out.extend(self.cells().iter().map(|c| c.pgm_value()));
        out
    }

    /// The YAML `map_server` metadata for an image file named `image_file_name`.
    pub fn to_yaml(&self, image_file_name: &str) -> String {
        let (ox, oy) = self.ros_origin();
        format!(
            "image: {image_file_name}\nresolution: {}\norigin: [{}, {}, 0.0]\nnegate: 0\n\
             occupied_thresh: {OCCUPIED_THRESH}\nfree_thresh: {FREE_THRESH}\nmode: trinary\n",
            self.resolution, ox, oy
        )
    }

    /// Map-frame position of the lower-left corner of the image (the YAML `origin`).
    pub fn ros_origin(&self) -> (f64, f64) {
        let ox = self.origin.x as f64;
        let oy = -(self.origin.y as f64 + self.height as f64 * self.resolution as f64);
        (ox, oy)
    }

    /// Write `<dir>/<stem>.pgm` and `<dir>/<stem>.yaml`, each through a temporary file renamed
    /// into place, so a reader never sees a half-written file.
    pub fn save_ros(&self, dir: impl AsRef<Path>, stem: &str) -> Result<()> {
        let dir = dir.as_ref();
        std::fs::create_dir_all(dir).map_err(|e| EnvError::io(dir, e))?;
        let pgm_name = format!("{stem}.pgm");
        write_atomic(&dir.join(&pgm_name), &self.to_pgm_bytes())?;
        write_atomic(
            &dir.join(format!("{stem}.yaml")),
            self.to_yaml(&pgm_name).as_bytes(),
        )
    }

    /// Read a `map_server` YAML and the image it names (relative to the YAML's folder). Pixels
    /// are classified like map_server's trinary mode: occupancy `p = (255 - v) / 255` (or `v/255`
    /// with `negate: 1`), `p > occupied_thresh` occupied, `p < free_thresh` free, else unknown.
    pub fn load_ros(yaml_path: impl AsRef<Path>) -> Result<GridMap> {
        let yaml_path = yaml_path.as_ref();
        let text = std::fs::read_to_string(yaml_path).map_err(|e| EnvError::io(yaml_path, e))?;
        let meta = MapYaml::parse(&text, yaml_path)?;
        let image_path = yaml_path
            .parent()
            .map(|d| d.join(&meta.image))
            .unwrap_or_else(|| PathBuf::from(&meta.image));
        let bytes = std::fs::read(&image_path).map_err(|e| EnvError::io(&image_path, e))?;
        let (width, height, maxval, pixels) = parse_pgm(&bytes, &image_path)?;
        let cells = pixels
            .iter()
            .map(|&v| {
                let v = v as f64 / maxval as f64;
                let p = if meta.negate { v } else { 1.0 - v };
                if p > meta.occupied_thresh {
                    CellState::Occupied
                } else if p < meta.free_thresh {
                    CellState::Free
                } else {
                    CellState::Unknown
                }
            })
            .collect();
        let res = meta.resolution;
        let origin = Vec2::new(
            meta.origin[0] as f32,
            (-(meta.origin[1] + height as f64 * res)) as f32,
        );
        GridMap::from_cells(width, height, res as f32, origin, cells)
            .map_err(|e| EnvError::parse(yaml_path, e.to_string()))
    }
}

fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, bytes).map_err(|e| EnvError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| EnvError::io(path, e))
}

struct MapYaml {
    image: String,
    resolution: f64,
    origin: [f64; 3],
    negate: bool,
    occupied_thresh: f64,
    free_thresh: f64,
}

impl MapYaml {
    /// Parse the flat `key: value` subset of YAML that map_server files use.
    fn parse(text: &str, path: &Path) -> Result<MapYaml> {
        let err = |m: String| EnvError::parse(path, m);
        let mut fields: Vec<(String, String)> = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let line = strip_comment(line).trim();
            if line.is_empty() || line == "---" {
                continue;
            }
            let Some((k, v)) = line.split_once(':') else {
                return Err(err(format!(
                    "line {}: expected `key: value`, found {line:?}",
                    n + 1
                )));
            };
            fields.push((k.trim().to_string(), unquote(v.trim()).to_string()));
        }
        let get = |k: &str| fields.iter().find(|(f, _)| f == k).map(|(_, v)| v.as_str());
        let need = |k: &str| get(k).ok_or_else(|| err(format!("missing field `{k}`")));
        let num = |k: &str, v: &str| -> Result<f64> {
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| err(format!("field `{k}` = {v:?} is not a finite number")))
        };
        let image = need("image")?.to_string();
        if image.is_empty() {
            return Err(err("field `image` is empty".into()));
        }
        let resolution = num("resolution", need("resolution")?)?;
        if resolution <= 0.0 {
            return Err(err(format!(
                "field `resolution` = {resolution} must be > 0"
            )));
        }
        let o = need("origin")?;
        let inner = o
            .strip_prefix('[')
            .and_then(|s| s.strip_suffix(']'))
            .ok_or_else(|| err(format!("field `origin` = {o:?} must be a list [x, y, yaw]")))?;
        let parts: Vec<&str> = inner.split(',').map(str::trim).collect();
        if parts.len() != 3 {
            return Err(err(format!(
                "field `origin` = {o:?} must have 3 values [x, y, yaw]"
            )));
        }
        let origin = [
            num("origin", parts[0])?,
            num("origin", parts[1])?,
            num("origin", parts[2])?,
        ];
        if origin[2] != 0.0 {
            return Err(err(format!(
                "field `origin` yaw = {} is not supported (only 0)",
                origin[2]
            )));
        }
        let negate = match get("negate").unwrap_or("0") {
            "0" | "false" => false,
            "1" | "true" => true,
            other => return Err(err(format!("field `negate` = {other:?} must be 0 or 1"))),
        };
        let occupied_thresh = num("occupied_thresh", need("occupied_thresh")?)?;
        let free_thresh = num("free_thresh", need("free_thresh")?)?;
        if !(0.0..=1.0).contains(&occupied_thresh)
            || !(0.0..=1.0).contains(&free_thresh)
            || free_thresh > occupied_thresh
        {
            return Err(err(format!(
                "fields `free_thresh` = {free_thresh} and `occupied_thresh` = {occupied_thresh} \
                 must satisfy 0 <= free_thresh <= occupied_thresh <= 1"
            )));
        }
        Ok(MapYaml {
            image,
            resolution,
            origin,
            negate,
            occupied_thresh,
            free_thresh,
        })
    }
}

fn strip_comment(line: &str) -> &str {
    match line.find('#') {
        Some(i) => &line[..i],
        None => line,
    }
}

fn unquote(v: &str) -> &str {
    for q in ['"', '\''] {
        if let Some(s) = v.strip_prefix(q).and_then(|s| s.strip_suffix(q)) {
            return s;
        }
    }
    v
}

/// Parse a binary 8-bit PGM: `(width, height, maxval, pixels)`.
fn parse_pgm(bytes: &[u8], path: &Path) -> Result<(u32, u32, u32, Vec<u8>)> {
    let err = |m: String| EnvError::parse(path, format!("corrupt PGM: {m}"));
    if bytes.len() < 2 || &bytes[..2] != b"P5" {
        return Err(err("magic number is not P5 (binary greyscale)".into()));
    }
    let mut pos = 2;
    let mut header = [0u64; 3];
    let names = ["width", "height", "maxval"];
    for (slot, name) in header.iter_mut().zip(names) {
        // Skip whitespace and comments.
        loop {
            match bytes.get(pos) {
                Some(b) if b.is_ascii_whitespace() => pos += 1,
                Some(b'#') => {
                    while bytes.get(pos).is_some_and(|&b| b != b'\n') {
                        pos += 1;
                    }
                }
                _ => break,
            }
        }
        let start = pos;
        while bytes.get(pos).is_some_and(u8::is_ascii_digit) {
            pos += 1;
        }
        let text = std::str::from_utf8(&bytes[start..pos]).unwrap_or("");
        *slot = text
            .parse::<u64>()
            .ok()
            .filter(|&v| v > 0 && v < u32::MAX as u64)
            .ok_or_else(|| err(format!("header field `{name}` is missing or invalid")))?;
    }
    if !bytes.get(pos).is_some_and(u8::is_ascii_whitespace) {
        return Err(err("no whitespace after the header".into()));
    }
    pos += 1;
    let [w, h, maxval] = header;
    if maxval > 255 {
        return Err(err(format!(
            "maxval {maxval} (16-bit PGM) is not supported; expected <= 255"
        )));
    }
    let n = w
        .checked_mul(h)
        .filter(|&n| n <= super::MAX_CELLS)
        .ok_or_else(|| err(format!("{w}x{h} pixels is too large")))? as usize;
    let data = &bytes[pos..];
    if data.len() < n {
        return Err(err(format!(
            "truncated: {w}x{h} needs {n} pixel bytes, found {}",
            data.len()
        )));
    }
    Ok((w as u32, h as u32, maxval as u32, data[..n].to_vec()))
}
