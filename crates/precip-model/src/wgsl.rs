//! The WGSL twins of this crate's Rust, one constant per file of `shaders/`, for
//! the GPU programs that join them (`precip-gpu`'s shader assembly reads them from
//! here, beside their Rust twins). Each file names its Rust twins in its first
//! lines; `docs/model.md` pairs every equation with both.

/// `layout.wgsl`: every struct that crosses between Rust and the GPU
/// ([`crate::particles::particle::Particle`], [`crate::particles::step::StepParams`],
/// [`crate::host::Frames`], …), and grid lookups.
pub const LAYOUT: &str = include_str!("../shaders/layout.wgsl");
/// `kind.wgsl`: what a particle is and every per-kind decision, twin of
/// [`crate::particles::kind`]; joined wherever `layout.wgsl` is.
pub const KIND: &str = include_str!("../shaders/kind.wgsl");
/// The value of `const NAME: u32 = …u;` in the WGSL `text` (tests check a Rust
/// constant against its twin with it).
#[cfg(test)]
pub(crate) fn u32_const(text: &str, name: &str) -> u32 {
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("const {name}: u32 = ")))
        .unwrap_or_else(|| panic!("the WGSL declares no {name}"));
    let value = line.rsplit("= ").next().unwrap_or_default();
    value
        .trim_end_matches(';')
        .trim_end_matches('u')
        .parse()
        .expect("a u32")
}

/// `rng.wgsl`: counter-based random numbers, twin of [`crate::particles::rng`].
pub const RNG: &str = include_str!("../shaders/rng.wgsl");
/// `physics.wgsl`: flakes, drops, grains, drag and rotation, twins of
/// [`crate::physics`].
pub const PHYSICS: &str = include_str!("../shaders/physics.wgsl");
/// `ground_map.wgsl`: the ground height map, twin of [`crate::GroundMap`].
pub const GROUND_MAP: &str = include_str!("../shaders/ground_map.wgsl");
/// `ground.wgsl`: how the ground turns the particles' wind, twin of
/// [`crate::physics::terrain_flow`].
pub const GROUND: &str = include_str!("../shaders/ground.wgsl");
/// `birth.wgsl`: birth and re-birth, twin of [`crate::particles::birth`].
pub const BIRTH: &str = include_str!("../shaders/birth.wgsl");
/// `step_particles.wgsl`: kernels `step_particles`, `birth_particles`,
/// `init_particles` and `reset_births`, twin of [`crate::particles::step`].
pub const STEP_PARTICLES: &str = include_str!("../shaders/step_particles.wgsl");
/// `water_physics.wgsl`: water's constants, the Weber number and the ripples'
/// phase speed.
pub const WATER_PHYSICS: &str = include_str!("../shaders/water_physics.wgsl");
/// `splash.wgsl`: splash droplets, twin of [`crate::physics::splash`].
pub const SPLASH: &str = include_str!("../shaders/splash.wgsl");
/// `water_waves.wgsl`: waves on water bodies, twin of
/// [`crate::physics::water_waves`].
pub const WATER_WAVES: &str = include_str!("../shaders/water_waves.wgsl");
/// `water_look.wgsl`: how water looks, twin of [`crate::drawing::water_look`].
pub const WATER_LOOK: &str = include_str!("../shaders/water_look.wgsl");
/// `drawing.wgsl`: sprite, tetrahedron, view cone, lighting and fog, twins of
/// [`crate::drawing`].
pub const DRAWING: &str = include_str!("../shaders/drawing.wgsl");
/// `optics.wgsl`: a particle's extinction and backscatter cross-sections, twins of
/// [`crate::sensors::optics`].
pub const OPTICS: &str = include_str!("../shaders/optics.wgsl");
/// `lidar.wgsl`: kernel `query_beams`, twin of [`crate::sensors::lidar`].
pub const LIDAR: &str = include_str!("../shaders/lidar.wgsl");
