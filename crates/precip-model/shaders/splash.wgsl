// splash.wgsl: a raindrop striking a surface throws up a splash droplet in its
// place. Rust twin: precip_model::physics::splash.

const SPLASH_THRESHOLD_K: f32 = 57.7;
const SPLASH_LIFT_M: f32 = 0.01;
const DRAW_SPLASH_AZIMUTH: u32 = 105u;
const DRAW_SPLASH_ELEVATION: u32 = 106u;
const DRAW_SPLASH_SPEED: u32 = 107u;

fn splash_number(diameter_m: f32, speed_mps: f32) -> f32 {
    let d = max(diameter_m, 0.0);
    let v = max(speed_mps, 0.0);
    let reynolds = WATER_DENSITY_KG_M3 * d * v / VISCOSITY_PA_S;
    return sqrt(weber_number(d, v)) * sqrt(sqrt(reynolds));
}

fn splashes(p: Particle) -> bool {
    return kind_is_drop(particle_kind(p.flags))
        && (p.flags & FLAG_SPLASH) == 0u
        && splash_number(p.diameter_m, length(p.velocity_mps)) > SPLASH_THRESHOLD_K;
}

fn splash_droplet(index: u32, p: Particle, surface_m: vec3<f32>) -> Particle {
    let key = particle_key(step_params.seed, index, p.generation);
    let azimuth = 6.283185307 * random_unit(key, DRAW_SPLASH_AZIMUTH);
    let elevation = radians(35.0 + 30.0 * random_unit(key, DRAW_SPLASH_ELEVATION));
    let speed = (0.2 + 0.2 * random_unit(key, DRAW_SPLASH_SPEED)) * length(p.velocity_mps);
    let diameter_m = 0.25 * p.diameter_m;
    var s = p;
    s.position_m = surface_m + vec3<f32>(0.0, SPLASH_LIFT_M, 0.0);
    s.velocity_mps = speed * vec3<f32>(cos(elevation) * cos(azimuth), sin(elevation), cos(elevation) * sin(azimuth));
    s.terminal_speed_mps = raindrop_terminal_speed_mps(max(diameter_m * 1.0e3, RAIN_DIAMETER_MIN_MM));
    s.diameter_m = diameter_m;
    s.water_kg = 0.0;
    s.flags = (p.flags & ~FLAG_LANDED) | FLAG_SPLASH;
    return s;
}
