//! Large buffers: fallible, and cheap to start.
//!
//! A normal map's texels and its mip levels, sized by the input, are asked for through
//! [`try_zeroed`], so an input too big for the machine becomes an [`OutOfMemory`] error that
//! says how many bytes it needed, not an abort.
//! This module does not estimate what a whole command needs; each error names the one buffer
//! that could not be had, and [`ensure_available`] checks a command's own estimate up front.
//!
//! A 4096² normal map with its mips is 90 MB written once. Fresh pages from the kernel cost a
//! fault and a clear each; with 4 KiB pages that is about half the time of making the map. On
//! Linux the buffers here ask for transparent huge pages (`madvise(MADV_HUGEPAGE)`) before
//! the first write, so the same bytes take 512 times fewer faults. Elsewhere they are plain
//! zeroed vectors.

/// A buffer the machine would not give: what it was for and its size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("not enough memory: {what} needs {}", Bytes(*bytes))]
pub struct OutOfMemory {
    /// What the buffer was to hold (`"the mip chain's level 0"`, `"the normal map"`).
    pub what: &'static str,
    /// Its size in bytes (saturated at `u64::MAX` when even that overflows).
    pub bytes: u64,
}

impl OutOfMemory {
    /// The error for `n` items of `T`.
    pub fn of<T>(what: &'static str, n: usize) -> Self {
        let bytes = (n as u64).saturating_mul(std::mem::size_of::<T>() as u64);
        Self { what, bytes }
    }
}

/// A byte count for people: `1.5 GiB`, `12.0 MiB`, `512 bytes`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bytes(pub u64);

impl std::fmt::Display for Bytes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const UNITS: [&str; 4] = ["KiB", "MiB", "GiB", "TiB"];
        if self.0 < 1024 {
            return write!(f, "{} bytes", self.0);
        }
        let (mut v, mut unit) = (self.0 as f64 / 1024.0, 0);
        while v >= 1024.0 && unit + 1 < UNITS.len() {
            v /= 1024.0;
            unit += 1;
        }
        write!(f, "{v:.1} {}", UNITS[unit])
    }
}

/// A zeroed vector of `n` RGBA8 texels, backed by huge pages where the system allows. Aborts
/// when memory runs out: for buffers whose size no input chooses (benchmarks).
pub fn zeroed_rgba8(n: usize) -> Vec<[u8; 4]> {
    zeroed(n)
}

/// [`try_zeroed`] that aborts when memory runs out, for buffers already bounded by a smaller
/// one the caller holds.
pub(crate) fn zeroed<T: crate::Texel>(n: usize) -> Vec<T> {
    try_zeroed(n, "texels").unwrap_or_else(|_| {
        std::alloc::handle_alloc_error(std::alloc::Layout::array::<T>(n).unwrap_or(std::alloc::Layout::new::<T>()))
    })
}

/// A zeroed vector of `n` texels of 8 or 16 bits, backed by huge pages where the system
/// allows; [`OutOfMemory`] naming `what` when the machine will not give it.
///
/// ```
/// use bumpmap_math::buffer::try_zeroed;
/// assert_eq!(try_zeroed::<[u8; 4]>(2, "test").unwrap(), vec![[0; 4]; 2]);
/// let e = try_zeroed::<[u16; 4]>(usize::MAX / 16, "a huge map").unwrap_err();
/// assert!(e.to_string().starts_with("not enough memory: a huge map needs"));
/// ```
pub fn try_zeroed<T: crate::Texel>(n: usize, what: &'static str) -> Result<Vec<T>, OutOfMemory> {
    #[cfg(target_os = "linux")]
    const HUGE: usize = 2 << 20;
    if n == 0 {
        return Ok(Vec::new());
    }
    let layout = std::alloc::Layout::array::<T>(n).map_err(|_| OutOfMemory::of::<T>(what, n))?;
    // SAFETY: the layout has a non-zero size; a null result is handled below.
    let ptr = unsafe { std::alloc::alloc_zeroed(layout) } as *mut T;
    if ptr.is_null() {
        return Err(OutOfMemory::of::<T>(what, n));
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
    Ok(unsafe { Vec::from_raw_parts(ptr, n, n) })
}

/// Whether the process may still have `bytes` more: asks the allocator for that much address
/// space and gives it back untouched (no page is written, so it costs no memory). For a
/// command to refuse work whose buffers together will not fit, before the first of them, rather
/// than running until some small allocation late in the work aborts.
///
/// ```
/// use bumpmap_math::buffer::ensure_available;
/// assert!(ensure_available(1 << 20, "a small scene").is_ok());
/// let e = ensure_available(u64::MAX / 2, "a huge scene").unwrap_err();
/// assert!(e.to_string().starts_with("not enough memory: a huge scene needs"));
/// ```
///
/// The probe asks for [`HEADROOM`] more than `bytes`: work that passes its estimate still makes
/// small buffers of its own (a triangle's setup, an encoder's rows, a thread's scratch), none
/// asked for fallibly, and an estimate met to the last page would leave them none.
pub fn ensure_available(bytes: u64, what: &'static str) -> Result<(), OutOfMemory> {
    let n = usize::try_from(bytes.saturating_add(HEADROOM)).map_err(|_| OutOfMemory { what, bytes })?;
    let mut probe: Vec<u8> = Vec::new();
    probe.try_reserve_exact(n).map_err(|_| OutOfMemory { what, bytes })
}

/// What [`ensure_available`] leaves over beyond an estimate, for the small buffers no estimate
/// counts: 16 MiB, a few times what a frame's per-thread setup and a PNG encoder's rows take.
pub const HEADROOM: u64 = 16 << 20;

/// An empty vector with room for `n`, or the error naming `what`.
pub(crate) fn try_vec<T>(n: usize, what: &'static str) -> Result<Vec<T>, OutOfMemory> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| OutOfMemory::of::<T>(what, n))?;
    Ok(v)
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

    #[test]
    fn a_buffer_too_big_is_an_error_with_its_size() {
        let e = super::try_zeroed::<[u16; 4]>(usize::MAX / 16, "level 0").unwrap_err();
        assert_eq!(e.bytes, (usize::MAX / 16) as u64 * 8);
        assert!(e.to_string().contains("level 0 needs"), "{e}");
        assert_eq!(super::Bytes(3 << 29).to_string(), "1.5 GiB");
        assert_eq!(super::Bytes(1000).to_string(), "1000 bytes");
    }
}
