//! Small process-wide caches of what is prepared per scene (baked light, a renderer's scene).
//!
//! A training run draws episodes from many homes and every environment loads the home of its
//! next episode; preparing a home costs far more than a step. [`ByteLru`] keeps the results
//! keyed by a hash of the content they were made from ([`ContentKey`]), so a home prepared once
//! is not prepared again while it fits in the byte budget, and a hit returns exactly what a
//! fresh preparation would.

use std::sync::{Arc, Mutex};

/// 64-bit content key (FNV-1a with an extra shift per word): what a cached result was made
/// from, word by word.
#[derive(Clone, Copy, Debug)]
pub struct ContentKey(u64);

impl Default for ContentKey {
    fn default() -> Self {
        Self::new()
    }
}

impl ContentKey {
    /// An empty key.
    pub const fn new() -> Self {
        ContentKey(0xcbf2_9ce4_8422_2325)
    }

    /// Mix in one word.
    pub fn u32(&mut self, v: u32) {
        self.0 = (self.0 ^ u64::from(v)).wrapping_mul(0x0000_0100_0000_01b3);
        self.0 ^= self.0 >> 29;
    }

    /// Mix in a float (its bits).
    pub fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }

    /// Mix in floats.
    pub fn f32s(&mut self, v: &[f32]) {
        v.iter().for_each(|c| self.f32(*c));
    }

    /// Mix in bytes (length first, then four to a word: imported images run to megabytes).
    pub fn bytes(&mut self, v: &[u8]) {
        self.u32(v.len() as u32);
        let words = v.chunks_exact(4);
        let tail = words.remainder();
        words.for_each(|w| self.u32(u32::from_le_bytes([w[0], w[1], w[2], w[3]])));
        tail.iter().for_each(|b| self.u32(u32::from(*b)));
    }

    /// The key.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// Least-recently-used results up to a byte budget (the newest is kept even when larger).
#[derive(Debug)]
pub struct ByteLru<T> {
    budget: usize,
    used: usize,
    /// Oldest first: key, value, bytes.
    entries: Vec<(u64, Arc<T>, usize)>,
}

impl<T> ByteLru<T> {
    /// An empty cache that holds up to `budget` bytes (0: holds nothing).
    pub const fn new(budget: usize) -> Self {
        ByteLru {
            budget,
            used: 0,
            entries: Vec::new(),
        }
    }

    /// The value for `key`, now the most recently used.
    pub fn get(&mut self, key: u64) -> Option<Arc<T>> {
        let i = self.entries.iter().position(|e| e.0 == key)?;
        let e = self.entries.remove(i);
        let v = e.1.clone();
        self.entries.push(e);
        Some(v)
    }

    /// The most recently used value for which `pred` holds, now the most recently used.
    pub fn find(&mut self, pred: impl Fn(&T) -> bool) -> Option<Arc<T>> {
        let i = self.entries.iter().rposition(|e| pred(&e.1))?;
        let e = self.entries.remove(i);
        let v = e.1.clone();
        self.entries.push(e);
        Some(v)
    }

    /// Keep `value` (of `bytes` bytes) under `key`, dropping the least recently used entries
    /// past the budget.
    pub fn insert(&mut self, key: u64, value: Arc<T>, bytes: usize) {
        if self.budget == 0 {
            return;
        }
        if let Some(i) = self.entries.iter().position(|e| e.0 == key) {
            self.used -= self.entries.remove(i).2;
        }
        self.entries.push((key, value, bytes));
        self.used += bytes;
        self.evict();
    }

    /// Measure every entry again with `bytes` (for values that grow after they were kept,
    /// such as a prepared scene unpacking its face textures as views draw them), dropping the
    /// least recently used entries past the budget.
    pub fn remeasure(&mut self, bytes: impl Fn(&T) -> usize) {
        self.used = 0;
        for e in &mut self.entries {
            e.2 = bytes(&e.1);
            self.used += e.2;
        }
        self.evict();
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether nothing is kept.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Bytes kept.
    pub fn bytes(&self) -> usize {
        self.used
    }

    fn evict(&mut self) {
        while self.used > self.budget && self.entries.len() > 1 {
            self.used -= self.entries.remove(0).2;
        }
    }
}

/// A [`ByteLru`] shared by the process.
pub type SharedLru<T> = Mutex<ByteLru<T>>;

/// A new [`SharedLru`] of `budget` bytes.
pub const fn shared_lru<T>(budget: usize) -> SharedLru<T> {
    Mutex::new(ByteLru::new(budget))
}

/// The cached value for `key` in `cache`, else `make()` stored with its size from `bytes`. A
/// poisoned lock only loses the caching.
///
/// `make` runs outside the lock and never waits for another thread making the same key: on a
/// rayon pool the thread making it may be this one, further down its stack (work stealing), so
/// waiting could deadlock. Two threads asking at the same moment may both make it; the first
/// one stored is kept and returned to both.
pub fn get_or_insert<T>(
    cache: &SharedLru<T>,
    key: u64,
    make: impl FnOnce() -> T,
    bytes: impl FnOnce(&T) -> usize,
) -> Arc<T> {
    if let Some(hit) = cache.lock().ok().and_then(|mut c| c.get(key)) {
        return hit;
    }
    let v = Arc::new(make());
    if let Ok(mut c) = cache.lock() {
        if let Some(first) = c.get(key) {
            return first;
        }
        c.insert(key, v.clone(), bytes(&v));
    }
    v
}

/// Megabytes from the environment variable `var` (a whole number), else `default_mb`; the
/// budget of a process-wide cache, read once when the cache is made (so a bad value warns
/// once per cache).
pub fn budget_from_env(var: &str, default_mb: usize) -> usize {
    match std::env::var(var) {
        Ok(v) => match v.trim().parse::<usize>() {
            Ok(mb) => mb << 20,
            Err(_) => {
                eprintln!(
                    "warning: {var}={v:?} is not a whole number of megabytes; using {default_mb}"
                );
                default_mb << 20
            }
        },
        Err(_) => default_mb << 20,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_recently_used_entries_leave_first_and_the_newest_stays() {
        let mut c = ByteLru::new(10);
        c.insert(1, Arc::new("a"), 4);
        c.insert(2, Arc::new("b"), 4);
        assert_eq!(c.get(1).as_deref(), Some(&"a")); // 1 is now the most recent
        c.insert(3, Arc::new("c"), 4); // over budget: 2 leaves
        assert!(c.get(2).is_none());
        assert_eq!((c.len(), c.bytes()), (2, 8));
        c.insert(4, Arc::new("d"), 50); // larger than the budget: kept alone
        assert_eq!((c.len(), c.bytes()), (1, 50));
        assert_eq!(c.get(4).as_deref(), Some(&"d"));
        c.insert(4, Arc::new("e"), 2); // same key: replaced
        assert_eq!((c.len(), c.bytes()), (1, 2));
        let mut none = ByteLru::new(0);
        none.insert(1, Arc::new(1), 1);
        assert!(none.is_empty());
    }

    #[test]
    fn remeasured_entries_that_grew_push_the_oldest_out() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let mut c = ByteLru::new(10);
        for k in 1..=3 {
            c.insert(k, Arc::new(AtomicUsize::new(3)), 3);
        }
        c.get(1).unwrap().store(5, Ordering::Relaxed); // 1 grew, and is the most recent
        c.remeasure(|v| v.load(Ordering::Relaxed));
        assert!(c.get(2).is_none(), "the oldest left");
        assert_eq!((c.len(), c.bytes()), (2, 8));
    }

    #[test]
    fn get_or_insert_makes_once_per_key() {
        let cache = shared_lru(1 << 20);
        let mut made = 0;
        for k in [1, 2, 1, 1, 2] {
            let v = get_or_insert(
                &cache,
                k,
                || {
                    made += 1;
                    k * 10
                },
                |_| 8,
            );
            assert_eq!(*v, k * 10);
        }
        assert_eq!(made, 2);
        assert_eq!(cache.lock().unwrap().bytes(), 16);
    }

    #[test]
    fn threads_asking_for_one_key_at_once_share_one_value() {
        // On a rayon pool with fewer threads than tasks (work stealing runs a waiting task's
        // neighbours on its stack): none waits for another, and all get the first value stored.
        let cache = shared_lru(1 << 20);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let got: Vec<Arc<Vec<u32>>> = pool.install(|| {
            use rayon::prelude::*;
            (0..16)
                .into_par_iter()
                .map(|_| {
                    get_or_insert(
                        &cache,
                        7,
                        || (0..1000u32).into_par_iter().map(|i| i * 2).collect(),
                        |v: &Vec<u32>| v.len() * 4,
                    )
                })
                .collect()
        });
        assert!(got.iter().all(|v| v[999] == 1998));
        let first = cache.lock().unwrap().get(7).unwrap();
        // Whether it found the value stored, stored it, or lost the race: every task holds the
        // one value kept.
        assert!(got.iter().all(|v| Arc::ptr_eq(v, &first)));
        assert_eq!(cache.lock().unwrap().len(), 1);
    }

    #[test]
    fn keys_differ_with_content_and_order() {
        let key = |w: &[u32]| {
            let mut k = ContentKey::new();
            w.iter().for_each(|v| k.u32(*v));
            k.finish()
        };
        assert_eq!(key(&[1, 2, 3]), key(&[1, 2, 3]));
        assert_ne!(key(&[1, 2, 3]), key(&[3, 2, 1]));
        assert_ne!(key(&[1, 2]), key(&[1, 2, 0]));
        let bytes = |b: &[u8]| {
            let mut k = ContentKey::new();
            k.bytes(b);
            k.finish()
        };
        assert_eq!(bytes(&[1, 2, 3, 4, 5]), bytes(&[1, 2, 3, 4, 5]));
        assert_ne!(bytes(&[1, 2, 3, 4, 5]), bytes(&[1, 2, 3, 4, 6]));
        assert_ne!(bytes(&[1, 2, 3, 4]), bytes(&[2, 1, 3, 4]));
        assert_ne!(bytes(&[1, 2, 3, 4]), bytes(&[1, 2, 3, 4, 0]));
    }
}
