//! Edge padding: texels outside every UV island take the mean of their filled neighbours, one
//! ring a pass, for as many passes as asked, so that filtering and mip levels near an island's
//! edge read the island's own values instead of the background.
//!
//! What this module does not do: choose the width (the baker's default covers its mip chain).

/// Fills up to `rings` texels beyond the `filled` ones of a `width`×`height` image of `values`,
/// each the mean of its filled 8-neighbours (`mean` averages a few values); returns the texels
/// filled now as well.
pub fn pad<T: Copy>(
    values: &mut [T],
    filled: &[bool],
    width: usize,
    height: usize,
    rings: u32,
    mean: impl Fn(&[T]) -> T,
) -> Vec<bool> {
    let mut filled = filled.to_vec();
    let mut around = Vec::with_capacity(8);
    for _ in 0..rings {
        let mut next = Vec::new();
        for y in 0..height {
            for x in 0..width {
                if filled[y * width + x] {
                    continue;
                }
                around.clear();
                for (dx, dy) in [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    if nx >= 0 && ny >= 0 && (nx as usize) < width && (ny as usize) < height {
                        let k = ny as usize * width + nx as usize;
                        if filled[k] {
                            around.push(values[k]);
                        }
                    }
                }
                if !around.is_empty() {
                    next.push((y * width + x, mean(&around)));
                }
            }
        }
        if next.is_empty() {
            break;
        }
        for (k, v) in next {
            values[k] = v;
            filled[k] = true;
        }
    }
    filled
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_pass_fills_one_ring() {
        let (w, h) = (7, 7);
        let mut values = vec![0.0f32; w * h];
        let mut filled = vec![false; w * h];
        values[3 * w + 3] = 5.0;
        filled[3 * w + 3] = true;
        let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
        let after = pad(&mut values, &filled, w, h, 2, mean);
        assert_eq!(after.iter().filter(|f| **f).count(), 25, "a 5×5 square after two rings");
        assert!(values.iter().zip(&after).all(|(v, f)| !*f || *v == 5.0));
        assert!(!after[0], "the corner is three rings away");
    }
}
