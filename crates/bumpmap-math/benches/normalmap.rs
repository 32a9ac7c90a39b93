//! Criterion benchmark: 8-bit height field → normal map + full mip chain (issue: 4096², here
//! also the parts, so a regression can be located).

use bumpmap_math::normalmap::normal_map_level0;
use bumpmap_math::{HeightField, HeightPreset, MipChain, MipMode, NormalMapOptions};
use criterion::{Criterion, criterion_group, criterion_main};

fn heights(size: usize) -> Vec<u8> {
    let bricks = HeightPreset::Bricks.render(size, size);
    let noise = HeightPreset::Noise(7).render(size, size);
    bricks.to_f32().iter().zip(&noise.to_f32()).map(|(b, n)| (b * 247.0 + n * 8.0).clamp(0.0, 255.0) as u8).collect()
}

fn bench(c: &mut Criterion) {
    let size = std::env::var("BUMPMAP_BENCH_SIZE").ok().and_then(|s| s.parse().ok()).unwrap_or(4096);
    let bytes = heights(size);
    let field = HeightField::from_u8(size, size, &bytes).unwrap();
    let opts = NormalMapOptions::default();
    let mut g = c.benchmark_group(format!("normalmap_{size}"));
    g.sample_size(10);
    g.bench_function("u8_to_field", |b| b.iter(|| HeightField::from_u8(size, size, &bytes).unwrap()));
    g.bench_function("level0", |b| b.iter(|| normal_map_level0(&field, &opts).unwrap()));
    g.bench_function("full_chain_from_u8", |b| {
        b.iter(|| {
            let f = HeightField::from_u8(size, size, &bytes).unwrap();
            MipChain::<[u8; 4]>::from_height(&f, &opts, MipMode::LengthInAlpha).unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
