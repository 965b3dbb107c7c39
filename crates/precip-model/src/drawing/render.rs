//! What the renderer needs besides the simulation: [`RenderSettings`] (the look,
//! validated with the setup) and [`RenderParams`], the per-frame uniform block both
//! GPU backends fill the same way from a [`View`], the weather and the setup.
//!
//! Matrices follow wgpu's conventions (glam's `rh::proj::directx`): right-handed world
//! (Y up), clip depth in `[0, 1]`, NDC Y up. The image's aspect ratio is the target's (`width / height`); the camera's
//! `aspect` field is not used for drawing. The sun's shadow map is an orthographic view
//! along the sunlight that encloses the scene's bounds.

use bytemuck::{Pod, Zeroable};
use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_to_mat4;
use glam::{Mat4, UVec4, Vec3, Vec4};
use precip_cover::{CoverParams, GridFrame};

use crate::backend::camera::{Camera, View};
use crate::backend::error::BackendError;
use crate::drawing::clouds::{
    CloudLayers, MAX_CLOUD_LAYERS, cloud_drift_m, cloud_extinction_at, cloud_noise,
    shaft_extinction_per_m,
};
use crate::drawing::fog_layer::{FOG_LAYER_BOTTOM_M, FogLayer};
use crate::drawing::multiplicity::PoolDrawing;
use crate::drawing::{Lighting, SpriteSizing, view_cone_cos};
use crate::weather::Weather;

/// The largest render target side accepted before asking the device, px.
pub const MAX_TARGET_SIDE_PX: u32 = 16_384;

/// Which standing water mirrors the scene, not only the sky (screen-space
/// reflections over the frame before).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mirrors {
    /// All standing water on a GPU; the water bodies only where the device
    /// rasterises on the CPU (lavapipe), on which every fragment of the ground pays
    /// for the ray's code, run or not (+30 ms a 1280×720 frame).
    #[default]
    Auto,
    /// The water bodies only: puddles on other surfaces mirror the sky.
    WaterBodies,
    /// The water bodies and the puddles on every other surface.
    AllWater,
}

/// The resolution rain and snow are drawn at, against the frame's (the scene is
/// always drawn at the frame's). Reduced, the sprites and streaks are drawn into an
/// image of a half or a quarter of the frame's side, each of their pixels tested
/// against the scene's depth at several of the frame's pixels it covers (the share
/// in front of the scene scales its opacity), and that image is laid over the frame
/// (filtered); what is smaller than `sizing.min_px` drawn pixels goes to the splat,
/// at the frame's resolution. The particles' fragments cost a quarter or a
/// sixteenth; thin streaks come out softer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ParticleResolution {
    /// The frame's.
    #[default]
    Full,
    /// Half the frame's width and height.
    Half,
    /// A quarter of the frame's width and height.
    Quarter,
}

impl ParticleResolution {
    /// Frame pixels per drawn pixel, along each side.
    #[must_use]
    pub const fn factor(self) -> u32 {
        match self {
            Self::Full => 1,
            Self::Half => 2,
            Self::Quarter => 4,
        }
    }

    /// The size particles are drawn at for a `size` frame (rounded up).
    #[must_use]
    pub const fn drawn_size(self, (width, height): (u32, u32)) -> (u32, u32) {
        let f = self.factor();
        (width.div_ceil(f), height.div_ceil(f))
    }
}

/// How much of a frame's cost the look may take: each level trades the same
/// physical picture (what falls, how densely, with what light) for detail.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Quality {
    /// Particles at a quarter of the frame's resolution, a 1024-texel shadow map,
    /// only the water bodies mirroring the scene.
    Low,
    /// Particles at half the frame's resolution.
    Medium,
    /// Everything at the frame's resolution (the defaults).
    #[default]
    High,
}

/// The look of a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Cull particles outside the view cone on the GPU before drawing (docs/model.md §5);
    /// off draws every particle (the images must not differ).
    pub view_cone_culling: bool,
    /// Direction toward the sun (need not be normalised; must point above the horizon).
    pub to_sun: Vec3,
    /// The seed's lighting terms.
    pub lighting: Lighting,
    /// Colour of the sky and of the fog, linear RGB.
    pub sky_colour: Vec3,
    /// Extinction of the air without precipitation, per m (haze).
    pub clear_air_extinction_per_m: f32,
    /// Sprite and streak sizes.
    pub sizing: SpriteSizing,
    /// Draw particles smaller than `sizing.min_px` by a compute splat (same light,
    /// order-independent) instead of enlarged sprites and streaks; off draws every
    /// particle as geometry (the reference the splat is tested against).
    pub splat_sub_pixel: bool,
    /// Make each snow sprite's quad (its corners' positions, light and opacity) once
    /// a frame and have its four corners read it, in a buffer of 64 bytes per sprite
    /// instance the frame may draw (at most 2²⁰ of them: `precip_gpu`'s
    /// `SNOW_QUAD_CAPACITY`; instances beyond make their own); off, each corner
    /// makes it anew (the first instance's excepted), four times the sprites'
    /// vertex work and a buffer of one quad (the images must not differ).
    pub snow_quads: bool,
    /// A factor on a rain streak's physical opacity (`crate::drawing::raindrop_sizing`),
    /// `[0, 1]`: 1 draws each drop's projected area.
    pub rain_opacity: f32,
    /// Raise upward surfaces by the snow depth.
    pub snow_displacement: bool,
    /// Shadow map side, px.
    pub shadow_map_px: u32,
    /// The most frames a stale shadow map is kept, `[1, 60]`: 1 redraws it as soon as
    /// the sun's view or the snow moved enough to show
    /// ([`crate::drawing::shadow_cache::ShadowCache`]); `n` keeps it, sampled as it was
    /// drawn, for up to `n − 1` more frames (a moving camera redraws it every `n`th
    /// frame, not every frame).
    pub shadow_refresh_frames: u32,
    /// Longest triangle edge after tessellation for the displacement, m.
    pub tessellation_edge_m: f32,
    /// Most triangles the tessellated scene may have.
    pub max_scene_triangles: u64,
    /// Depth of the scene's water bodies, m (how much of their bottom shows through:
    /// [`crate::drawing::water_look::water_body_colour`]).
    pub water_body_depth_m: f32,
    /// Which water mirrors the scene.
    pub mirrors: Mirrors,
    /// The resolution rain and snow are drawn at.
    pub particle_resolution: ParticleResolution,
    /// A layer of fog up to a height (valley and ground fog), lit by the sky and
    /// the sun ([`crate::drawing::fog_layer`]); `None`: no fog but the uniform haze.
    pub fog_layer: Option<FogLayer>,
    /// Layers of volumetric clouds ([`crate::drawing::clouds`], up to three);
    /// none: the overcast sky alone.
    pub cloud_layers: CloudLayers,
    /// The rate of rain or snow (the weather's kind) averaged over the land beyond
    /// the camera's surroundings ([`crate::drawing::clouds::LOCAL_WEATHER_RADIUS_M`]),
    /// mm/h of water, falling in shafts under the lowest cloud layer's clouds
    /// (docs/model.md (6.16)); `None`: the weather's own (it rains as much there
    /// as here). Showers seen from a dry place: 0 mm/h here, 20 there.
    pub rate_beyond_mm_per_h: Option<f32>,
    /// Draw the land beyond the scene below the horizon
    /// ([`crate::drawing::far_ground`]); off, the sky goes on below it (a scene
    /// that carries its own horizon, an island in a sea of sky). A scene with a sea
    /// draws none (its sea runs to the horizon).
    pub land_beyond: bool,
    /// The open sea (drawn where a mesh is tagged `"water": "sea"`).
    pub sea: crate::drawing::sea::SeaSettings,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            view_cone_culling: true,
            snow_quads: true,
            to_sun: Vec3::new(0.4, 0.8, 0.3),
            lighting: Lighting {
                ambient: 0.45,
                diffuse: 0.65,
                specular: 0.25,
                shininess: 24.0,
                shadow_colour: 0.0,
                shadow_density: 0.6,
                attenuation: 1.0,
            },
            sky_colour: Vec3::new(0.62, 0.66, 0.72),
            clear_air_extinction_per_m: 3.912 / 30_000.0,
            sizing: SpriteSizing::default(),
            splat_sub_pixel: true,
            rain_opacity: 1.0,
            snow_displacement: true,
            shadow_map_px: 2048,
            shadow_refresh_frames: 1,
            tessellation_edge_m: 0.5,
            max_scene_triangles: 2_000_000,
            water_body_depth_m: 1.5,
            mirrors: Mirrors::Auto,
            particle_resolution: ParticleResolution::Full,
            fog_layer: None,
            cloud_layers: CloudLayers::NONE,
            rate_beyond_mm_per_h: None,
            land_beyond: true,
            sea: crate::drawing::sea::SeaSettings::default(),
        }
    }
}

/// The most frames [`Quality::Low`] keeps a stale shadow map.
pub const LOW_SHADOW_REFRESH_FRAMES: u32 = 4;

fn bad(field: &'static str, problem: String) -> BackendError {
    BackendError::Setup { field, problem }
}

impl RenderSettings {
    /// These settings at `quality`: its particle resolution, shadow map, shadow
    /// refresh and mirrors (the rest kept).
    #[must_use]
    pub fn at_quality(self, quality: Quality) -> Self {
        let high = Self::default();
        match quality {
            Quality::High => Self {
                particle_resolution: ParticleResolution::Full,
                ..self
            },
            Quality::Medium => Self {
                particle_resolution: ParticleResolution::Half,
                ..self
            },
            Quality::Low => Self {
                particle_resolution: ParticleResolution::Quarter,
                shadow_map_px: self.shadow_map_px.min(high.shadow_map_px / 2),
                shadow_refresh_frames: self.shadow_refresh_frames.max(LOW_SHADOW_REFRESH_FRAMES),
                mirrors: Mirrors::WaterBodies,
                ..self
            },
        }
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<(), BackendError> {
        let sun = self.to_sun.normalize_or_zero();
        if !(sun.is_finite() && sun.y > 0.01) {
            return Err(bad(
                "render.to_sun",
                format!(
                    "= {} must be a finite direction above the horizon",
                    self.to_sun
                ),
            ));
        }
        let l = &self.lighting;
        for (field, value, lo, hi) in [
            ("render.lighting.ambient", l.ambient, 0.0, 10.0),
            ("render.lighting.diffuse", l.diffuse, 0.0, 10.0),
            ("render.lighting.specular", l.specular, 0.0, 10.0),
            ("render.lighting.shininess", l.shininess, 0.0, 128.0),
            ("render.lighting.shadow_colour", l.shadow_colour, 0.0, 10.0),
            ("render.lighting.shadow_density", l.shadow_density, 0.0, 1.0),
            ("render.lighting.attenuation", l.attenuation, 0.0, 10.0),
            (
                "render.clear_air_extinction_per_m",
                self.clear_air_extinction_per_m,
                0.0,
                10.0,
            ),
            (
                "render.sizing.snow_scale",
                self.sizing.snow_scale,
                0.01,
                1000.0,
            ),
            ("render.sizing.min_px", self.sizing.min_px, 0.0, 64.0),
            (
                "render.sizing.min_opacity",
                self.sizing.min_opacity,
                0.0,
                1.0,
            ),
            ("render.rain_opacity", self.rain_opacity, 0.0, 1.0),
            (
                "render.rate_beyond_mm_per_h",
                self.rate_beyond_mm_per_h.unwrap_or(0.0),
                0.0,
                Weather::MAX_INTENSITY_MM_PER_H,
            ),
            (
                "render.water_body_depth_m",
                self.water_body_depth_m,
                0.0,
                1.0e4,
            ),
            (
                "render.tessellation_edge_m",
                self.tessellation_edge_m,
                0.01,
                1.0e6,
            ),
        ] {
            if !(value.is_finite() && (lo..=hi).contains(&value)) {
                return Err(bad(field, format!("= {value} must be in [{lo}, {hi}]")));
            }
        }
        if !(self.sky_colour.is_finite() && self.sky_colour.min_element() >= 0.0) {
            return Err(bad(
                "render.sky_colour",
                format!("= {} must be finite and non-negative", self.sky_colour),
            ));
        }
        if !(1..=60).contains(&self.shadow_refresh_frames) {
            return Err(bad(
                "render.shadow_refresh_frames",
                format!(
                    "= {} must be in [1, 60] (1: redraw a stale shadow map at once)",
                    self.shadow_refresh_frames
                ),
            ));
        }
        if !(16..=8192).contains(&self.shadow_map_px) {
            return Err(bad(
                "render.shadow_map_px",
                format!("= {} must be in [16, 8192]", self.shadow_map_px),
            ));
        }
        if let Some(fog) = &self.fog_layer {
            fog.validate()?;
        }
        self.cloud_layers.validate()?;
        self.sea.validate()?;
        if self.max_scene_triangles == 0 {
            return Err(bad(
                "render.max_scene_triangles",
                "must be at least 1".into(),
            ));
        }
        Ok(())
    }
}

/// The per-frame uniform block of the render program.
///
/// WGSL twin: `RenderParams` in `shaders/render_layout.wgsl` (1632 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct RenderParams {
    /// World → clip of the camera.
    pub view_proj: Mat4,
    /// World → clip of the sun's shadow map.
    pub sun_view_proj: Mat4,
    /// Camera position, m; w: the view cone's cosine.
    pub camera_m_cone_cos: Vec4,
    /// Unit viewing direction; w: the angle one pixel spans, rad.
    pub view_dir_pixel_angle: Vec4,
    /// Unit direction to the sun; w: fog extinction, per m.
    pub to_sun_extinction: Vec4,
    /// Sky/fog colour (linear); w: time, s.
    pub sky_colour_time: Vec4,
    /// k_A·I_A, k_D·I_D, k_S·I_S, shininess.
    pub light: Vec4,
    /// Shadow colour, shadow density, attenuation λ, shadow-map texel size (uv).
    pub shadow: Vec4,
    /// Snow scale, min px (of the frame: `sizing.min_px` drawn pixels), min opacity,
    /// the lens's exposure s.
    pub sizing: Vec4,
    /// Rain opacity, displacement on (1/0), the cover's depletion exponent, mask edge.
    pub cover_look: Vec4,
    /// Wet darkening R_d, albedo decay per day, exposure tolerance m, the flake
    /// texture's mean opacity.
    pub cover_look2: Vec4,
    /// Rain rings struck per m² and s, 1 when the scene and depth of the frame
    /// before (at [`RenderParams::previous_view_proj`]) are there for the water's
    /// reflections (else 0: the renderer sets it), water bodies' depth m, 0
    /// ([`crate::drawing::water_look`]).
    pub water_look: Vec4,
    /// The ground map's grid.
    pub ground: GridFrame,
    /// The cover grid.
    pub cover: GridFrame,
    /// The water bodies' wave grid ([`crate::physics::water_waves`]).
    pub waves: GridFrame,
    /// Particle count, culling on (1/0), cull workgroups, the splat target's width in
    /// px (0: splat off).
    pub counts: UVec4,
    /// The pools ([`crate::drawing::multiplicity::PoolDrawing`]): world particle
    /// count, first lifted world particle, end of the camera volume's drawn ones,
    /// copies of each camera-volume sprite.
    pub pools: UVec4,
    /// The camera volume's centre, m; w: the world emitter's multiplicity.
    pub camera_box_centre_m: Vec4,
    /// The camera volume's half extent, m (0 without one); w: its multiplicity.
    pub camera_box_half_m: Vec4,
    /// The lens: aperture m, focus distance m ([`crate::backend::camera::Lens`]);
    /// frame pixels per particle pixel ([`ParticleResolution::factor`]), 0.
    pub lens: Vec4,
    /// Clip → world of the camera (the sky's rays).
    pub inverse_view_proj: Mat4,
    /// World → clip of the camera of the frame before, whose scene and depth the
    /// water's reflections read (this frame's until the renderer sets it).
    pub previous_view_proj: Mat4,
    /// World → clip through the water bodies' mirror
    /// ([`crate::drawing::water_mirror::FrameMirror::view_proj`]; the camera's when
    /// none is drawn).
    pub mirror_view_proj: Mat4,
    /// The mirror's level m, 1 when the frame draws it (else 0: the renderer sets
    /// it), 0, 0.
    pub mirror: Vec4,
    /// The fog layer ([`crate::drawing::fog_layer`]): its top m, its bottom m (far
    /// below the ground; the mirror's pass reflects the layer about the water), its
    /// extinction B per m (0: none), the sun's scattered light on (1/0).
    pub fog_layer: Vec4,
    /// The cloud layers ([`crate::drawing::clouds::CloudLayers`]), lowest first:
    /// each one's base m, top m, coverage, kind
    /// ([`crate::drawing::clouds::CloudKind::index`]); zeros past the last.
    pub clouds: [Vec4; MAX_CLOUD_LAYERS],
    /// Each layer's most extinction per m
    /// ([`crate::drawing::clouds::CloudKind::extinction_per_m`]); the
    /// precipitation's extinction per m, what falls from the lowest layer (rain and
    /// snow, not sand or dust: its shafts, [`crate::drawing::clouds::precipitation_haze`]).
    pub cloud_extinction: Vec4,
    /// The clouds' drift with the wind (x, z m), the extinction per m under a
    /// shaft of the lowest layer ([`crate::drawing::clouds::shaft_extinction_per_m`]),
    /// the offset of the march's jitter in `[0, 1)` (0 here; the renderer moves it
    /// on every [`crate::drawing::clouds::CLOUD_MARCH_ALL`] frames,
    /// [`crate::drawing::clouds::cloud_march_round_offset`]).
    pub cloud_drift: Vec4,
    /// The share of the sun's light that reaches the ground under the camera through
    /// the cloud layer ([`crate::drawing::clouds::cloud_sun_transmittance`]: the
    /// clouds' shadow, one share for the frame; 1 without a layer); the frame's
    /// slot of the clouds' march ([`crate::drawing::clouds::cloud_march_slot`];
    /// [`crate::drawing::clouds::CLOUD_MARCH_ALL`]: every tile, as made here — the
    /// renderer sets it where the frame before's image can be reused); the clouds'
    /// drift since that image (x, z m).
    pub cloud_shadow: Vec4,
    /// The land beyond the scene ([`crate::drawing::far_ground`]): its height m,
    /// 1 when it is drawn (the scene has a ground map), 0, 0.
    pub far_ground: Vec4,
    /// The clouds' shadow map ([`crate::drawing::clouds::cloud_shadow_map`]): its
    /// corner x, z m ([`crate::drawing::clouds::cloud_shadow_map_origin_m`]), 1
    /// while a layer is drawn (the kernel writes it and the lit fragments read it;
    /// else 0), 0.
    pub cloud_shadow_map: Vec4,
    /// The grain of what the budget does not draw one by one
    /// ([`crate::drawing::unresolved_streaks::UnresolvedStreaks`]): its scale `C`
    /// (0: none), reach `ū` m, near end `z₁` m, streak length px.
    pub unresolved_streaks: Vec4,
    /// The streaks' direction on screen (a unit vector in pixels, y down), the
    /// exposure's number (`⌊t/T⌋`, a new grain each), 0.
    pub streak_direction: Vec4,
    /// Where the lens's axis is from the target's corner, px (x right, y down),
    /// negated: the grain is laid in pixels from the axis, so the channels of a
    /// rig (lens shifts of one image plane) draw the same grain where they
    /// overlap; 0, 0.
    pub streak_origin: Vec4,
    /// The sea's wind: its speed m/s 10 m above the water, the fetch m, the unit
    /// direction it blows toward (x, z) ([`crate::drawing::sea`]).
    pub ocean_wind: Vec4,
    /// The sea: its choppiness λ, depth m, seed (an integer), 0.
    pub ocean: Vec4,
    /// The colour deep sea water sends out (linear RGB, of a white diffuser's 1),
    /// the share of the sea whitecaps cover.
    pub sea_colour: Vec4,
    /// The sea's diffuse attenuation per m (RGB), 0.
    pub sea_attenuation: Vec4,
    /// The seabed's colour seen through the surface (RGB), 0.
    pub sea_bed: Vec4,
    /// The sea's spectrum (0 JONSWAP, 1 Phillips), 0, 0, 0.
    pub ocean_spectrum: Vec4,
    /// The shore's grid ([`crate::drawing::shore`]): its corner x, z m, its cell m,
    /// the still level m (zeros without a shore; the renderer sets the shore's rows).
    pub shore_grid: Vec4,
    /// The shore's cells along x and z, the step of this frame's shore steps s, the
    /// water's speed cap m/s.
    pub shore_size: Vec4,
    /// Each side's edge: west, east, south, north ([`crate::drawing::shore::ShoreEdge`]).
    pub shore_edges: Vec4,
    /// The shore's steps this frame, its bed's Manning roughness s/m^⅓, 0, 0.
    pub shore_steps: Vec4,
    /// The waves coming in: each sinusoid's amplitude m, angular frequency rad/s,
    /// phase at this frame's first shore step rad, wavenumber along the edge rad/m.
    pub shore_waves: [Vec4; crate::drawing::shore::SHORE_WAVE_COMPONENTS],
    /// The terrain's clipmap ([`crate::scene::terrain::ClipmapRows::placement`]):
    /// the pyramid's corner x, z m, level 0's spacing m, the levels drawn.
    pub terrain: Vec4,
    /// The first level drawn, the pyramid's levels, the first word of the frame's
    /// windows in the ground buffer, the first level the water's mirror draws.
    pub terrain_levels: UVec4,
    /// Each level's samples along x and z, two levels a row.
    pub terrain_samples: [UVec4; crate::scene::terrain::MAX_TERRAIN_LEVELS / 2],
    /// Each level's window origin, x and z as two `i16` (x low), four levels a
    /// row ([`crate::scene::terrain::ClipmapRows::windows`]).
    pub terrain_windows: [UVec4; crate::scene::terrain::MAX_TERRAIN_LEVELS / 4],
    /// Where the cover beyond the cover grid is read ([`crate::host::FarCoverRows`]):
    /// its cells' corner x, z and a cell's size along x, z, m.
    pub far_cover_grid: Vec4,
    /// Its cells along x and z, the first word of its rows in the ground buffer
    /// (each texel's three rows as the grid's three textures hold a texel), 0.
    pub far_cover_cells: UVec4,
    /// The terrain's land cover ([`crate::scene::terrain::LandCoverRows`]): its GPU
    /// copy's pixels along x and z, first word in the ground buffer, 1 if present.
    pub land_cover: UVec4,
    /// The terrain's corner x, z and size along x, z, m.
    pub land_cover_extent: Vec4,
    /// Each land class ([`crate::scene::LandClass`] order): its share of the snow
    /// seen from above, its far cover's triple, its row of the terrain's colour
    /// ramp (v), 0.
    pub land_classes: [Vec4; crate::scene::land_cover::LAND_CLASSES],
}
const _: () = assert!(size_of::<RenderParams>() == 1632);

/// The block's rows of the land classes (`RenderParams::land_classes`).
fn land_class_rows() -> [Vec4; crate::scene::land_cover::LAND_CLASSES] {
    crate::scene::LandClass::ALL.map(|c| {
        let slot = c.surface().map_or(0, crate::host::far_cover_slot);
        Vec4::new(
            c.snow_share(),
            slot as f32,
            crate::scene::terrain::terrain_ramp_v(c),
            0.0,
        )
    })
}

/// The block's rows of the cloud layers: base m, top m, coverage, kind each.
fn cloud_layer_rows(layers: &CloudLayers) -> [Vec4; MAX_CLOUD_LAYERS] {
    let mut rows = [Vec4::ZERO; MAX_CLOUD_LAYERS];
    for (row, c) in rows.iter_mut().zip(layers.iter()) {
        *row = Vec4::new(c.base_m, c.top_m(), c.coverage, c.kind.index() as f32);
    }
    rows
}

/// The block's row of the layers' most extinction per m and the precipitation's
/// extinction `falling_per_m` (0 without a layer to fall from).
fn cloud_extinction_row(layers: &CloudLayers, falling_per_m: f32) -> Vec4 {
    let mut row = [0.0; 4];
    for (e, c) in row.iter_mut().zip(layers.iter()) {
        *e = c.kind.extinction_per_m();
    }
    if !layers.is_empty() {
        row[3] = falling_per_m.max(0.0);
    }
    Vec4::from_array(row)
}

/// The camera's world → clip matrix for a target of `aspect` (width / height).
#[must_use]
pub fn view_projection(camera: &Camera, aspect: f32) -> Mat4 {
    let proj = directx::perspective(camera.vertical_fov_rad, aspect, camera.near_m, camera.far_m);
    // The lens shift moves clip space by −shift·w: what was at NDC `u` is drawn at
    // `u − shift`.
    let shift = Mat4::from_translation(Vec3::new(-camera.lens_shift.x, -camera.lens_shift.y, 0.0));
    let view = look_to_mat4(camera.position_m, camera.forward.normalize(), camera.up);
    shift * proj * view
}

/// The sun's view of the box `(lo, hi)`: world → light space, looking along the
/// sunlight from `2·radius` sunward of the box's centre, and that radius (the box's
/// bounding sphere, at least 1 m). Depths `0 … 4·radius` hold the whole box.
#[must_use]
pub fn sun_view(to_sun: Vec3, lo: Vec3, hi: Vec3) -> (Mat4, f32) {
    let sun = to_sun.normalize();
    let centre = 0.5 * (lo + hi);
    let radius = (0.5 * (hi - lo).length()).max(1.0);
    let up = if sun.cross(Vec3::Y).length_squared() > 1e-6 {
        Vec3::Y
    } else {
        Vec3::Z
    };
    (look_to_mat4(centre + sun * 2.0 * radius, -sun, up), radius)
}

/// An orthographic view along the sunlight enclosing the box `(lo, hi)`.
#[must_use]
pub fn sun_view_projection(to_sun: Vec3, lo: Vec3, hi: Vec3) -> Mat4 {
    let (view, radius) = sun_view(to_sun, lo, hi);
    let proj = directx::orthographic(-radius, radius, -radius, radius, 0.0, 4.0 * radius);
    proj * view
}

/// The horizontal field of view of `camera` on a target of `aspect`.
#[must_use]
pub fn horizontal_fov_rad(camera: &Camera, aspect: f32) -> f32 {
    2.0 * ((0.5 * camera.vertical_fov_rad).tan() * aspect).atan()
}

/// Checks a view: its camera and a target of `1..=MAX_TARGET_SIDE_PX` pixels a side.
pub fn validate_view(view: &View) -> Result<(), BackendError> {
    view.camera.validate()?;
    for (what, px) in [("width_px", view.width_px), ("height_px", view.height_px)] {
        if !(1..=MAX_TARGET_SIDE_PX).contains(&px) {
            return Err(BackendError::InvalidView(format!(
                "{what} = {px}: a target needs 1 to {MAX_TARGET_SIDE_PX} pixels a side"
            )));
        }
    }
    Ok(())
}

/// Everything a frame's uniform block is made from.
#[derive(Debug, Clone, Copy)]
pub struct FrameInputs<'a> {
    /// Camera and target.
    pub view: &'a View,
    /// The current weather (fog).
    pub weather: &'a Weather,
    /// The look.
    pub settings: &'a RenderSettings,
    /// Cover constants (patches, darkening).
    pub cover_params: &'a CoverParams,
    /// Ground map grid.
    pub ground: GridFrame,
    /// Cover grid.
    pub cover: GridFrame,
    /// The water bodies' wave grid.
    pub waves: GridFrame,
    /// The scene's bounds `(lo, hi)`, m: the shadow map keeps every caster in them
    /// and spreads its texels over the part in view ([`crate::drawing::shadow_fit`]).
    pub shadow_bounds_m: (Vec3, Vec3),
    /// Simulated time, s.
    pub time_s: f32,
    /// Particles.
    pub particle_count: u32,
    /// Workgroups of the cull kernels.
    pub cull_groups: u32,
    /// How each pool's particles are weighed ([`crate::drawing::multiplicity`]).
    pub pools: PoolDrawing,
    /// The height of the land beyond the scene, m
    /// ([`crate::drawing::far_ground::far_ground_level_m`]); `None`: none drawn.
    pub far_ground_level_m: Option<f32>,
    /// The scene has a sea: the block's sea rows are made (else left zero: an idle
    /// sea costs nothing, on the host either).
    pub sea: bool,
}

impl crate::Setup {
    /// The frame's uniform block for `view` under `weather` at `time_s`, the shadow map
    /// enclosing `shadow_bounds_m`, for `particle_count` particles and the wave grid
    /// `waves` (the one [`crate::Setup::frames`] gave at configure), the pools weighed
    /// as `pools` says ([`crate::Setup::pool_drawing`], made once per weather change):
    /// what every GPU backend draws a frame of this setup with.
    #[must_use]
    #[expect(
        clippy::too_many_arguments,
        reason = "each is one input of the block; FrameInputs gathers them"
    )]
    pub fn render_params(
        &self,
        view: &View,
        weather: &Weather,
        shadow_bounds_m: (Vec3, Vec3),
        time_s: f64,
        particle_count: u32,
        waves: GridFrame,
        pools: PoolDrawing,
    ) -> RenderParams {
        let sea = self
            .scene
            .as_ref()
            .is_some_and(|s| s.meshes.iter().any(crate::scene::Mesh::is_sea));
        RenderParams::new(&FrameInputs {
            view,
            weather,
            settings: &self.render,
            cover_params: &self.cover.params,
            ground: self.ground.frame,
            cover: self.cover.frame,
            waves,
            shadow_bounds_m,
            time_s: time_s as f32,
            particle_count,
            cull_groups: crate::host::cull_groups(particle_count),
            pools,
            // A scene with a sea: the sea runs to the horizon, no land beyond.
            far_ground_level_m: (self.render.land_beyond && !sea)
                .then(|| crate::drawing::far_ground::far_ground_level_m(&self.ground)),
            sea,
        })
    }
}

/// The fog layer of the frame's block: the settings' fog layer, or where the camera
/// is inside a cloud and its extinction there is the larger, the cloud's layer as a
/// fog of that extinction (the camera flying through a cloud sees the scene fade;
/// docs/model.md (6.13)), its sun's share left out; in a layer's transition band,
/// the band's side (below the base or above the top) as a fog of the band's air
/// at the camera.
fn air_layer(settings: &RenderSettings, weather: &Weather, time_s: f32, camera_m: Vec3) -> Vec4 {
    let fog = settings.fog_layer.map_or(Vec4::ZERO, |fog| {
        Vec4::new(fog.top_m, FOG_LAYER_BOTTOM_M, fog.extinction_per_m(), 1.0)
    });
    let drift = cloud_drift_m(weather.wind.mean_wind_mps, time_s);
    let Some((layer, offset)) = settings.cloud_layers.containing(camera_m.y, drift) else {
        return fog;
    };
    let in_cloud = cloud_extinction_at(cloud_noise(), &layer, offset, camera_m);
    let (low_m, high_m) = layer.extent_with_band_m();
    let (top_m, bottom_m) = if camera_m.y < layer.base_m {
        (layer.base_m, low_m)
    } else if camera_m.y > layer.top_m() {
        (high_m, layer.top_m())
    } else {
        (layer.top_m(), layer.base_m)
    };
    if in_cloud > fog.z {
        Vec4::new(top_m, bottom_m, in_cloud, 0.0)
    } else {
        fog
    }
}

/// The colour of air thick with sand or dust (a brown-orange haze, as photographed
/// in haboobs and Saharan dust events).
pub const DUST_HAZE_COLOUR: Vec3 = Vec3::new(0.66, 0.5, 0.33);

/// The colour of the sky and the fog in `weather`: sand and dust scatter the
/// daylight warm, so the haze takes their colour in proportion to their share of
/// the extinction (the backends clear the frame to it, too).
#[must_use]
pub fn haze_colour(settings: &RenderSettings, weather: &Weather) -> Vec3 {
    let extinction_per_m = settings.clear_air_extinction_per_m + weather.extinction_per_m();
    let grain_share = (weather.grain_extinction_per_m() / extinction_per_m.max(f32::MIN_POSITIVE))
        .clamp(0.0, 1.0);
    settings.sky_colour.lerp(DUST_HAZE_COLOUR, grain_share)
}

impl RenderParams {
    /// The block for one frame.
    #[must_use]
    pub fn new(f: &FrameInputs<'_>) -> Self {
        let camera = &f.view.camera;
        let aspect = f.view.width_px as f32 / f.view.height_px as f32;
        // Culling and the shadow map see the on-axis frustum enclosing a shifted one.
        let (enclosing_fov, enclosing_aspect) = camera.enclosing_frustum(aspect);
        let enclosing = Camera {
            vertical_fov_rad: enclosing_fov,
            lens_shift: glam::Vec2::ZERO,
            ..*camera
        };
        let hfov = horizontal_fov_rad(&enclosing, enclosing_aspect);
        let cone_cos = view_cone_cos(hfov, enclosing_fov);
        let pixel_angle = 2.0 * (0.5 * camera.vertical_fov_rad).tan() / f.view.height_px as f32;
        let s = f.settings;
        let l = &s.lighting;
        let ground_cell = f.ground.cell_m();
        let extinction_per_m = s.clear_air_extinction_per_m + f.weather.extinction_per_m();
        let haze = haze_colour(s, f.weather);
        let wind = f.weather.wind.mean_wind_mps;
        let sea_rows = if f.sea {
            s.sea.rows([wind.x, wind.z])
        } else {
            [Vec4::ZERO; 6]
        };
        Self {
            view_proj: view_projection(camera, aspect),
            sun_view_proj: crate::drawing::shadow_fit::fitted_sun_view_projection(
                s.to_sun,
                f.shadow_bounds_m,
                &enclosing,
                enclosing_aspect,
                crate::drawing::shadow_fit::shadow_distance_m(camera, extinction_per_m),
            ),
            camera_m_cone_cos: camera.position_m.extend(cone_cos),
            view_dir_pixel_angle: camera.forward.normalize().extend(pixel_angle),
            to_sun_extinction: s.to_sun.normalize().extend(extinction_per_m),
            sky_colour_time: haze.extend(f.time_s),
            light: Vec4::new(l.ambient, l.diffuse, l.specular, l.shininess),
            shadow: Vec4::new(
                l.shadow_colour,
                l.shadow_density,
                l.attenuation,
                1.0 / s.shadow_map_px as f32,
            ),
            sizing: Vec4::new(
                s.sizing.snow_scale,
                // In drawn pixels: a sprite or streak is at least `min_px` of the
                // particles' image, whatever its resolution (below, it is splatted).
                s.sizing.min_px * s.particle_resolution.factor() as f32,
                // The enlarged sprite's least ink kept in the frame's pixels: over
                // factor² of them a drawn pixel.
                s.sizing.min_opacity / (s.particle_resolution.factor().pow(2)) as f32,
                f.view.camera.lens.exposure_s,
            ),
            cover_look: Vec4::new(
                s.rain_opacity,
                if s.snow_displacement { 1.0 } else { 0.0 },
                f.cover_params.cover_depletion_exponent,
                f.cover_params.mask_edge,
            ),
            cover_look2: Vec4::new(
                f.cover_params.wet_darkening,
                f.cover_params.albedo_decay_per_day,
                crate::scene::displacement::exposure_tolerance_m(ground_cell),
                crate::drawing::flake_mean_opacity(),
            ),
            water_look: Vec4::new(
                crate::drawing::water_look::ring_rate_per_m2_s(f.weather.rain_rate_mm_per_h()),
                0.0,
                s.water_body_depth_m,
                0.0,
            ),
            ground: f.ground,
            cover: f.cover,
            waves: f.waves,
            counts: UVec4::new(
                f.particle_count,
                u32::from(s.view_cone_culling),
                f.cull_groups,
                if s.splat_sub_pixel {
                    f.view.width_px
                } else {
                    0
                },
            ),
            pools: UVec4::new(
                f.pools.world_count,
                f.pools.lift_from,
                f.pools.camera_drawn_end,
                f.pools.snow_copies,
            ),
            camera_box_centre_m: f
                .pools
                .camera_box_m
                .map_or(Vec3::ZERO, |b| b.0)
                .extend(f.pools.world_multiplicity),
            camera_box_half_m: f
                .pools
                .camera_box_m
                .map_or(Vec3::ZERO, |b| b.1)
                .extend(f.pools.camera_multiplicity),
            lens: Vec4::new(
                f.view
                    .camera
                    .lens
                    .aperture_m(f.view.camera.vertical_fov_rad),
                f.view.camera.lens.focus_distance_m,
                s.particle_resolution.factor() as f32,
                0.0,
            ),
            inverse_view_proj: view_projection(camera, aspect).inverse(),
            previous_view_proj: view_projection(camera, aspect),
            mirror_view_proj: view_projection(camera, aspect),
            mirror: Vec4::ZERO,
            clouds: cloud_layer_rows(&f.settings.cloud_layers),
            cloud_extinction: cloud_extinction_row(
                &f.settings.cloud_layers,
                f.weather.extinction_per_m() - f.weather.grain_extinction_per_m(),
            ),
            cloud_drift: f
                .settings
                .cloud_layers
                .lowest()
                .map_or(Vec4::ZERO, |lowest| {
                    let beyond = Weather {
                        intensity_mm_per_h: f
                            .settings
                            .rate_beyond_mm_per_h
                            .unwrap_or(f.weather.intensity_mm_per_h),
                        ..*f.weather
                    };
                    cloud_drift_m(f.weather.wind.mean_wind_mps, f.time_s)
                        .extend(shaft_extinction_per_m(&beyond, &lowest))
                        .extend(0.0)
                }),
            fog_layer: air_layer(f.settings, f.weather, f.time_s, camera.position_m),
            cloud_shadow: Vec4::new(
                f.settings.cloud_layers.sun_transmittance(
                    cloud_noise(),
                    cloud_drift_m(f.weather.wind.mean_wind_mps, f.time_s),
                    Vec3::new(camera.position_m.x, 0.0, camera.position_m.z),
                    f.settings.to_sun.normalize(),
                ),
                crate::drawing::clouds::CLOUD_MARCH_ALL as f32,
                0.0,
                0.0,
            ),
            far_ground: f
                .far_ground_level_m
                .map_or(Vec4::ZERO, |level| Vec4::new(level, 1.0, 0.0, 0.0)),
            cloud_shadow_map: if f.settings.cloud_layers.is_empty() {
                Vec4::ZERO
            } else {
                let origin = crate::drawing::clouds::cloud_shadow_map_origin_m(glam::Vec2::new(
                    camera.position_m.x,
                    camera.position_m.z,
                ));
                Vec4::new(origin.x, origin.y, 1.0, 0.0)
            },
            unresolved_streaks: Vec4::ZERO,
            streak_direction: Vec4::ZERO,
            streak_origin: Vec4::ZERO,
            ocean_wind: sea_rows[0],
            ocean: sea_rows[1],
            sea_colour: sea_rows[2],
            sea_attenuation: sea_rows[3],
            sea_bed: sea_rows[4],
            ocean_spectrum: sea_rows[5],
            shore_grid: Vec4::ZERO,
            shore_size: Vec4::ZERO,
            shore_edges: Vec4::ZERO,
            shore_steps: Vec4::ZERO,
            shore_waves: [Vec4::ZERO; crate::drawing::shore::SHORE_WAVE_COMPONENTS],
            terrain: Vec4::ZERO,
            terrain_levels: UVec4::ZERO,
            terrain_samples: [UVec4::ZERO; crate::scene::terrain::MAX_TERRAIN_LEVELS / 2],
            terrain_windows: [UVec4::ZERO; crate::scene::terrain::MAX_TERRAIN_LEVELS / 4],
            far_cover_grid: Vec4::ZERO,
            far_cover_cells: UVec4::ZERO,
            land_cover: UVec4::ZERO,
            land_cover_extent: Vec4::ZERO,
            land_classes: land_class_rows(),
        }
        .with_unresolved_streaks(f, pixel_angle, aspect)
    }

    /// The block with the shore's rows `rows` ([`crate::drawing::shore::ShoreFrames::next_frame`]).
    #[must_use]
    pub fn with_shore_rows(mut self, rows: &[Vec4; crate::drawing::shore::SHORE_ROWS]) -> Self {
        self.shore_grid = rows[0];
        self.shore_size = rows[1];
        self.shore_edges = rows[2];
        self.shore_steps = rows[3];
        self.shore_waves.copy_from_slice(&rows[4..]);
        self
    }

    /// The block with where the cover beyond the grid is read
    /// ([`crate::host::HostState::far_cover_rows`]).
    #[must_use]
    pub fn with_far_cover_rows(mut self, rows: &crate::host::FarCoverRows) -> Self {
        self.far_cover_grid = rows.grid;
        self.far_cover_cells = rows.cells;
        self
    }

    /// The block with the terrain's land cover rows
    /// ([`crate::host::HostState::land_cover_rows`]).
    #[must_use]
    pub fn with_land_cover_rows(mut self, rows: &crate::scene::terrain::LandCoverRows) -> Self {
        self.land_cover = rows.pixels;
        self.land_cover_extent = rows.extent_m;
        self
    }

    /// The terrain's clipmap rows it holds.
    #[must_use]
    pub fn clipmap_rows(&self) -> crate::scene::terrain::ClipmapRows {
        crate::scene::terrain::ClipmapRows {
            placement: self.terrain,
            levels: self.terrain_levels,
            samples: self.terrain_samples,
            windows: self.terrain_windows,
        }
    }

    /// The block with the terrain's clipmap rows ([`crate::host::HostState::clipmap_rows`]).
    #[must_use]
    pub fn with_clipmap_rows(mut self, rows: &crate::scene::terrain::ClipmapRows) -> Self {
        self.terrain = rows.placement;
        self.terrain_levels = rows.levels;
        self.terrain_samples = rows.samples;
        self.terrain_windows = rows.windows;
        self
    }

    /// The block with the grain of `f`'s weather beyond its camera volume
    /// ([`crate::drawing::unresolved_streaks`]).
    fn with_unresolved_streaks(
        mut self,
        f: &FrameInputs<'_>,
        pixel_angle: f32,
        aspect: f32,
    ) -> Self {
        use crate::drawing::unresolved_streaks::{UnresolvedStreaks, unresolved_size_classes};
        let m_world = f.pools.world_multiplicity;
        let unresolved = if m_world > 1.0 {
            1.0 - 1.0 / m_world
        } else {
            0.0
        };
        let classes = unresolved_size_classes(f.weather, unresolved);
        let exposure_s = f.view.camera.lens.exposure_s;
        let near_m = f
            .pools
            .camera_box_m
            .map_or(0.0, |(_, half)| half.x.min(half.z));
        let grain = UnresolvedStreaks::of(&classes, exposure_s, pixel_angle, near_m);
        if grain.scale <= 0.0 {
            return self;
        }
        // The fall's direction on screen at the grain's depth ahead of the camera.
        let camera = &f.view.camera;
        let ahead = camera.position_m + camera.forward.normalize() * grain.near_m;
        let moved = ahead + grain.velocity_mps.normalize_or_zero() * 0.01 * grain.near_m;
        let view_proj = view_projection(camera, aspect);
        let screen = |p: Vec3| {
            let clip = view_proj * p.extend(1.0);
            glam::Vec2::new(clip.x, -clip.y) / clip.w.max(1.0e-6)
                * glam::Vec2::new(f.view.width_px as f32, f.view.height_px as f32)
        };
        let along = (screen(moved) - screen(ahead))
            .try_normalize()
            .unwrap_or(glam::Vec2::Y);
        let exposure = if exposure_s > 0.0 {
            (f.time_s / exposure_s).floor()
        } else {
            0.0
        };
        self.unresolved_streaks =
            Vec4::new(grain.scale, grain.reach_m, grain.near_m, grain.length_px);
        self.streak_direction = Vec4::new(along.x, along.y, exposure % 16_777_216.0, 0.0);
        let (w, h) = (f.view.width_px as f32, f.view.height_px as f32);
        let shift = camera.lens_shift;
        self.streak_origin = Vec4::new(
            0.5 * w * (shift.x - 1.0),
            -0.5 * h * (1.0 + shift.y),
            0.0,
            0.0,
        );
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_quality_level_sets_only_its_knobs() {
        let mine = RenderSettings {
            shadow_map_px: 4096,
            rain_opacity: 0.7,
            mirrors: Mirrors::AllWater,
            ..RenderSettings::default()
        };
        let high = mine.at_quality(Quality::High);
        assert_eq!(high, mine);
        let medium = mine.at_quality(Quality::Medium);
        assert_eq!(medium.particle_resolution, ParticleResolution::Half);
        assert_eq!(
            RenderSettings {
                particle_resolution: ParticleResolution::Full,
                ..medium
            },
            mine
        );
        let low = mine.at_quality(Quality::Low);
        assert_eq!(low.particle_resolution, ParticleResolution::Quarter);
        assert_eq!(
            (low.shadow_map_px, low.mirrors, low.shadow_refresh_frames),
            (1024, Mirrors::WaterBodies, LOW_SHADOW_REFRESH_FRAMES)
        );
        assert_eq!(
            RenderSettings {
                particle_resolution: ParticleResolution::Full,
                shadow_map_px: 4096,
                shadow_refresh_frames: 1,
                mirrors: Mirrors::AllWater,
                ..low
            },
            mine,
            "the look's other settings are kept"
        );
        assert!(low.validate().is_ok());
        assert_eq!(
            ParticleResolution::Quarter.drawn_size((1281, 720)),
            (321, 180)
        );
    }

    #[test]
    fn the_camera_matrix_puts_the_view_direction_at_the_centre() {
        let camera = Camera::default();
        let m = view_projection(&camera, 1.5);
        let ahead = camera.position_m + camera.forward * 10.0;
        let clip = m * ahead.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        assert!(ndc.x.abs() < 1e-5 && ndc.y.abs() < 1e-5);
        assert!((0.0..=1.0).contains(&ndc.z));
        // The top edge of the vertical field of view maps to y = 1.
        let up = (0.5 * camera.vertical_fov_rad).tan() * 10.0;
        let top = m * (ahead + Vec3::Y * up).extend(1.0);
        assert!((top.y / top.w - 1.0).abs() < 1e-4);
        // Shifted half a height up, the top edge is the image's centre.
        let shifted = Camera {
            lens_shift: glam::Vec2::new(0.0, 1.0),
            ..camera
        };
        let top = view_projection(&shifted, 1.5) * (ahead + Vec3::Y * up).extend(1.0);
        assert!((top.y / top.w).abs() < 1e-4);
    }

    #[test]
    fn the_sun_view_encloses_the_box() {
        let (lo, hi) = (Vec3::new(-20.0, 0.0, -20.0), Vec3::new(20.0, 6.0, 20.0));
        let m = sun_view_projection(Vec3::new(0.4, 0.8, 0.3), lo, hi);
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            let p = m * c.extend(1.0);
            assert!(
                p.x.abs() <= 1.0 && p.y.abs() <= 1.0 && (0.0..=1.0).contains(&p.z),
                "{c}"
            );
        }
        // Straight overhead sun: the fallback up axis.
        let m = sun_view_projection(Vec3::Y, lo, hi);
        assert!(m.is_finite());
    }

    #[test]
    fn bad_settings_and_views_are_refused() {
        assert!(RenderSettings::default().validate().is_ok());
        for bad in [
            RenderSettings {
                to_sun: Vec3::NEG_Y,
                ..RenderSettings::default()
            },
            RenderSettings {
                shadow_map_px: 0,
                ..RenderSettings::default()
            },
            RenderSettings {
                rain_opacity: f32::NAN,
                ..RenderSettings::default()
            },
        ] {
            assert!(matches!(bad.validate(), Err(BackendError::Setup { .. })));
        }
        let view = |w, h| View {
            camera: Camera::default(),
            width_px: w,
            height_px: h,
        };
        assert!(validate_view(&view(64, 48)).is_ok());
        for (w, h) in [(0, 10), (10, 0), (100_000, 10)] {
            assert!(matches!(
                validate_view(&view(w, h)),
                Err(BackendError::InvalidView(_))
            ));
        }
    }
}
