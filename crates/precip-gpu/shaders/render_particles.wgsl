// render_particles.wgsl: snow sprites and rain tetrahedra built in the vertex shader
// from the particle buffer (vertex pulling: instance = drawn particle, vertex = corner),
// lit by the sun through the shadow map and fogged like the scene.

struct ParticleVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
    // Snow: lit, fogged colour and opacity. Rain: (lit, fog, _, opacity).
    @location(1) shade: vec4<f32>,
    @location(2) normal: vec3<f32>,
    @location(3) world_m: vec3<f32>,
}

// Quartz sand and mineral dust in daylight (sRGB ~ #c8a878, linear).
const GRAIN_COLOUR: vec3<f32> = vec3<f32>(0.58, 0.39, 0.19);

// The light a snowflake (or a grain of sand or dust, drawn the same way) sends toward
// the camera, fogged: a thin translucent plate, lit from whichever side the sun is on
// (sprites and splats alike).
fn snow_colour(p: Particle, distance_m: f32) -> vec3<f32> {
    let to_sun = params.to_sun_extinction.xyz;
    let n = normalize_or_zero(params.camera_m_cone_cos.xyz - p.position_m);
    let facing = select(-n, n, dot(n, to_sun) >= 0.0);
    let lit = shadow_lit(p.position_m);
    let light = blinn_phong(params.light, params.shadow, facing, to_sun, n, lit);
    let kind = (p.flags >> FLAG_KIND_SHIFT) & FLAG_KIND_MASK;
    var albedo = vec3<f32>(select(0.95, 0.85, kind == KIND_WET_SNOW));
    if (kind == KIND_GRAIN) {
        albedo = GRAIN_COLOUR;
    }
    let fog = fog_transmittance(distance_m, params.to_sun_extinction.w);
    return mix(params.sky_colour_time.xyz, albedo * light, fog);
}

// The light of a drop's face of normal `n` toward `to_viewer`, fogged by `fog`.
fn rain_colour(n: vec3<f32>, to_viewer: vec3<f32>, lit: f32, fog: f32) -> vec3<f32> {
    let light = blinn_phong(params.light, params.shadow, n, params.to_sun_extinction.xyz, to_viewer, lit);
    let water = vec3<f32>(0.75, 0.8, 0.85) * light;
    return mix(params.sky_colour_time.xyz, water, fog);
}

@vertex
fn vs_snow(@builtin(vertex_index) corner: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    let p = particles[drawn[instance]];
    let camera = params.camera_m_cone_cos.xyz;
    let distance_m = distance(p.position_m, camera);
    let size = snow_sprite_sizing(p.diameter_m, distance_m, params.view_dir_pixel_angle.w, params.sizing);
    let turn = flake_spin_tumble(rotation0_rad(p.rotation0), p.rotation_rad);
    let world = snow_sprite_corner(p.position_m, camera, size.x, turn.x, turn.y, corner);
    var out: ParticleVarying;
    out.clip = params.view_proj * vec4<f32>(world, 1.0);
    out.uv = snow_sprite_uv(corner);
    out.shade = vec4<f32>(snow_colour(p, distance_m), size.y * near_fade(distance_m));
    out.normal = normalize_or_zero(camera - p.position_m);
    out.world_m = world;
    return out;
}

@fragment
fn fs_snow(in: ParticleVarying) -> @location(0) vec4<f32> {
    let opacity = textureSample(flake_opacity, flake_sampler, in.uv).r * in.shade.a;
    return vec4<f32>(in.shade.rgb, opacity);
}

@vertex
fn vs_rain(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> ParticleVarying {
    let p = particles[drawn[params.counts.x + instance]];
    let camera = params.camera_m_cone_cos.xyz;
    let distance_m = distance(p.position_m, camera);
    let size = raindrop_sizing(length(p.velocity_mps), distance_m, params.view_dir_pixel_angle.w, params.sizing);
    let v = raindrop_vertex(p.position_m, p.velocity_mps, size.x, size.y, rain_tetrahedron_face_vertex(vertex));
    var out: ParticleVarying;
    out.clip = params.view_proj * vec4<f32>(v.position_m, 1.0);
    out.uv = vec2<f32>(0.0);
    out.shade = vec4<f32>(
        shadow_lit(p.position_m),
        fog_transmittance(distance_m, params.to_sun_extinction.w),
        0.0,
        params.cover_look.x * size.z * near_fade(distance_m),
    );
    out.normal = v.normal;
    out.world_m = v.position_m;
    return out;
}

@fragment
fn fs_rain(in: ParticleVarying) -> @location(0) vec4<f32> {
    let to_viewer = normalize_or_zero(params.camera_m_cone_cos.xyz - in.world_m);
    var n = normalize_or_zero(in.normal);
    if (dot(n, to_viewer) < 0.0) {
        n = -n;
    }
    return vec4<f32>(rain_colour(n, to_viewer, in.shade.x, in.shade.y), in.shade.w);
}
