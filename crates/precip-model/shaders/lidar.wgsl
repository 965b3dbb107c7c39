// lidar.wgsl: LiDAR beams against the particles and the ground map. Rust twin:
// precip_model::lidar, function by function. Kernel `query_beams`: one invocation a
// beam; the workgroup reads the particles 64 at a time into shared memory and each
// beam tests them in index order (ties go to the lower index, as on the CPU).

struct Beam {
    origin_m: vec3<f32>,
    divergence_rad: f32,
    direction: vec3<f32>,
    max_range_m: f32,
}

struct BeamHit {
    particle_range_m: f32,
    particle_diameter_m: f32,
    particle_flags: u32,
    target_range_m: f32,
}

struct BeamParams {
    beam_count: u32,
    particle_count: u32,
    aperture_radius_m: f32,
    march_step_m: f32,
}

// Rust: precip_model::gpu::beam_bindings.
@group(0) @binding(0) var<uniform> beam_params: BeamParams;
@group(0) @binding(1) var<uniform> frames: Frames;
@group(0) @binding(2) var<storage, read> ground_height: array<f32>;
@group(0) @binding(3) var<storage, read> particles: array<Particle>;
@group(0) @binding(4) var<storage, read> beams: array<Beam>;
@group(0) @binding(5) var<storage, read_write> hits: array<BeamHit>;

// Rust: lidar::{MAX_MARCH_STEPS, BISECTIONS, NO_PARTICLE}.
const LIDAR_MAX_MARCH_STEPS: u32 = 8192u;
const LIDAR_BISECTIONS: u32 = 16u;
const LIDAR_NO_PARTICLE: u32 = 0xffffffffu;

// Rust: beam_radius_m.
fn beam_radius_m(beam: Beam, aperture_radius_m: f32, range_m: f32) -> f32 {
    return aperture_radius_m + range_m * tan(0.5 * beam.divergence_rad);
}

// Rust: beam_strike_range_m (−1 for None).
fn beam_strike_range_m(beam: Beam, aperture_radius_m: f32, centre_m: vec3<f32>, diameter_m: f32) -> f32 {
    let relative = centre_m - beam.origin_m;
    let t = dot(relative, beam.direction);
    if (!(t > 0.0 && t <= beam.max_range_m)) {
        return -1.0;
    }
    let off_axis = relative - beam.direction * t;
    let reach = 0.5 * diameter_m + beam_radius_m(beam, aperture_radius_m, t);
    return select(-1.0, t, dot(off_axis, off_axis) <= reach * reach);
}

// Rust: under_ground.
fn under_ground(point_m: vec3<f32>) -> bool {
    let g = ground_height_at(point_m.xz);
    return g.x > 0.0 && point_m.y <= g.y;
}

// Rust: hard_target_range_m (−1 for None).
fn hard_target_range_m(beam: Beam, march_step_m: f32) -> f32 {
    if (under_ground(beam.origin_m)) {
        return 0.0;
    }
    let step = max(march_step_m, beam.max_range_m / f32(LIDAR_MAX_MARCH_STEPS));
    let steps = u32(ceil(beam.max_range_m / step));
    var before = 0.0;
    for (var i = 1u; i <= steps; i++) {
        let t = min(f32(i) * step, beam.max_range_m);
        if (under_ground(beam.origin_m + beam.direction * t)) {
            var above = before;
            var below = t;
            for (var k = 0u; k < LIDAR_BISECTIONS; k++) {
                let middle = 0.5 * (above + below);
                if (under_ground(beam.origin_m + beam.direction * middle)) {
                    below = middle;
                } else {
                    above = middle;
                }
            }
            return below;
        }
        before = t;
    }
    return -1.0;
}

// A tile of particles: centre and diameter, and flags.
var<workgroup> tile_spheres: array<vec4<f32>, 64>;
var<workgroup> tile_flags: array<u32, 64>;

// Rust: query_on_cpu.
@compute @workgroup_size(64)
fn query_beams(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let b = linear_index(id, groups);
    let live = b < beam_params.beam_count;
    let beam = beams[min(b, beam_params.beam_count - 1u)];
    var target_range = -1.0;
    if (live) {
        target_range = hard_target_range_m(beam, beam_params.march_step_m);
    }
    var hit = BeamHit(0.0, 0.0, LIDAR_NO_PARTICLE, target_range);
    let count = beam_params.particle_count;
    for (var base = 0u; base < count; base += 64u) {
        let i = base + lid;
        if (i < count) {
            let p = particles[i];
            tile_spheres[lid] = vec4<f32>(p.position_m, p.diameter_m);
            tile_flags[lid] = p.flags;
        }
        workgroupBarrier();
        if (live) {
            let in_tile = min(64u, count - base);
            for (var j = 0u; j < in_tile; j++) {
                let sphere = tile_spheres[j];
                let t = beam_strike_range_m(beam, beam_params.aperture_radius_m, sphere.xyz, sphere.w);
                let nearer = hit.particle_flags == LIDAR_NO_PARTICLE || t < hit.particle_range_m;
                if (t >= 0.0 && nearer && (target_range < 0.0 || t < target_range)) {
                    hit.particle_range_m = t;
                    hit.particle_diameter_m = sphere.w;
                    hit.particle_flags = tile_flags[j];
                }
            }
        }
        workgroupBarrier();
    }
    if (live) {
        hits[b] = hit;
    }
}
