// particle_lists.wgsl: how each particle is drawn this frame — not at all (outside the
// view cone, or past the count), splatted by compute (sub-pixel), or as a sprite or a
// tetrahedron. One function for the cull kernels (which list the drawn ones) and the
// splat kernel (which takes the rest), so a particle is drawn exactly once.
// Needs `params: RenderParams`, `frame_counts()` (the counts, read so a branch on them
// is never inlined: render_scene.wgsl) and `particles: array<Particle>`.

fn drawn_as(i: u32) -> u32 {
    let counts = frame_counts();
    if (i >= counts.x) {
        return DRAWN_NOT;
    }
    let p = particles[i];
    let camera = params.camera_m_cone_cos.xyz;
    if (counts.y != 0u && !in_view_cone(p.position_m, camera, params.view_dir_pixel_angle.xyz, params.camera_m_cone_cos.w)) {
        return DRAWN_NOT;
    }
    let kind = (p.flags >> FLAG_KIND_SHIFT) & FLAG_KIND_MASK;
    if (counts.w != 0u) {
        let distance_m = distance(p.position_m, camera);
        var length_m = p.diameter_m * params.sizing.x;
        if (kind == KIND_RAIN) {
            length_m = params.sizing.w * length(p.velocity_mps);
        }
        if (sub_pixel(length_m, distance_m, params.view_dir_pixel_angle.w, params.sizing.y)) {
            return DRAWN_SPLAT;
        }
    }
    return select(DRAWN_SNOW, DRAWN_RAIN, kind == KIND_RAIN);
}
