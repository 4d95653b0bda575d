//! What an evaluation derives from one scene (navigable map, distance fields, scene graph) and
//! a bounded cache of them, so that memory stays flat in the
//! number of scenes of a split.

use std::collections::{BTreeMap, VecDeque};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, PoisonError};

use glam::Vec2;
use vlnverse_env::geodesic::{DistanceField, LevelField, LevelPoint, MultiLevelMap, Portal};
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::Scene;
use vlnverse_sensors::SceneMesh;

use crate::end_fields::EndFieldStore;
use crate::error::{Result, TaskError};
use vlnverse_score::score::navigable_map_path;

/// Distance fields kept per scene (coarse styles share goals); the cache is cleared beyond it.
const FIELD_CACHE: usize = 48;

/// A goal's distance field, built by the first thread that asks for it.
type FieldCell = Arc<OnceLock<Option<Arc<DistanceField>>>>;

/// A scene's place in a [`SceneCache`], filled by the first thread that asks for the scene
/// while the others wait (empty when that load failed: the next to ask tries again).
type SceneSlot = Arc<Mutex<Option<Arc<SceneContext>>>>;

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A scene and what is derived from it, shared by the workers of an evaluation.
pub struct SceneContext {
    /// The scene.
    pub scene: Arc<Scene>,
    /// Its navigable (agent-dilated) map.
    pub navigable: Arc<GridMap>,
    graph: OnceLock<Arc<SceneGraph>>,
    /// Built by the first thread that asks; the others wait for it instead of building it too.
    mesh: Mutex<Option<Arc<SceneMesh>>>,
    /// The light `scene.glb` holds (a loaded home), for its mesh: kept here while the home is,
    /// not in the process-wide light cache, which would keep every home ever loaded.
    light: Option<Arc<vlnverse_env::light::BakedLight>>,
    /// The scene's folder, when loaded from one (the renderer may find it prepared there).
    dir: Option<PathBuf>,
    /// Per goal, its field once built (`None`: it could not be).
    fields: Mutex<BTreeMap<(u32, u32, u32), FieldCell>>,
    /// A home on several floors: every level's navigable map joined by the stairs (level 0's
    /// is `navigable`); `None` for a single-storey scene.
    levels: Option<Arc<MultiLevelMap>>,
    level_fields: Mutex<BTreeMap<(u32, u32, u32), Arc<LevelField>>>,
}

impl SceneContext {
    /// A context for a scene and its navigable map (e.g. a scene built in memory).
    pub fn new(scene: Scene, navigable: GridMap) -> Self {
        SceneContext {
            scene: Arc::new(scene),
            navigable: Arc::new(navigable),
            graph: OnceLock::new(),
            mesh: Mutex::new(None),
            light: None,
            dir: None,
            fields: Mutex::new(BTreeMap::new()),
            levels: None,
            level_fields: Mutex::new(BTreeMap::new()),
        }
    }

    /// A context for a home on several floors from its levels' navigable maps (lowest first);
    /// the stairs join them. An error when the maps do not fit the scene's levels.
    pub fn with_levels(scene: Scene, levels: Vec<GridMap>) -> Result<Self> {
        if levels.len() != scene.level_count() || levels.is_empty() {
            return Err(TaskError::invalid(
                "levels",
                levels.len(),
                format!(
                    "scene `{}` has {} levels; give one navigable map each",
                    scene.id,
                    scene.level_count()
                ),
            ));
        }
        let portals: Vec<Portal> = scene.storeys.stairs.iter().map(Portal::of_stairs).collect();
        let multi = MultiLevelMap::new(levels.clone(), portals)?;
        let ground = levels.into_iter().next().expect("checked non-empty");
        Ok(SceneContext {
            levels: scene.is_multi_level().then(|| Arc::new(multi)),
            ..SceneContext::new(scene, ground)
        })
    }

    /// The levels' maps joined by the stairs, in a home on several floors.
    pub fn levels(&self) -> Option<&Arc<MultiLevelMap>> {
        self.levels.as_ref()
    }

    /// The navigable map of the level a 3-D point stands on (`navigable` in a single-storey
    /// scene).
    pub fn navigable_at(&self, p: [f32; 3]) -> &GridMap {
        match &self.levels {
            Some(m) => m
                .level(self.scene.level_at_height(p[1]))
                .unwrap_or(&self.navigable),
            None => &self.navigable,
        }
    }

    /// The field toward a goal across floors (cached), in a home on several floors; `None` in
    /// a single-storey scene (use [`SceneContext::field`]). It shares the goal's
    /// [`SceneContext::field`] and the home's fields toward the stairs' ends.
    pub fn level_field(&self, goal: [f32; 3]) -> Result<Option<Arc<LevelField>>> {
        let Some(multi) = &self.levels else {
            return Ok(None);
        };
        let key = (goal[0].to_bits(), goal[1].to_bits(), goal[2].to_bits());
        if let Some(f) = lock(&self.level_fields).get(&key) {
            return Ok(Some(f.clone()));
        }
        let heights: Vec<f32> = (0..self.scene.level_count() as u32)
            .map(|l| {
                self.scene
                    .level_height(l)
                    .unwrap_or(self.scene.floor_height)
            })
            .collect();
        let half: Vec<f32> = self
            .scene
            .storeys
            .stairs
            .iter()
            .map(|s| 0.5 * s.width)
            .collect();
        // The goal's own field is the one `field` caches (the same map and point), and the
        // fields toward the stairs' ends are built once per home by `multi`: a new goal costs
        // one sweep, not one per flight end besides.
        let f = Arc::new(LevelField::with_goal_field(
            multi,
            &heights,
            &half,
            LevelPoint::from_world(&self.scene, goal),
            self.field(goal)?,
        )?);
        let mut c = lock(&self.level_fields);
        if c.len() >= FIELD_CACHE {
            c.clear();
        }
        c.insert(key, f.clone());
        Ok(Some(f))
    }

    /// Load `dataset/scenes/<id>/` (the scene and its navigable map).
    pub fn load(dataset: &Path, scene_id: &str) -> Result<Self> {
        let dir = dataset.join("scenes").join(scene_id);
        if !dir.is_dir() {
            return Err(TaskError::invalid(
                "scene_id",
                scene_id,
                format!("no scene folder {}", dir.display()),
            ));
        }
        let (scene, light) = vlnverse_env::io::load_scene_and_light(&dir)?;
        let light = light.map(Arc::new);
        let navigable = GridMap::load_ros(navigable_map_path(dataset, scene_id))?;
        if scene.is_multi_level() {
            // The upper floors' maps beside the ground floor's (`navigable_level<k>.yaml`).
            let mut levels = vec![navigable];
            for k in 1..scene.level_count() as u32 {
                let file = dir.join(vlnverse_env::occupancy::level_map_file(
                    "navigable",
                    k,
                    "yaml",
                ));
                levels.push(GridMap::load_ros(&file)?);
            }
            return Ok(SceneContext {
                dir: Some(dir),
                light,
                ..SceneContext::with_levels(scene, levels)?
            });
        }
        Ok(SceneContext {
            dir: Some(dir),
            light,
            ..SceneContext::new(scene, navigable)
        })
    }

    /// The scene graph, built on first use (only dialogue episodes need it).
    pub fn graph(&self) -> Arc<SceneGraph> {
        self.graph
            .get_or_init(|| Arc::new(SceneGraph::build(&self.scene)))
            .clone()
    }

    /// The scene prepared for rendering, built on first use and shared by every environment
    /// that shows this scene (a thread asking while another builds it waits for that one). A
    /// scene loaded from its folder names the rasteriser's prepared file there
    /// ([`vlnverse_sensors::raster::PREPARED_FILE`]), so the renderer loads what generation
    /// prepared instead of preparing it again.
    pub fn mesh(&self) -> Result<Arc<SceneMesh>> {
        let mut held = lock(&self.mesh);
        if let Some(m) = held.as_ref() {
            return Ok(m.clone());
        }
        let mut m = match &self.light {
            Some(light) => SceneMesh::with_light(&self.scene, light)?,
            None => SceneMesh::new(&self.scene)?,
        };
        m.prepared_file = self
            .dir
            .as_ref()
            .map(|d| d.join(vlnverse_sensors::raster::PREPARED_FILE));
        Ok(held.insert(Arc::new(m)).clone())
    }

    /// Whether the distance field to a goal point is cached now (built by
    /// [`SceneContext::field`] and not cleared since).
    pub fn has_field(&self, goal: [f32; 3]) -> bool {
        let key = (goal[0].to_bits(), goal[1].to_bits(), goal[2].to_bits());
        lock(&self.fields)
            .get(&key)
            .is_some_and(|c| c.get().is_some_and(Option::is_some))
    }

    /// The distance field to a goal point (cached), on the goal's level's map.
    ///
    /// A field is built once: a thread asking for one that another thread is building (the
    /// prefetch thread of a vector environment, a reset) waits for it instead of building it
    /// again.
    pub fn field(&self, goal: [f32; 3]) -> Result<Arc<DistanceField>> {
        let key = (goal[0].to_bits(), goal[1].to_bits(), goal[2].to_bits());
        let cell = {
            let mut c = lock(&self.fields);
            match c.get(&key) {
                Some(cell) => cell.clone(),
                None => {
                    if c.len() >= FIELD_CACHE {
                        c.clear();
                    }
                    c.entry(key).or_default().clone()
                }
            }
        };
        let (map, at) = (self.navigable_at(goal), Vec2::new(goal[0], goal[2]));
        match cell.get_or_init(|| DistanceField::new(map, at).ok().map(Arc::new)) {
            Some(f) => Ok(f.clone()),
            // Not built (non-finite coordinates): the field's own error, built again to say so.
            None => Ok(Arc::new(DistanceField::new(map, at)?)),
        }
    }
}

/// The scenes of a dataset, loaded on demand and kept in a least-recently-used cache of a
/// fixed size. An evicted scene stays alive while an episode still runs in it and is loaded
/// again if asked for later; evaluation visits episodes in scene order, so that is rare.
pub struct SceneCache {
    dataset: PathBuf,
    capacity: usize,
    /// Most recently used last.
    entries: Mutex<VecDeque<(String, SceneSlot)>>,
    loads: std::sync::atomic::AtomicUsize,
    /// The stairs' end fields of homes let go, given back when they are loaded again
    /// ([`SceneCache::keeping_end_fields`], [`SceneCache::sharing_end_fields`]; none kept by
    /// default), by the home's folder.
    end_fields: Arc<Mutex<EndFieldStore>>,
}

impl SceneCache {
    /// A cache over `dataset/scenes/` holding at most `capacity` scenes (at least 1).
    pub fn new(dataset: &Path, capacity: usize) -> Self {
        SceneCache {
            dataset: dataset.to_path_buf(),
            capacity: capacity.max(1),
            entries: Mutex::new(VecDeque::new()),
            loads: std::sync::atomic::AtomicUsize::new(0),
            end_fields: Arc::new(Mutex::new(EndFieldStore::new(0))),
        }
    }

    /// This cache, keeping up to `budget` bytes of the fields toward the stairs' ends of the
    /// homes on several floors it lets go ([`MultiLevelMap::end_field`], built once per home
    /// whatever the goals), and giving them back when such a home is loaded again: for a
    /// workload that comes back to homes (train order), not one that leaves them for good
    /// (an evaluation in scene order).
    pub fn keeping_end_fields(mut self, budget: usize) -> Self {
        self.end_fields = Arc::new(Mutex::new(EndFieldStore::new(budget)));
        self
    }

    /// [`SceneCache::keeping_end_fields`] into one store for the whole process (the first
    /// call's `budget`), shared by every cache made so, as prepared raster scenes are: vector
    /// environments made one after another over a dataset find the fields the earlier ones
    /// built (kept by the home's folder, and checked against the home's maps when given back).
    pub fn sharing_end_fields(mut self, budget: usize) -> Self {
        static SHARED: OnceLock<Arc<Mutex<EndFieldStore>>> = OnceLock::new();
        let store = SHARED.get_or_init(|| Arc::new(Mutex::new(EndFieldStore::new(budget))));
        self.end_fields = store.clone();
        self
    }

    /// The key of home `id` in the end-field store: its folder.
    fn end_key(&self, id: &str) -> String {
        self.dataset.join("scenes").join(id).display().to_string()
    }

    /// Bytes of the stairs' end fields kept for homes let go
    /// ([`SceneCache::keeping_end_fields`]).
    pub fn end_field_bytes(&self) -> usize {
        lock(&self.end_fields).bytes()
    }

    /// Let the least recently used scenes go until one more fits, keeping their stairs' end
    /// fields.
    fn make_room(&self, e: &mut VecDeque<(String, SceneSlot)>) {
        while e.len() >= self.capacity {
            let Some((id, slot)) = e.pop_front() else {
                break;
            };
            self.keep_end_fields(&id, &slot);
        }
    }

    /// The stairs' end fields of a scene let go, kept for when it comes back (none when it is
    /// still being loaded: its loader keeps it).
    fn keep_end_fields(&self, id: &str, slot: &SceneSlot) {
        let Ok(held) = slot.try_lock() else {
            return;
        };
        if let Some(m) = held.as_ref().and_then(|ctx| ctx.levels()) {
            lock(&self.end_fields).keep(&self.end_key(id), m);
        }
    }

    /// The place of scene `id`, made (empty) if the cache has none, marked most recently used.
    fn slot(&self, id: &str) -> SceneSlot {
        let mut e = lock(&self.entries);
        if let Some(i) = e.iter().position(|(k, _)| k == id) {
            let hit = e.remove(i).expect("index from position");
            let slot = hit.1.clone();
            e.push_back(hit);
            return slot;
        }
        self.make_room(&mut e);
        let slot = SceneSlot::default();
        e.push_back((id.to_string(), slot.clone()));
        slot
    }

    /// The scene `id`, loaded if it is not cached. Threads asking for a scene another thread
    /// is loading wait for that load instead of loading it again; other scenes stay available
    /// meanwhile.
    pub fn get(&self, id: &str) -> Result<Arc<SceneContext>> {
        let slot = self.slot(id);
        let mut held = lock(&slot);
        if let Some(ctx) = held.as_ref() {
            return Ok(ctx.clone());
        }
        let ctx = match SceneContext::load(&self.dataset, id) {
            Ok(ctx) => Arc::new(ctx),
            Err(e) => {
                drop(held);
                self.forget_if_empty(id, &slot);
                return Err(e);
            }
        };
        if let Some(m) = ctx.levels() {
            lock(&self.end_fields).give(&self.end_key(id), m);
        }
        self.loads
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(held.insert(ctx).clone())
    }

    /// Drop `id`'s entry after a failed load, so that it does not count as held or take a
    /// place in the cache (making room for it may already have let the least recently used
    /// home go). Left when another thread holds the slot: it is waiting to load it, or has.
    fn forget_if_empty(&self, id: &str, slot: &SceneSlot) {
        let mut e = lock(&self.entries);
        // Slots are cloned only under the entries lock: two holders are the entry and us.
        let alone = Arc::strong_count(slot) == 2;
        if alone && slot.try_lock().is_ok_and(|held| held.is_none()) {
            e.retain(|(k, s)| !(k == id && Arc::ptr_eq(s, slot)));
        }
    }

    /// Scene `id` as `ctx` (loaded from this cache's dataset earlier and still held by its
    /// caller), marked most recently used: the one cached when the cache holds it, else `ctx`,
    /// put back without loading it again.
    pub fn keep(&self, id: &str, ctx: Arc<SceneContext>) -> Arc<SceneContext> {
        let slot = self.slot(id);
        let mut held = lock(&slot);
        held.get_or_insert(ctx).clone()
    }

    /// Let every scene go (their stairs' end fields kept as when the cache makes room). A
    /// scene still held elsewhere stays alive until its holder lets it go.
    pub fn clear(&self) {
        let gone: Vec<_> = lock(&self.entries).drain(..).collect();
        for (id, slot) in gone {
            self.keep_end_fields(&id, &slot);
        }
    }

    /// Scenes held now.
    pub fn len(&self) -> usize {
        lock(&self.entries).len()
    }

    /// Whether no scene is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Scene loads so far (reloads after eviction included).
    pub fn loads(&self) -> usize {
        self.loads.load(std::sync::atomic::Ordering::Relaxed)
    }
}

impl Drop for SceneCache {
    /// The homes still held leave too: their stairs' end fields are kept like those of homes
    /// let go (for the next cache sharing the store).
    fn drop(&mut self) {
        self.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_env::geodesic::GeodesicDistance;
    use vlnverse_env::occupancy::{build_level_maps, OccupancyConfig};
    use vlnverse_env::SceneSource;
    use vlnverse_procgen::{HomeGenerator, Preset};

    /// The `tiny` preset's first home, with this share of homes on two floors (the preset's
    /// when `None`).
    fn first_tiny_home(two_storey_share: Option<f32>) -> Scene {
        let mut pc = Preset::Tiny.config().unwrap();
        pc.scenes.count = 1;
        if let Some(share) = two_storey_share {
            pc.floors.two_storey_share = share;
        }
        HomeGenerator::new(pc).unwrap().scene(0).unwrap()
    }

    /// A loaded home's mesh is lit with the light its `scene.glb` holds, kept by the context
    /// (not the process-wide cache): the same colours as the mesh of the scene loaded the old
    /// way, whose light went through that cache.
    #[test]
    fn a_loaded_home_is_lit_with_its_own_light() {
        let scene = first_tiny_home(None);
        let id = scene.id.clone();
        let dir = tempfile::tempdir().unwrap();
        let scenes = dir.path().join("scenes");
        vlnverse_env::io::write_scene_bundle(&scenes, scene, &OccupancyConfig::default()).unwrap();
        let (_, light) = vlnverse_env::io::load_scene_and_light(scenes.join(&id)).unwrap();
        assert!(light.is_some(), "a generated home holds its light");
        let ctx = SceneContext::load(dir.path(), &id).unwrap();
        assert!(ctx.light.is_some());
        let mesh = ctx.mesh().unwrap();
        let old = SceneMesh::new(&vlnverse_env::io::load_scene(scenes.join(&id)).unwrap()).unwrap();
        assert!(mesh.color == old.color, "other colours");
        assert!(mesh.positions == old.positions);
    }

    /// A home on two floors let go by a cache keeping end fields gets its stairs' end fields
    /// back when loaded again (the same fields, not swept again); without the budget, or for
    /// another home, nothing is given.
    #[test]
    fn a_home_visited_again_gets_its_stairs_end_fields_back() {
        let mut pc = Preset::Tiny.config().unwrap();
        pc.scenes.count = 2;
        pc.floors.two_storey_share = 1.0;
        let gen = HomeGenerator::new(pc).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let ids: Vec<String> = (0..2)
            .map(|i| {
                let scene = gen.scene(i).unwrap();
                assert!(scene.is_multi_level());
                let id = scene.id.clone();
                vlnverse_env::io::write_scene_bundle(
                    dir.path().join("scenes"),
                    scene,
                    &OccupancyConfig::default(),
                )
                .unwrap();
                id
            })
            .collect();
        let ends = |ctx: &SceneContext| -> Vec<Arc<DistanceField>> {
            let m = ctx.levels().unwrap();
            (0..m.portals().len())
                .flat_map(|p| [false, true].map(|u| m.end_field(p, u).unwrap()))
                .collect()
        };
        let keeping = SceneCache::new(dir.path(), 1).keeping_end_fields(64 << 20);
        let first = ends(&keeping.get(&ids[0]).unwrap());
        assert!(!first.is_empty());
        assert_eq!(keeping.end_field_bytes(), 0, "nothing let go yet");
        let other = ends(&keeping.get(&ids[1]).unwrap());
        let kept = keeping.end_field_bytes();
        assert_eq!(kept, first.iter().map(|f| f.bytes()).sum::<usize>());
        let again = keeping.get(&ids[0]).unwrap();
        assert_eq!(keeping.loads(), 3, "loaded again");
        let m = again.levels().unwrap();
        let given = m.built_end_fields();
        assert!(
            given.iter().flatten().all(Option::is_some),
            "every end given"
        );
        for (a, b) in first.iter().zip(ends(&again)) {
            assert!(Arc::ptr_eq(a, &b), "the kept field, not a new sweep");
        }
        // Another home's fields do not fit this one; a field is not given twice.
        assert!(!m.give_end_field(0, false, other[0].clone()));
        assert!(!m.give_end_field(0, false, first[0].clone()));
        // Caches sharing the process's store find each other's fields.
        let (a, b) = (
            SceneCache::new(dir.path(), 1).sharing_end_fields(64 << 20),
            SceneCache::new(dir.path(), 1).sharing_end_fields(64 << 20),
        );
        let built = ends(&a.get(&ids[0]).unwrap());
        a.get(&ids[1]).unwrap();
        let found = ends(&b.get(&ids[0]).unwrap());
        assert!(built.iter().zip(&found).all(|(x, y)| Arc::ptr_eq(x, y)));
        // A cache dropped keeps the fields of the homes it still held.
        let held = ends(&b.get(&ids[1]).unwrap());
        // (`a` still holds home 1 without its end fields: leaving after `b`, it loses none.)
        drop(b);
        drop(a);
        let c = SceneCache::new(dir.path(), 1).sharing_end_fields(64 << 20);
        let again = ends(&c.get(&ids[1]).unwrap());
        assert!(held.iter().zip(&again).all(|(x, y)| Arc::ptr_eq(x, y)));
        // A cache without the budget keeps nothing.
        let plain = SceneCache::new(dir.path(), 1);
        ends(&plain.get(&ids[0]).unwrap());
        plain.get(&ids[1]).unwrap();
        let fresh = plain.get(&ids[0]).unwrap();
        assert_eq!(plain.end_field_bytes(), 0);
        assert!(fresh
            .levels()
            .unwrap()
            .built_end_fields()
            .iter()
            .flatten()
            .all(Option::is_none));
    }

    /// Threads asking for one home at once share one load and one mesh; a home that cannot be
    /// loaded fails for each asker, and is loaded once it can be; `clear` lets every home go.
    #[test]
    fn threads_entering_a_home_together_load_it_and_its_mesh_once() {
        let scene = first_tiny_home(None);
        let id = scene.id.clone();
        let dir = tempfile::tempdir().unwrap();
        let cache = SceneCache::new(dir.path(), 2);
        assert!(cache.get(&id).is_err(), "no scene folder yet");
        assert!(cache.get(&id).is_err());
        assert_eq!(cache.loads(), 0);
        assert!(cache.is_empty(), "a failed load holds no entry");
        vlnverse_env::io::write_scene_bundle(
            dir.path().join("scenes"),
            scene,
            &OccupancyConfig::default(),
        )
        .unwrap();
        let got: Vec<(Arc<SceneContext>, Arc<SceneMesh>)> = std::thread::scope(|s| {
            let asks: Vec<_> = (0..4)
                .map(|_| {
                    s.spawn(|| {
                        let ctx = cache.get(&id).unwrap();
                        let mesh = ctx.mesh().unwrap();
                        (ctx, mesh)
                    })
                })
                .collect();
            asks.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert_eq!(cache.loads(), 1, "one load for four threads");
        assert!(got
            .iter()
            .all(|(c, m)| Arc::ptr_eq(c, &got[0].0) && Arc::ptr_eq(m, &got[0].1)));
        assert_eq!(cache.len(), 1);
        cache.clear();
        assert!(cache.is_empty());
        let again = cache.get(&id).unwrap();
        assert!(!Arc::ptr_eq(&again, &got[0].0), "loaded again after clear");
        assert_eq!(cache.loads(), 2);
    }

    /// Threads asking for one goal's field at once share one field (built once); a goal with
    /// non-finite coordinates is the field's error, every time, and nothing is cached for it.
    #[test]
    fn a_goal_field_is_built_once_for_threads_asking_together() {
        let scene = first_tiny_home(Some(0.0));
        let maps = build_level_maps(&scene, &OccupancyConfig::default()).unwrap();
        let nav = maps[0].navigable.clone();
        let cells: Vec<Vec2> = nav
            .free_cells()
            .map(|(c, r)| nav.cell_center(c, r))
            .collect();
        let at = cells[cells.len() / 2];
        let goal = [at.x, scene.floor_height, at.y];
        let ctx = SceneContext::new(scene, nav);
        assert!(!ctx.has_field(goal));
        let fields: Vec<Arc<DistanceField>> = std::thread::scope(|s| {
            let asks: Vec<_> = (0..4)
                .map(|_| s.spawn(|| ctx.field(goal).unwrap()))
                .collect();
            asks.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert!(fields.iter().all(|f| Arc::ptr_eq(f, &fields[0])));
        assert!(ctx.has_field(goal));
        assert_eq!(fields[0].goal(), Some(at));
        let bad = [f32::NAN, 0.0, at.y];
        for _ in 0..2 {
            let e = ctx.field(bad).unwrap_err().to_string();
            assert!(e.contains("finite"), "{e}");
        }
        assert!(!ctx.has_field(bad));
    }

    /// A goal upstairs in a two-storey home: the field across floors is built on the goal's
    /// cached field (the same one, not a second sweep) and measures what a field built alone
    /// measures, at every free cell of both floors.
    #[test]
    fn a_field_across_floors_shares_the_goal_field_and_measures_the_same() {
        let scene = first_tiny_home(Some(1.0));
        assert!(scene.is_multi_level());
        let navigable: Vec<GridMap> = build_level_maps(&scene, &OccupancyConfig::default())
            .unwrap()
            .into_iter()
            .map(|m| m.navigable)
            .collect();
        let ctx = SceneContext::with_levels(scene.clone(), navigable.clone()).unwrap();
        let h1 = scene.level_height(1).unwrap();
        let up: Vec<Vec2> = {
            let n = &navigable[1];
            n.free_cells().map(|(c, r)| n.cell_center(c, r)).collect()
        };
        let heights = [scene.floor_height, h1];
        let half: Vec<f32> = scene.storeys.stairs.iter().map(|s| 0.5 * s.width).collect();
        let portals: Vec<Portal> = scene.storeys.stairs.iter().map(Portal::of_stairs).collect();
        for g in [up[up.len() / 4], up[3 * up.len() / 4]] {
            let goal = [g.x, h1, g.y];
            let shared = ctx.level_field(goal).unwrap().unwrap();
            assert!(Arc::ptr_eq(shared.goal_field(), &ctx.field(goal).unwrap()));
            let alone_map = MultiLevelMap::new(navigable.clone(), portals.clone()).unwrap();
            let alone =
                LevelField::new(&alone_map, &heights, &half, LevelPoint::new(1, g.x, g.y)).unwrap();
            let mut reachable = 0;
            for (l, y) in [(0, scene.floor_height), (1, h1)] {
                let n = &navigable[l];
                for (c, r) in n.free_cells() {
                    let p = n.cell_center(c, r);
                    let d = shared.distance([p.x, y, p.y]);
                    assert_eq!(d, alone.distance([p.x, y, p.y]), "level {l} at {p}");
                    reachable += usize::from(matches!(d, GeodesicDistance::Reachable(_)));
                }
            }
            assert!(
                reachable > up.len(),
                "the ground floor reaches the goal too"
            );
        }
    }
}
