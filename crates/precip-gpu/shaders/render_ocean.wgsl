// render_ocean.wgsl: the open sea each frame (docs/model.md (13.8)): its cascades'
// spectra at the frame's time, their inverse FFTs, and the surfaces they give, in
// two atlases the sea's draw reads; then the sea's draw (vs_sea, fs_sea).
//
// The kernels (the `ocean` pass, while a mesh tagged "water": "sea" is drawn):
//   ocean_spectrum    one invocation per cascade point: h~(k, t) from the amplitudes
//                     drawn anew from the weather's wind (ocean.wgsl sea_amplitude:
//                     no upload when the wind changes), packed as two spectra of
//                     four real fields each (sea_fields);
//   ocean_fft_rows    one workgroup per line of a field (OCEAN_N / 2 invocations, a
//   ocean_fft_columns butterfly each a stage, the line in workgroup memory: Stockham's
//                     radix 2, fft.rs inverse_stage), rows then columns;
//   ocean_resolve     one invocation per atlas texel: the surfaces into the atlases,
//                     each cascade's square with a one-texel border wrapped from the
//                     far side, so a bilinear read tiles without a seam.
// Rust reference: precip_sea::ocean::SeaState::cascade(c).surface_at(t, λ).
// Program: the Render program's files, after render_reflections.wgsl.

// The cascades' spectra, (cascade, field 0/1, row z, column x), row by row.
@group(0) @binding(24) var<storage, read_write> ocean_spectra: array<vec4<f32>>;
// The atlases the kernels write: (λ·Dx, h, λ·Dz, 0) m and (∂h/∂x, ∂h/∂z, J, 0).
@group(0) @binding(25) var ocean_displacement_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(26) var ocean_slope_out: texture_storage_2d<rgba16float, write>;
// The same atlases as the sea's draw reads them.
@group(0) @binding(22) var ocean_displacement: texture_2d<f32>;
@group(0) @binding(23) var ocean_slope: texture_2d<f32>;
// The water's depth under the sea's level over the ground grid, a fraction of
// SEA_DEPTH_RANGE_M (precip_model::drawing::sea::sea_depth_map).
@group(0) @binding(27) var sea_depth: texture_2d<f32>;

// precip_model::drawing::sea BREAKER_INDEX, SEA_DEPTH_RANGE_M.
const BREAKER_INDEX: f32 = 0.78;
const SEA_DEPTH_RANGE_M: f32 = 25.5;

// The water's depth under the sea's level at xz_m, m (deep off the ground grid).
fn sea_depth_at(xz_m: vec2<f32>) -> f32 {
    let g = params.ground;
    let uv = (xz_m - g.origin_m) / g.size_m;
    var depth = SEA_DEPTH_RANGE_M;
    if (all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0))) {
        depth = textureSampleLevel(sea_depth, cover_sampler, uv, 0.0).r * SEA_DEPTH_RANGE_M;
    }
    return depth;
}

// The share of the open sea's waves `depth_m` of water holds: min(1, γ_b·d/H_s)
// (precip_model::drawing::sea: a wave breaks at γ_b times the depth).
fn sea_wave_share(depth_m: f32) -> f32 {
    return clamp(BREAKER_INDEX * depth_m / max(params.ocean.w, 1.0e-3), 0.0, 1.0);
}

// What the sea's draw hands its fragments.
struct SeaVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) world_m: vec3<f32>,
    // The still surface's point (the waves' atlases are read there).
    @location(1) surface_m: vec3<f32>,
    @location(2) cloud_sun: f32,
    // The water's depth there, m; the share of the waves it holds; the crest's
    // height over H_s.
    @location(3) depth_m: f32,
    @location(4) share: f32,
    @location(5) crest: f32,
    // The foam of the shore's breaking water (its bores and swash).
    @location(6) shore_foam: f32,
}

// An atlas's square per cascade: its points and a border texel each side.
const OCEAN_ATLAS_SIDE: u32 = OCEAN_N + 2u;
// log2(OCEAN_N): the FFT's stages (a line of OCEAN_N points, OCEAN_N / 2 = 64
// butterflies a stage, one per invocation).
const OCEAN_FFT_STAGES: u32 = 7u;

fn ocean_index(c: u32, field: u32, z: u32, x: u32) -> u32 {
    return ((c * 2u + field) * OCEAN_N + z) * OCEAN_N + x;
}

@compute @workgroup_size(64)
fn ocean_spectrum(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = (wid.x + wid.y * groups.x) * 64u + lid;
    if (i >= OCEAN_CASCADES * OCEAN_N * OCEAN_N) {
        return;
    }
    let c = i / (OCEAN_N * OCEAN_N);
    let p = i % (OCEAN_N * OCEAN_N);
    let x = p % OCEAN_N;
    let z = p / OCEAN_N;
    let dk = SEA_TAU / sea_cascade_size_m(c);
    let k = vec2<f32>(sea_wavenumber(x, OCEAN_N), sea_wavenumber(z, OCEAN_N)) * dk;
    // Its mirror −k, as the grid holds it.
    let mx = (OCEAN_N - x) % OCEAN_N;
    let mz = (OCEAN_N - z) % OCEAN_N;
    let k_mirror = vec2<f32>(sea_wavenumber(mx, OCEAN_N), sea_wavenumber(mz, OCEAN_N)) * dk;
    let band = sea_cascade_band(c);
    let seed = sea_cascade_seed(u32(switches.ocean.z), c);
    let wind = switches.ocean_wind.xy;
    let direction = switches.ocean_wind.zw;
    let jonswap = switches.ocean_spectrum.x < 0.5;
    // The Nyquist lines hold no wave (synthesis.rs OceanCascade::banded).
    let nyquist = x == OCEAN_N / 2u || z == OCEAN_N / 2u;
    let h0 = select(sea_amplitude(k, dk, band, seed, p, wind, direction, SHORTEST_WAVE_M, jonswap), vec2<f32>(0.0), nyquist);
    let h0_mirror = select(sea_amplitude(k_mirror, dk, band, seed, mz * OCEAN_N + mx, wind, direction, SHORTEST_WAVE_M, jonswap), vec2<f32>(0.0), nyquist);
    let omega = sea_dispersion(length(k), switches.ocean.y);
    let h = sea_evolved(h0, h0_mirror, omega, switches.sky_colour_time.w);
    let fields = sea_fields(k, h);
    ocean_spectra[ocean_index(c, 0u, z, x)] = fields[0];
    ocean_spectra[ocean_index(c, 1u, z, x)] = fields[1];
}

// A line and its ping-pong copy.
var<workgroup> ocean_line: array<vec4<f32>, 256>;

@compute @workgroup_size(64)
fn ocean_fft_rows(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    ocean_fft_line(wid.x + wid.y * groups.x, lid, 1u, OCEAN_N);
}

@compute @workgroup_size(64)
fn ocean_fft_columns(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    ocean_fft_line(wid.x + wid.y * groups.x, lid, OCEAN_N, 1u);
}

// The inverse FFT of line `g` (its field block g / N, its line g % N: a row when
// `stride` is 1, a column when it is N), in place.
fn ocean_fft_line(g: u32, lid: u32, stride: u32, line_step: u32) {
    let lines = OCEAN_CASCADES * 2u * OCEAN_N;
    // g is the workgroup's: every invocation of it takes the same branch.
    let live = g < lines;
    let base = min(g, lines - 1u) / OCEAN_N * OCEAN_N * OCEAN_N + (min(g, lines - 1u) % OCEAN_N) * line_step;
    let half = OCEAN_N / 2u;
    ocean_line[lid] = ocean_spectra[base + lid * stride];
    ocean_line[lid + half] = ocean_spectra[base + (lid + half) * stride];
    workgroupBarrier();
    for (var stage = 0u; stage < OCEAN_FFT_STAGES; stage += 1u) {
        let source = (stage % 2u) * OCEAN_N;
        let dest = OCEAN_N - source;
        let m = 1u << stage;
        let j = lid / m;
        let k = lid % m;
        let out = sea_butterfly(ocean_line[source + j * m + k], ocean_line[source + j * m + k + half], k, m);
        ocean_line[dest + j * 2u * m + k] = out[0];
        ocean_line[dest + j * 2u * m + k + m] = out[1];
        workgroupBarrier();
    }
    let last = (OCEAN_FFT_STAGES % 2u) * OCEAN_N;
    if (live) {
        ocean_spectra[base + lid * stride] = ocean_line[last + lid];
        ocean_spectra[base + (lid + half) * stride] = ocean_line[last + lid + half];
    }
}

@compute @workgroup_size(64)
fn ocean_resolve(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = (wid.x + wid.y * groups.x) * 64u + lid;
    let square = OCEAN_ATLAS_SIDE * OCEAN_ATLAS_SIDE;
    if (i >= OCEAN_CASCADES * square) {
        return;
    }
    let c = i / square;
    let bx = (i % square) % OCEAN_ATLAS_SIDE;
    let bz = (i % square) / OCEAN_ATLAS_SIDE;
    let x = (bx + OCEAN_N - 1u) % OCEAN_N;
    let z = (bz + OCEAN_N - 1u) % OCEAN_N;
    // (h, Dx, Dz, ∂h/∂x) and (∂h/∂z, ∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z): sea_fields.
    let a = ocean_spectra[ocean_index(c, 0u, z, x)];
    let b = ocean_spectra[ocean_index(c, 1u, z, x)];
    let lambda = switches.ocean.x;
    let texel = vec2<u32>(c * OCEAN_ATLAS_SIDE + bx, bz);
    textureStore(ocean_displacement_out, texel, vec4<f32>(lambda * a.y, a.x, lambda * a.z, 0.0));
    textureStore(ocean_slope_out, texel, vec4<f32>(a.w, b.x, sea_jacobian(b.y, b.z, b.w, lambda), 0.0));
}

// Where cascade c's surface at xz_m lies in an atlas (uv).
fn ocean_atlas_uv(c: u32, xz_m: vec2<f32>) -> vec2<f32> {
    let s = fract(xz_m / sea_cascade_size_m(c)) * f32(OCEAN_N);
    let atlas = vec2<f32>(f32(OCEAN_CASCADES * OCEAN_ATLAS_SIDE), f32(OCEAN_ATLAS_SIDE));
    return (vec2<f32>(f32(c * OCEAN_ATLAS_SIDE), 0.0) + 1.5 + s) / atlas;
}

// The sea's surface moved by the waves: each cascade's displacement at the still
// point (a vertex shader's: one read per cascade).
@vertex
fn vs_sea(v: SceneVertex) -> SeaVarying {
    var moved = vec3<f32>(0.0);
    var longest = vec3<f32>(0.0);
    for (var c = 0u; c < OCEAN_CASCADES; c += 1u) {
        let d = textureSampleLevel(ocean_displacement, cover_sampler, ocean_atlas_uv(c, v.position_m.xz), 0.0).xyz;
        moved += d;
        longest = select(longest, d, c == 0u);
    }
    // Toward the shore the waves shoal and break: cut to what the depth holds.
    var depth = sea_depth_at(v.position_m.xz);
    var share = sea_wave_share(depth);
    var p = v.position_m + moved * share;
    let significant = max(params.ocean.w, 1.0e-3);
    var crest = moved.y / significant;
    var foam = 0.0;
    // Over the shore's grid its water stands for the sea's longest waves (it
    // carries them in over its incoming edge, runs them up the beach and off the
    // walls); the shorter ones ride on it as deep as its water holds them; dry
    // land's cells sink out of sight under the ground (render_shore.wgsl).
    if (switches.shore_size.x > 0.5) {
        let w = shore_weight(v.position_m.xz);
        if (w > 0.0) {
            let s = shore_surface(v.position_m.xz);
            let fine_share = sea_wave_share(s.y);
            let on_shore = vec3<f32>(v.position_m.x, params.shore_grid.w + s.x, v.position_m.z) + (moved - longest) * fine_share;
            p = mix(p, on_shore, w);
            depth = mix(depth, s.y, w);
            share = mix(share, fine_share, w);
            crest = mix(crest, s.x / significant, w);
            foam = w * shore_foam(s);
        }
    }
    var out: SeaVarying;
    out.clip = params.view_proj * vec4<f32>(p, 1.0);
    out.world_m = p;
    out.surface_m = v.position_m;
    out.depth_m = depth;
    out.share = share;
    out.crest = crest;
    out.shore_foam = foam;
    out.cloud_sun = cloud_sun_share(p);
    return out;
}

// Foam where the surface folds: from a Jacobian this far under 1 ...
const SEA_FOAM_ONSET: f32 = 0.45;
// ... to full cover this much further; whitecaps (their share W of the sea by the
// wind, Monahan & O'Muircheartaigh) raise the onset by SEA_WHITECAP_ONSET·W.
const SEA_FOAM_RANGE: f32 = 0.35;
const SEA_WHITECAP_ONSET: f32 = 3.0;
// How much a wave broken to nothing on a shoal folds the surface (its foam) at
// its crest (its height over H_s at least a half), and in its trough.
const SEA_SURF_FOAM: f32 = 1.2;
const SEA_SURF_FOAM_TROUGH: f32 = 0.45;
// The surf's foam torn by the short waves: its cover times this plus the finer
// cascades' folding (mean 0) times SEA_SURF_GRAIN.
const SEA_SURF_GRAIN_MEAN: f32 = 0.7;
const SEA_SURF_GRAIN: f32 = 3.0;
// Foam's albedo.
const SEA_FOAM_ALBEDO: f32 = 0.8;
// The sun's glint on the sea (a Blinn–Phong lobe as narrow as a calm sea's).
const SEA_GLINT_SHININESS: f32 = 600.0;

@fragment
fn fs_sea(in: SeaVarying) -> @location(0) vec4<f32> {
    let camera = params.camera_m_cone_cos.xyz;
    let to_viewer = normalize_or_zero(camera - in.world_m);
    // A pixel's footprint: a cascade finer than it fades (its waves would alias:
    // they show as the roughness the coarser cascades' glint spreads over).
    let footprint_m = length(fwidth(in.surface_m.xz));
    var slope = vec2<f32>(0.0);
    var fold = 0.0;
    // The finer cascades' folding alone: the grain of the foam.
    var fine_fold = 0.0;
    for (var c = 0u; c < OCEAN_CASCADES; c += 1u) {
        let texel_m = sea_cascade_size_m(c) / f32(OCEAN_N);
        let keep = clamp(2.0 - footprint_m / texel_m, 0.0, 1.0);
        let s = textureSampleLevel(ocean_slope, cover_sampler, ocean_atlas_uv(c, in.surface_m.xz), 0.0);
        slope += s.xy * keep;
        fold += (1.0 - s.z) * keep;
        fine_fold += select(0.0, (1.0 - s.z) * keep, c > 0u);
    }
    // Cut waves are broken ones: the surf foams where they break (the more of a
    // wave the depth cuts, the more), most on their crests; the broken water stays
    // as rough as the sea beyond.
    let share = clamp(in.share, 0.0, 1.0);
    let crest = clamp(SEA_SURF_FOAM_TROUGH + 2.0 * in.crest, 0.0, 1.0);
    let grain = clamp(SEA_SURF_GRAIN_MEAN + SEA_SURF_GRAIN * fine_fold, 0.0, 1.5);
    fold += SEA_SURF_FOAM * (1.0 - share) * crest * grain;
    // The shore's bores and swash, torn likewise.
    fold += SEA_SURF_FOAM * in.shore_foam * grain;
    // The rain's rings on it, as on a pond.
    let ring_fade = clamp(1.0 - footprint_m / (0.5 * RING_WAVELENGTH_M), 0.0, 1.0);
    slope += water_slope(0.0, 1.0, in.surface_m.xz, ring_fade);
    let n = normalize(vec3<f32>(-slope.x, 1.0, -slope.y));
    let f = fresnel_unpolarised(max(dot(n, to_viewer), 0.0), WATER_REFRACTIVE_INDEX);
    var sky = overcast_sky(params.sky_colour_time.xyz, reflect(-to_viewer, n));
    // The scene it mirrors: the planar mirror's image at its level (the waves tilt
    // the ray it is read along), where the frame draws one there (a ray followed
    // over the frame before, as the ponds' without a mirror, would meet the waves'
    // own crests and cost a march in every fragment of the sea).
    let mirrored = switches.mirror.y > 0.5 && abs(in.surface_m.y - switches.mirror.x) <= MIRROR_LEVEL_TOLERANCE_M;
    if (f > REFLECTION_LEAST && mirrored) {
        sky += planar_mirrored_scene(in.clip.xy, to_viewer, slope);
    }
    let lit = in.cloud_sun * scene_shadow_lit(in.world_m);
    let to_sun = params.to_sun_extinction.xyz;
    // What lights the water column and the foam: the sky's and the sun's light on a
    // level surface, as the land's (no highlight: the glint is the water's).
    let diffuse_only = vec4<f32>(params.light.xy, 0.0, 1.0);
    let light = blinn_phong(diffuse_only, params.shadow, vec3<f32>(0.0, 1.0, 0.0), to_sun, to_viewer, lit);
    let half_vector = normalize_or_zero(to_sun + to_viewer);
    let glint = lit * params.light.z * 8.0 * pow(max(dot(half_vector, n), 0.0), SEA_GLINT_SHININESS);
    // The water's own colour: the deep sea's, or in shallow water the bed's through
    // the column (optics.rs shallow_colour).
    let own = sea_shallow_colour(params.sea_colour.rgb, params.sea_bed.rgb, params.sea_attenuation.rgb, in.depth_m);
    let water = (1.0 - f) * own * light + f * sky + vec3<f32>(glint);
    let onset = SEA_FOAM_ONSET - SEA_WHITECAP_ONSET * params.sea_colour.w;
    let foam = clamp((fold - onset) / SEA_FOAM_RANGE, 0.0, 1.0);
    let shaded = mix(water, vec3<f32>(SEA_FOAM_ALBEDO * light), foam);
    let seen = with_air(shaded, air_between(camera, in.world_m, switches.fog_layer));
    return vec4<f32>(with_unresolved_streaks(seen, in.clip.xy, distance(camera, in.world_m)), 1.0);
}
