// particle_lists.wgsl: how each particle is drawn this frame — not at all (outside the
// view cone, or past the count), splatted by compute (sub-pixel), or as a sprite or a
// tetrahedron. One function for the cull kernels (which list the drawn ones) and the
// splat kernel (which takes the rest), so a particle is drawn exactly once.
// Needs `params: RenderParams`, `frame_counts()` and `frame_pools()` (the counts and
// pools, read so a branch on them is never inlined: render_scene.wgsl) and
// `particles: array<Particle>`.

// particle_multiplicity (precip_model::drawing::multiplicity): how many real particles
// particle `i` at `position_m` stands for; 0 for a world particle in the camera box.
fn particle_multiplicity(i: u32, position_m: vec3<f32>) -> f32 {
    let pools = frame_pools();
    if (i >= pools.x) {
        return params.camera_box_half_m.w;
    }
    if (i >= pools.y) {
        return 1.0;
    }
    // Without a camera volume its half extent is 0: nothing is inside.
    if (all(abs(position_m - params.camera_box_centre_m.xyz) < params.camera_box_half_m.xyz)) {
        return 0.0;
    }
    return params.camera_box_centre_m.w;
}

// snow_copies: copies of each camera-volume flake drawn as a sprite (≥ 1).
fn snow_copies() -> u32 {
    return max(frame_pools().w, 1u);
}

// snow_copy_position (precip_model::drawing::multiplicity).
fn snow_copy_position(index: u32, copy: u32, position_m: vec3<f32>) -> vec3<f32> {
    if (copy == 0u) {
        return position_m;
    }
    let centre = params.camera_box_centre_m.xyz;
    let half = params.camera_box_half_m.xyz;
    let key = index ^ (copy * 0x68e31da4u);
    let offset = vec3<f32>(
        multiplicity_rank(key),
        multiplicity_rank(key ^ 0x1b873593u),
        multiplicity_rank(key ^ 0xcc9e2d51u),
    ) * 2.0 * half;
    let q = position_m + offset - centre;
    return centre + q - 2.0 * half * floor((q + half) / (2.0 * half));
}

// particle_weight (precip_model::drawing::multiplicity): the ink particle `i` is
// drawn with, in particles; 0 when not drawn.
fn particle_weight(i: u32, position_m: vec3<f32>) -> f32 {
    let pools = frame_pools();
    if (i >= pools.x) {
        return select(0.0, max(params.camera_box_half_m.w, 1.0), i < pools.z);
    }
    return drawn_weight(i, particle_multiplicity(i, position_m));
}

// The length drawn_as tests against min px: a flake's sprite side, a drop's streak.
fn drawn_length_m(p: Particle) -> f32 {
    if (kind_is_drop(particle_kind(p.flags))) {
        return params.sizing.w * length(p.velocity_mps);
    }
    return p.diameter_m * params.sizing.x;
}

// Whether particle `p` is at least min px of the frame (else what it stands for
// beyond itself is in the haze): in the frame's pixels whatever the resolution the
// particles are drawn at (sizing.y is min px of the frame times lens.z, the frame
// pixels a drawn pixel spans).
fn resolved(p: Particle) -> bool {
    let distance_m = distance(p.position_m, params.camera_m_cone_cos.xyz);
    let min_px = params.sizing.y / max(params.lens.z, 1.0);
    return !sub_pixel(drawn_length_m(p), distance_m, params.view_dir_pixel_angle.w, min_px);
}

// Whether particle `p` is drawn at least min px of the particles' image (else the
// splat takes it, at the frame's resolution).
fn drawn_big_enough(p: Particle) -> bool {
    let distance_m = distance(p.position_m, params.camera_m_cone_cos.xyz);
    return !sub_pixel(drawn_length_m(p), distance_m, params.view_dir_pixel_angle.w, params.sizing.y);
}

// The ink particle `i` is drawn with, in particles: its multiplicity's when resolved,
// its own (at most 1) when sub-pixel, as what it stands for beyond itself is in the
// haze, whose extinction is the whole air's (precip_model::drawing::multiplicity).
fn resolved_weight(i: u32, p: Particle) -> f32 {
    let w = particle_weight(i, p.position_m);
    return select(min(w, 1.0), w, resolved(p));
}

fn drawn_as(i: u32) -> u32 {
    let counts = frame_counts();
    if (i >= counts.x) {
        return DRAWN_NOT;
    }
    let p = particles[i];
    // What the air holds: a share of an over-full pool is drawn, none in dry air.
    if (particle_weight(i, p.position_m) <= 0.0) {
        return DRAWN_NOT;
    }
    let camera = params.camera_m_cone_cos.xyz;
    if (counts.y != 0u && !in_view_cone(p.position_m, camera, params.view_dir_pixel_angle.xyz, params.camera_m_cone_cos.w)) {
        return DRAWN_NOT;
    }
    let drop = kind_is_drop(particle_kind(p.flags));
    if (counts.w != 0u && !drawn_big_enough(p)) {
        return DRAWN_SPLAT;
    }
    // At a reduced resolution a drop narrower than the image's minimum would be
    // widened there into a soft blob: it is splatted along its streak at the
    // frame's resolution instead (render_splat.wgsl).
    if (counts.w != 0u && drop && params.lens.z > 1.0) {
        let distance_m = distance(p.position_m, camera);
        if (sub_pixel(p.diameter_m, distance_m, params.view_dir_pixel_angle.w, params.sizing.y)) {
            return DRAWN_SPLAT;
        }
    }
    return select(DRAWN_SNOW, DRAWN_RAIN, drop);
}
