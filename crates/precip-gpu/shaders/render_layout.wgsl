// render_layout.wgsl: the renderer's shared structs. Rust twins:
// precip_model::drawing::render::RenderParams, the indirect draw arguments of wgpu/Vulkan.

struct RenderParams {
    view_proj: mat4x4<f32>,
    sun_view_proj: mat4x4<f32>,
    camera_m_cone_cos: vec4<f32>,
    view_dir_pixel_angle: vec4<f32>,
    to_sun_extinction: vec4<f32>,
    sky_colour_time: vec4<f32>,
    // k_A·I_A, k_D·I_D, k_S·I_S, shininess
    light: vec4<f32>,
    // shadow colour, shadow density, attenuation, shadow-map texel (uv)
    shadow: vec4<f32>,
    // snow scale, min px (of the frame), min opacity, the lens's exposure s
    sizing: vec4<f32>,
    // rain opacity, displacement on, cover depletion exponent, mask edge
    cover_look: vec4<f32>,
    // wet darkening, albedo decay per day, exposure tolerance m, flake mean opacity
    cover_look2: vec4<f32>,
    // rain rings per m² s, the frame before's scene and depth there (1/0), water bodies' depth m, 0
    water_look: vec4<f32>,
    ground: GridFrame,
    cover: GridFrame,
    waves: GridFrame,
    // particle count, culling on, cull workgroups, splat target width px (0: no splat)
    counts: vec4<u32>,
    // world particle count, first lifted world particle, camera volume present, snow copies
    pools: vec4<u32>,
    // the camera volume's centre m, the world emitter's multiplicity
    camera_box_centre_m: vec4<f32>,
    // the camera volume's half extent m, its multiplicity
    camera_box_half_m: vec4<f32>,
    // the lens: aperture m, focus distance m; frame pixels per particle pixel
    // (ParticleResolution::factor), 0
    lens: vec4<f32>,
    // clip → world of the camera
    inverse_view_proj: mat4x4<f32>,
    // world → clip of the camera of the frame before (the reflections' copies)
    previous_view_proj: mat4x4<f32>,
    // world → clip through the water bodies' mirror (the camera's when none)
    mirror_view_proj: mat4x4<f32>,
    // the mirror's level m, drawn this frame (1/0), 0, 0
    mirror: vec4<f32>,
    // the fog layer: top m, bottom m, extinction B per m (0: none), the sun's light on
    fog_layer: vec4<f32>,
    // the cloud layers, lowest first: base m, top m, coverage, kind (0 stratus …
    // 3 cumulonimbus); zeros past the last
    clouds: array<vec4<f32>, 3>,
    // each layer's most extinction per m; the precipitation's extinction per m
    // (what falls from the lowest layer: rain and snow, not sand or dust)
    cloud_extinction: vec4<f32>,
    // the clouds' drift x, z m, the extinction per m under a shaft of the lowest
    // layer, drawn (1/0)
    cloud_drift: vec4<f32>,
    // the share of the sun's light the clouds let through (their shadow), the
    // clouds' march slot, their drift since the image reused (x, z m)
    cloud_shadow: vec4<f32>,
    // the land beyond the scene: its height m, drawn (1/0), 0, 0
    far_ground: vec4<f32>,
    // the clouds' shadow map: its corner x, z m, written and read (1/0), 0
    cloud_shadow_map: vec4<f32>,
    // the grain of what the budget does not draw one by one: its scale (0: none),
    // reach m, near end m, streak length px
    unresolved_streaks: vec4<f32>,
    // the streaks' unit direction on screen (px, y down), the exposure's number, 0
    streak_direction: vec4<f32>,
    // the target's corner from the lens's axis, px (the grain is laid from the axis,
    // alike in every channel of a rig), 0, 0
    streak_origin: vec4<f32>,
    // the sea's wind: speed m/s, fetch m, the direction it blows toward (x, z)
    ocean_wind: vec4<f32>,
    // the sea: choppiness, depth m, seed (an integer), 0
    ocean: vec4<f32>,
    // the colour deep sea water sends out (linear RGB), the whitecaps' share
    sea_colour: vec4<f32>,
    // the sea's diffuse attenuation per m (RGB), 0
    sea_attenuation: vec4<f32>,
    // the seabed's colour seen through the surface (RGB), 0
    sea_bed: vec4<f32>,
    // the sea's spectrum: 0 JONSWAP, 1 Phillips; 0, 0, 0
    ocean_spectrum: vec4<f32>,
    // the shore's grid: its corner x, z m, its cell m, the still level m
    shore_grid: vec4<f32>,
    // its cells along x and z (0: no shore), this frame's shore step s, speed cap m/s
    shore_size: vec4<f32>,
    // each side's edge (west, east, south, north): 0 wall, 1 open, 2 the sea's waves
    shore_edges: vec4<f32>,
    // the shore's steps this frame, its bed's Manning roughness s/m^(1/3), 0, 0
    shore_steps: vec4<f32>,
    // the waves coming in: amplitude m, angular frequency rad/s, phase rad,
    // wavenumber along the incoming edge rad/m
    shore_waves: array<vec4<f32>, 8>,
    // The terrain's clipmap (render_terrain.wgsl; Rust: precip_model::scene::terrain::ClipmapRows).
    terrain: vec4<f32>,
    terrain_levels: vec4<u32>,
    terrain_samples: array<vec4<u32>, 8>,
    terrain_windows: array<vec4<u32>, 4>,
    // The cover beyond the grid (Rust: RenderParams::far_cover_grid/_cells,
    // precip_model::host::FarCover): its cells' corner x, z and size x, z, m; cells
    // along x, z, the first word of their rows in ground_height (each cell's texels
    // of precip_model::host::FAR_COVER_SURFACES, each cover_at's A, B, C), 0.
    far_cover_grid: vec4<f32>,
    far_cover_cells: vec4<u32>,
    // The terrain's land cover (render_terrain.wgsl; Rust: LandCoverRows): pixels x,
    // z, first word in the ground buffer, present; the terrain's corner and size, m.
    land_cover: vec4<u32>,
    land_cover_extent: vec4<f32>,
    // Each land class: snow share seen from above, far cover triple, ramp row v, 0.
    land_classes: array<vec4<f32>, 12>,
}

// drawIndirect's arguments (Rust: precip_gpu::recipe::DrawArgs).
struct DrawArgs {
    vertex_count: u32,
    instance_count: u32,
    first_vertex: u32,
    first_instance: u32,
}

// What the cull writes each frame (Rust: precip_gpu::recipe::FrameDraws).
struct FrameDraws {
    snow: DrawArgs,
    rain: DrawArgs,
    splatted: u32,
    sprite_particles: u32,
    reserved1: u32,
    reserved2: u32,
    // The snow sprite instances beyond the kept quads (vs_snow_made).
    snow_made: DrawArgs,
}

// A snow sprite's quad as the frame draws it, made once a frame for each sprite
// instance (kernel snow_quads_write, render_particles.wgsl) and read by its four corners
// (Rust: precip_gpu::recipe::SNOW_QUAD_BYTES): its centre (the copy's), its sides
// (SnowQuadAxes, drawing.wgsl) and stretch, its lit and fogged colour and opacity.
// A stretch of 0: the instance draws nothing (a copy that is not).
struct SnowQuad {
    centre_m: vec3<f32>,
    stretch: f32,
    across_m: vec3<f32>,
    opacity: f32,
    along_m: vec3<f32>,
    colour: vec3<f32>,
}

// Vertices per snow sprite and per rain tetrahedron (strips both).
const SNOW_SPRITE_VERTICES: u32 = 4u;
const RAIN_TETRAHEDRON_VERTICES: u32 = 6u;

// What a particle is drawn as: nothing, a sprite, a tetrahedron, or a splat.
const DRAWN_NOT: u32 = 0u;
const DRAWN_SNOW: u32 = 1u;
const DRAWN_RAIN: u32 = 2u;
const DRAWN_SPLAT: u32 = 3u;
