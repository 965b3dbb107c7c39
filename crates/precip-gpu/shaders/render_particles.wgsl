// render_particles.wgsl: snow sprites and rain tetrahedra built in the vertex shader
// from the particle buffer (vertex pulling: instance = drawn particle, vertex = corner),
// lit by the sun through the shadow map and fogged like the scene.

struct ParticleVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
    // Snow: lit, fogged colour and opacity. Rain: (lit, fog, the environment's
    // radiance it refracts over the horizon's, opacity).
    @location(1) shade: vec4<f32>,
    @location(2) normal: vec3<f32>,
    @location(3) world_m: vec3<f32>,
    // Snow: a streak's length over its width (1: a sprite; snow_streak_corner).
    // Rain: the sun's light the fog layer scatters on the way (air_between's y) —
    // one interpolant for both, as every one costs a CPU rasteriser per fragment.
    @location(4) stretch: f32,
}

// The light a snowflake (or a grain of sand or dust, drawn the same way) sends toward
// the camera, fogged: a thin translucent plate facing the camera, its sunlight
// scattered forward (flake_sun_phase of the angle between the sun's light and the
// way to the camera, in place of Blinn–Phong's diffuse term), its glint Blinn–Phong's
// from the sun's side (sprites and splats alike).
fn snow_colour(p: Particle) -> vec3<f32> {
    let to_sun = params.to_sun_extinction.xyz;
    let n = normalize_or_zero(params.camera_m_cone_cos.xyz - p.position_m);
    let facing = select(-n, n, dot(n, to_sun) >= 0.0);
    let lit = shadow_lit(p.position_m);
    let no_diffuse = vec4<f32>(params.light.x, 0.0, params.light.z, params.light.w);
    let sh = params.shadow.y * (1.0 - lit);
    let light = blinn_phong(no_diffuse, params.shadow, facing, to_sun, n, lit)
        + params.shadow.z * (1.0 - sh) * params.light.y * flake_sun_phase(dot(-to_sun, n));
    let albedo = kind_albedo(particle_kind(p.flags));
    return with_air(albedo * light, air_between(switches.camera_m_cone_cos.xyz, p.position_m, switches.fog_layer));
}

// The light of a drop's face of normal `n` toward `to_viewer`, through the air `air`
// (air_between). A drop
// is a wide-angle lens: it shows the environment over some 165° around the viewing
// direction at about 94 % of its radiance (Garg & Nayar, *Vision and rain*, IJCV
// 2007), `environment` times the horizon sky's (drop_environment_factor), plus the
// sun's glint off its surface; so a streak is bright against a dark background and
// all but vanishes against the sky.
fn rain_colour(n: vec3<f32>, to_viewer: vec3<f32>, lit: f32, air: vec2<f32>, environment: f32) -> vec3<f32> {
    let light = blinn_phong(params.light, params.shadow, n, params.to_sun_extinction.xyz, to_viewer, lit);
    let refracted = min(environment * params.sky_colour_time.xyz, vec3<f32>(1.0));
    let water = mix(refracted, vec3<f32>(0.75, 0.8, 0.85) * light, 0.2);
    return with_air(water, air);
}

@vertex
fn vs_snow(@builtin(vertex_index) corner: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    return snow_vertex(corner, instance);
}

@vertex
fn vs_snow_reduced(@builtin(vertex_index) corner: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    return snow_vertex(corner, instance);
}

// The instances beyond the kept quads (their own draw, FrameDraws::snow_made,
// numbered from the quads' capacity): each corner makes its quad itself.
@vertex
fn vs_snow_made(@builtin(vertex_index) corner: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    return snow_quad_vertex(snow_quad(arrayLength(&snow_quads) + instance), corner);
}

@vertex
fn vs_snow_made_reduced(@builtin(vertex_index) corner: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    return snow_quad_vertex(snow_quad(arrayLength(&snow_quads) + instance), corner);
}

// The frame's snow quads: read by the sprites' corners (group 2 of their draws),
// written by snow_quads_write (group 2 of the kernel).
@group(2) @binding(9) var<storage, read> snow_quads: array<SnowQuad>;
@group(2) @binding(10) var<storage, read_write> snow_quads_out: array<SnowQuad>;

// Each snow instance's quad, once a frame, where its four corners read it (vertex
// shading each corner anew cost four times the flake's lighting, fog and sizing: on
// a CPU device the particles' pass was three quarters vertex work). Over the sprite
// instances the cull counted, up to the quads' capacity, each invocation walking
// them with the dispatch's stride (precip_gpu::recipe::DispatchOver::ParticleList).
@compute @workgroup_size(64)
fn snow_quads_write(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let lanes = groups.x * groups.y * 64u;
    let count = min(splat_draws.snow.instance_count, arrayLength(&snow_quads_out));
    for (var k = linear_index(id, groups); k < count; k += lanes) {
        snow_quads_out[k] = snow_quad(k);
    }
}

// Instance `instance`'s quad: a drawn flake × its copies (snow_copy_position), a
// camera-volume flake standing for `m` of the air's drawn as `copies` flakes of
// `m/copies` ink each.
fn snow_quad(instance: u32) -> SnowQuad {
    let copies = snow_copies();
    let i = drawn[instance / copies];
    let copy = instance % copies;
    var p = particles[i];
    let in_camera_volume = i >= frame_pools().x;
    let original = particles[i];
    let is_resolved = resolved(original);
    if (copy != 0u && !(in_camera_volume && is_resolved)) {
        // A world or sub-pixel particle has no copies.
        return SnowQuad(p.position_m, 0.0, vec3<f32>(0.0), 0.0, vec3<f32>(0.0), vec3<f32>(0.0));
    }
    p.position_m = snow_copy_position(i, copy, p.position_m);
    let camera = params.camera_m_cone_cos.xyz;
    let distance_m = distance(p.position_m, camera);
    let sharp = snow_sprite_sizing(p.diameter_m, distance_m, params.view_dir_pixel_angle.w, params.sizing);
    // Out of focus: spread over the lens's blur circle, the ink kept.
    let size = defocused(sharp.x, sharp.y, defocus_blur_m(params.lens.x, params.lens.y, distance_m), 2);
    let turn = flake_spin_tumble(rotation0_rad(p.rotation0), p.rotation_rad);
    // Swept over the exposure (sizing.w): a streak when it moves half its side.
    let axes = snow_quad_axes(p.position_m, camera, size.x, turn, p.velocity_mps, params.sizing.w);
    // Its multiplicity's ink, up to opaque (precip_model::drawing::multiplicity): a
    // resolved flake's over its copies, a sub-pixel one's its own.
    let weight = resolved_weight(i, original) / select(1.0, f32(copies), in_camera_volume && is_resolved);
    // The ink spreads over the streak: opacity over the stretch.
    let opacity = min(1.0, weight * size.y * near_fade(distance_m) / axes.stretch);
    return SnowQuad(p.position_m, axes.stretch, axes.across_m, opacity, axes.along_m, snow_colour(p));
}

// A kept quad's corner. The instances beyond the quads' capacity
// (precip_gpu::recipe::SNOW_QUAD_CAPACITY) are drawn apart (vs_snow_made), not
// here under a branch: a CPU device's vertex shader runs both sides of it.
fn snow_vertex(corner: u32, instance: u32) -> ParticleVarying {
    return snow_quad_vertex(snow_quads[instance], corner);
}

fn snow_quad_vertex(quad: SnowQuad, corner: u32) -> ParticleVarying {
    var out: ParticleVarying;
    if (quad.stretch == 0.0) {
        // Nothing drawn: a degenerate triangle, clipped.
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0);
        return out;
    }
    let c = snow_quad_corner(quad.centre_m, SnowQuadAxes(quad.across_m, quad.along_m, quad.stretch), corner);
    out.clip = params.view_proj * vec4<f32>(c.position_m, 1.0);
    out.uv = c.uv;
    out.stretch = c.stretch;
    out.shade = vec4<f32>(quad.colour, quad.opacity);
    out.normal = normalize_or_zero(params.camera_m_cone_cos.xyz - quad.centre_m);
    out.world_m = c.position_m;
    return out;
}

@fragment
fn fs_snow(in: ParticleVarying) -> @location(0) vec4<f32> {
    return snow_fragment(in);
}

@fragment
fn fs_snow_reduced(in: ParticleVarying) -> @location(0) vec4<f32> {
    let c = snow_fragment(in);
    return vec4<f32>(c.rgb, c.a * in_front_of_scene(in.clip));
}

// The same for the instances beyond the kept quads (a pipeline is named by its
// fragment entry point: one each).
@fragment
fn fs_snow_made(in: ParticleVarying) -> @location(0) vec4<f32> {
    return snow_fragment(in);
}

@fragment
fn fs_snow_made_reduced(in: ParticleVarying) -> @location(0) vec4<f32> {
    let c = snow_fragment(in);
    return vec4<f32>(c.rgb, c.a * in_front_of_scene(in.clip));
}

fn snow_fragment(in: ParticleVarying) -> vec4<f32> {
    let uv = vec2<f32>(in.uv.x, snow_streak_texture_v(in.uv.y, in.stretch));
    let opacity = textureSample(flake_opacity, flake_sampler, uv).r * in.shade.a;
    return vec4<f32>(in.shade.rgb, opacity);
}

@vertex
fn vs_rain(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    return rain_vertex(vertex, instance);
}

@vertex
fn vs_rain_reduced(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    return rain_vertex(vertex, instance);
}

fn rain_vertex(vertex: u32, instance: u32) -> ParticleVarying {
    let i = drawn[params.counts.x + instance];
    let p = particles[i];
    let camera = params.camera_m_cone_cos.xyz;
    let distance_m = distance(p.position_m, camera);
    let sharp = raindrop_sizing(length(p.velocity_mps), p.diameter_m, distance_m, params.view_dir_pixel_angle.w, params.sizing);
    // Out of focus: the streak widened by the lens's blur circle, the ink kept.
    let wide = defocused(sharp.y, sharp.z, defocus_blur_m(params.lens.x, params.lens.y, distance_m), 1);
    let size = vec3<f32>(sharp.x, wide.x, wide.y);
    let k = rain_tetrahedron_strip_vertex(vertex);
    let v = raindrop_vertex(p.position_m, p.velocity_mps, size.x, size.y, k);
    var out: ParticleVarying;
    out.clip = params.view_proj * vec4<f32>(v.position_m, 1.0);
    // The drop's oscillation along its streak (docs/model.md (5.4b)): its phase (a
    // hash of its index) at the head, the cycles it rang through over the streak's
    // time (h/|v|) more at the tail (vertex 0), interpolated along the axis.
    let cycles = drop_oscillation_hz(p.diameter_m) * size.x / max(length(p.velocity_mps), 1.0e-3);
    let phase = f32(pcg_hash(i) >> 8u) / 16777216.0;
    out.uv = vec2<f32>(phase + select(0.0, cycles, k == 0u), 0.0);
    // What the drop refracts: the sky and the ground over its field of view, the
    // ground's albedo the cover's around the camera (drop_ground, once a frame).
    let view_sin_elevation = (p.position_m.y - camera.y) / max(distance_m, 1.0e-6);
    let air = air_between(camera, p.position_m, switches.fog_layer);

    out.shade = vec4<f32>(
        shadow_lit(p.position_m),
        air.x,
        drop_environment_factor(view_sin_elevation, drop_ground_albedo[0]),
        min(1.0, resolved_weight(i, p) * params.cover_look.x * size.z * near_fade(distance_m)),
    );
    out.normal = v.normal;
    out.world_m = v.position_m;
    out.stretch = air.y;
    return out;
}

@fragment
fn fs_rain(in: ParticleVarying) -> @location(0) vec4<f32> {
    return rain_fragment(in);
}

@fragment
fn fs_rain_reduced(in: ParticleVarying) -> @location(0) vec4<f32> {
    let c = rain_fragment(in);
    return vec4<f32>(c.rgb, c.a * in_front_of_scene(in.clip));
}

fn rain_fragment(in: ParticleVarying) -> vec4<f32> {
    let to_viewer = normalize_or_zero(params.camera_m_cone_cos.xyz - in.world_m);
    var n = normalize_or_zero(in.normal);
    if (dot(n, to_viewer) < 0.0) {
        n = -n;
    }
    let colour = rain_colour(n, to_viewer, in.shade.x, vec2<f32>(in.shade.y, in.stretch), in.shade.z);
    return vec4<f32>(colour * drop_oscillation_brightness(in.uv.x), in.shade.w);
}

// Particles at a reduced resolution (precip_model::ParticleResolution): the share of
// the frame's pixels under a drawn pixel at `frag` where the particle stands in front
// of the scene (the depth test the frame's resolution would make, less-or-equal), at
// four of them (all four at half resolution; at a quarter, one in each quadrant).
fn in_front_of_scene(frag: vec4<f32>) -> f32 {
    let factor = u32(params.lens.z);
    let last = vec2<i32>(textureDimensions(scene_depth)) - 1;
    let corner = vec2<i32>(floor(frag.xy)) * i32(factor);
    let step = i32(max(factor / 2u, 1u));
    let first = select(0, step / 2, factor > 2u);
    var front = 0.0;
    for (var k = 0; k < 4; k += 1) {
        let at = corner + vec2<i32>(first + step * (k & 1), first + step * (k >> 1u));
        let scene = textureLoad(scene_depth, clamp(at, vec2<i32>(0), last), 0);
        front += select(0.0, 0.25, frag.z <= scene);
    }
    return front;
}

// The splat resolved and the particles' image (premultiplied) over it, laid over
// the frame in one full-screen pass.
@group(2) @binding(7) var particle_image: texture_2d<f32>;

@vertex
fn vs_particles_composite(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_particles_composite(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    // Drawn pixel i covers the frame's pixels [i·f, (i + 1)·f).
    let drawn = vec2<f32>(textureDimensions(particle_image)) * params.lens.z;
    let image = textureSampleLevel(particle_image, cover_sampler, pixel.xy / drawn, 0.0);
    let splat = resolved_splat(pixel);
    return image + vec4<f32>(splat.rgb * splat.a, splat.a) * (1.0 - image.a);
}
