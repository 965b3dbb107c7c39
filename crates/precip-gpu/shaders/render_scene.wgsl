// render_scene.wgsl: the render program's bindings, the shadow map, the cover seen by
// a surface, and the scene's passes (vs_shadow; vs_scene + fs_scene). The bindings
// are listed in precip_gpu::recipe::render_bindings.

// Group 0: the frame.
// RenderParams is a uniform block, and the same block is bound again as read-only
// storage (`switches`) for every branch that tests nothing but the block — also in
// the functions block values are passed to (the fog's and the clouds' slab tests:
// the clouds' shadow leaked 1.9 MB a frame with `params` there): Mesa's
// lavapipe up to 23.1 inlines the uniforms such a branch tests, recompiling at every
// draw and never freeing the variants (1.8 MB a frame here); storage is never
// inlined (precip_gpu::recipe::render_bindings::PARAMS_SWITCHES).
@group(0) @binding(0) var<uniform> params: RenderParams;
@group(0) @binding(11) var<storage, read> switches: RenderParams;

// The frame's counts, for branches (particle_lists.wgsl; the cull program reads its
// storage block).
fn frame_counts() -> vec4<u32> {
    return switches.counts;
}
fn frame_pools() -> vec4<u32> {
    return switches.pools;
}
@group(0) @binding(2) var<storage, read> ground_height: array<f32>;
@group(0) @binding(3) var<storage, read> particles: array<Particle>;
// Drawn particles: sprites at [0, N), streaks at [N, 2N) (N = particle count).
@group(0) @binding(4) var<storage, read> drawn: array<u32>;
// The cover as three filtered textures (cover_texture.wgsl writes them from the cover
// texels each frame): A = (depth mm, SWE mm, peak SWE mm, wetness),
// B = (accumulation mask, melt mask, age days, standing water over the surface's
// roughness), C = (sand and dust settled kg/m², the surface's roughness length under
// snow m, 0, 0);
// linear, clamped to the edge.
@group(0) @binding(5) var cover_a: texture_2d<f32>;
@group(0) @binding(6) var cover_b: texture_2d<f32>;
@group(0) @binding(13) var cover_c: texture_2d<f32>;
@group(0) @binding(7) var cover_sampler: sampler;
// The water bodies' waves (water_waves.wgsl's buffer, read here as plain words).
@group(0) @binding(12) var<storage, read> waves_read: array<i32>;
// The albedo of the ground the drops refract (cover_texture.wgsl's drop_ground).
@group(0) @binding(15) var<storage, read> drop_ground_albedo: array<f32>;
// The clouds' coverage map (precip_model::drawing::clouds::cloud_coverage_map),
// tiling, and the clouds' image the sky lays over itself.
@group(0) @binding(17) var cloud_map: texture_2d<f32>;
@group(0) @binding(18) var cloud_sampler: sampler;
// The clouds' detail: a tiling 3D noise's slices side by side (clouds/detail.rs).
@group(0) @binding(21) var cloud_detail_atlas_texture: texture_2d<f32>;
// The clouds' shadow map (render_clouds.wgsl's cloud_shadow_map kernel).
@group(0) @binding(19) var cloud_shadow: texture_2d<f32>;
// The clouds' pass reads the other image there: the frame before's.
@group(1) @binding(4) var cloud_image: texture_2d<f32>;
// Group 1: light and the flake's opacity.
@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(1) var shadow_sampler: sampler_comparison;
@group(1) @binding(2) var flake_opacity: texture_2d<f32>;
@group(1) @binding(3) var flake_sampler: sampler;
// Group 2: the mesh's material.
struct Material {
    base_colour: vec4<f32>,
}
@group(2) @binding(0) var<uniform> material: Material;
@group(2) @binding(1) var base_colour_texture: texture_2d<f32>;
@group(2) @binding(2) var material_sampler: sampler;

// Depth offset (NDC) of the shadow test, against acne.
const SHADOW_BIAS: f32 = 0.0005;

// Visibility of the sun at `world_m` near the camera (the particles): the scene's
// shadow times the clouds' at the camera. The scene's surfaces take the clouds'
// shadow map at their vertices (SceneVarying::cloud_sun).
fn shadow_lit(world_m: vec3<f32>) -> f32 {
    return params.cloud_shadow.x * scene_shadow_lit(world_m);
}

// The share of the sun's light the clouds let through to `world_m` (docs/model.md
// (6.12)): the clouds' shadow map where it lies (the branch reads `switches`: no
// sample without a layer), fading at its edges into the frame's one share at the
// camera, which stands in beyond. Read per vertex by the scene (a sampling
// instruction costs a CPU rasteriser in every fragment of a shader that has it,
// taken or not) and per pixel by the land beyond the scene.
fn cloud_sun_share(world_m: vec3<f32>) -> f32 {
    if (switches.cloud_shadow_map.z < 0.5) {
        return params.cloud_shadow.x;
    }
    let uv = (world_m.xz - params.cloud_shadow_map.xy) / CLOUD_SHADOW_MAP_SPAN_M;
    let mapped = textureSampleLevel(cloud_shadow, cover_sampler, clamp(uv, vec2<f32>(0.0), vec2<f32>(1.0)), 0.0).r;
    return mix(params.cloud_shadow.x, mapped, cloud_shadow_map_weight(uv));
}

// The shadow map's: one comparison sample, which the sampler's linear filter turns
// into a 2×2 percentage-closer filter in the texture unit; 1 outside the map.
fn scene_shadow_lit(world_m: vec3<f32>) -> f32 {
    let p = params.sun_view_proj * vec4<f32>(world_m, 1.0);
    let ndc = p.xyz / p.w;
    let uv = vec2<f32>(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y);
    if (any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || ndc.z > 1.0 || ndc.z < 0.0) {
        return 1.0;
    }
    return textureSampleCompareLevel(shadow_map, shadow_sampler, uv, ndc.z - SHADOW_BIAS);
}

struct SkyVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

// The sky behind everything: a triangle covering the target at the far plane, drawn
// after the meshes where nothing stands (depth less-equal 1).
@vertex
fn vs_sky(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

// One triangle covering the target, at the far plane.
fn sky_triangle(v: u32) -> SkyVarying {
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    let ndc = uv * 2.0 - 1.0;
    var out: SkyVarying;
    out.clip = vec4<f32>(ndc, 1.0, 1.0);
    out.ndc = ndc;
    return out;
}

// The CIE overcast sky in this pixel's direction (water_look.wgsl's overcast_sky, what
// puddles reflect), its horizon the haze's colour.
@fragment
fn fs_sky(in: SkyVarying) -> @location(0) vec4<f32> {
    let far = params.inverse_view_proj * vec4<f32>(in.ndc, 1.0, 1.0);
    let ray = normalize_or_zero(far.xyz / far.w - switches.camera_m_cone_cos.xyz);
    let land_m = land_distance_m(ray);
    let seen = sky_through_air(land_or_sky(overcast_sky(params.sky_colour_time.xyz, ray), ray, land_m), ray, land_m);
    return vec4<f32>(with_unresolved_streaks(seen.rgb, in.clip.xy, select(SKY_DISTANCE_M, land_m, land_m >= 0.0)), 1.0);
}

// How far along `ray` it meets the land beyond the scene (docs/model.md (6.18)),
// m; negative for never (looking up, no land drawn).
fn land_distance_m(ray: vec3<f32>) -> f32 {
    if (params.far_ground.y < 0.5) {
        return -1.0;
    }
    return far_ground_distance_m(switches.camera_m_cone_cos.y, ray.y, params.far_ground.x);
}

// The land beyond the scene where `ray` meets it `land_m` along (land_distance_m;
// precip_model::drawing::far_ground), else `sky`: lit as level ground, its albedo
// the cover's over the whole grid (drop_ground's second number), through the clear
// air's haze (a fog layer then lies over it up to the land as over the sky:
// sky_through_air; one path through the layer's code, which a CPU rasteriser
// pays for at every call site).
fn land_or_sky(sky: vec3<f32>, ray: vec3<f32>, land_m: f32) -> vec3<f32> {
    if (land_m < 0.0) {
        return sky;
    }
    let camera = switches.camera_m_cone_cos.xyz;
    let lit = far_ground_colour(drop_ground_albedo[1], params.light.xy, params.to_sun_extinction.y, cloud_sun_share(camera + ray * land_m));
    return with_air(lit, vec2<f32>(fog_transmittance(land_m, params.to_sun_extinction.w), 0.0));
}

// The sky under a drawn cloud layer (a pipeline of its own, so frames without one
// carry none of its code): the layer stands for the deck the overcast sky stood
// for — the clear sky between its clouds, their image over it (premultiplied).
@vertex
fn vs_sky_clouds(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

@fragment
fn fs_sky_clouds(in: SkyVarying) -> @location(0) vec4<f32> {
    return sky_under_clouds(in);
}

// The same over the clouds' image B (render_clouds.wgsl: the images alternate).
@vertex
fn vs_sky_clouds_b(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

@fragment
fn fs_sky_clouds_b(in: SkyVarying) -> @location(0) vec4<f32> {
    return sky_under_clouds(in);
}

fn sky_under_clouds(in: SkyVarying) -> vec4<f32> {
    let far = params.inverse_view_proj * vec4<f32>(in.ndc, 1.0, 1.0);
    let ray = normalize_or_zero(far.xyz / far.w - switches.camera_m_cone_cos.xyz);
    let cloud = textureSampleLevel(cloud_image, cover_sampler, in.ndc * vec2<f32>(0.5, -0.5) + 0.5, 0.0);
    let land_m = land_distance_m(ray);
    let sky = land_or_sky(clear_sky(params.sky_colour_time.xyz, ray), ray, land_m) * (1.0 - cloud.a) + cloud.rgb;
    let seen = sky_through_air(sky, ray, land_m);
    return vec4<f32>(with_unresolved_streaks(seen.rgb, in.clip.xy, select(SKY_DISTANCE_M, land_m, land_m >= 0.0)), 1.0);
}

// `sky` (or the land `land_m` along, where that is not negative) seen along `ray`
// through the fog layer.
fn sky_through_air(sky: vec3<f32>, ray: vec3<f32>, land_m: f32) -> vec4<f32> {
    let camera = switches.camera_m_cone_cos.xyz;
    // Inside a cloud (a fog layer without the sun's share, precip_model's air_layer)
    // the clouds' image has marched the sky's rays through it already.
    if (switches.fog_layer.z <= 0.0 || switches.fog_layer.w < 0.5) {
        return vec4<f32>(sky, 1.0);
    }
    // Through the fog layer only (the haze's colour is the horizon's already).
    let distance = select(SKY_DISTANCE_M, land_m, land_m >= 0.0);
    let air = air_path(camera, ray, distance, 0.0, switches.fog_layer, switches.to_sun_extinction.xyz);
    return vec4<f32>(with_air(sky, air), 1.0);
}

// The air between `camera` and `world_m` (air_path, drawing.wgsl; docs/model.md
// (6.5)): the transmittance and the sun's light the fog layer `layer` scatters.
// Without a layer, the uniform haze's transmittance alone: the branch reads the
// storage copy of the block (`switches`), so every invocation takes the same way
// and a GPU skips the layer's arithmetic.
fn air_between(camera: vec3<f32>, world_m: vec3<f32>, layer: vec4<f32>) -> vec2<f32> {
    let offset = world_m - camera;
    let d = length(offset);
    if (switches.fog_layer.z <= 0.0) {
        return vec2<f32>(fog_transmittance(d, params.to_sun_extinction.w), 0.0);
    }
    return air_path(camera, offset / max(d, 1.0e-6), d, switches.to_sun_extinction.w, layer, switches.to_sun_extinction.xyz);
}

// The grain of the flakes and drops the budget does not draw one by one, from the
// camera volume's reach to `distance_m` (precip_model::drawing::unresolved_streaks;
// docs/model.md (5.15b)): `colour` moved toward the haze's by the deviation of their
// ink at `pixel`. Without it (no precipitation, or all of it drawn) the branch reads
// the storage copy, so every invocation skips it alike. Its arithmetic reads the
// uniform block, which lavapipe treats as the same for every fragment of the draw
// (from the storage copy the grain took 26 ms more of the demo's 193 ms scene pass
// at 1280×720); what a branch compares (the grain's near end, in
// unresolved_streak_variance's test) stays the storage copy's, so lavapipe never
// builds the shader again for its value.
fn with_unresolved_streaks(colour: vec3<f32>, pixel: vec2<f32>, distance_m: f32) -> vec3<f32> {
    if (switches.unresolved_streaks.x <= 0.0) {
        return colour;
    }
    let grain = vec4<f32>(params.unresolved_streaks.xy, switches.unresolved_streaks.z, params.unresolved_streaks.w);
    let along = params.streak_direction;
    let deviation = sqrt(max(unresolved_streak_variance(grain, distance_m), 0.0))
        * streak_grain(pixel + params.streak_origin.xy, along.xy, grain.w, u32(along.z));
    return colour + (params.sky_colour_time.xyz - colour) * clamp(deviation, -1.0, 1.0);
}

// `shaded` seen through the air `air` (air_between): what passes, the sky's light
// scattered in (the haze's colour) and the sun's (white, as bright as on a white
// surface facing it times the path's share).
fn with_air(shaded: vec3<f32>, air: vec2<f32>) -> vec3<f32> {
    return shaded * air.x + params.sky_colour_time.xyz * (1.0 - air.x) + vec3<f32>(params.light.y * air.y);
}

// The ground map's height at (x, z) between texel centres (bilinear, clamped at
// the edges). Rust: GroundMap::height_between_texels_at.
fn ground_top_m(xz_m: vec2<f32>) -> f32 {
    let n = vec2<i32>(params.ground.texels);
    let cell = params.ground.size_m / vec2<f32>(params.ground.texels);
    let t = (xz_m - params.ground.origin_m) / cell - 0.5;
    let base = floor(t);
    let w = t - base;
    let c0 = clamp(vec2<i32>(base), vec2<i32>(0), n - 1);
    let c1 = clamp(vec2<i32>(base) + 1, vec2<i32>(0), n - 1);
    let h00 = ground_height[c0.x + n.x * c0.y];
    let h10 = ground_height[c1.x + n.x * c0.y];
    let h01 = ground_height[c0.x + n.x * c1.y];
    let h11 = ground_height[c1.x + n.x * c1.y];
    let low = h00 + (h10 - h00) * w.x;
    let high = h01 + (h11 - h01) * w.x;
    return low + (high - low) * w.y;
}

// How much a surface point is the top-most at its (x, z), [0, 1]: 1 within a
// tolerance (texel size, slope) of the ground map's height there, fading to 0 over
// one more tolerance below. Off the map: 1. Rust: displacement::exposure.
fn exposure(world_m: vec3<f32>, normal: vec3<f32>) -> f32 {
    if (grid_texel_index(params.ground, world_m.xz) < 0) {
        return 1.0;
    }
    let top = ground_top_m(world_m.xz);
    let cell = params.ground.size_m / vec2<f32>(params.ground.texels);
    let slope = length(normal.xz) / max(abs(normal.y), 0.05);
    let tolerance = params.cover_look2.z + max(cell.x, cell.y) * min(slope, 4.0);
    return smoothstep(top - 2.0 * tolerance, top - tolerance, world_m.y);
}

// How much a surface faces up for snow: none below 0.2, full from 0.6.
fn upward(normal: vec3<f32>) -> f32 {
    return smoothstep(0.2, 0.6, normal.y);
}

// The cover at (x, z), interpolated between texel centres (clamped at the grid's
// edges) by the texture unit: the particles' landings are discrete, so a surface
// reads a smoothed pack, and the threshold masks give patches with smooth borders
// finer than the grid. Each field is interpolated on its own, as texels were mixed
// before (the fields the surface does not read are zero).
// The roughness length the snow buries at the point cover_at last read, m (texture
// C.y, cover_texture.wgsl): kept here from the same sample, as CoverTexel has no
// field for it.
var<private> cover_roughness_m: f32;
// Which of the far cover's texels a fragment off the grid reads
// (precip_model::host::far_cover_slot of its surface): 0, grass, unless the
// terrain's fragment set another (fs_terrain).
var<private> far_cover_slot: u32;

// Texels a far cell holds (Rust: precip_model::host::FAR_COVER_SURFACES), their
// surfaces (precip_cover::Surface as u32: grass, soil, paving, water), and the
// floats a texel's two rows take (Rust: FAR_ROW_FLOATS).
const FAR_SLOTS: u32 = 4u;
const FAR_SLOT_SURFACES: vec4<f32> = vec4<f32>(2.0, 0.0, 1.0, 4.0);
const FAR_ROW_FLOATS: u32 = 8u;
// The far texels' masks (Rust: FarCover's texels, at their middle).
const FAR_MASK: f32 = 0.5;

// The share of the cover grid's shorter side over which, inside its edge, its
// cover gives way to the far cover's (Rust: precip_model::host::GRID_BLEND_SHARE).
const GRID_BLEND_SHARE: f32 = 0.0625;

// How much of the grid's cover shows at (x, z) against the far cover's: 1 inside
// the grid beyond GRID_BLEND_SHARE of its side from its edge, smoothly to 0 at the
// edge, 0 off it. Rust twin: precip_model::host::grid_blend.
fn grid_blend(grid: GridFrame, xz_m: vec2<f32>) -> f32 {
    let band = GRID_BLEND_SHARE * min(grid.size_m.x, grid.size_m.y);
    let lo = xz_m - grid.origin_m;
    let hi = grid.origin_m + grid.size_m - xz_m;
    let inside = min(min(lo.x, lo.y), min(hi.x, hi.y));
    if (!(inside > 0.0)) {
        return 0.0;
    }
    let t = min(inside / band, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Row `row` (0: depth, SWE, peak SWE, wetness; 1: age, puddle ratio, dust, the
// cell's mean height) of slot `slot`'s texel in far cell `cell`.
fn far_row(cell: vec2<u32>, slot: u32, row: u32) -> vec4<f32> {
    let n = params.far_cover_cells.xy;
    let w = params.far_cover_cells.z + ((cell.x + n.x * cell.y) * FAR_SLOTS + slot) * FAR_ROW_FLOATS + 4u * row;
    return vec4<f32>(ground_height[w], ground_height[w + 1u], ground_height[w + 2u], ground_height[w + 3u]);
}

// The far cells around (x, z), the lower one and the upper (clamped to the cells),
// and the weights between them: bilinear between the cells' centres.
struct FarCells {
    low: vec2<u32>,
    high: vec2<u32>,
    f: vec2<f32>,
}

fn far_cells(xz_m: vec2<f32>) -> FarCells {
    let n = max(params.far_cover_cells.xy, vec2<u32>(1u));
    let t = clamp((xz_m - params.far_cover_grid.xy) / params.far_cover_grid.zw - 0.5, vec2<f32>(0.0), vec2<f32>(n - 1u));
    var c: FarCells;
    c.low = vec2<u32>(floor(t));
    c.high = min(c.low + 1u, n - 1u);
    c.f = t - floor(t);
    return c;
}

// How far in height a far cell's state stands for a point, m: the cells around a
// point weigh by 1 / (1 + (Δh / FAR_HEIGHT_BLEND_M)²) on their bilinear weights.
const FAR_HEIGHT_BLEND_M: f32 = 25.0;

// The far cover of slot `slot` for a point at height `height_m` among the cells
// `c`: each cell's two rows weighed bilinearly between the cells' centres and by
// how near the cell's mean height is to the point's, so the snow line (each
// cell's air is at its mean height: Rust precip_model::host::FarCover) follows
// the terrain's contours rather than the cells.
struct FarRows {
    a: vec4<f32>,
    b: vec4<f32>,
}

fn far_cover_rows(c: FarCells, slot: u32, height_m: f32) -> FarRows {
    let cells = array<vec2<u32>, 4>(c.low, vec2<u32>(c.high.x, c.low.y), vec2<u32>(c.low.x, c.high.y), c.high);
    let bilinear = vec4<f32>((1.0 - c.f.x) * (1.0 - c.f.y), c.f.x * (1.0 - c.f.y), (1.0 - c.f.x) * c.f.y, c.f.x * c.f.y);
    var out: FarRows;
    var total = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let b = far_row(cells[k], slot, 1u);
        let dh = (height_m - b.w) / FAR_HEIGHT_BLEND_M;
        let w = bilinear[k] / (1.0 + dh * dh);
        out.a += w * far_row(cells[k], slot, 0u);
        out.b += w * b;
        total += w;
    }
    let inv = 1.0 / max(total, 1.0e-12);
    out.a *= inv;
    out.b *= inv;
    return out;
}

// The far cover's snow depth alone (far_cover_rows' first field), mm.
fn far_depth_mm(c: FarCells, slot: u32, height_m: f32) -> f32 {
    let cells = array<vec2<u32>, 4>(c.low, vec2<u32>(c.high.x, c.low.y), vec2<u32>(c.low.x, c.high.y), c.high);
    let bilinear = vec4<f32>((1.0 - c.f.x) * (1.0 - c.f.y), c.f.x * (1.0 - c.f.y), (1.0 - c.f.x) * c.f.y, c.f.x * c.f.y);
    let n = params.far_cover_cells.xy;
    var depth = 0.0;
    var total = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let w0 = params.far_cover_cells.z + ((cells[k].x + n.x * cells[k].y) * FAR_SLOTS + slot) * FAR_ROW_FLOATS;
        let dh = (height_m - ground_height[w0 + 7u]) / FAR_HEIGHT_BLEND_M;
        let w = bilinear[k] / (1.0 + dh * dh);
        depth += w * ground_height[w0];
        total += w;
    }
    return depth / max(total, 1.0e-12);
}

// The cover at the surface point `p_m` (x and z looked up, y the point's height
// for the far cover's weights); the far cover read only with `far_cover`.
fn cover_at(p_m: vec3<f32>, far_cover: bool) -> CoverTexel {
    let xz_m = p_m.xz;
    let uv = (xz_m - params.cover.origin_m) / params.cover.size_m;
    // On the grid its textures, off it the cover beyond it at its place
    // (far_cover_row), and inside its edge the one giving way to the other
    // (grid_blend): a grid that differs from the land round it (its drifts, its
    // particles' snow) shows no seam.
    let w = grid_blend(params.cover, xz_m);
    var a = vec4<f32>(0.0);
    var b = vec4<f32>(0.0);
    var c = vec4<f32>(0.0);
    if (w > 0.0) {
        a = textureSampleLevel(cover_a, cover_sampler, uv, 0.0);
        b = textureSampleLevel(cover_b, cover_sampler, uv, 0.0);
        c = textureSampleLevel(cover_c, cover_sampler, uv, 0.0);
    }
    // (Without `far_cover` the caller stands where w is 1: a constant the
    // compiler folds, so this code is not in its shader.)
    if (far_cover && w < 1.0) {
        // The far texel's rows as the grid's textures hold a texel's.
        let slot = min(far_cover_slot, FAR_SLOTS - 1u);
        let far = far_cover_rows(far_cells(xz_m), slot, p_m.y);
        let fb = vec4<f32>(FAR_MASK, FAR_MASK, far.b.x, far.b.y);
        let fc = vec4<f32>(far.b.z, surface_snow_roughness_m(u32(FAR_SLOT_SURFACES[slot])), 0.0, 0.0);
        a = mix(far.a, a, w);
        b = mix(fb, b, w);
        c = mix(fc, c, w);
    }
    var t: CoverTexel;
    t.dust_kg_m2 = c.x;
    cover_roughness_m = c.y;
    t.depth_mm = a.x;
    t.swe_mm = a.y;
    t.peak_swe_mm = a.z;
    t.wetness = a.w;
    t.accumulation_mask = b.x;
    t.melt_mask = b.y;
    t.age_days = b.z;
    // The puddle ratio rides in the standing-water field (fs_scene reads it so).
    t.standing_mm = b.w;
    return t;
}

// A water body's wave height at cell `cell` of the wave grid, m (0 off the grid).
fn wave_height_at(cell: vec2<i32>) -> f32 {
    let n = vec2<i32>(params.waves.texels);
    if (any(cell < vec2<i32>(0)) || any(cell >= n)) {
        return 0.0;
    }
    return f32(waves_read[u32(cell.x + n.x * cell.y) * 4u]) / 1.0e7;
}

// The slope of the waves at (x, z) by central differences, and whether (x, z) is on
// the wave grid (z component).
fn wave_slope(xz_m: vec2<f32>) -> vec3<f32> {
    let cell_m = params.waves.size_m / vec2<f32>(params.waves.texels);
    let t = (xz_m - params.waves.origin_m) / cell_m;
    let c = vec2<i32>(floor(t));
    let n = vec2<i32>(params.waves.texels);
    if (any(c < vec2<i32>(0)) || any(c >= n) || n.x * n.y <= 1) {
        return vec3<f32>(0.0);
    }
    let dx = wave_height_at(c + vec2<i32>(1, 0)) - wave_height_at(c - vec2<i32>(1, 0));
    let dz = wave_height_at(c + vec2<i32>(0, 1)) - wave_height_at(c - vec2<i32>(0, 1));
    return vec3<f32>(dx / (2.0 * cell_m.x), dz / (2.0 * cell_m.y), 1.0);
}

struct SceneVertex {
    @location(0) position_m: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) eligibility: f32,
}

struct SceneVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) world_m: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) eligibility: f32,
    // The surface before displacement: where the cover is looked up.
    @location(4) surface_m: vec3<f32>,
    // The share of the sun's light the clouds let through to it (cloud_sun_share).
    @location(5) cloud_sun: f32,
}

// The vertex raised by the snow on it (upward, eligible, exposed surfaces).
fn displaced(v: SceneVertex) -> vec3<f32> {
    var p = v.position_m;
    if (switches.cover_look.y < 0.5) {
        return p;
    }
    let n = normalize(v.normal);
    // The depth alone (cover_at's first texture; off the grid the cover beyond it).
    let uv = (p.xz - params.cover.origin_m) / params.cover.size_m;
    let w = grid_blend(params.cover, p.xz);
    var depth_mm = 0.0;
    if (w > 0.0) {
        depth_mm = textureSampleLevel(cover_a, cover_sampler, uv, 0.0).x;
    }
    if (w < 1.0) {
        let far_mm = far_depth_mm(far_cells(p.xz), min(far_cover_slot, FAR_SLOTS - 1u), p.y);
        depth_mm = mix(far_mm, depth_mm, w);
    }
    p.y += depth_mm * 1.0e-3 * clamp(v.eligibility, 0.0, 1.0) * upward(n) * exposure(p, n);
    return p;
}

@vertex
fn vs_shadow(v: SceneVertex) -> @builtin(position) vec4<f32> {
    return params.sun_view_proj * vec4<f32>(displaced(v), 1.0);
}

@vertex
fn vs_scene(v: SceneVertex) -> SceneVarying {
    return scene_varying(v, params.view_proj);
}

// The scene reflected about the water bodies' level (render_reflections.wgsl).
@vertex
fn vs_mirror(v: SceneVertex) -> SceneVarying {
    return scene_varying(v, params.mirror_view_proj);
}

fn scene_varying(v: SceneVertex, view_proj: mat4x4<f32>) -> SceneVarying {
    let p = displaced(v);
    var out: SceneVarying;
    out.clip = view_proj * vec4<f32>(p, 1.0);
    out.world_m = p;
    out.normal = v.normal;
    out.uv = v.uv;
    out.eligibility = v.eligibility;
    out.surface_m = v.position_m;
    out.cloud_sun = cloud_sun_share(p);
    return out;
}

// A surface as lit and wetted, before the fog: its colour; the weight its sharp
// mirror (a puddle's, a water body's) gives the sky it reflects, as a share of the
// surface's colour.
struct SurfaceLook {
    shaded: vec3<f32>,
    mirror: f32,
    // The standing water's slope (water_slope), which bends the mirror's ray.
    water_slope: vec2<f32>,
}

@fragment
fn fs_scene(in: SceneVarying) -> @location(0) vec4<f32> {
    return scene_fragment(in, true);
}

// The same for the tiles on the cover grid's interior (the plan's
// SCENE_ON_GRID_DRAW), where the grid's cover shows alone: the far cover's reads
// are not in its code (a CPU rasteriser runs a branch's code in every fragment).
@fragment
fn fs_scene_on_grid(in: SceneVarying) -> @location(0) vec4<f32> {
    return scene_fragment(in, false);
}

// A surface of the scene (a mesh's, the terrain's) lit, wetted and seen through the
// air; `far_cover`: it may lie where the cover beyond the grid shows (cover_at).
fn scene_fragment(in: SceneVarying, far_cover: bool) -> vec4<f32> {
    let camera = params.camera_m_cone_cos.xyz;
    let look = surface_look(in, camera, far_cover);
    let seen = with_air(look.shaded, air_between(camera, in.world_m, switches.fog_layer));
    return vec4<f32>(with_unresolved_streaks(seen, in.clip.xy, distance(camera, in.world_m)), 1.0);
}

// The water bodies: as fs_scene, their sharp mirror showing the scene where its ray
// meets it, not the sky (render_reflections.wgsl) — a pipeline of its own, so only
// their fragments carry the ray's loop (precip_gpu::frame's WATER_BODY_DRAW).
@fragment
fn fs_water_body(in: SceneVarying) -> @location(0) vec4<f32> {
    let camera = params.camera_m_cone_cos.xyz;
    var look = surface_look(in, camera, true);
    if (look.mirror > REFLECTION_LEAST) {
        let to_viewer = normalize_or_zero(camera - in.world_m);
        look.shaded += look.mirror * mirrored_scene(in.world_m, to_viewer, look.water_slope);
    }
    let seen = with_air(look.shaded, air_between(camera, in.world_m, switches.fog_layer));
    return vec4<f32>(with_unresolved_streaks(seen, in.clip.xy, distance(camera, in.world_m)), 1.0);
}

// The look of a surface seen from `camera` (the camera, or its reflection about the
// water's level for the mirror: the light's path through the mirror is as long and
// arrives as from there), before the air (air_between); `far_cover` as
// scene_fragment's.
fn surface_look(in: SceneVarying, camera: vec3<f32>, far_cover: bool) -> SurfaceLook {
    let base = material.base_colour * textureSample(base_colour_texture, material_sampler, in.uv);
    let to_viewer = normalize_or_zero(camera - in.world_m);
    var n = normalize_or_zero(in.normal);
    // Two-sided: a face seen from behind (a roof's underside) is lit as its back.
    if (dot(n, to_viewer) < 0.0) {
        n = -n;
    }
    var colour = base.rgb;
    // A pixel's footprint on the surface, for the rain rings' level of detail (taken
    // here: derivatives need uniform control flow).
    let footprint_m = length(fwidth(in.surface_m.xz));
    let ring_fade = clamp(1.0 - footprint_m / (0.5 * RING_WAVELENGTH_M), 0.0, 1.0);
    var puddle_ratio = 0.0;
    var wetness = 0.0;
    var open_water = 0.0;
    // A water body's vertices carry eligibility -1 (gpu_scene::WATER_BODY_ELIGIBILITY).
    let body = select(0.0, 1.0, in.eligibility < -0.5);
    // On the cover grid its texels, beyond it the cover the weather laid there
    // (cover_at): every surface under the sky takes the weather.
    {
        // Read the cover a little off the point (under half a texel), so where a
        // drift or a bare patch ends follows no texel's edge.
        let cell = params.cover.size_m / vec2<f32>(params.cover.texels);
        let warped_xz = in.surface_m.xz + cover_warp_m(in.surface_m.xz, cell);
        let texel = cover_at(vec3<f32>(warped_xz.x, in.surface_m.y, warped_xz.y), far_cover);
        // The texel's threshold moved by noise finer than a texel, so patch borders
        // and thin snow follow neither texels nor triangles.
        var threshold = texel.accumulation_mask;
        if (texel.depth_mm > 0.0) {
            threshold = sub_texel_threshold(threshold, in.surface_m.xz);
        }
        let s = cover_shading(texel, threshold, texel.melt_mask, cover_roughness_m, params.cover_look.z, params.cover_look.w, params.cover_look2.x);
        let sky_facing = exposure(in.surface_m, n) * upward(n);
        let snow = s.snow_alpha * clamp(in.eligibility, 0.0, 1.0) * sky_facing;
        let darkening = mix(1.0, s.ground_darkening, sky_facing);
        // Settled sand and dust over the bare surface, under any snow (not on water).
        let grains = settled_grain_cover(texel.dust_kg_m2) * sky_facing * (1.0 - body);
        colour = mix(colour, SETTLED_GRAIN_COLOUR, grains);
        // Fresh snow (albedo 0.8) shows near white; it greys as it ages.
        let snow_colour = vec3<f32>(min(1.0, 1.2 * snow_albedo(texel.age_days, params.cover_look2.y)));
        colour = mix(colour * darkening, snow_colour, snow);
        // Water shows where the sky reaches and no snow lies over it.
        open_water = sky_facing * (1.0 - snow);
        puddle_ratio = texel.standing_mm;
        wetness = texel.wetness;
    }
    let lit = in.cloud_sun * scene_shadow_lit(in.world_m);
    let intensity = blinn_phong(params.light, params.shadow, n, params.to_sun_extinction.xyz, to_viewer, lit);
    var look: SurfaceLook;
    look.shaded = colour * intensity;
    look.mirror = 0.0;
    look.water_slope = vec2<f32>(0.0);
    // Dry ground (no film, no puddle, no water body) looks as it is lit: water_surface
    // would return `shaded` and no mirror, so a GPU skips it there. (lavapipe runs
    // the branch's code wherever it is in the shader: the water's 33 of the scene
    // pass's 130 ms at 1280x720 stay.)
    let holds_water = wetness > 0.0 || puddle_cover(puddle_ratio) > 0.0 || body > 0.0;
    if (open_water > 0.0 && holds_water) {
        look.water_slope = water_slope(puddle_ratio, body, in.surface_m.xz, ring_fade);
        let wet = water_surface(look.shaded, puddle_ratio, wetness, body, look.water_slope, to_viewer, lit);
        look.shaded = mix(look.shaded, wet.rgb, open_water);
        look.mirror = wet.w * open_water;
    }
    return look;
}
