//! Large output buffers that start cheap.
//!
//! A 4096² normal map with its mips is 90 MB written once. Fresh pages from the kernel cost a
//! fault and a clear each; with 4 KiB pages that is about half the time of making the map. On
//! Linux the buffers here ask for transparent huge pages (`madvise(MADV_HUGEPAGE)`) before
//! the first write, so the same bytes take 512 times fewer faults. Elsewhere they are plain
//! zeroed vectors.

/// A zeroed vector of `n` RGBA8 texels, backed by huge pages where the system allows.
pub fn zeroed_rgba8(n: usize) -> Vec<[u8; 4]> {
    zeroed(n)
}

/// A zeroed vector of `n` texels of 8 or 16 bits, backed by huge pages where the system allows.
pub fn zeroed<T: crate::Texel>(n: usize) -> Vec<T> {
    const HUGE: usize = 2 << 20;
    if n == 0 {
        return Vec::new();
    }
    let layout = std::alloc::Layout::array::<T>(n).expect("texel buffer size overflows");
    // SAFETY: the layout has a non-zero size; a null result is handled below.
    let ptr = unsafe { std::alloc::alloc_zeroed(layout) } as *mut T;
    if ptr.is_null() {
        std::alloc::handle_alloc_error(layout);
    }
    #[cfg(target_os = "linux")]
    if layout.size() >= 4 * HUGE {
        // Advise only the 2 MiB-aligned interior; the pages are still untouched.
        let start = (ptr as usize).next_multiple_of(HUGE);
        let end = (ptr as usize + layout.size()) / HUGE * HUGE;
        if end > start {
            // SAFETY: [start, end) lies inside the allocation; madvise only changes how its
            // pages are backed, never their contents, and failure is harmless.
            unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
        }
    }
    // SAFETY: allocated by the global allocator with `Layout::array::<T>(n)`, which is the
    // layout `Vec` uses for this capacity; zeroed bytes are valid texels.
    unsafe { Vec::from_raw_parts(ptr, n, n) }
}

#[cfg(test)]
mod tests {
    #[test]
    fn buffers_are_zeroed_and_sized() {
        for n in [0, 1, 1000, 3 << 20] {
            let v = super::zeroed_rgba8(n);
            assert_eq!(v.len(), n);
            assert!(v.iter().all(|t| *t == [0; 4]));
        }
    }
}
