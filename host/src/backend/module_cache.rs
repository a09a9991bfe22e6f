//! Pruned kernel modules kept between renders (`$XDG_CACHE_HOME/caustic/modules`, else
//! `~/.cache/caustic/modules`): a scene rendered again skips the pruning (0.2-0.3 s a module on an
//! H200's host, the path loops side by side), as the driver's own cache skips its compile. A file is
//! named by what the module is pruned from and to (the kernel's words, the feature mask, the path
//! loop, the entry points) and ends with a checksum of its contents: a missing, short, foreign or
//! damaged one only means the module is pruned again. At most `KEPT` files are kept, the oldest
//! removed first.
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// Modules kept: a pruned module is 0.2-2.5 MB (52,251 words for the Cornell box's path tracer,
/// 620,349 for thin glass's module with all six entry points), so at most about 160 MB.
const KEPT: usize = 64;

pub struct ModuleCache {
    dir: Option<PathBuf>,
}

impl ModuleCache {
    /// The user's cache directory's (none where neither `XDG_CACHE_HOME` nor `HOME` is set).
    pub fn in_cache() -> Self {
        ModuleCache { dir: super::variant::cache_base().map(|b| b.join("caustic").join("modules")) }
    }

    /// A cache in `dir` (the tests').
    pub fn at(dir: &Path) -> Self {
        ModuleCache { dir: Some(dir.to_path_buf()) }
    }

    /// The key of a module: the kernel it is pruned from (`digest`), the mask and loop frozen in, the
    /// entry points kept.
    pub fn key(kernel: u64, mask: u32, path_loop: u32, entries: &[&str]) -> u64 {
        let mut h = std::hash::DefaultHasher::new();
        (kernel, mask, path_loop, entries).hash(&mut h);
        h.finish()
    }

    /// A kernel's digest, for `key` (its 30 MB take about 20 ms).
    pub fn digest(kernel: &[u32]) -> u64 {
        let mut h = std::hash::DefaultHasher::new();
        kernel.hash(&mut h);
        h.finish()
    }

    /// Module `key`, if a whole one is kept.
    pub fn load(&self, key: u64) -> Option<Vec<u32>> {
        let bytes = std::fs::read(self.path(key)?).ok()?;
        if bytes.len() % 4 != 0 {
            return None;
        }
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
        let (module, sum) = words.split_at(words.len().checked_sub(2)?);
        let whole = module.len() > 5 && module[0] == super::spirv::MAGIC && sum == checksum(module);
        whole.then(|| module.to_vec())
    }

    /// Keeps module `key` (written beside, then renamed into place, so a reader never sees half of
    /// it), and removes the oldest files past `KEPT`. Failing to write only costs the next render
    /// the pruning.
    pub fn store(&self, key: u64, module: &[u32]) {
        let (Some(dir), Some(path)) = (&self.dir, self.path(key)) else { return };
        if std::fs::create_dir_all(dir).is_err() {
            return;
        }
        let mut words = module.to_vec();
        words.extend_from_slice(&checksum(module));
        let partial = dir.join(format!("{key:016x}.{}.partial", std::process::id()));
        if std::fs::write(&partial, bytemuck::cast_slice(&words)).is_err()
            || std::fs::rename(&partial, &path).is_err()
        {
            let _ = std::fs::remove_file(&partial);
            return;
        }
        self.trim(dir);
    }

    fn path(&self, key: u64) -> Option<PathBuf> {
        Some(self.dir.as_ref()?.join(format!("{key:016x}.spv")))
    }

    /// Removes the oldest modules past `KEPT`.
    fn trim(&self, dir: &Path) {
        let Ok(entries) = std::fs::read_dir(dir) else { return };
        let mut kept: Vec<(std::time::SystemTime, PathBuf)> = entries
            .flatten()
            .filter(|e| e.path().extension().is_some_and(|x| x == "spv"))
            .filter_map(|e| Some((e.metadata().ok()?.modified().ok()?, e.path())))
            .collect();
        if kept.len() > KEPT {
            kept.sort();
            for (_, path) in &kept[..kept.len() - KEPT] {
                let _ = std::fs::remove_file(path);
            }
        }
    }
}

/// Two words of a module's hash.
fn checksum(module: &[u32]) -> [u32; 2] {
    let mut h = std::hash::DefaultHasher::new();
    module.hash(&mut h);
    let sum = h.finish();
    [sum as u32, (sum >> 32) as u32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_module_comes_back_and_a_damaged_one_does_not() {
        let dir = std::env::temp_dir().join(format!("caustic-module-cache-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let cache = ModuleCache::at(&dir);
        let module: Vec<u32> = [super::super::spirv::MAGIC, 0x0001_0500, 0, 9, 0, 0x0002_0011, 1].to_vec();
        let kernel = ModuleCache::digest(&module);
        let key = ModuleCache::key(kernel, 3, 1, &["entry::render"]);
        assert_ne!(key, ModuleCache::key(kernel, 3, 0, &["entry::render"]), "the loop is in the key");
        assert_ne!(key, ModuleCache::key(kernel, 3, 1, &["entry::light"]), "so are the entry points");
        assert_ne!(key, ModuleCache::key(kernel + 1, 3, 1, &["entry::render"]), "and the kernel");
        assert_eq!(cache.load(key), None, "nothing kept yet");
        cache.store(key, &module);
        assert_eq!(cache.load(key), Some(module.clone()));
        // Damaged: a word changed, the file cut short, a byte more; each is pruned again.
        let path = dir.join(format!("{key:016x}.spv"));
        let whole = std::fs::read(&path).unwrap();
        let mut changed = whole.clone();
        changed[24] ^= 1;
        for bytes in [changed, whole[..whole.len() - 4].to_vec(), [whole.clone(), vec![0]].concat()] {
            std::fs::write(&path, bytes).unwrap();
            assert_eq!(cache.load(key), None);
        }
        // No more than `KEPT` files stay.
        for k in 0..KEPT as u64 + 3 {
            cache.store(k, &module);
        }
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), KEPT);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
