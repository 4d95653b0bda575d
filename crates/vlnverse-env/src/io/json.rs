//! `scene.json`: the scene model as JSON (mesh vertex data excluded; it lives in `scene.glb`).

use crate::error::{EnvError, Result};
use crate::scene::{Scene, Shape, SCENE_FORMAT_VERSION};
use std::path::Path;

/// Serialise a scene as pretty-printed `scene.json` bytes (ends with a newline).
pub fn scene_to_json(scene: &Scene) -> Vec<u8> {
    let mut v = serde_json::to_vec_pretty(scene).expect("the scene model is always serialisable");
    v.push(b'\n');
    v
}

/// Parse `scene.json` bytes; `path` names the file in errors. Checks `format_version` first so
/// a file from another version says so instead of failing on a field.
pub fn scene_from_json(bytes: &[u8], path: &Path) -> Result<Scene> {
    // One pass over the document when it parses (the common case: ~0.8 MB for a generated
    // home, and the version-only pass cost a third of the whole parse). A document that
    // parses holds a `format_version` (a `u32` field of `Scene`), checked as below; one that
    // does not is checked for its version first, as before, so a file of another version
    // says so instead of failing on a field.
    let scene = match serde_json::from_slice::<Scene>(bytes) {
        Ok(scene) if scene.format_version == SCENE_FORMAT_VERSION => scene,
        Ok(scene) => return Err(version_error(path, scene.format_version)),
        Err(e) => {
            check_version(bytes, path)?;
            // Inside a shape (a tagged enum) serde points at the shape's end, not the field.
            return Err(bad_bevel(bytes, path).unwrap_or_else(|| json_error(path, bytes, &e)));
        }
    };
    check_values(&scene, path)?;
    scene.validate_storeys().map_err(|e| e.in_file(path))?;
    Ok(scene)
}

/// The error for a `format_version` of another version (`shown` as the file writes it).
fn version_error(path: &Path, shown: impl std::fmt::Display) -> EnvError {
    EnvError::parse(
        path,
        format!(
            "field `format_version` = {shown}: this build reads version {SCENE_FORMAT_VERSION}"
        ),
    )
}

/// `format_version` alone: an error when it is missing or not this build's.
fn check_version(bytes: &[u8], path: &Path) -> Result<()> {
    #[derive(serde::Deserialize)]
    struct Version {
        format_version: Option<serde_json::Value>,
    }
    let v: Version = serde_json::from_slice(bytes).map_err(|e| json_error(path, bytes, &e))?;
    match v.format_version {
        None => Err(EnvError::parse(path, "missing field `format_version`")),
        Some(serde_json::Value::Number(n)) if n.as_u64() == Some(SCENE_FORMAT_VERSION as u64) => {
            Ok(())
        }
        Some(other) => Err(version_error(path, other)),
    }
}

/// Values serde accepts but a scene cannot hold: negative or non-finite physics or bevels
/// (an `f32` field reads a too-large number such as `1e39` as infinity).
fn check_values(scene: &Scene, path: &Path) -> Result<()> {
    for o in &scene.objects {
        for (k, p) in o.parts.iter().enumerate() {
            if let Shape::Cuboid { bevel, .. } = p.shape {
                if !(bevel.is_finite() && bevel >= 0.0) {
                    return Err(EnvError::parse(
                        path,
                        format!(
                            "object {} (`{}`) part {k}: field `bevel` = {bevel}: must be finite and >= 0",
                            o.id, o.name
                        ),
                    ));
                }
            }
        }
        for (field, v) in [
            ("physics.mass", o.physics.mass),
            ("physics.friction", o.physics.friction),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(EnvError::parse(
                    path,
                    format!(
                        "object {} (`{}`): field `{field}` = {v}: must be finite and >= 0",
                        o.id, o.name
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The first `bevel` that is not a number (a NaN bevel is written as `null`), as an error
/// naming its object and part; `None` when every bevel is a number or the file is not a scene.
fn bad_bevel(bytes: &[u8], path: &Path) -> Option<EnvError> {
    let v: serde_json::Value = serde_json::from_slice(bytes).ok()?;
    for o in v.get("objects")?.as_array()? {
        let parts = o.get("parts").and_then(|p| p.as_array());
        for (k, p) in parts.into_iter().flatten().enumerate() {
            match p.get("shape").and_then(|s| s.get("bevel")) {
                Some(b) if !b.is_number() => {
                    return Some(EnvError::parse(
                        path,
                        format!(
                            "object {} (`{}`) part {k}: field `bevel` = {b}: must be a finite \
                             number >= 0 (a NaN bevel is written as null)",
                            o.get("id").unwrap_or(&serde_json::Value::Null),
                            o.get("name").and_then(|n| n.as_str()).unwrap_or("?"),
                        ),
                    ));
                }
                _ => {}
            }
        }
    }
    None
}

fn json_error(path: &Path, bytes: &[u8], e: &serde_json::Error) -> EnvError {
    let what = match e.classify() {
        serde_json::error::Category::Io => "cannot read JSON",
        serde_json::error::Category::Syntax => "invalid JSON",
        serde_json::error::Category::Data => "invalid scene",
        serde_json::error::Category::Eof => "truncated JSON",
    };
    match offending_line(bytes, e) {
        Some(l) => EnvError::parse(path, format!("{what}: {e}: `{l}`")),
        None => EnvError::parse(path, format!("{what}: {e}")),
    }
}

/// The line a serde data error points at, trimmed, when it holds a `"field": value` pair.
/// serde says "at line L column C" but not which field; our JSON files are pretty-printed with
/// one field per line, so quoting that line names the field and its value.
pub(crate) fn offending_line(bytes: &[u8], e: &serde_json::Error) -> Option<String> {
    if e.classify() != serde_json::error::Category::Data || e.line() == 0 {
        return None;
    }
    let line = bytes.split(|&b| b == b'\n').nth(e.line() - 1)?;
    let line = String::from_utf8_lossy(line).trim().to_string();
    (line.contains(':') && line.chars().count() <= 160).then_some(line)
}
