//! What a backend makes of shared scene data (a texture unit's copy of a map, an upload, a
//! buffer of indices), kept per `Arc` for as long as anything but the cache holds that `Arc`:
//! a model of many parts keeps every part's textures and meshes from frame to frame, and
//! what a dropped scene used goes at the next [`ArcCache::evict_unused`].
//!
//! What this module does not do: bound the memory (what is kept is what live scenes use), or
//! key by contents (two equal maps in two `Arc`s are made twice).

use std::collections::HashMap;
use std::sync::Arc;

/// Values made from `Arc<K>`s, one per `Arc` (by address; the cache holds the `Arc`, so the
/// address cannot be reused while the entry lives).
#[derive(Debug)]
pub struct ArcCache<K, V> {
    entries: HashMap<usize, (Arc<K>, V)>,
}

impl<K, V> Default for ArcCache<K, V> {
    fn default() -> Self {
        Self { entries: HashMap::new() }
    }
}

impl<K, V: Clone> ArcCache<K, V> {
    /// The value made of `key`, made by `make` the first time.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use bumpmap_core::cache::ArcCache;
    ///
    /// let mut cache = ArcCache::default();
    /// let (a, b) = (Arc::new(2), Arc::new(2));
    /// let mut made = 0;
    /// for key in [&a, &a, &b] {
    ///     cache.get_or_try_make(key, |k| { made += 1; Ok::<_, ()>(**k * 10) }).unwrap();
    /// }
    /// assert_eq!((made, cache.len()), (2, 2), "once per Arc, not per value");
    /// drop(b);
    /// cache.evict_unused();
    /// assert_eq!(cache.len(), 1, "what only the cache holds goes");
    /// ```
    pub fn get_or_try_make<E>(&mut self, key: &Arc<K>, make: impl FnOnce(&Arc<K>) -> Result<V, E>) -> Result<V, E> {
        let address = Arc::as_ptr(key) as *const () as usize;
        if let Some((_, v)) = self.entries.get(&address) {
            return Ok(v.clone());
        }
        let v = make(key)?;
        self.entries.insert(address, (key.clone(), v.clone()));
        Ok(v)
    }

    /// Drops every entry whose `Arc` nothing but the cache holds any more.
    pub fn evict_unused(&mut self) {
        self.entries.retain(|_, (k, _)| Arc::strong_count(k) > 1);
    }

    /// How many entries are kept.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether nothing is kept.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}
