//! Whatever texels a map holds — random bytes, a constant, a blue-only or an empty-blue image, at
//! every size from 1×1 to 40×40, read as 8-bit, BC5 and BC7 — `inspect` answers and `height`
//! either refuses or gives finite heights: no panic, no NaN.

#[test]
fn hostile_texels_get_answers_and_finite_heights() {
    use bumpmap::inspect::{DecodedMap, StoredAs, inspect_map};
    let mut seed = 12345u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for _ in 0..400 {
        let w = (next() % 40 + 1) as usize;
        let h = (next() % 40 + 1) as usize;
        let mode = next() % 4;
        let texels: Vec<[u8; 4]> = (0..w * h)
            .map(|_| {
                let r = next();
                match mode {
                    0 => [r as u8, (r >> 8) as u8, (r >> 16) as u8, (r >> 24) as u8],
                    1 => [128, 128, 255, 255],
                    2 => [(r as u8) | 0x80, 0, 0, 0],
                    _ => [r as u8, (r >> 8) as u8, 0, 255],
                }
            })
            .collect();
        let levels = vec![bumpmap_math::Image::new(w, h, texels)];
        for stored in [StoredAs::Unorm8, StoredAs::Bc5, StoredAs::Bc7] {
            let map = DecodedMap::from_unorm(&levels, stored);
            let r = inspect_map("x", &map);
            let _ = (r.lines(), r.to_json());
            for method in [None, Some(bumpmap_math::integration::Boundary::Free)] {
                let o = bumpmap::heights::HeightOptions { boundary: method, ..Default::default() };
                if let Ok(hh) = bumpmap::heights::heights_from_normals(&map.levels[0], &o) {
                    assert!(hh.texels.iter().all(|v| v.is_finite()), "{w}x{h} mode {mode}");
                    let n = hh.normalized();
                    assert!(n.iter().all(|v| v.is_finite()));
                }
            }
        }
    }
}
