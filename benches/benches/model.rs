//! The CPU-side model work every backend shares: baking the wind volume (on each
//! weather change with new noise), one cover update on the CPU reference, and one
//! far step of the cover beyond the grid over 10 km of generated terrain (the host
//! does it every `FAR_STEP_EVERY` steps, for every backend).
//!
//! `cargo bench -p precip-benches --bench model`

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use precip_benches::scenario;
use precip_model::wind::{WindField, WindVolume, WindVolumeSpec};

fn wind_bake(c: &mut Criterion) {
    let mut group = c.benchmark_group("wind_bake");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(4));
    let field = WindField {
        mean_wind_mps: glam::Vec3::new(5.0, 0.0, 2.0),
        ..WindField::calm()
    };
    for side in [32u32, 64] {
        let spec = WindVolumeSpec {
            texels: glam::UVec3::new(side, side / 2, side),
            ..WindVolumeSpec::default()
        };
        group.throughput(Throughput::Elements(u64::from(side * side / 2 * side)));
        group.bench_function(BenchmarkId::from_parameter(side), |b| {
            b.iter(|| WindVolume::bake(&field, &spec).expect("valid"));
        });
    }
    group.finish();
}

fn cover_update(c: &mut Criterion) {
    let mut group = c.benchmark_group("cover_update");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(3));
    let setup = scenario(1_000);
    let mut grid = setup.initial_cover().expect("valid");
    let block = setup.cover_step_params(&setup.weather, 0.02);
    let air = block.air();
    group.throughput(Throughput::Elements(grid.texels.len() as u64));
    let mut deposits = precip_model::cover::DepositBuffer::new(grid.texels.len());
    group.bench_function(BenchmarkId::new("cpu", grid.texels.len()), |b| {
        b.iter(|| {
            grid.step(&mut deposits, air, block.dt_days, &setup.cover.params);
        });
    });
    group.finish();
}

fn far_cover_step(c: &mut Criterion) {
    use precip_model::host::{FAR_STEP_EVERY, FarCover, WaterBeyond};
    use precip_viewer::terrain_file::{TerrainScale, TerrainSource, load_terrain};
    let mut group = c.benchmark_group("far_cover_step");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(3));
    let terrain = load_terrain(
        &TerrainSource::Generated,
        TerrainScale {
            spacing_m: None,
            heights_m: None,
        },
    )
    .expect("the generated terrain");
    let setup = scenario(1_000);
    let mut far = FarCover::over(&terrain, &setup.cover.frame);
    let input = precip_model::cover::CoverInput {
        snow_mm: 0.01,
        rain_mm: 0.0,
        air_temperature_c: -2.0,
        relative_humidity: 0.8,
        wind_speed_mps: 3.0,
        dt_days: 1.0e-5,
    };
    let beyond = WaterBeyond {
        camera_xz_m: glam::Vec2::ZERO,
        snow_mm: 0.01,
        rain_mm: 0.0,
        shafts: None,
    };
    let cells = far.cells();
    group.throughput(Throughput::Elements(u64::from(cells.x * cells.y)));
    group.bench_function(BenchmarkId::new("cells", cells.x * cells.y), |b| {
        b.iter(|| {
            for _ in 0..FAR_STEP_EVERY {
                far.add_step(input, beyond, glam::Vec3::Y, &setup.cover.params);
            }
        });
    });
    group.finish();
}

criterion_group!(benches, wind_bake, cover_update, far_cover_step);
criterion_main!(benches);
