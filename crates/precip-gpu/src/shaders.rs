//! The WGSL sources: one file per kernel plus shared files, joined in a fixed order.
//!
//! WGSL has no `#include`, so each GPU program is the concatenation of the shared
//! files it needs and its kernel file, in the order [`Program::files`] gives. Every
//! backend takes its source from [`Program::source`]: wgpu loads it as it is, the
//! Vulkan backend translates the same text to SPIR-V with naga at build time.

/// One WGSL file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShaderFile {
    /// File name: under `shaders/` of the crate of its Rust twin (`precip-model`,
    /// `precip-wind`, `precip-cover`), or of this crate for GPU-only files.
    pub name: &'static str,
    /// Its text.
    pub source: &'static str,
}

/// A file of another crate, beside its Rust twin.
macro_rules! twin_file {
    ($name:literal, $source:path) => {
        ShaderFile {
            name: $name,
            source: $source,
        }
    };
}

/// A GPU-only file of this crate's `shaders/`.
macro_rules! shader_file {
    ($name:literal) => {
        ShaderFile {
            name: $name,
            source: include_str!(concat!("../shaders/", $name)),
        }
    };
}

/// Structs shared with Rust, grid lookups.
pub const LAYOUT: ShaderFile = twin_file!("layout.wgsl", precip_model::wgsl::LAYOUT);
/// What a particle is: its kind's table (needs `DEPOSIT`).
pub const KIND: ShaderFile = twin_file!("kind.wgsl", precip_model::wgsl::KIND);
/// Counter-based RNG.
pub const RNG: ShaderFile = twin_file!("rng.wgsl", precip_model::wgsl::RNG);
/// Flakes, drops, drag, rotation.
pub const PHYSICS: ShaderFile = twin_file!("physics.wgsl", precip_model::wgsl::PHYSICS);
/// The wind sampler.
pub const WIND: ShaderFile = twin_file!("wind.wgsl", precip_wind::wgsl::WIND);
/// The ground height map.
pub const GROUND_MAP: ShaderFile = twin_file!("ground_map.wgsl", precip_model::wgsl::GROUND_MAP);
/// How the ground turns the particles' wind.
pub const GROUND: ShaderFile = twin_file!("ground.wgsl", precip_model::wgsl::GROUND);
/// LiDAR beams: kernel `query_beams` (Rust twin: `lidar`).
pub const LIDAR: ShaderFile = twin_file!("lidar.wgsl", precip_model::wgsl::LIDAR);
/// Fixed-point deposits.
pub const DEPOSIT: ShaderFile = twin_file!("deposit.wgsl", precip_cover::wgsl::DEPOSIT);
/// Birth and re-birth.
pub const BIRTH: ShaderFile = twin_file!("birth.wgsl", precip_model::wgsl::BIRTH);
/// The snow cover model.
pub const COVER: ShaderFile = twin_file!("cover.wgsl", precip_cover::wgsl::COVER);
/// Kernels `step_particles`, `birth_particles` and `init_particles`.
pub const STEP_PARTICLES: ShaderFile =
    twin_file!("step_particles.wgsl", precip_model::wgsl::STEP_PARTICLES);
/// How water looks (Rust twin: `water_look`).
pub const WATER_LOOK: ShaderFile = twin_file!("water_look.wgsl", precip_model::wgsl::WATER_LOOK);
/// Water's constants, the Weber number and the ripples' phase speed.
pub const WATER_PHYSICS: ShaderFile =
    twin_file!("water_physics.wgsl", precip_model::wgsl::WATER_PHYSICS);
/// Waves on water bodies (Rust twin: `water_waves`).
pub const WATER_WAVES: ShaderFile = twin_file!("water_waves.wgsl", precip_model::wgsl::WATER_WAVES);
/// Splash droplets (Rust twin: `splash`).
pub const SPLASH: ShaderFile = twin_file!("splash.wgsl", precip_model::wgsl::SPLASH);
/// Kernel `cover_update`.
/// When the wind lifts snow and how much it carries (Rust twin:
/// `precip_cover::blowing`).
pub const BLOWING: ShaderFile = twin_file!("blowing.wgsl", precip_cover::wgsl::BLOWING);
/// Kernels `cover_update`, `snow_wind`, `snow_outflow`, `snow_inflow`,
/// `water_outflow`, `water_inflow`.
pub const COVER_UPDATE: ShaderFile =
    twin_file!("cover_update.wgsl", precip_cover::wgsl::COVER_UPDATE);
/// Test kernel `probe_rng`.
pub const PROBE_RNG: ShaderFile = shader_file!("probe_rng.wgsl");
/// The renderer's structs.
pub const RENDER_LAYOUT: ShaderFile = shader_file!("render_layout.wgsl");
/// Sprite, tetrahedron, view cone, lighting, fog.
pub const DRAWING: ShaderFile = twin_file!("drawing.wgsl", precip_model::wgsl::DRAWING);
/// The cover as a surface sees it.
pub const SHADING: ShaderFile = twin_file!("shading.wgsl", precip_cover::wgsl::SHADING);
/// The render bindings, shadow map and scene passes.
pub const RENDER_SCENE: ShaderFile = shader_file!("render_scene.wgsl");
/// The terrain's clipmap (Rust twin: `scene::terrain`).
pub const RENDER_TERRAIN: ShaderFile = shader_file!("render_terrain.wgsl");
/// Snow sprites and rain tetrahedra.
pub const RENDER_PARTICLES: ShaderFile = shader_file!("render_particles.wgsl");
/// Kernel `cover_texture`: the cover texels into the surfaces' filtered textures.
pub const COVER_TEXTURE: ShaderFile = shader_file!("cover_texture.wgsl");
/// How each particle is drawn this frame (`drawn_as`), for the cull and splat kernels.
pub const PARTICLE_LISTS: ShaderFile = shader_file!("particle_lists.wgsl");
/// Sub-pixel particles: kernel `splat_particles` and its resolve draw.
pub const RENDER_SPLAT: ShaderFile = shader_file!("render_splat.wgsl");
/// The scene mirrored in standing water (the scene pass calls it).
pub const RENDER_REFLECTIONS: ShaderFile = shader_file!("render_reflections.wgsl");
/// The open sea: kernels `ocean_spectrum`, `ocean_fft_rows`, `ocean_fft_columns`,
/// `ocean_resolve`, and the sea's draw.
pub const RENDER_OCEAN: ShaderFile = shader_file!("render_ocean.wgsl");
/// The shore's formulas (precip-sea).
pub const SHORE: ShaderFile = twin_file!("shore.wgsl", precip_sea::wgsl::SHORE);
/// The shore: kernels `shore_faces_first`, `shore_update_first`,
/// `shore_faces_second`, `shore_update_second`, and its surface for the sea's draw.
pub const RENDER_SHORE: ShaderFile = shader_file!("render_shore.wgsl");
/// The cloud layer marched into the clouds' image.
pub const RENDER_CLOUDS: ShaderFile = shader_file!("render_clouds.wgsl");
/// Kernels `cull_count`, `cull_scan`, `cull_write`.
pub const CULL_PARTICLES: ShaderFile = shader_file!("cull_particles.wgsl");
/// Particles' cross-sections (Rust twin: `sensors::optics`).
pub const OPTICS: ShaderFile = twin_file!("optics.wgsl", precip_model::wgsl::OPTICS);
/// Kernel `optics_sums`: the camera volume's cross-sections per workgroup.
pub const OPTICS_SUMS: ShaderFile = shader_file!("optics_sums.wgsl");
/// Test kernel `probe_drawing`.
pub const PROBE_DRAWING: ShaderFile = shader_file!("probe_drawing.wgsl");
/// The open sea's formulas (precip-sea).
pub const OCEAN: ShaderFile = twin_file!("ocean.wgsl", precip_sea::wgsl::OCEAN);
/// Test kernel `probe_ocean`.
pub const PROBE_OCEAN: ShaderFile = shader_file!("probe_ocean.wgsl");

/// A GPU program: the files it is joined from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Program {
    /// Particle initialisation and step.
    StepParticles,
    /// The cover update.
    CoverUpdate,
    /// A test probe of the RNG.
    ProbeRng,
    /// The scene and precipitation draws (vertex and fragment entry points), and the
    /// splat of sub-pixel particles (a compute kernel and its resolve draw).
    Render,
    /// View-cone culling and compaction of the particles.
    CullParticles,
    /// A test probe of the drawing formulas.
    ProbeDrawing,
    /// A test probe of the open sea's formulas.
    ProbeOcean,
    /// LiDAR beams against the particles and the ground.
    QueryBeams,
    /// The camera volume's cross-sections summed per workgroup (`Backend::optics`).
    OpticsSums,
}

impl Program {
    /// Every program.
    pub const ALL: [Self; 9] = [
        Self::StepParticles,
        Self::CoverUpdate,
        Self::ProbeRng,
        Self::Render,
        Self::CullParticles,
        Self::ProbeDrawing,
        Self::ProbeOcean,
        Self::QueryBeams,
        Self::OpticsSums,
    ];

    /// The files, in the order they are joined.
    #[must_use]
    pub const fn files(self) -> &'static [ShaderFile] {
        match self {
            Self::StepParticles => &[
                LAYOUT,
                KIND,
                RNG,
                PHYSICS,
                WIND,
                GROUND_MAP,
                GROUND,
                DEPOSIT,
                BIRTH,
                WATER_PHYSICS,
                SPLASH,
                STEP_PARTICLES,
                WATER_WAVES,
            ],
            Self::CoverUpdate => &[
                LAYOUT,
                KIND,
                DEPOSIT,
                WATER_PHYSICS,
                COVER,
                BLOWING,
                COVER_UPDATE,
            ],
            Self::ProbeRng => &[RNG, PROBE_RNG],
            Self::Render => &[
                LAYOUT,
                KIND,
                DEPOSIT,
                RNG,
                WATER_PHYSICS,
                COVER,
                RENDER_LAYOUT,
                DRAWING,
                SHADING,
                WATER_LOOK,
                RENDER_SCENE,
                RENDER_TERRAIN,
                PARTICLE_LISTS,
                RENDER_PARTICLES,
                RENDER_SPLAT,
                RENDER_REFLECTIONS,
                OCEAN,
                RENDER_OCEAN,
                SHORE,
                RENDER_SHORE,
                RENDER_CLOUDS,
                COVER_TEXTURE,
            ],
            Self::CullParticles => &[
                LAYOUT,
                KIND,
                DEPOSIT,
                RNG,
                RENDER_LAYOUT,
                DRAWING,
                PARTICLE_LISTS,
                CULL_PARTICLES,
            ],
            Self::ProbeDrawing => &[
                LAYOUT,
                KIND,
                DEPOSIT,
                RNG,
                DRAWING,
                WATER_PHYSICS,
                COVER,
                SHADING,
                PROBE_DRAWING,
            ],
            Self::ProbeOcean => &[RNG, OCEAN, PROBE_OCEAN],
            Self::QueryBeams => &[LAYOUT, KIND, DEPOSIT, GROUND_MAP, LIDAR],
            Self::OpticsSums => &[LAYOUT, KIND, DEPOSIT, OPTICS, OPTICS_SUMS],
        }
    }

    /// Its entry points, read from its files: every function after an
    /// `@compute`, `@vertex` or `@fragment` attribute, in file order. A new kernel
    /// in an existing file needs nothing here (tests check the list against naga's
    /// reflection of the joined source).
    #[must_use]
    pub fn entry_points(self) -> Vec<&'static str> {
        self.files()
            .iter()
            .flat_map(|file| entry_points_of(file.source))
            .collect()
    }

    /// A label for debuggers.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::StepParticles => "precip step_particles",
            Self::CoverUpdate => "precip cover_update",
            Self::ProbeRng => "precip probe_rng",
            Self::Render => "precip render",
            Self::CullParticles => "precip cull_particles",
            Self::ProbeDrawing => "precip probe_drawing",
            Self::ProbeOcean => "precip probe_ocean",
            Self::QueryBeams => "precip query_beams",
            Self::OpticsSums => "precip optics_sums",
        }
    }

    /// The joined WGSL text, each file headed by a comment naming it.
    #[must_use]
    pub fn source(self) -> String {
        let mut text = String::new();
        for file in self.files() {
            text.push_str("// ---- ");
            text.push_str(file.name);
            text.push_str(" ----\n");
            text.push_str(file.source);
            text.push('\n');
        }
        text
    }
}

/// The entry points of one WGSL text: each `fn` name after a stage attribute
/// (`@compute`, `@vertex`, `@fragment`), outside `//` comments.
fn entry_points_of(source: &'static str) -> impl Iterator<Item = &'static str> {
    let mut staged = false;
    source.lines().filter_map(move |line| {
        let code = line.split("//").next().unwrap_or_default();
        if ["@compute", "@vertex", "@fragment"]
            .iter()
            .any(|a| code.contains(a))
        {
            staged = true;
        }
        let name = code
            .split_once("fn ")
            .filter(|_| staged)
            .and_then(|(_, rest)| rest.split('(').next())
            .map(str::trim)
            .filter(|n| !n.is_empty());
        if name.is_some() {
            staged = false;
        }
        name
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entry_points_are_the_staged_functions_only() {
        let wgsl: &'static str = "fn helper() {}\n// @compute fn commented() {}\n@compute @workgroup_size(64)\nfn first(@builtin(global_invocation_id) id: vec3<u32>) {}\n@vertex fn second() -> vec4<f32> { return vec4<f32>(0.0); }\nfn after() {}\n";
        assert_eq!(
            entry_points_of(wgsl).collect::<Vec<_>>(),
            ["first", "second"]
        );
        assert!(
            Program::StepParticles
                .entry_points()
                .contains(&"step_particles")
        );
        assert!(Program::Render.entry_points().contains(&"fs_sky"));
        assert_eq!(Program::ProbeRng.entry_points(), ["probe_rng"]);
    }
}
