//! Each vertex's triangle corners, as compressed rows, made by a parallel counting sort.
//!
//! Both tangent modes need, for every vertex (or every welded vertex), the corners that touch it
//! in triangle order; the order matters, since tangents are summed and clustered in it. This
//! module only groups: it computes no geometry and does not weld.

use std::sync::atomic::{AtomicU32, Ordering};

use rayon::prelude::*;

/// Meshes with fewer triangles than this are grouped on one thread (the per-part counts would
/// cost more than they save).
const PARALLEL_TRIANGLES: usize = 100_000;

/// The corners of each row (corner c = 3·triangle + k): row r's are
/// `corners[start[r]..start[r + 1]]`, in increasing c.
pub(super) struct CornersByVertex {
    pub start: Vec<u32>,
    pub corners: Vec<u32>,
}

impl CornersByVertex {
    /// Groups the corners of `indices` by `row_of(vertex)`, which must be below `rows`.
    ///
    /// The triangles are cut into parts, one per worker: each part counts its corners per row,
    /// the counts give every part its first slot in every row (parts in order, so each row
    /// stays in increasing corner order), and each part then fills its slots. The result is
    /// the same as a serial counting sort.
    pub fn new(indices: &[[u32; 3]], rows: usize, row_of: impl Fn(u32) -> usize + Sync) -> Self {
        let n = indices.len();
        let parts = if n < PARALLEL_TRIANGLES { 1 } else { rayon::current_num_threads().clamp(1, 8) };
        let range = |p: usize| p * n / parts..(p + 1) * n / parts;
        // counts[p][r]: part p's corners in row r; then, in place, part p's first slot in row r.
        let mut counts: Vec<Vec<u32>> = (0..parts)
            .into_par_iter()
            .map(|p| {
                let mut count = vec![0u32; rows];
                for t in &indices[range(p)] {
                    for &v in t {
                        count[row_of(v)] += 1;
                    }
                }
                count
            })
            .collect();
        let mut start = vec![0u32; rows + 1];
        let mut total = 0u32;
        for r in 0..rows {
            start[r] = total;
            for count in counts.iter_mut() {
                let c = count[r];
                count[r] = total;
                total += c;
            }
        }
        start[rows] = total;
        let corners: Vec<AtomicU32> = (0..3 * n).map(|_| AtomicU32::new(0)).collect();
        counts.par_iter_mut().enumerate().for_each(|(p, next)| {
            let first = range(p).start;
            for (i, t) in indices[range(p)].iter().enumerate() {
                for (k, &v) in t.iter().enumerate() {
                    let r = row_of(v);
                    let slot = next[r];
                    next[r] += 1;
                    // Every slot is written by exactly one part (the counts partition each
                    // row), so relaxed stores suffice; the join below orders them before reads.
                    corners[slot as usize].store((3 * (first + i) + k) as u32, Ordering::Relaxed);
                }
            }
        });
        let corners = corners.into_iter().map(AtomicU32::into_inner).collect();
        Self { start, corners }
    }

    /// The corners of row `r`.
    pub fn row(&self, r: usize) -> &[u32] {
        &self.corners[self.start[r] as usize..self.start[r + 1] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A serial counting sort, the definition the parallel one must match.
    fn serial(indices: &[[u32; 3]], rows: usize, row_of: impl Fn(u32) -> usize) -> (Vec<u32>, Vec<u32>) {
        let mut start = vec![0u32; rows + 1];
        for t in indices {
            for &v in t {
                start[row_of(v) + 1] += 1;
            }
        }
        for r in 0..rows {
            start[r + 1] += start[r];
        }
        let mut fill = start.clone();
        let mut corners = vec![0u32; 3 * indices.len()];
        for (i, t) in indices.iter().enumerate() {
            for (k, &v) in t.iter().enumerate() {
                corners[fill[row_of(v)] as usize] = (3 * i + k) as u32;
                fill[row_of(v)] += 1;
            }
        }
        (start, corners)
    }

    #[test]
    fn parallel_grouping_equals_the_serial_counting_sort() {
        // Pseudo-random triangles over few vertices (long rows) and a welding map that merges
        // vertices, large enough to run in parts.
        let (vertices, rows) = (5_000u32, 1_700usize);
        let mut x = 12345u64;
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((x >> 33) % vertices as u64) as u32
        };
        let indices: Vec<[u32; 3]> = (0..2 * PARALLEL_TRIANGLES).map(|_| [next(), next(), next()]).collect();
        let row_of = |v: u32| (v as usize * 7) % rows;
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        let grouped = pool.install(|| CornersByVertex::new(&indices, rows, row_of));
        let (start, corners) = serial(&indices, rows, row_of);
        assert_eq!(grouped.start, start);
        assert_eq!(grouped.corners, corners);
        assert_eq!(grouped.row(3), &corners[start[3] as usize..start[4] as usize]);
    }
}
