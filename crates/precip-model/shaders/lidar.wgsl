// lidar.wgsl: LiDAR beams against the particles and the ground map. Rust twin:
// precip_model::sensors::lidar, function by function. Kernel `query_beams`: one invocation a
// beam; the workgroup bounds its 64 beams by one cone, reads the particles 64 at a
// time, keeps in shared memory those the cone may reach, and each beam tests the
// kept ones (ties go to the lower particle index, as on the CPU).

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
    particle_first: u32,
    particle_end: u32,
    aperture_radius_m: f32,
    march_step_m: f32,
    reserved0: u32,
    reserved1: u32,
    reserved2: u32,
}

// Rust: precip_gpu::recipe::beam_bindings.
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

// Rust: lidar::{GROUP_ANGLE_SLACK_RAD, GROUP_DISTANCE_SLACK_M, GROUP_RELATIVE_SLACK}.
const GROUP_ANGLE_SLACK_RAD: f32 = 1.0e-3;
const GROUP_DISTANCE_SLACK_M: f32 = 1.0e-3;
const GROUP_RELATIVE_SLACK: f32 = 1.0e-4;
const HALF_PI: f32 = 1.5707964;

// Rust: BeamGroupBound.
struct BeamGroupBound {
    apex_m: vec3<f32>,
    axis: vec3<f32>,
    half_angle_rad: f32,
    pad_m: f32,
    reach_m: f32,
}

// The workgroup's beams (lanes past the query repeat its last beam).
var<workgroup> group_beams: array<Beam, 64>;

// Rust: beam_group_bound, over the workgroup's 64 beams.
fn beam_group_bound(aperture_radius_m: f32) -> BeamGroupBound {
    var apex = vec3<f32>(0.0);
    var mean = vec3<f32>(0.0);
    for (var k = 0u; k < 64u; k++) {
        apex += group_beams[k].origin_m;
        mean += group_beams[k].direction;
    }
    apex = apex / 64.0;
    var axis = group_beams[0].direction;
    if (dot(mean, mean) > 1.0e-6) {
        axis = normalize(mean);
    }
    var half_angle = 0.0;
    var spread = 0.0;
    var reach = 0.0;
    for (var k = 0u; k < 64u; k++) {
        let b = group_beams[k];
        half_angle = max(half_angle, acos(clamp(dot(b.direction, axis), -1.0, 1.0)) + 0.5 * b.divergence_rad);
        let offset = length(b.origin_m - apex);
        spread = max(spread, offset);
        reach = max(reach, offset + b.max_range_m * (1.0 + tan(0.5 * b.divergence_rad)));
    }
    return BeamGroupBound(apex, axis, half_angle + GROUP_ANGLE_SLACK_RAD, spread + aperture_radius_m, reach);
}

// Rust: group_may_strike.
fn group_may_strike(bound: BeamGroupBound, centre_m: vec3<f32>, diameter_m: f32) -> bool {
    let v = centre_m - bound.apex_m;
    let distance = length(v);
    let pad = bound.pad_m + 0.5 * diameter_m + GROUP_DISTANCE_SLACK_M + GROUP_RELATIVE_SLACK * distance;
    if (distance > bound.reach_m + pad) {
        return false;
    }
    if (distance <= pad || bound.half_angle_rad >= HALF_PI) {
        return true;
    }
    let angle = acos(clamp(dot(v, bound.axis) / distance, -1.0, 1.0));
    let outside = angle - bound.half_angle_rad;
    if (outside <= 0.0) {
        return true;
    }
    if (outside >= HALF_PI) {
        return distance <= pad;
    }
    return distance * sin(outside) <= pad;
}

// The particles of a tile the group's cone may reach: centre and diameter, flags,
// index; `kept` of them.
var<workgroup> tile_spheres: array<vec4<f32>, 64>;
var<workgroup> tile_flags: array<u32, 64>;
var<workgroup> tile_index: array<u32, 64>;
var<workgroup> kept: atomic<u32>;

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
    group_beams[lid] = beam;
    workgroupBarrier();
    let bound = beam_group_bound(beam_params.aperture_radius_m);
    var hit = BeamHit(0.0, 0.0, LIDAR_NO_PARTICLE, target_range);
    var hit_index = 0u;
    // The particles in the air: the ones resting are not (query_on_cpu).
    let count = beam_params.particle_end;
    for (var base = beam_params.particle_first; base < count; base += 64u) {
        if (lid == 0u) {
            atomicStore(&kept, 0u);
        }
        workgroupBarrier();
        let i = base + lid;
        if (i < count) {
            let p = particles[i];
            if (group_may_strike(bound, p.position_m, p.diameter_m)) {
                let slot = atomicAdd(&kept, 1u);
                tile_spheres[slot] = vec4<f32>(p.position_m, p.diameter_m);
                tile_flags[slot] = p.flags;
                tile_index[slot] = i;
            }
        }
        workgroupBarrier();
        let in_tile = atomicLoad(&kept);
        if (live) {
            for (var j = 0u; j < in_tile; j++) {
                let sphere = tile_spheres[j];
                let t = beam_strike_range_m(beam, beam_params.aperture_radius_m, sphere.xyz, sphere.w);
                let index = tile_index[j];
                let none = hit.particle_flags == LIDAR_NO_PARTICLE;
                // The nearest; of equal ranges the lower index (the CPU's order).
                let nearer = none || t < hit.particle_range_m || (t == hit.particle_range_m && index < hit_index);
                if (t >= 0.0 && nearer && (target_range < 0.0 || t < target_range)) {
                    hit.particle_range_m = t;
                    hit.particle_diameter_m = sphere.w;
                    hit.particle_flags = tile_flags[j];
                    hit_index = index;
                }
            }
        }
        workgroupBarrier();
    }
    if (live) {
        hits[b] = hit;
    }
}
