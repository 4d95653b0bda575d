//! The fields toward the stairs' ends of homes left behind, kept by scene id within a byte
//! budget, so that a home on several floors visited again (train order comes back to homes the
//! scene cache has let go) gets them back instead of sweeping them again
//! ([`MultiLevelMap::end_field`]). They depend on the home alone, not on any goal.

use std::collections::VecDeque;
use std::sync::Arc;

use vlnverse_env::geodesic::{DistanceField, MultiLevelMap};

/// Fields per portal `[lower, upper]` (`None`: not built).
type Ends = Vec<[Option<Arc<DistanceField>>; 2]>;

/// Homes' end fields, least recently left first, within `budget` bytes.
#[derive(Default)]
pub(crate) struct EndFieldStore {
    budget: usize,
    held: usize,
    entries: VecDeque<(String, Ends, usize)>,
}

impl EndFieldStore {
    /// A store holding at most `budget` bytes of fields (0: none kept).
    pub(crate) fn new(budget: usize) -> Self {
        EndFieldStore {
            budget,
            ..Default::default()
        }
    }

    /// Keep the end fields `map` of home `id` has built (with those kept for it that `map` has
    /// not built), the least recently kept homes let go beyond the budget.
    pub(crate) fn keep(&mut self, id: &str, map: &MultiLevelMap) {
        if self.budget == 0 {
            return;
        }
        let mut ends = map.built_end_fields();
        if let Some((_, old, _)) = self.entries.iter().find(|(k, _, _)| k == id) {
            for (new, old) in ends.iter_mut().zip(old) {
                for (n, o) in new.iter_mut().zip(old) {
                    if n.is_none() {
                        n.clone_from(o);
                    }
                }
            }
        }
        let bytes: usize = ends.iter().flatten().flatten().map(|f| f.bytes()).sum();
        if bytes == 0 {
            return;
        }
        self.remove(id);
        if bytes > self.budget {
            return;
        }
        while self.held + bytes > self.budget {
            let Some((_, _, b)) = self.entries.pop_front() else {
                break;
            };
            self.held -= b;
        }
        self.held += bytes;
        self.entries.push_back((id.to_string(), ends, bytes));
    }

    /// Give `map` (home `id`, loaded again) the end fields kept for it (those that fit it:
    /// [`MultiLevelMap::give_end_field`]); how many it took. They stay kept.
    pub(crate) fn give(&self, id: &str, map: &MultiLevelMap) -> usize {
        let Some((_, ends, _)) = self.entries.iter().find(|(k, _, _)| k == id) else {
            return 0;
        };
        let mut taken = 0;
        for (portal, pair) in ends.iter().enumerate() {
            for (upper, f) in [false, true].into_iter().zip(pair) {
                if let Some(f) = f {
                    taken += usize::from(map.give_end_field(portal, upper, f.clone()));
                }
            }
        }
        taken
    }

    fn remove(&mut self, id: &str) {
        if let Some(i) = self.entries.iter().position(|(k, _, _)| k == id) {
            let (_, _, b) = self.entries.remove(i).expect("index from position");
            self.held -= b;
        }
    }

    /// Bytes of fields kept now.
    pub(crate) fn bytes(&self) -> usize {
        self.held
    }
}
