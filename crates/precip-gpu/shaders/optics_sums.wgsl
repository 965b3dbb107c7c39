// optics_sums.wgsl: kernel optics_sums, the camera volume's particles' cross-sections
// summed per workgroup for Backend::optics (Rust twin:
// precip_model::sensors::optics::CrossSectionSums::of_particles; the host adds the
// workgroups' partials in order: CrossSectionSums::of_partials). Reads 64 bytes a
// particle and writes 32 a workgroup, in place of reading every particle back.

// Rust: precip_gpu::recipe::OpticsParams (16 bytes).
struct OpticsParams {
    particle_count: u32,
    reserved0: u32,
    reserved1: u32,
    reserved2: u32,
}

@group(0) @binding(0) var<uniform> optics_params: OpticsParams;
@group(0) @binding(1) var<storage, read> optics_particles: array<Particle>;
@group(0) @binding(2) var<storage, read_write> optics_partials: array<OpticsPartial>;

var<workgroup> extinction_lanes: array<vec3<f32>, 64>;
var<workgroup> backscatter_lanes: array<vec3<f32>, 64>;
var<workgroup> sampled_lanes: array<u32, 64>;

@compute @workgroup_size(64)
fn optics_sums(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
    @builtin(workgroup_id) group: vec3<u32>,
) {
    let i = linear_index(id, groups);
    var extinction = vec3<f32>(0.0);
    var backscatter = vec3<f32>(0.0);
    var sampled = 0u;
    if i < optics_params.particle_count {
        let p = optics_particles[i];
        if (p.flags & FLAG_CAMERA_VOLUME) != 0u && p.diameter_m > 0.0 {
            let kind = particle_kind(p.flags);
            for (var band = 0u; band < 3u; band++) {
                extinction[band] = extinction_cross_section_m2(kind, p.diameter_m, band);
                backscatter[band] = backscatter_cross_section_m2_sr(kind, p.diameter_m, band);
            }
            sampled = 1u;
        }
    }
    extinction_lanes[lane] = extinction;
    backscatter_lanes[lane] = backscatter;
    sampled_lanes[lane] = sampled;
    workgroupBarrier();
    // A fixed tree: the same sums in the same order on every device.
    for (var stride = 32u; stride > 0u; stride = stride / 2u) {
        if lane < stride {
            extinction_lanes[lane] += extinction_lanes[lane + stride];
            backscatter_lanes[lane] += backscatter_lanes[lane + stride];
            sampled_lanes[lane] += sampled_lanes[lane + stride];
        }
        workgroupBarrier();
    }
    if lane == 0u {
        optics_partials[group.x + group.y * groups.x] = OpticsPartial(
            extinction_lanes[0],
            sampled_lanes[0],
            backscatter_lanes[0],
            0u,
        );
    }
}
