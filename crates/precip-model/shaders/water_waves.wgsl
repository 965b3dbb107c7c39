// water_waves.wgsl: rain on water bodies, a height field struck by the drops that
// land and carried by the damped wave equation. Rust twin: precip_model::physics::water_waves.
// The buffer: WAVE_WORDS_PER_CELL i32 a cell (fixed point, WAVE_UNITS_PER_M): height
// now, a sub-step before, the strikes summed (then the next height), water (0/1).

@group(0) @binding(8) var<storage, read_write> waves: array<atomic<i32>>;

const WAVE_CELL_M: f32 = 0.04;
const WAVE_UNITS_PER_M: f32 = 1.0e7;
const WAVE_DAMPING_PER_S: f32 = 1.0;
const WAVE_WORDS_PER_CELL: u32 = 4u;

fn wave_speed_mps() -> f32 {
    return ripple_phase_speed_mps(4.0 * WAVE_CELL_M);
}

fn crater_volume_m3(diameter_m: f32, speed_mps: f32) -> f32 {
    let crater = max(diameter_m, 0.0) * sqrt(sqrt(weber_number(diameter_m, speed_mps)));
    return 3.14159265 / 12.0 * crater * crater * crater;
}

fn strike_units(diameter_m: f32, speed_mps: f32, cell_area_m2: f32) -> i32 {
    let depth_m = crater_volume_m3(diameter_m, speed_mps) / max(cell_area_m2, 1.0e-6);
    return -i32(min(depth_m * WAVE_UNITS_PER_M, 1.0e9));
}

fn wave_next_height(now: f32, before: f32, neighbours: vec4<f32>, dt_s: f32) -> f32 {
    let r = wave_speed_mps() * dt_s / WAVE_CELL_M;
    let laplacian = neighbours.x + neighbours.y + neighbours.z + neighbours.w - 4.0 * now;
    let g = 0.5 * WAVE_DAMPING_PER_S * dt_s;
    return ((2.0 * now - (1.0 - g) * before) + r * r * laplacian) / (1.0 + g);
}

fn wave_height_m(cell: i32) -> f32 {
    if (cell < 0) {
        return 0.0;
    }
    return f32(atomicLoad(&waves[u32(cell) * WAVE_WORDS_PER_CELL])) / WAVE_UNITS_PER_M;
}

// The landed particles strike the cells they land in, where those are water (before
// birth_particles re-births them).
@compute @workgroup_size(64)
fn wave_excite(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let lanes = groups.x * groups.y * 64u;
    let count = atomicLoad(&pending.count);
    let area = WAVE_CELL_M * WAVE_CELL_M;
    for (var k = linear_index(id, groups); k < count; k += lanes) {
        let p = particles[pending.indices[k]];
        if ((p.flags & FLAG_LANDED) == 0u || !kind_rings_water(particle_kind(p.flags))) {
            continue;
        }
        let cell = grid_texel_index(frames.waves, p.position_m.xz);
        if (cell < 0 || atomicLoad(&waves[u32(cell) * WAVE_WORDS_PER_CELL + 3u]) == 0) {
            continue;
        }
        atomicAdd(&waves[u32(cell) * WAVE_WORDS_PER_CELL + 2u], strike_units(p.diameter_m, length(p.velocity_mps), area));
    }
}

// The next height of every water cell (the strikes added), into its third word;
// land cells stay at rest.
@compute @workgroup_size(64)
fn wave_step(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    let n = frames.waves.texels;
    if (i >= n.x * n.y) {
        return;
    }
    let base = i * WAVE_WORDS_PER_CELL;
    let strikes = atomicLoad(&waves[base + 2u]);
    if (atomicLoad(&waves[base + 3u]) == 0) {
        atomicStore(&waves[base + 2u], 0);
        return;
    }
    let x = i32(i % n.x);
    let z = i32(i / n.x);
    let nx = i32(n.x);
    let nz = i32(n.y);
    let left = select(-1, i32(i) - 1, x > 0);
    let right = select(-1, i32(i) + 1, x + 1 < nx);
    let back = select(-1, i32(i) - nx, z > 0);
    let front = select(-1, i32(i) + nx, z + 1 < nz);
    let neighbours = vec4<f32>(wave_height_m(left), wave_height_m(right), wave_height_m(back), wave_height_m(front));
    let now = f32(atomicLoad(&waves[base])) / WAVE_UNITS_PER_M;
    let before = f32(atomicLoad(&waves[base + 1u])) / WAVE_UNITS_PER_M;
    let next = wave_next_height(now, before, neighbours, step_params.dt_s);
    let units = clamp(next * WAVE_UNITS_PER_M, -1.0e9, 1.0e9);
    atomicStore(&waves[base + 2u], i32(units) + strikes);
}

// Every cell moves on a sub-step: before = now, now = next, and the strikes' word
// is emptied for the next sub-step.
@compute @workgroup_size(64)
fn wave_shift(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    let n = frames.waves.texels;
    if (i >= n.x * n.y) {
        return;
    }
    let base = i * WAVE_WORDS_PER_CELL;
    atomicStore(&waves[base + 1u], atomicLoad(&waves[base]));
    atomicStore(&waves[base], atomicLoad(&waves[base + 2u]));
    atomicStore(&waves[base + 2u], 0);
}
