//! Scene folders: `<out>/<scene_id>/` with `scene.glb`, `scene.json` and companion files,
//! written atomically (a temporary folder renamed into place) so an interrupted job never leaves
//! a folder that looks complete.

use super::glb::{
    assign_glb_mesh_indices, read_baked_light, read_glb_bytes, restore_mesh_parts, write_glb,
};
use super::json::{scene_from_json, scene_to_json};
use crate::error::{EnvError, Result};
use crate::scene::{Scene, Shape};
use std::path::{Path, PathBuf};

/// File name of the glTF binary in a scene folder.
pub const SCENE_GLB: &str = "scene.glb";
/// File name of the scene description in a scene folder.
pub const SCENE_JSON: &str = "scene.json";
/// Every file of a complete scene folder as written by [`super::write_scene_bundle`].
pub const BUNDLE_FILES: [&str; 7] = [
    SCENE_GLB,
    SCENE_JSON,
    "scene_graph.json",
    "occupancy.pgm",
    "occupancy.yaml",
    "navigable.pgm",
    "navigable.yaml",
];

fn check_id(scene: &Scene) -> Result<()> {
    let id = &scene.id;
    let ok = !id.is_empty()
        && !id.starts_with('.')
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if ok {
        Ok(())
    } else {
        Err(EnvError::InvalidScene {
            scene: id.clone(),
            message: format!(
                "field `id` = {id:?} cannot be a folder name (use letters, digits, `_`, `-`, `.`)"
            ),
        })
    }
}

fn has_noncanonical_mesh_indices(scene: &Scene) -> bool {
    let mut k = 0u32;
    for p in scene.objects.iter().flat_map(|o| &o.parts) {
        if let Shape::Mesh(m) = &p.shape {
            if m.glb_mesh != Some(k) {
                return true;
            }
            k += 1;
        }
    }
    false
}

/// Write `<out_dir>/<scene.id>/` with `scene.glb`, `scene.json` and `extra_files`
/// (`(file name, bytes)`), atomically: everything goes into `<out_dir>/.<id>.tmp-<pid>` first,
/// which is then renamed; an existing folder of that name is replaced. Mesh parts get their
/// canonical `glb_mesh` index in the written `scene.json` (see [`super::glb`]). Returns the
/// folder.
pub fn write_scene_dir(
    out_dir: impl AsRef<Path>,
    scene: &Scene,
    extra_files: &[(&str, Vec<u8>)],
) -> Result<PathBuf> {
    let out_dir = out_dir.as_ref();
    check_id(scene)?;
    for (name, _) in extra_files {
        if name.is_empty() || name.contains(['/', '\\']) || name.starts_with('.') {
            return Err(EnvError::invalid(
                "extra_files.name",
                name,
                "a plain file name is required",
            ));
        }
    }
    std::fs::create_dir_all(out_dir).map_err(|e| EnvError::io(out_dir, e))?;
    let json = if has_noncanonical_mesh_indices(scene) {
        let mut s = scene.clone();
        assign_glb_mesh_indices(&mut s);
        scene_to_json(&s)
    } else {
        scene_to_json(scene)
    };
    let glb = write_glb(scene);
    let final_dir = out_dir.join(&scene.id);
    let tmp = out_dir.join(format!(".{}.tmp-{}", scene.id, std::process::id()));
    if tmp.exists() {
        std::fs::remove_dir_all(&tmp).map_err(|e| EnvError::io(&tmp, e))?;
    }
    std::fs::create_dir(&tmp).map_err(|e| EnvError::io(&tmp, e))?;
    let write = |name: &str, bytes: &[u8]| {
        let p = tmp.join(name);
        std::fs::write(&p, bytes).map_err(|e| EnvError::io(p, e))
    };
    let res = (|| {
        write(SCENE_GLB, &glb)?;
        write(SCENE_JSON, &json)?;
        for (name, bytes) in extra_files {
            write(name, bytes)?;
        }
        if final_dir.exists() {
            std::fs::remove_dir_all(&final_dir).map_err(|e| EnvError::io(&final_dir, e))?;
        }
        std::fs::rename(&tmp, &final_dir).map_err(|e| EnvError::io(&final_dir, e))
    })();
    if res.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    res.map(|_| final_dir)
}

/// Check the 12-byte GLB header: magic, version 2, declared length equal to the file size.
fn check_glb_header(bytes: &[u8], path: &Path) -> Result<()> {
    if bytes.len() < 12 || &bytes[0..4] != b"glTF" {
        return Err(EnvError::parse(
            path,
            "not a glTF binary (bad magic or too short)",
        ));
    }
    let version = u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]);
    let len = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize;
    if version != 2 {
        return Err(EnvError::parse(
            path,
            format!("glTF version {version}, expected 2"),
        ));
    }
    if len != bytes.len() {
        return Err(EnvError::parse(
            path,
            format!(
                "truncated or padded: header says {len} bytes, file has {}",
                bytes.len()
            ),
        ));
    }
    Ok(())
}

/// Load a scene folder: `scene.json` plus the vertex data of mesh parts from `scene.glb`, whose
/// baked light is handed to [`crate::light::remember`] (procedural homes).
/// Errors name the file and what is wrong (missing file, corrupt `.glb`, invalid JSON with its
/// line and column, wrong `format_version`).
pub fn load_scene(dir: impl AsRef<Path>) -> Result<Scene> {
    let (scene, light) = load_scene_and_light(dir)?;
    if let Some(light) = light {
        crate::light::remember(&scene, light);
    }
    Ok(scene)
}

/// [`load_scene`] that hands the light baked at generation to the caller instead of the
/// process-wide cache: a caller that keeps it while it holds the home (and builds its mesh with
/// it) does not add every home it ever loaded to that cache. `None` for a scene without baked
/// light, or whose light does not fit it (then the renderers bake, as before).
pub fn load_scene_and_light(
    dir: impl AsRef<Path>,
) -> Result<(Scene, Option<crate::light::BakedLight>)> {
    let dir = dir.as_ref();
    let json_path = dir.join(SCENE_JSON);
    let glb_path = dir.join(SCENE_GLB);
    let json = std::fs::read(&json_path).map_err(|e| EnvError::io(&json_path, e))?;
    let mut scene = scene_from_json(&json, &json_path)?;
    let glb = std::fs::read(&glb_path).map_err(|e| EnvError::io(&glb_path, e))?;
    check_glb_header(&glb, &glb_path)?;
    let has_mesh = scene
        .objects
        .iter()
        .flat_map(|o| &o.parts)
        .any(|p| matches!(p.shape, Shape::Mesh(_)));
    if has_mesh {
        let contents = read_glb_bytes(&glb, &glb_path)?;
        restore_mesh_parts(&mut scene, &contents, &glb_path)?;
    }
    // The light baked at generation: kept for the renderers, so they do not bake it again. A
    // file whose light does not fit (or does not parse) leaves them to bake, as before.
    let light = if crate::light::is_lit(&scene) {
        read_baked_light(&scene, &glb, &glb_path).ok().flatten()
    } else {
        None
    };
    Ok((scene, light))
}

/// Whether `dir` is a finished scene folder: every file of [`BUNDLE_FILES`] is present,
/// `scene.glb` has a valid header and `scene.json` parses. Used to resume interrupted jobs.
pub fn is_complete_scene_dir(dir: impl AsRef<Path>) -> bool {
    is_complete_scene_dir_with(dir, &BUNDLE_FILES)
}

/// Like [`is_complete_scene_dir`] with an explicit list of required files (which should include
/// `scene.glb` and `scene.json`).
pub fn is_complete_scene_dir_with(dir: impl AsRef<Path>, files: &[&str]) -> bool {
    let dir = dir.as_ref();
    if !files.iter().all(|f| dir.join(f).is_file()) {
        return false;
    }
    let glb_path = dir.join(SCENE_GLB);
    let glb_ok = std::fs::read(&glb_path)
        .ok()
        .is_some_and(|b| check_glb_header(&b, &glb_path).is_ok());
    let json_path = dir.join(SCENE_JSON);
    glb_ok
        && std::fs::read(&json_path)
            .ok()
            .is_some_and(|b| scene_from_json(&b, &json_path).is_ok())
}

/// Whether `name` is a temporary entry an interrupted writer of this workspace can leave behind:
/// `.<name>.tmp-<pid>` (scene folders and [`super::write_atomic`]), `.<name>.tmp<pid>` (the
/// task layer's atomic writes) and `[.]<name>.png.link<pid>` (hard-linked reference images).
/// Other names, dot-files included (`.lock`, `.gitignore`), are never temporary.
pub fn is_temp_leftover(name: &str) -> bool {
    let stem = name.trim_end_matches(|c: char| c.is_ascii_digit());
    if stem.len() == name.len() {
        return false;
    }
    if let Some(base) = stem.strip_suffix(".png.link") {
        return !base.trim_start_matches('.').is_empty();
    }
    let Some(stem) = stem.strip_prefix('.') else {
        return false;
    };
    stem.strip_suffix(".tmp-")
        .or_else(|| stem.strip_suffix(".tmp"))
        .is_some_and(|base| !base.is_empty())
}

/// Remove the temporary leftovers ([`is_temp_leftover`]) directly inside `dir` (files and
/// folders; a missing `dir` has none). Only call this while no other job writes into `dir`
/// (under its output lock): a running writer's temporary entries look the same. Returns what
/// was removed, sorted.
pub fn remove_temp_leftovers(dir: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
    let dir = dir.as_ref();
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(EnvError::io(dir, e)),
    };
    let mut removed = Vec::new();
    for e in entries {
        let e = e.map_err(|e| EnvError::io(dir, e))?;
        if !is_temp_leftover(&e.file_name().to_string_lossy()) {
            continue;
        }
        let p = e.path();
        let is_dir = e.file_type().map_err(|err| EnvError::io(&p, err))?.is_dir();
        let r = if is_dir {
            std::fs::remove_dir_all(&p)
        } else {
            std::fs::remove_file(&p)
        };
        match r {
            Ok(()) => removed.push(p),
            Err(err) if err.kind() == std::io::ErrorKind::NotFound => {}
            Err(err) => return Err(EnvError::io(&p, err)),
        }
    }
    removed.sort();
    Ok(removed)
}

/// The scene folders directly under `dir` (those holding a `scene.json`), sorted by name.
/// Entries whose name starts with `.` are never scenes (temporary folders of an interrupted
/// writer, lock files) and are left out; scene ids cannot start with `.` either.
pub fn list_scene_dirs(dir: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
    let dir = dir.as_ref();
    let entries = std::fs::read_dir(dir).map_err(|e| EnvError::io(dir, e))?;
    let mut dirs = Vec::new();
    for e in entries {
        let e = e.map_err(|e| EnvError::io(dir, e))?;
        if e.file_name().to_string_lossy().starts_with('.') {
            continue;
        }
        let p = e.path();
        if p.join(SCENE_JSON).is_file() {
            dirs.push(p);
        }
    }
    dirs.sort();
    Ok(dirs)
}
