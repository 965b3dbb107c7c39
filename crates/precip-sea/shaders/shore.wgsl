// shore.wgsl: the coastal zone's finite-volume scheme, WGSL twins of
// precip_sea::shore (src/shore/scheme.rs; docs/model.md (13.1)–(13.3)): MUSCL
// faces with the monotonized-central limiter, the hydrostatic reconstruction at
// each face (Audusse et al. 2004), the HLL flux, the centred bed source, the
// open sea's waves at an incoming edge, the bed's friction, the speed cap. The kernels that step a
// grid with them are precip-gpu's render_shore.wgsl.
//
// A cell's state is (h, q_normal, q_tangent, b) along the axis a sweep runs; a
// face is (h, b, u_normal, u_tangent).

// shore/mod.rs GRAVITY_MPS2, DRY_DEPTH_M.
const SHORE_G: f32 = 9.81;
const SHORE_DRY_DEPTH_M: f32 = 1.0e-5;

// scheme.rs velocity: none where the cell is dry.
fn shore_velocity(h: f32, q: f32) -> f32 {
    if (h > SHORE_DRY_DEPTH_M) {
        return q / h;
    }
    return 0.0;
}

// scheme.rs limited_slope: minmod(2a, (a + b)/2, 2b) (van Leer 1977).
fn shore_limited_slope(a: f32, b: f32) -> f32 {
    if (a * b <= 0.0) {
        return 0.0;
    }
    let m = min(min(2.0 * abs(a), 2.0 * abs(b)), 0.5 * abs(a + b));
    return select(-m, m, a > 0.0);
}

// scheme.rs sweep's `values`: (h, η = h + b, u_normal, u_tangent) of a cell's
// state (h, q_normal, q_tangent, b).
fn shore_values(cell: vec4<f32>) -> vec4<f32> {
    let h = cell.x;
    return vec4<f32>(h, h + cell.w, shore_velocity(h, cell.y), shore_velocity(h, cell.z));
}

// scheme.rs sweep's `face`: the face of the cell `here` toward `sign` (−1 the
// face before, +1 the face after) from its and its neighbours' values.
fn shore_face(before: vec4<f32>, here: vec4<f32>, after: vec4<f32>, sign: f32) -> vec4<f32> {
    let d0 = here - before;
    let d1 = after - here;
    let slope = vec4<f32>(
        shore_limited_slope(d0.x, d1.x),
        shore_limited_slope(d0.y, d1.y),
        shore_limited_slope(d0.z, d1.z),
        shore_limited_slope(d0.w, d1.w),
    );
    let h = here.x + sign * 0.5 * slope.x;
    let eta = here.y + sign * 0.5 * slope.y;
    return vec4<f32>(h, eta - h, here.z + sign * 0.5 * slope.z, here.w + sign * 0.5 * slope.w);
}

// scheme.rs hll: the HLL flux of (h, h·u_n, h·u_t) between two faces.
fn shore_hll(left: vec4<f32>, right: vec4<f32>) -> vec3<f32> {
    if (left.x <= SHORE_DRY_DEPTH_M && right.x <= SHORE_DRY_DEPTH_M) {
        return vec3<f32>(0.0);
    }
    let wet_l = left.x > SHORE_DRY_DEPTH_M;
    let wet_r = right.x > SHORE_DRY_DEPTH_M;
    let unl = select(0.0, left.z, wet_l);
    let utl = select(0.0, left.w, wet_l);
    let unr = select(0.0, right.z, wet_r);
    let utr = select(0.0, right.w, wet_r);
    let fl = vec3<f32>(left.x * unl, left.x * unl * unl + 0.5 * SHORE_G * left.x * left.x, left.x * unl * utl);
    let fr = vec3<f32>(right.x * unr, right.x * unr * unr + 0.5 * SHORE_G * right.x * right.x, right.x * unr * utr);
    let ul = vec3<f32>(left.x, left.x * unl, left.x * utl);
    let ur = vec3<f32>(right.x, right.x * unr, right.x * utr);
    let cl = sqrt(SHORE_G * left.x);
    let cr = sqrt(SHORE_G * right.x);
    let sl = min(unl - cl, unr - cr);
    let sr = max(unl + cl, unr + cr);
    if (sl >= 0.0) {
        return fl;
    }
    if (sr <= 0.0) {
        return fr;
    }
    return (sr * fl - sl * fr + sl * sr * (ur - ul)) / (sr - sl);
}

// scheme.rs sweep's faces: the flux through the face between the left cell's
// face after (`left`) and the right cell's face before (`right`), by the
// hydrostatic reconstruction: (mass, the left cell's normal momentum with the
// pressure it keeps, the right cell's likewise, tangential momentum).
fn shore_face_flux(left: vec4<f32>, right: vec4<f32>) -> vec4<f32> {
    let bed = max(left.y, right.y);
    let hl = max(left.x + left.y - bed, 0.0);
    let hr = max(right.x + right.y - bed, 0.0);
    let flux = shore_hll(vec4<f32>(hl, left.yzw), vec4<f32>(hr, right.yzw));
    return vec4<f32>(
        flux.x,
        flux.y + 0.5 * SHORE_G * (left.x * left.x - hl * hl),
        flux.y + 0.5 * SHORE_G * (right.x * right.x - hr * hr),
        flux.z,
    );
}

// scheme.rs sweep's bed source: g·(h₋ + h₊)/2·(b₊ − b₋) of a cell's faces before
// (`minus`) and after (`plus`); the normal momentum's rate loses it over Δx.
fn shore_bed_source(minus: vec4<f32>, plus: vec4<f32>) -> f32 {
    return SHORE_G * 0.5 * (minus.x + plus.x) * (plus.y - minus.y);
}

// scheme.rs bed_friction: the discharge of water `h` deep after a step `dt` of the
// bed's friction by Manning's n, implicitly.
fn shore_bed_friction(h: f32, q: vec2<f32>, dt: f32, manning_n: f32) -> vec2<f32> {
    if (h <= SHORE_DRY_DEPTH_M || manning_n <= 0.0) {
        return q;
    }
    let n = sqrt(q.x * q.x + q.y * q.y);
    let f = 1.0 + dt * SHORE_G * manning_n * manning_n * n / (h * h * pow(h, 1.0 / 3.0));
    return q / f;
}

// scheme.rs capped_discharge: the discharge of water `h` deep with its speed cut
// to `cap_mps`.
fn shore_capped(h: f32, q: vec2<f32>, cap_mps: f32) -> vec2<f32> {
    let most = cap_mps * h;
    let n = sqrt(q.x * q.x + q.y * q.y);
    if (n > most && n > 0.0) {
        return q * (most / n);
    }
    return q;
}

// scheme.rs incoming_ghost: the ghost's depth and normal velocity at an edge the
// sea's waves come in by: the edge cell's bed, depth and normal discharge, which
// way is inward along the axis (±1), the still level and the surface's rise there.
fn shore_incoming(bed: f32, h: f32, q_normal: f32, inward: f32, still_level_m: f32, rise_m: f32) -> vec2<f32> {
    let still = still_level_m - bed;
    if (still <= SHORE_DRY_DEPTH_M) {
        return vec2<f32>(0.0);
    }
    let wave_depth = max(still + rise_m, 0.0);
    let coming = rise_m * sqrt(SHORE_G / still) + 2.0 * sqrt(SHORE_G * wave_depth);
    let leaving = inward * shore_velocity(h, q_normal) - 2.0 * sqrt(SHORE_G * h);
    let c = max(0.25 * (coming - leaving), 0.0);
    return vec2<f32>(c * c / SHORE_G, inward * 0.5 * (coming + leaving));
}
