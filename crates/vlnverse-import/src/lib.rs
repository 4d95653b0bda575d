#![doc = include_str!("../README.md")]

mod classify;
mod mapping;
mod raw;
pub mod rooms;

pub use classify::{class_defaults, color_word, structure_guess, DEFAULT_COLOR};
pub use mapping::{Mapping, MatchOn, Rule};
pub use raw::RawLabel;
pub use rooms::{RoomAnnotation, RoomParams};

use glam::Vec3;
use raw::RawNode;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::{
    Aabb, EnvError, MeshData, Motion, Part, Physics, Pose, Result, Scene, SceneObject, SceneSource,
    SemanticClass, Shape, SCENE_FORMAT_VERSION,
};

/// Which axis points up in the source file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum UpAxis {
    /// +Y up (glTF's convention; our own).
    #[default]
    Y,
    /// +Z up (Blender, Habitat stages, many CAD exports): `(x, y, z)` becomes `(x, z, -y)`.
    Z,
}

/// Length unit of the source file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    /// Metres.
    #[default]
    M,
    /// Centimetres.
    Cm,
    /// Millimetres.
    Mm,
}

impl Unit {
    /// Metres per source unit.
    pub fn meters(self) -> f32 {
        match self {
            Unit::M => 1.0,
            Unit::Cm => 0.01,
            Unit::Mm => 0.001,
        }
    }
}

impl std::str::FromStr for UpAxis {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "y" | "Y" => Ok(UpAxis::Y),
            "z" | "Z" => Ok(UpAxis::Z),
            _ => Err(format!("up axis `{s}`: expected `y` or `z`")),
        }
    }
}

impl std::str::FromStr for Unit {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "m" => Ok(Unit::M),
            "cm" => Ok(Unit::Cm),
            "mm" => Ok(Unit::Mm),
            _ => Err(format!("unit `{s}`: expected `m`, `cm` or `mm`")),
        }
    }
}

/// How to import a file.
#[derive(Clone, Debug)]
pub struct ImportOptions {
    /// Up axis of the source.
    pub up: UpAxis,
    /// Unit of the source.
    pub unit: Unit,
    /// Mapping file (TOML rules, see [`Mapping`]); when None the built-in generic English
    /// rules are used if `builtin_mapping` is set.
    pub mapping: Option<PathBuf>,
    /// Use [`Mapping::builtin`] when no mapping file is given.
    pub builtin_mapping: bool,
    /// Room annotation file (TOML, see [`RoomAnnotation`]); overrides segmentation.
    pub rooms: Option<PathBuf>,
    /// Scene id; default: the file stem, lower-cased, with other characters than `[a-z0-9_-]`
    /// replaced by `_`.
    pub scene_id: Option<String>,
    /// Translate the scene vertically so that the detected floor is at `y = 0` (as in
    /// generated homes). When false the geometry keeps its height and `floor_height` says
    /// where the floor is.
    pub floor_to_zero: bool,
    /// Segment rooms from the occupancy map when there is no room annotation.
    pub segment_rooms: bool,
    /// Occupancy settings for the maps used by room segmentation.
    pub occupancy: OccupancyConfig,
    /// Room segmentation settings.
    pub room_params: RoomParams,
}

impl Default for ImportOptions {
    fn default() -> Self {
        ImportOptions {
            up: UpAxis::Y,
            unit: Unit::M,
            mapping: None,
            builtin_mapping: true,
            rooms: None,
            scene_id: None,
            floor_to_zero: true,
            segment_rooms: true,
            occupancy: OccupancyConfig::default(),
            room_params: RoomParams::default(),
        }
    }
}

/// Where an object's class came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LabelSource {
    /// glTF `extras` (`{"class": ...}`) of the node or an ancestor.
    Extras,
    /// A rule of the mapping file.
    Mapping,
    /// Geometry heuristics (walls, floors, ceilings).
    Heuristic,
    /// Nothing matched: `SemanticClass::Unknown`.
    Unknown,
}

/// What an import did, for people (Display) and for tools (Serialize).
#[derive(Clone, Debug, Default, Serialize)]
pub struct ImportReport {
    /// The source file.
    pub file: PathBuf,
    /// `glb`, `gltf` or `obj`.
    pub format: String,
    /// Scene id.
    pub scene_id: String,
    /// Mapping file used (`builtin` for the generic rules, empty for none).
    pub mapping: String,
    /// Geometry-carrying nodes read from the file.
    pub nodes: usize,
    /// Objects in the scene.
    pub objects: usize,
    /// Triangles in the scene.
    pub triangles: usize,
    /// Objects per class name.
    pub objects_by_class: BTreeMap<String, usize>,
    /// Objects per label source (`extras`, `mapping`, `heuristic`, `unknown`).
    pub objects_by_source: BTreeMap<String, usize>,
    /// Names of objects no label source matched (classified by heuristics or unknown), sorted.
    pub unmatched_names: Vec<String>,
    /// Names of nodes left out by `drop` rules, sorted.
    pub dropped: Vec<String>,
    /// Floor height detected in the source (after axis and unit conversion), metres.
    pub detected_floor: f32,
    /// Vertical translation applied (`-detected_floor` when `floor_to_zero`).
    pub y_shift: f32,
    /// Size of the scene's bounding box (x, y, z) in metres.
    pub size: [f32; 3],
    /// Where the rooms came from: `annotation`, `segmentation` or `none`.
    pub rooms_source: String,
    /// Rooms per type name.
    pub rooms_by_type: BTreeMap<String, usize>,
    /// Doors and openings.
    pub doors: usize,
    /// Non-structure objects that got a room.
    pub objects_in_rooms: usize,
}

impl fmt::Display for ImportReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "imported {} ({}) as `{}`",
            self.file.display(),
            self.format,
            self.scene_id
        )?;
        writeln!(
            f,
            "  size {:.2} x {:.2} x {:.2} m, floor detected at y = {:.3} (shifted by {:+.3})",
            self.size[0], self.size[1], self.size[2], self.detected_floor, self.y_shift
        )?;
        writeln!(
            f,
            "  {} nodes -> {} objects, {} triangles; mapping: {}",
            self.nodes,
            self.objects,
            self.triangles,
            if self.mapping.is_empty() {
                "none"
            } else {
                &self.mapping
            }
        )?;
        let join = |m: &BTreeMap<String, usize>| {
            m.iter()
                .map(|(k, v)| format!("{k} {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        writeln!(f, "  label sources: {}", join(&self.objects_by_source))?;
        writeln!(f, "  classes: {}", join(&self.objects_by_class))?;
        writeln!(
            f,
            "  rooms ({}): {}; {} doors; {} objects in rooms",
            self.rooms_source,
            join(&self.rooms_by_type),
            self.doors,
            self.objects_in_rooms
        )?;
        if !self.unmatched_names.is_empty() {
            writeln!(f, "  unmatched: {}", self.unmatched_names.join(", "))?;
        }
        if !self.dropped.is_empty() {
            writeln!(f, "  dropped: {}", self.dropped.join(", "))?;
        }
        Ok(())
    }
}

/// Everything an import produces.
#[derive(Clone, Debug)]
pub struct ImportOutput {
    /// The scene.
    pub scene: Scene,
    /// What happened.
    pub report: ImportReport,
}

/// Import one glTF/GLB/OBJ file as a [`Scene`] (see the crate documentation).
pub fn import_scene(path: &Path, opts: &ImportOptions) -> Result<(Scene, ImportReport)> {
    let out = import_scene_full(path, opts)?;
    Ok((out.scene, out.report))
}

/// Scene id from a file name: the stem, lower-cased, other characters than `[a-z0-9_-]`
/// replaced by `_`.
pub fn scene_id_from_path(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "scene".into());
    stem.chars()
        .map(|c| {
            let c = c.to_ascii_lowercase();
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Source format of a file, by extension.
fn format_of(path: &Path) -> Result<&'static str> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "glb" => Ok("glb"),
        "gltf" => Ok("gltf"),
        "obj" => Ok("obj"),
        _ => Err(EnvError::invalid(
            "input",
            path.display(),
            "expected a .glb, .gltf or .obj file",
        )),
    }
}

struct Group {
    name: String,
    label: Option<RawLabel>,
    source: LabelSource,
    prims: Vec<raw::RawPrim>,
}

/// Resolve labels and merge geometry into object groups (see the crate documentation for the
/// order of label sources).
fn group_nodes(
    nodes: Vec<RawNode>,
    mapping: Option<&Mapping>,
    dropped: &mut Vec<String>,
) -> Vec<Group> {
    let mut groups: Vec<Group> = Vec::new();
    let mut index: BTreeMap<(usize, Option<String>), usize> = BTreeMap::new();
    let mut add = |key: (usize, Option<String>),
                   name: String,
                   label: Option<RawLabel>,
                   source: LabelSource,
                   prims: Vec<raw::RawPrim>,
                   groups: &mut Vec<Group>| {
        if let Some(&g) = index.get(&key) {
            groups[g].prims.extend(prims);
        } else {
            index.insert(key, groups.len());
            groups.push(Group {
                name,
                label,
                source,
                prims,
            });
        }
    };
    for node in nodes {
        // 1. extras of the node, then of its ancestors (the labelled ancestor is the object).
        let extras = node
            .extras
            .clone()
            .map(|l| (node.index, node.name.clone(), l))
            .or_else(|| {
                node.ancestors
                    .iter()
                    .find_map(|(i, n, l)| l.clone().map(|l| (*i, n.clone(), l)))
            });
        if let Some((i, n, l)) = extras {
            add(
                (i, None),
                n,
                Some(l),
                LabelSource::Extras,
                node.prims,
                &mut groups,
            );
            continue;
        }
        // 2. mapping on the node name, the mesh name, then ancestors' names.
        let by_name = mapping.and_then(|m| {
            m.lookup(&node.name, MatchOn::Node)
                .map(|l| (node.index, node.name.clone(), l.clone()))
                .or_else(|| {
                    node.mesh_name
                        .as_deref()
                        .and_then(|mn| m.lookup(mn, MatchOn::Mesh))
                        .map(|l| (node.index, node.name.clone(), l.clone()))
                })
                .or_else(|| {
                    node.ancestors.iter().find_map(|(i, n, _)| {
                        m.lookup(n, MatchOn::Node)
                            .map(|l| (*i, n.clone(), l.clone()))
                    })
                })
        });
        if let Some((i, n, l)) = by_name {
            if l.drop {
                dropped.push(n);
                continue;
            }
            add(
                (i, None),
                n,
                Some(l),
                LabelSource::Mapping,
                node.prims,
                &mut groups,
            );
            continue;
        }
        // 3. mapping on material names, primitive by primitive; the rest stays with the node.
        for prim in node.prims {
            let hit = mapping.and_then(|m| {
                prim.material.as_deref().and_then(|mat| {
                    m.lookup(mat, MatchOn::Material)
                        .map(|l| (mat.to_string(), l.clone()))
                })
            });
            match hit {
                Some((mat, l)) if l.drop => dropped.push(format!("{}/{mat}", node.name)),
                Some((mat, l)) => add(
                    (node.index, Some(mat.clone())),
                    format!("{}/{mat}", node.name),
                    Some(l),
                    LabelSource::Mapping,
                    vec![prim],
                    &mut groups,
                ),
                None => add(
                    (node.index, None),
                    node.name.clone(),
                    None,
                    LabelSource::Unknown,
                    vec![prim],
                    &mut groups,
                ),
            }
        }
    }
    dropped.sort();
    dropped.dedup();
    groups.retain(|g| g.prims.iter().any(|p| !p.indices.is_empty()));
    groups
}

/// Floor height: the height holding the most upward-facing triangle area (2 cm bins), or the
/// lowest one holding nearly as much (80 %: a floor split by thresholds); terraces, steps and
/// ground around a house hold less than its floor. Falls back to the lowest vertex.
pub fn detect_floor(triangles: impl Iterator<Item = [Vec3; 3]>) -> Option<f32> {
    const BIN: f32 = 0.02;
    let mut bins: BTreeMap<i64, (f64, f64)> = BTreeMap::new();
    let mut lowest = f32::INFINITY;
    for [a, b, c] in triangles {
        lowest = lowest.min(a.y).min(b.y).min(c.y);
        let n = (b - a).cross(c - a);
        let area2 = n.length();
        if area2 <= 1e-12 || n.y / area2 < 0.95 {
            continue;
        }
        let y = (a.y + b.y + c.y) / 3.0;
        let e = bins.entry((y / BIN).floor() as i64).or_insert((0.0, 0.0));
        e.0 += area2 as f64 * 0.5;
        e.1 += (area2 * 0.5 * y) as f64;
    }
    if !lowest.is_finite() {
        return None;
    }
    let max = bins.values().map(|v| v.0).fold(0.0, f64::max);
    if max < 0.5 {
        return Some(lowest);
    }
    let (&k, _) = bins.iter().find(|(_, v)| v.0 >= 0.8 * max)?;
    // Area-weighted mean height over the bin and its neighbours.
    let (a, ay) = (k - 1..=k + 1)
        .filter_map(|i| bins.get(&i))
        .fold((0.0, 0.0), |(a, ay), v| (a + v.0, ay + v.1));
    Some((ay / a) as f32)
}

/// Import one file (same as [`import_scene`], returning an [`ImportOutput`]).
pub fn import_scene_full(path: &Path, opts: &ImportOptions) -> Result<ImportOutput> {
    let format = format_of(path)?;
    opts.occupancy.validate()?;
    opts.room_params.validate()?;
    let nodes = match format {
        "obj" => raw::load_obj(path, opts)?,
        _ => raw::load_gltf(path, opts)?,
    };
    let (mapping, mapping_name) = match &opts.mapping {
        Some(p) => (Some(Mapping::load(p)?), p.display().to_string()),
        None if opts.builtin_mapping => (Some(Mapping::builtin()), "builtin".to_string()),
        None => (None, String::new()),
    };
    let scene_id = opts
        .scene_id
        .clone()
        .unwrap_or_else(|| scene_id_from_path(path));
    let mut report = ImportReport {
        file: path.to_path_buf(),
        format: format.into(),
        scene_id: scene_id.clone(),
        mapping: mapping_name,
        nodes: nodes.len(),
        ..Default::default()
    };
    let mut groups = group_nodes(nodes, mapping.as_ref(), &mut report.dropped);
    if groups.is_empty() {
        return Err(EnvError::parse(path, "no triangle geometry in the file"));
    }
    let tris = groups.iter().flat_map(|g| &g.prims).flat_map(|p| {
        p.indices
            .iter()
            .map(move |t| t.map(|i| p.positions[i as usize]))
    });
    let detected = detect_floor(tris).unwrap_or(0.0);
    let shift = if opts.floor_to_zero { -detected } else { 0.0 };
    let floor_height = detected + shift;
    if shift != 0.0 {
        for p in groups.iter_mut().flat_map(|g| &mut g.prims) {
            for v in &mut p.positions {
                v.y += shift;
            }
        }
    }
    report.detected_floor = detected;
    report.y_shift = shift;

    let mut objects = Vec::with_capacity(groups.len());
    let mut used_names: BTreeMap<String, usize> = BTreeMap::new();
    for g in groups {
        let mut bbox = Aabb::EMPTY;
        for p in &g.prims {
            for t in &p.indices {
                for &i in t {
                    bbox.extend(p.positions[i as usize]);
                }
            }
        }
        let (class, source) = match g.label.as_ref().and_then(|l| l.class) {
            Some(c) => (c, g.source),
            None => match structure_guess(&bbox, floor_height) {
                SemanticClass::Unknown => (SemanticClass::Unknown, LabelSource::Unknown),
                c => (c, LabelSource::Heuristic),
            },
        };
        if matches!(source, LabelSource::Heuristic | LabelSource::Unknown) {
            report.unmatched_names.push(g.name.clone());
        }
        let origin = Vec3::new(bbox.center().x, bbox.min[1], bbox.center().z);
        let mut parts = Vec::with_capacity(g.prims.len());
        let mut color_acc = [0.0f32; 3];
        let mut area_acc = 0.0f32;
        for p in g.prims {
            // Keep only referenced vertices, in object-local coordinates.
            let mut remap = vec![u32::MAX; p.positions.len()];
            let mut positions = Vec::new();
            let mut uvs = Vec::new();
            let textured = p.texture.is_some() && p.uvs.len() == p.positions.len();
            let mut indices = Vec::with_capacity(p.indices.len());
            for t in &p.indices {
                let [a, b, c] = t.map(|i| p.positions[i as usize]);
                let area = (b - a).cross(c - a).length() * 0.5;
                area_acc += area;
                for (acc, c) in color_acc.iter_mut().zip(p.color) {
                    *acc += c * area;
                }
                indices.push(t.map(|i| {
                    let r = &mut remap[i as usize];
                    if *r == u32::MAX {
                        *r = positions.len() as u32;
                        positions.push((p.positions[i as usize] - origin).to_array());
                        if textured {
                            uvs.push(p.uvs[i as usize]);
                        }
                    }
                    *r
                }));
            }
            if indices.is_empty() {
                continue;
            }
            parts.push(Part {
                shape: Shape::Mesh(MeshData {
                    positions,
                    indices,
                    glb_mesh: None,
                    uvs,
                    texture: if textured { p.texture } else { None },
                }),
                transform: Pose::IDENTITY,
                color: p.color,
            });
        }
        let mean_color = if area_acc > 0.0 {
            color_acc.map(|c| c / area_acc)
        } else {
            DEFAULT_COLOR
        };
        let (mass, friction, material) = class_defaults(class);
        let label = g.label.unwrap_or_default();
        let n = used_names.entry(g.name.clone()).or_insert(0);
        *n += 1;
        let name = if *n == 1 {
            g.name.clone()
        } else {
            format!("{}_{}", g.name, n)
        };
        *report
            .objects_by_source
            .entry(source_name(source).into())
            .or_insert(0) += 1;
        *report
            .objects_by_class
            .entry(class.name().into())
            .or_insert(0) += 1;
        objects.push(SceneObject {
            id: objects.len() as u32 + 1,
            name,
            class,
            room: None,
            pose: Pose {
                position: origin.to_array(),
                rotation: [0.0, 0.0, 0.0, 1.0],
            },
            bbox,
            color: label
                .color
                .clone()
                .unwrap_or_else(|| color_word(mean_color).to_string()),
            material: label
                .material
                .clone()
                .unwrap_or_else(|| material.to_string()),
            shade: None,
            features: Vec::new(),
            physics: Physics {
                mass: label.mass.unwrap_or(mass),
                friction: label.friction.unwrap_or(friction),
                motion: label.motion.unwrap_or(Motion::Static),
            },
            supported_by: None,
            parts,
        });
    }
    report.unmatched_names.sort();
    set_supports(&mut objects);
    let mut scene = Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: scene_id,
        source: format!(
            "import:{}",
            path.file_name()
                .map(|f| f.to_string_lossy())
                .unwrap_or_default()
        ),
        seed: None,
        floor_height,
        rooms: Vec::new(),
        doors: Vec::new(),
        objects,
        storeys: Default::default(),
    };
    report.objects = scene.objects.len();
    report.triangles = scene.triangle_count();
    report.size = scene.bounds().size().to_array();

    if let Some(rooms_file) = &opts.rooms {
        let ann = RoomAnnotation::load(rooms_file)?;
        rooms::apply_annotation(&mut scene, &ann, &opts.occupancy, &opts.room_params)?;
        report.rooms_source = "annotation".into();
    } else if opts.segment_rooms {
        rooms::segment_into(&mut scene, &opts.occupancy, &opts.room_params)?;
        report.rooms_source = "segmentation".into();
    } else {
        report.rooms_source = "none".into();
    }
    for r in &scene.rooms {
        *report
            .rooms_by_type
            .entry(r.kind.name().into())
            .or_insert(0) += 1;
    }
    report.doors = scene.doors.len();
    report.objects_in_rooms = scene
        .objects
        .iter()
        .filter(|o| !o.is_structure() && o.room.is_some())
        .count();
    tracing::info!(
        file = %path.display(),
        objects = report.objects,
        triangles = report.triangles,
        rooms = scene.rooms.len(),
        "imported"
    );
    Ok(ImportOutput { scene, report })
}

fn source_name(s: LabelSource) -> &'static str {
    match s {
        LabelSource::Extras => "extras",
        LabelSource::Mapping => "mapping",
        LabelSource::Heuristic => "heuristic",
        LabelSource::Unknown => "unknown",
    }
}

/// `supported_by`: for each non-structure object, the non-structure object whose top lies
/// within 5 cm of its bottom with the largest footprint overlap.
fn set_supports(objects: &mut [SceneObject]) {
    let boxes: Vec<(u32, Aabb, bool)> = objects
        .iter()
        .map(|o| {
            (
                o.id,
                o.bbox,
                o.is_structure() || o.class == SemanticClass::Rug,
            )
        })
        .collect();
    for o in objects.iter_mut() {
        if o.is_structure() {
            continue;
        }
        let b = o.bbox;
        let mut best: Option<(f32, u32)> = None;
        for (id, s, skip) in &boxes {
            if *id == o.id || *skip || (b.min[1] - s.max[1]).abs() > 0.05 {
                continue;
            }
            let ox = (b.max[0].min(s.max[0]) - b.min[0].max(s.min[0])).max(0.0);
            let oz = (b.max[2].min(s.max[2]) - b.min[2].max(s.min[2])).max(0.0);
            let overlap = ox * oz;
            let own = (b.size().x * b.size().z).max(1e-6);
            if overlap > 0.3 * own && best.is_none_or(|(a, _)| overlap > a) {
                best = Some((overlap, *id));
            }
        }
        o.supported_by = best.map(|(_, id)| id);
    }
}

/// A [`SceneSource`] over a list of files, one scene per file.
#[derive(Clone, Debug)]
pub struct Importer {
    /// Input files, in index order.
    pub files: Vec<PathBuf>,
    /// Options for every file (its `scene_id` is ignored when there are several files).
    pub options: ImportOptions,
}

impl Importer {
    /// Source over the given files.
    pub fn new(files: Vec<PathBuf>, options: ImportOptions) -> Self {
        Importer { files, options }
    }

    /// Every `.glb`, `.gltf` and `.obj` file directly in `dir`, sorted by name.
    pub fn from_dir(dir: &Path, options: ImportOptions) -> Result<Self> {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| EnvError::io(dir, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && format_of(p).is_ok())
            .collect();
        files.sort();
        Ok(Importer { files, options })
    }
}

impl SceneSource for Importer {
    fn len(&self) -> usize {
        self.files.len()
    }

    fn scene_id(&self, index: usize) -> String {
        match (&self.options.scene_id, self.files.len()) {
            (Some(id), 1) => id.clone(),
            _ => self
                .files
                .get(index)
                .map(|f| scene_id_from_path(f))
                .unwrap_or_default(),
        }
    }

    fn scene(&self, index: usize) -> Result<Scene> {
        let file = self.files.get(index).ok_or_else(|| {
            EnvError::invalid(
                "index",
                index,
                format!("the importer has {} files", self.files.len()),
            )
        })?;
        let mut opts = self.options.clone();
        opts.scene_id = Some(self.scene_id(index));
        import_scene(file, &opts).map(|(s, _)| s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_is_the_largest_upward_surface() {
        // A 4x4 floor at y=0.3, a 1x1 box top at 1.0, a stray tiny triangle at -2, and a
        // 3x3 terrace at 0.1 outside (less area than the floor).
        let quad = |y: f32, s: f32| {
            let a = Vec3::new(0.0, y, 0.0);
            let b = Vec3::new(0.0, y, s);
            let c = Vec3::new(s, y, s);
            let d = Vec3::new(s, y, 0.0);
            vec![[a, b, c], [a, c, d]]
        };
        let mut t = quad(0.3, 4.0);
        t.extend(quad(1.0, 1.0));
        t.extend(quad(-2.0, 0.05));
        t.extend(quad(0.1, 3.0));
        let f = detect_floor(t.into_iter()).unwrap();
        assert!((f - 0.3).abs() < 1e-4, "{f}");
    }

    #[test]
    fn scene_ids_are_sanitised() {
        assert_eq!(
            scene_id_from_path(Path::new("/a/My House.v2.glb")),
            "my_house_v2"
        );
    }
}
