//! A layer of volumetric clouds: where they stand, how dense, how they are lit
//! (docs/model.md (6.9)–(6.12)).
//!
//! *Source: seed 002's volumetric clouds (Perlin noise in a texture, a height
//! distribution function shaping the cloud, a threshold cutting thin parts, rays
//! marched from the camera and secondary rays toward the sun), with the layer's
//! coverage made exact and the light as in Schneider & Vos 2015 (Beer's law along
//! the sun's ray, a two-lobe Henyey–Greenstein phase function).*
//!
//! ## Where the cloud is
//!
//! A point `p` of the layer `[base, base + thickness]` is in a cloudy column when the
//! coverage map `m(x, z)` (tiling Perlin noise whose values are replaced by their rank,
//! so they are spread evenly over `[0, 1)`), raised by the detail, `m′ = m + A·d(p)`,
//! is below the coverage `c`: the share of the sky the layer covers is about `c`
//! whatever the noise. Inside a column the density is `edge(c − m′)·profile(h/r)`,
//! `r = clamp((c − m′)/D, 0.05, 1)` the share of the layer the column reaches
//! (domes rising from their edges), cut by the seed's threshold τ and rescaled:
//! `max(0, (ρ − τ)/(1 − τ))`; `h` is the height in the layer (0 at its base, 1 at
//! its top), `profile` the kind's (stratus thin and flat, cumulus rising from a flat
//! base to a rounded top, cumulonimbus filling the whole depth), `d` the tiling 3D
//! Perlin–Worley detail at `p` (`detail`, docs/model.md (6.9b)): where it is high
//! the column's side and its dome's top move in by up to [`CLOUD_DETAIL_DEPTH`] of
//! the map's range, so billows are carved into them. The map and the detail drift
//! with the mean wind. Both textures are [`CloudNoise`].
//!
//! ## How it is lit
//!
//! Along the camera's ray through the layer, in `N` steps: extinction `σ = σ_max·ρ`,
//! the sun's light dimmed by `e^(−Σσ·Δ)` over secondary samples toward it, scattered
//! by the two-lobe phase function [`cloud_phase`] with octaves of multiple
//! scattering ([`cloud_sun_light`]); the sky's light scattered
//! isotropically, weaker with depth below the top. Each step adds its scattered light
//! integrated over the step (`S·(1 − e^(−σΔ))/σ`, energy conserving: Hillaire 2016)
//! times the transmittance so far.
//!
//! ## A sixteenth a frame
//!
//! A frame marches one pixel in each block of 4 × 4 of the clouds' image
//! ([`cloud_march_slot`], [`cloud_fresh_pixel`]) into a small image of its own,
//! and takes every other pixel from the frame before's image where its camera saw
//! it ([`cloud_history_uv`]), clamped to what this frame marched around it
//! ([`cloud_history_clamped`]) as far as the camera's move makes the history
//! stale ([`cloud_history_clamp_weight`]; docs/model.md (6.14)).
//!
//! WGSL twins: `cloud_profile`, `cloud_density`, `cloud_map_uv`, `cloud_phase`, `cloud_slab`,
//! `cloud_march_slot`, `cloud_fresh_pixel`, `cloud_history_uv`,
//! `cloud_history_clamped`, `cloud_history_clamp_weight` in drawing.wgsl, `clouds_with_history` in
//! render_clouds.wgsl.

use glam::{Mat4, UVec2, Vec2, Vec3, Vec4};

use crate::BackendError;

mod detail;
mod layers;
mod shadow_map;
mod shafts;
pub use detail::{
    CLOUD_BILLOW_SHARE, CLOUD_DETAIL_ATLAS_COLUMNS, CLOUD_DETAIL_ATLAS_PX, CLOUD_DETAIL_PX,
    CLOUD_DETAIL_TILE_PX, cloud_detail, cloud_detail_at, cloud_detail_atlas,
    cloud_detail_atlas_texels, cloud_detail_point, sample_cloud_detail_atlas,
};
pub use layers::{CloudLayers, MAX_CLOUD_LAYERS, cloud_layer_map_offset_m};
pub use shadow_map::{
    CLOUD_SHADOW_MAP_FADE, CLOUD_SHADOW_MAP_PX, CLOUD_SHADOW_MAP_SPAN_M, cloud_shadow_map,
    cloud_shadow_map_origin_m, cloud_shadow_map_point_m, cloud_shadow_map_weight,
};
pub use shafts::{
    CLOUD_BASE_SKY_SHARE, HazeExtinctions, LOCAL_WEATHER_RADIUS_M, MIN_SHAFT_COVERAGE,
    RAIN_SHAFT_SAMPLES, precipitation_haze, shaft_extinction_per_m, shaft_share,
};

/// The cloud types the layer can have (WMO genera).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CloudKind {
    /// A thin, flat, grey sheet (drizzle).
    Stratus,
    /// A thick, dark, even deck (steady rain and snow).
    #[default]
    Nimbostratus,
    /// Separate heaps with flat bases and rounded tops (fair weather).
    Cumulus,
    /// Towers through the whole troposphere's lower part (downpours, hail).
    Cumulonimbus,
}

impl CloudKind {
    /// Every kind, in the order of [`CloudKind::index`].
    pub const ALL: [Self; 4] = [
        Self::Stratus,
        Self::Nimbostratus,
        Self::Cumulus,
        Self::Cumulonimbus,
    ];

    /// The kind's number in the uniform block (0–3).
    #[must_use]
    pub const fn index(self) -> u32 {
        match self {
            Self::Stratus => 0,
            Self::Nimbostratus => 1,
            Self::Cumulus => 2,
            Self::Cumulonimbus => 3,
        }
    }

    /// Typical base and thickness, m (WMO International Cloud Atlas: stratus below
    /// 500 m and a few hundred metres thick; nimbostratus from about 600 m, kilometres
    /// thick; cumulus bases near 1 km, a kilometre or two deep; cumulonimbus towering
    /// 8 km or more).
    #[must_use]
    pub const fn typical_base_thickness_m(self) -> (f32, f32) {
        match self {
            Self::Stratus => (300.0, 400.0),
            Self::Nimbostratus => (600.0, 2_500.0),
            Self::Cumulus => (1_000.0, 1_500.0),
            Self::Cumulonimbus => (800.0, 8_000.0),
        }
    }

    /// The height profile's rise and fall `(a, b)`: `profile(h) = smoothstep(0, a,
    /// h)·(1 − smoothstep(b, 1, h))`.
    #[must_use]
    pub const fn profile_rise_fall(self) -> (f32, f32) {
        match self {
            Self::Stratus => (0.15, 0.6),
            Self::Nimbostratus => (0.05, 0.85),
            Self::Cumulus => (0.07, 0.35),
            Self::Cumulonimbus => (0.02, 0.8),
        }
    }

    /// The most extinction inside, per m: visibility inside water clouds is some 20
    /// to 130 m (`3/σ`), thicker in convective cores.
    #[must_use]
    pub const fn extinction_per_m(self) -> f32 {
        match self {
            Self::Stratus => 0.03,
            Self::Nimbostratus => 0.05,
            Self::Cumulus => 0.06,
            Self::Cumulonimbus => 0.1,
        }
    }
}

/// A layer of clouds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudLayer {
    /// Height of its base, m (world `y`).
    pub base_m: f32,
    /// Its thickness, m.
    pub thickness_m: f32,
    /// The share of the sky it covers, `[0, 1]` (oktas / 8).
    pub coverage: f32,
    /// Its type.
    pub kind: CloudKind,
    /// The height of the band below its base and above its top over which the air
    /// thickens from clear to the layer's ([`CloudLayer::mean_extinction_per_m`]),
    /// m: CIGI's transition band; 0 for a sharp edge (docs/model.md (6.13)).
    pub transition_band_m: f32,
}

impl CloudLayer {
    /// A layer of `kind` at its typical base and thickness covering `coverage`.
    #[must_use]
    pub const fn typical(kind: CloudKind, coverage: f32) -> Self {
        let (base_m, thickness_m) = kind.typical_base_thickness_m();
        Self {
            base_m,
            thickness_m,
            coverage,
            kind,
            transition_band_m: 0.0,
        }
    }

    /// The deck `weather` falls from, covering `coverage`: its kind's
    /// ([`crate::PrecipitationKind::falls_from`]).
    #[must_use]
    pub fn implied_by(weather: &crate::Weather, coverage: f32) -> Self {
        Self::typical(
            weather.kind.falls_from(weather.intensity_mm_per_h),
            coverage,
        )
    }

    /// Its top, m.
    #[must_use]
    pub fn top_m(&self) -> f32 {
        self.base_m + self.thickness_m
    }

    /// The layer's extinction spread over its area, per m: its clouds' most
    /// extinction times its coverage (what the air of its transition band tends
    /// to at the layer).
    #[must_use]
    pub fn mean_extinction_per_m(&self) -> f32 {
        self.kind.extinction_per_m() * self.coverage
    }

    /// How much of [`CloudLayer::mean_extinction_per_m`] the air at height `y_m`
    /// outside the layer has: `1 − d/b` within its transition band `b`, `d` the
    /// distance to the layer, 0 beyond and within the layer (its clouds are there).
    #[must_use]
    pub fn band_share(&self, y_m: f32) -> f32 {
        let d = (self.base_m - y_m).max(y_m - self.top_m());
        if d <= 0.0 || self.transition_band_m <= 0.0 {
            return 0.0;
        }
        (1.0 - d / self.transition_band_m).max(0.0)
    }

    /// The heights its clouds and its transition band span, m.
    #[must_use]
    pub fn extent_with_band_m(&self) -> (f32, f32) {
        let b = self.transition_band_m.max(0.0);
        (self.base_m - b, self.top_m() + b)
    }

    /// Checks the base (within ±20 km), thickness (`[10, 15 000]` m) and coverage.
    pub fn validate(&self) -> Result<(), BackendError> {
        let bad = |field, problem: String| Err(BackendError::Setup { field, problem });
        if !(self.base_m.is_finite() && self.base_m.abs() <= 20_000.0) {
            return bad(
                "render.cloud_layers[].base_m",
                format!("= {} must be a height within ±20 000 m", self.base_m),
            );
        }
        if !(self.thickness_m.is_finite() && (10.0..=15_000.0).contains(&self.thickness_m)) {
            return bad(
                "render.cloud_layers[].thickness_m",
                format!("= {} must be in [10, 15000] m", self.thickness_m),
            );
        }
        if !(self.coverage.is_finite() && (0.0..=1.0).contains(&self.coverage)) {
            return bad(
                "render.cloud_layers[].coverage",
                format!(
                    "= {} must be in [0, 1] (a fraction of the sky: oktas / 8)",
                    self.coverage
                ),
            );
        }
        if !(self.transition_band_m.is_finite()
            && (0.0..=5_000.0).contains(&self.transition_band_m))
        {
            return bad(
                "render.cloud_layers[].transition_band_m",
                format!(
                    "= {} must be in [0, 5000] m (0: a sharp edge)",
                    self.transition_band_m
                ),
            );
        }
        Ok(())
    }
}

/// The coverage map's side, texels.
pub const CLOUD_MAP_PX: u32 = 256;
/// The ground distance one period of the coverage map spans, m.
pub const CLOUD_MAP_PERIOD_M: f32 = 12_000.0;
/// The detail volume's period along each axis, m.
pub const CLOUD_DETAIL_PERIOD_M: f32 = 1_700.0;
/// How far the detail `d` raises a point's map value, `A` (its column's edge and
/// its dome's top move by up to this much of the map's range: billows).
pub const CLOUD_DETAIL_DEPTH: f32 = 0.12;
/// The seed's threshold τ: density below it is cut.
pub const CLOUD_THRESHOLD: f32 = 0.12;
/// The width of a column's edge in the coverage map's values.
pub const CLOUD_EDGE: f32 = 0.04;
/// How far below the coverage the map must lie for a column to reach the layer's
/// top: a column of `c − m` reaches `min(1, (c − m)/D)` of it (at least a twentieth),
/// so clouds rise into domes from their edges (the seed's height distribution).
pub const CLOUD_DOME: f32 = 0.25;
/// Steps along the camera's ray through the layer.
pub const CLOUD_VIEW_STEPS: u32 = 20;
/// Secondary samples toward the sun from each step.
pub const CLOUD_SUN_SAMPLES: u32 = 3;
/// The longest path through the layer marched, m (beyond, the haze hides it).
pub const CLOUD_MAX_PATH_M: f32 = 30_000.0;
/// The longest path marched from a camera inside the layer, m: a cloud's visibility
/// is tens of metres, so the steps stay short enough to meet the cloud around the
/// camera (over the full path they would step past it and show far clouds
/// through it as sparkles).
pub const CLOUD_INSIDE_PATH_M: f32 = 2_000.0;
/// The two lobes of the phase function: forward asymmetry, backward asymmetry and
/// the forward lobe's weight (a silver lining toward the sun, a little back-scatter
/// away from it; Schneider & Vos 2015 use two lobes the same way).
pub const CLOUD_LOBES: (f32, f32, f32) = (0.8, -0.3, 0.75);

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The kind's height profile at `h` (0 at the base, 1 at the top).
#[must_use]
pub fn cloud_profile(kind: CloudKind, h: f32) -> f32 {
    let (a, b) = kind.profile_rise_fall();
    if !(0.0..=1.0).contains(&h) {
        return 0.0;
    }
    smoothstep(0.0, a, h) * (1.0 - smoothstep(b, 1.0, h))
}

/// How much a column whose coverage-map value is `m` stands under a cloud of a
/// layer covering `coverage`: 1 inside, 0 outside, a narrow edge between.
#[must_use]
pub fn cloud_column(coverage: f32, m: f32) -> f32 {
    smoothstep(0.0, CLOUD_EDGE, coverage - m)
}

/// The density `[0, 1]` at height fraction `h` of a column whose coverage-map value
/// is `m`, with detail `d`, in a layer covering `coverage` (module docs).
#[must_use]
pub fn cloud_density(kind: CloudKind, coverage: f32, m: f32, d: f32, h: f32) -> f32 {
    let carved = m + CLOUD_DETAIL_DEPTH * d;
    let column = cloud_column(coverage, carved);
    let reach = ((coverage - carved) / CLOUD_DOME).clamp(0.05, 1.0);
    let raw = column * cloud_profile(kind, h / reach);
    ((raw - CLOUD_THRESHOLD) / (1.0 - CLOUD_THRESHOLD)).max(0.0)
}

/// The two-lobe Henyey–Greenstein phase function, mean 1 over the sphere
/// ([`CLOUD_LOBES`]); `cos_mu` between the sun's light and the way to the camera.
#[must_use]
pub fn cloud_phase(cos_mu: f32) -> f32 {
    cloud_phase_scaled(cos_mu, 1.0)
}

/// The two-lobe phase function with both asymmetries scaled by `scale`.
fn cloud_phase_scaled(cos_mu: f32, scale: f32) -> f32 {
    let (g1, g2, w) = CLOUD_LOBES;
    let hg = |g: f32| {
        let g = g * scale;
        let d = 1.0 + g * g - 2.0 * g * cos_mu.clamp(-1.0, 1.0);
        (1.0 - g * g) / (d * d.sqrt())
    };
    w * hg(g1) + (1.0 - w) * hg(g2)
}

/// Octaves of multiple scattering (Wrenninge, Kulla & Lundqvist 2013, *Oz: the
/// great and volumetric*; as Hillaire 2016): the sun's light scattered toward the
/// camera by a unit of extinction behind an optical depth `optical` toward the sun,
/// `Σₙ aⁿ·P(μ; cⁿg)·e^(−bⁿ·τ)` over [`CLOUD_OCTAVES`] octaves, `a = b = c = ½`: light
/// scattered many times goes deeper, less peaked, so a thick cloud is bright on its
/// sunlit side, not only where it glows forward.
#[must_use]
pub fn cloud_sun_light(cos_mu: f32, optical: f32) -> f32 {
    (0..CLOUD_OCTAVES)
        .map(|n| {
            let k = 0.5f32.powi(n as i32);
            k * cloud_phase_scaled(cos_mu, k) * (-k * optical).exp()
        })
        .sum()
}

/// Octaves in [`cloud_sun_light`].
pub const CLOUD_OCTAVES: u32 = 3;

/// Where a ray from `camera_y_m` going up `dir_y` a metre crosses the layer
/// `[base_m, top_m]`: `(t₀, t₁)`, at most [`CLOUD_MAX_PATH_M`] long, and at most
/// [`CLOUD_INSIDE_PATH_M`] from a camera inside the layer; `t₀ = t₁` when it does
/// not.
#[must_use]
pub fn cloud_slab(camera_y_m: f32, dir_y: f32, base_m: f32, top_m: f32) -> (f32, f32) {
    let (s0, s1) = crate::drawing::fog_layer::fog_layer_segment(
        camera_y_m,
        dir_y,
        CLOUD_MAX_PATH_M * 4.0,
        base_m,
        top_m,
    );
    let longest = if (base_m..=top_m).contains(&camera_y_m) {
        CLOUD_INSIDE_PATH_M
    } else {
        CLOUD_MAX_PATH_M
    };
    (s0, s1.min(s0 + longest))
}

/// Side of the block of the clouds' image one pixel of which a frame marches, px:
/// the clouds' fresh image is this many times smaller along each side.
pub const CLOUD_MARCH_BLOCK_PX: u32 = 4;
/// Frames over which every pixel is marched once; the slot that marches every
/// pixel (no history to reproject).
pub const CLOUD_MARCH_ALL: u32 = 16;
/// How far past the range of the freshly marched neighbours a pixel's history may
/// lie, as a share of that range (plus [`CLOUD_HISTORY_SLACK`]): a pixel's own
/// light is often just outside its neighbours' (a bright rim), and clamping it
/// there would flicker.
pub const CLOUD_HISTORY_MARGIN: f32 = 0.25;
/// The least slack of the clamp, in the image's units (light and opacity, 0 … 1).
pub const CLOUD_HISTORY_SLACK: f32 = 0.02;
/// How deep behind a ray's entry into a layer its parallax is measured, m (about
/// as deep as a ray sees into a cumulus).
pub const CLOUD_PARALLAX_DEPTH_M: f32 = 500.0;
/// The parallax a frame, px of the clouds' image, at which a reused pixel is
/// clamped fully: over the [`CLOUD_MARCH_ALL`] frames it may be reused, 4 px.
pub const CLOUD_PARALLAX_FULL_PX: f32 = 0.25;

/// The weight of a pixel's new march against its history (an exponential mean
/// over its marches, one every [`CLOUD_MARCH_ALL`] frames, each at other depths:
/// [`cloud_march_round_offset`]): the grain of a march at grazing angles, where a
/// step spans kilometres, averages out over about `2/w − 1` marches.
pub const CLOUD_FRESH_WEIGHT: f32 = 0.25;

/// The weight of a pixel's new march against its history: [`CLOUD_FRESH_WEIGHT`]
/// where the history is this pixel's own, unchanged (the camera still, the history
/// read at a texel's centre, `history_px` its place in texels), rising to 1 — the
/// new march alone — as the history is read a quarter of a texel or more off a
/// centre (a bilinear read of a moving camera's image blurs, and would blur again
/// at each frame it is kept) or is clamped (`clamp_weight`,
/// [`cloud_history_clamp_weight`]). WGSL twin: `cloud_fresh_weight` (drawing.wgsl).
#[must_use]
pub fn cloud_fresh_weight(clamp_weight: f32, history_px: Vec2) -> f32 {
    let from_centre = history_px - Vec2::splat(0.5);
    let off = from_centre - from_centre.round();
    let resampled = (off.length() * 4.0).clamp(0.0, 1.0);
    CLOUD_FRESH_WEIGHT.max(clamp_weight).max(resampled)
}

/// The offset of the march's jitter in round `round` (`frame / CLOUD_MARCH_ALL`),
/// `[0, 1)`: the golden ratio's multiples, so a pixel's successive marches fall
/// between each other's steps. WGSL reads it from `cloud_drift.w`.
#[must_use]
pub fn cloud_march_round_offset(round: u64) -> f32 {
    const GOLDEN: f64 = 0.618_033_988_749_895;
    ((round % 1_000_003) as f64 * GOLDEN).fract() as f32
}

/// The 4 × 4 Bayer order: the frame of [`CLOUD_MARCH_ALL`] that marches the pixel
/// at `(x mod 4, y mod 4)` of its block, row by row.
const BAYER: [u32; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];

/// Which frame of [`CLOUD_MARCH_ALL`] marches `pixel` of the clouds' image: the
/// 4 × 4 Bayer order within each block, so a frame's pixels are one per block and
/// consecutive frames' lie far apart (Schneider & Vos 2015, *The real-time
/// volumetric cloudscapes of Horizon Zero Dawn*: one pixel in 16 a frame). WGSL
/// twin: `cloud_march_slot` (drawing.wgsl).
#[must_use]
pub fn cloud_march_slot(pixel: UVec2) -> u32 {
    BAYER[((pixel.y % 4) * 4 + pixel.x % 4) as usize]
}

/// The pixel of the clouds' image that pixel `fresh` of the fresh image marches in
/// frame `slot` (below [`CLOUD_MARCH_ALL`]): the one of block `fresh` whose
/// [`cloud_march_slot`] is `slot`. WGSL twin: `cloud_fresh_pixel` (drawing.wgsl).
#[must_use]
pub fn cloud_fresh_pixel(fresh: UVec2, slot: u32) -> UVec2 {
    let k = BAYER
        .iter()
        .position(|&b| b == slot % CLOUD_MARCH_ALL)
        .unwrap_or(0) as u32;
    fresh * CLOUD_MARCH_BLOCK_PX + UVec2::new(k % 4, k / 4)
}

/// A pixel's history (light premultiplied, opacity) clamped to the range `low …
/// high` of this frame's freshly marched pixels around it, widened by
/// [`CLOUD_HISTORY_MARGIN`] of the range and at least [`CLOUD_HISTORY_SLACK`]:
/// what the frame before saw there but the clouds no longer show (they moved,
/// grew, or the camera saw them from elsewhere) cannot stay (the neighbourhood
/// clamp of temporal reprojection, Karis 2014, *High-quality temporal
/// supersampling*). WGSL twin: `cloud_history_clamped` (drawing.wgsl).
#[must_use]
pub fn cloud_history_clamped(history: Vec4, low: Vec4, high: Vec4) -> Vec4 {
    let slack = ((high - low) * CLOUD_HISTORY_MARGIN).max(Vec4::splat(CLOUD_HISTORY_SLACK));
    history.clamp(low - slack, high + slack)
}

/// How much of the clamp ([`cloud_history_clamped`]) a reused pixel takes, 0 … 1:
/// where the frame before's camera (`previous_view_proj`) saw the ray's entry
/// into the layer `entry_m` and the point [`CLOUD_PARALLAX_DEPTH_M`] deeper along
/// it `deeper_m` at one place of its image (`image_px` its size), the history is
/// this ray's (the camera turned, or the clouds drifted: both are reprojected
/// exactly) and is kept as it is: clamping it to the fresh pixels, 4 pixels
/// apart, would blur what lies between them. As the two part (the camera moved
/// across the ray: the history mixes in columns this ray does not cross), the
/// clamp takes over, fully at [`CLOUD_PARALLAX_FULL_PX`]. Behind that camera: 1.
/// WGSL twin: `cloud_history_clamp_weight` (drawing.wgsl).
#[must_use]
pub fn cloud_history_clamp_weight(
    previous_view_proj: Mat4,
    entry_m: Vec3,
    deeper_m: Vec3,
    image_px: Vec2,
) -> f32 {
    let a = previous_view_proj * entry_m.extend(1.0);
    let b = previous_view_proj * deeper_m.extend(1.0);
    if a.w <= 0.0 || b.w <= 0.0 {
        return 1.0;
    }
    let apart_px =
        ((Vec2::new(a.x, a.y) / a.w - Vec2::new(b.x, b.y) / b.w) * 0.5 * image_px).length();
    (apart_px / CLOUD_PARALLAX_FULL_PX).clamp(0.0, 1.0)
}

/// Where the clouds' image of the frame before (its camera `previous_view_proj`)
/// holds the point `p_m`: its texture coordinates (`v` down), or `None` where it
/// was behind that camera or outside its image (the pixel is marched again).
/// WGSL twin: `cloud_history_uv` (drawing.wgsl).
#[must_use]
pub fn cloud_history_uv(previous_view_proj: Mat4, p_m: Vec3) -> Option<Vec2> {
    let clip = previous_view_proj * p_m.extend(1.0);
    if clip.w <= 0.0 {
        return None;
    }
    let uv = Vec2::new(clip.x, -clip.y) / clip.w * 0.5 + 0.5;
    (uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()).then_some(uv)
}

/// The tiling coverage map: Perlin noise of five octaves over a [`CLOUD_MAP_PX`]²
/// torus, each value replaced by its rank (so the values spread evenly over
/// `[0, 1)`), as bytes (R8Unorm), deterministic.
#[must_use]
pub fn cloud_coverage_map() -> Vec<u8> {
    let n = CLOUD_MAP_PX as usize;
    let values: Vec<f32> = (0..n * n)
        .map(|i| {
            let p = Vec2::new((i % n) as f32, (i / n) as f32) / n as f32;
            octaves(5, |period, octave| {
                tiling_perlin(p * period as f32, period, octave)
            })
        })
        .collect();
    ranks(&values)
}

/// `Σ 2⁻ᵏ·noise(4·2ᵏ, k)` over `count` octaves `k`: a tiling noise's sum over
/// periods of 4, 8, 16, … lattice cells.
fn octaves(count: u32, noise: impl Fn(u32, u32) -> f32) -> f32 {
    (0..count)
        .map(|octave| noise(4u32 << octave, octave) / (1u32 << octave) as f32)
        .sum()
}

/// Each value replaced by its rank, as a byte: the values spread evenly over
/// `[0, 255]` (ties in the order of their index).
fn ranks(values: &[f32]) -> Vec<u8> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
    let mut bytes = vec![0u8; values.len()];
    for (rank, &i) in order.iter().enumerate() {
        bytes[i] = ((rank * 256) / values.len()) as u8;
    }
    bytes
}

/// 2D Perlin noise of period `period` (lattice cells) at `p`, about `[-0.7, 0.7]`.
fn tiling_perlin(p: Vec2, period: u32, seed: u32) -> f32 {
    let cell = p.floor();
    let f = p - cell;
    let corner = |dx: u32, dy: u32| {
        let x = (cell.x as i64 + i64::from(dx)).rem_euclid(i64::from(period)) as u32;
        let y = (cell.y as i64 + i64::from(dy)).rem_euclid(i64::from(period)) as u32;
        let h = crate::particles::rng::pcg_hash(
            x.wrapping_mul(0x9e37_79b1)
                ^ y.wrapping_mul(0x85eb_ca77)
                ^ seed.wrapping_mul(0xc2b2_ae3d),
        );
        let angle = (h as f32 / u32::MAX as f32) * std::f32::consts::TAU;
        Vec2::new(angle.cos(), angle.sin()).dot(f - Vec2::new(dx as f32, dy as f32))
    };
    let fade = |t: f32| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let (u, v) = (fade(f.x), fade(f.y));
    let a = corner(0, 0) + u * (corner(1, 0) - corner(0, 0));
    let b = corner(0, 1) + u * (corner(1, 1) - corner(0, 1));
    a + v * (b - a)
}

/// Samples along the sun's ray through the layer for a cloud's shadow.
pub const CLOUD_SHADOW_SAMPLES: u32 = 3;

/// The share of the sun's light that reaches `p` through the layer (its shadow on
/// the scene, docs/model.md (6.12)): `e^(−σ_max·Σρ·ℓ/n)` over [`CLOUD_SHADOW_SAMPLES`]
/// points of the sun's ray's part `ℓ` in the layer (at most [`CLOUD_MAX_PATH_M`]),
/// `to_sun` a unit vector, the map drifted by `offset_m`.
#[must_use]
pub fn cloud_sun_transmittance(
    noise: &CloudNoise,
    layer: &CloudLayer,
    offset_m: Vec2,
    p: Vec3,
    to_sun: Vec3,
) -> f32 {
    let (t0, t1) = cloud_slab(p.y, to_sun.y, layer.base_m, layer.top_m());
    if t1 <= t0 {
        return 1.0;
    }
    let n = CLOUD_SHADOW_SAMPLES;
    let density: f32 = (0..n)
        .map(|k| {
            let q = p + to_sun * (t0 + (t1 - t0) * (k as f32 + 0.5) / n as f32);
            noise.density(layer, offset_m, q)
        })
        .sum();
    (-layer.kind.extinction_per_m() * density * (t1 - t0) / n as f32).exp()
}

/// The clouds' two textures as the GPU holds them: the coverage map
/// ([`cloud_coverage_map`], R8) and the detail volume's atlas
/// ([`cloud_detail_atlas_texels`], RGBA8).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CloudNoise {
    /// The coverage map's texels.
    pub coverage: Vec<u8>,
    /// The detail atlas's texels.
    pub detail: Vec<u8>,
}

impl CloudNoise {
    /// Both textures, made (deterministic).
    #[must_use]
    pub fn make() -> Self {
        Self {
            coverage: cloud_coverage_map(),
            detail: cloud_detail_atlas_texels(),
        }
    }

    /// `layer`'s density `[0, 1]` at `p`, its map and detail drifted by `offset_m`,
    /// read as the GPU reads them (WGSL: `cloud_density_at`).
    #[must_use]
    pub fn density(&self, layer: &CloudLayer, offset_m: Vec2, p: Vec3) -> f32 {
        let h = (p.y - layer.base_m) / layer.thickness_m;
        let m = sample_coverage_map(&self.coverage, cloud_map_uv(p, offset_m));
        let d = cloud_detail_at(&self.detail, p, offset_m);
        cloud_density(layer.kind, layer.coverage, m, d, h)
    }
}

/// [`CloudNoise`], made once.
#[must_use]
pub fn cloud_noise() -> &'static CloudNoise {
    static NOISE: std::sync::OnceLock<CloudNoise> = std::sync::OnceLock::new();
    NOISE.get_or_init(CloudNoise::make)
}

/// How far the clouds have drifted by `time_s` in a mean wind `wind_mps`, m,
/// wrapped to the map's period (the uniform block's `cloud_drift.xy`).
#[must_use]
pub fn cloud_drift_m(wind_mps: Vec3, time_s: f32) -> Vec2 {
    let travel = Vec2::new(wind_mps.x, wind_mps.z) * time_s;
    Vec2::new(
        travel.x.rem_euclid(CLOUD_MAP_PERIOD_M),
        travel.y.rem_euclid(CLOUD_MAP_PERIOD_M),
    )
}

/// The cloud's extinction at `p`, per m: its clouds' within the layer, the
/// thickening air of its transition band around it ([`CloudLayer::band_share`]),
/// 0 beyond.
#[must_use]
pub fn cloud_extinction_at(noise: &CloudNoise, layer: &CloudLayer, offset_m: Vec2, p: Vec3) -> f32 {
    let h = (p.y - layer.base_m) / layer.thickness_m;
    if !(0.0..=1.0).contains(&h) {
        return layer.band_share(p.y) * layer.mean_extinction_per_m();
    }
    layer.kind.extinction_per_m() * noise.density(layer, offset_m, p)
}

/// Steps of [`cloud_optical_depth`] along a path.
pub const CLOUD_PATH_STEPS: u32 = 32;

/// The cloud's optical depth from `origin` along the unit `dir` for `length_m`
/// (midpoints of [`CLOUD_PATH_STEPS`] steps over the path's part in the layer and
/// its transition band).
#[must_use]
pub fn cloud_optical_depth(
    noise: &CloudNoise,
    layer: &CloudLayer,
    offset_m: Vec2,
    origin: Vec3,
    dir: Vec3,
    length_m: f32,
) -> f32 {
    let (low_m, high_m) = layer.extent_with_band_m();
    let (s0, s1) =
        crate::drawing::fog_layer::fog_layer_segment(origin.y, dir.y, length_m, low_m, high_m);
    if s1 <= s0 {
        return 0.0;
    }
    let n = CLOUD_PATH_STEPS;
    let ds = (s1 - s0) / n as f32;
    (0..n)
        .map(|k| {
            cloud_extinction_at(
                noise,
                layer,
                offset_m,
                origin + dir * (s0 + (k as f32 + 0.5) * ds),
            )
        })
        .sum::<f32>()
        * ds
}

/// The coverage map's value at `uv` (texels wrap), bilinear as the GPU's sampler.
#[must_use]
pub fn sample_coverage_map(map: &[u8], uv: Vec2) -> f32 {
    sample_repeating(CLOUD_MAP_PX, uv, |i| {
        Vec4::splat(map.get(i).map_or(0.0, |&b| f32::from(b) / 255.0))
    })
    .x
}

/// A square texture of `side`² texels read at `uv` as a GPU's linear, repeating
/// sampler reads it; `texel(i)` is the value of texel `i` (rows packed).
fn sample_repeating(side: u32, uv: Vec2, texel: impl Fn(usize) -> Vec4) -> Vec4 {
    let n = i64::from(side);
    let p = uv * side as f32 - Vec2::splat(0.5);
    let cell = p.floor();
    let f = p - cell;
    let at = |dx: i64, dy: i64| {
        let x = (cell.x as i64 + dx).rem_euclid(n);
        let y = (cell.y as i64 + dy).rem_euclid(n);
        texel((y * n + x) as usize)
    };
    let a = at(0, 0).lerp(at(1, 0), f.x);
    let b = at(0, 1).lerp(at(1, 1), f.x);
    a.lerp(b, f.y)
}

/// Where a point's column samples the coverage map (drifting with `offset_m`, the
/// wind's travel).
#[must_use]
pub fn cloud_map_uv(p: Vec3, offset_m: Vec2) -> Vec2 {
    (Vec2::new(p.x, p.z) + offset_m) / CLOUD_MAP_PERIOD_M
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pixel_is_marched_once_in_sixteen_frames_one_per_block_a_frame() {
        // A 64 × 48 image (a quarter of 256 × 192): 16 × 12 blocks.
        let mut marched = vec![0u32; 64 * 48];
        for slot in 0..CLOUD_MARCH_ALL {
            let mut blocks = Vec::new();
            for y in 0..48u32 {
                for x in 0..64u32 {
                    let pixel = UVec2::new(x, y);
                    if cloud_march_slot(pixel) == slot {
                        marched[(y * 64 + x) as usize] += 1;
                        blocks.push(pixel / CLOUD_MARCH_BLOCK_PX);
                        // The fresh image's pixel of the block marches this one.
                        assert_eq!(cloud_fresh_pixel(pixel / CLOUD_MARCH_BLOCK_PX, slot), pixel);
                    }
                }
            }
            assert_eq!(blocks.len(), 16 * 12, "slot {slot}");
            blocks.sort_by_key(|b| (b.y, b.x));
            blocks.dedup();
            assert_eq!(blocks.len(), 16 * 12, "slot {slot}: one pixel per block");
        }
        assert!(marched.iter().all(|&n| n == 1));
        // Consecutive frames' pixels are not neighbours.
        for slot in 0..CLOUD_MARCH_ALL - 1 {
            let a = cloud_fresh_pixel(UVec2::ZERO, slot).as_ivec2();
            let b = cloud_fresh_pixel(UVec2::ZERO, slot + 1).as_ivec2();
            assert!(
                (a - b).abs().max_element() >= 1 && (a - b).length_squared() >= 2,
                "{slot}"
            );
        }
    }

    #[test]
    fn a_transition_band_thickens_the_air_toward_the_layer() {
        let map = cloud_noise();
        let layer = CloudLayer {
            transition_band_m: 200.0,
            ..CloudLayer::typical(CloudKind::Nimbostratus, 0.9)
        };
        let (base, top) = (layer.base_m, layer.top_m());
        let mean = layer.mean_extinction_per_m();
        assert!((mean - CloudKind::Nimbostratus.extinction_per_m() * 0.9).abs() < 1e-9);
        // Linear from the layer's mean at its edges to clear air a band away.
        for (y, share) in [
            (base - 1e-3, 1.0),
            (base - 50.0, 0.75),
            (base - 100.0, 0.5),
            (top + 150.0, 0.25),
            (base - 200.0, 0.0),
            (top + 300.0, 0.0),
        ] {
            assert!(
                (layer.band_share(y) - share).abs() < 1e-4,
                "{y}: {}",
                layer.band_share(y)
            );
            let p = Vec3::new(10.0, y, -20.0);
            let sigma = cloud_extinction_at(map, &layer, Vec2::ZERO, p);
            assert!(
                (sigma - share * mean).abs() < 1e-6 * mean.max(1.0),
                "{y}: {sigma}"
            );
        }
        // Inside, the clouds' own; without a band, clear air at once.
        assert!(layer.band_share(base + 10.0).abs() < f32::EPSILON);
        let sharp = CloudLayer {
            transition_band_m: 0.0,
            ..layer
        };
        assert!(
            cloud_extinction_at(map, &sharp, Vec2::ZERO, Vec3::new(0.0, base - 1.0, 0.0)) == 0.0
        );
        // A vertical path up through the band to the base: the triangle's area.
        let depth = cloud_optical_depth(
            map,
            &layer,
            Vec2::ZERO,
            Vec3::new(0.0, base - 300.0, 0.0),
            Vec3::Y,
            300.0,
        );
        assert!(
            (depth - mean * 100.0).abs() < 0.01 * mean * 100.0,
            "{depth}"
        );
        // The layers find the layer a height is in the band of; bad bands refused.
        let layers = CloudLayers::one(layer);
        assert!(layers.containing(base - 50.0, Vec2::ZERO).is_some());
        assert!(layers.containing(base - 250.0, Vec2::ZERO).is_none());
        for bad in [-1.0, f32::NAN, 6_000.0] {
            let err = CloudLayer {
                transition_band_m: bad,
                ..layer
            }
            .validate()
            .expect_err("refused");
            assert!(err.to_string().contains("transition_band_m"), "{err}");
        }
    }

    #[test]
    fn the_history_is_clamped_only_as_far_as_the_camera_moved_across_the_ray() {
        let camera = |position_m: Vec3, yaw_rad: f32| {
            let camera = crate::Camera {
                position_m,
                forward: Vec3::new(yaw_rad.sin(), 0.4, -yaw_rad.cos()).normalize(),
                up: Vec3::Y,
                ..crate::Camera::default()
            };
            crate::drawing::render::view_projection(&camera, 16.0 / 9.0)
        };
        let image = Vec2::new(320.0, 180.0);
        let here = Vec3::new(0.0, 2.0, 0.0);
        let ray = Vec3::new(0.1, 0.5, -1.0).normalize();
        let entry = here + ray * 3000.0;
        let deeper = entry + ray * CLOUD_PARALLAX_DEPTH_M;
        // Turned: the same ray, no parallax.
        let turned = cloud_history_clamp_weight(camera(here, 0.02), entry, deeper, image);
        assert!(turned < 1e-3, "{turned}");
        // Moved along the ray: nearly none.
        let along =
            cloud_history_clamp_weight(camera(here - ray * 30.0, 0.0), entry, deeper, image);
        assert!(along < 0.05, "{along}");
        // Moved 50 m across it (a frame at 3 000 m/s, or 16 frames at 190 m/s):
        // clamped fully.
        let across =
            cloud_history_clamp_weight(camera(here + Vec3::X * 50.0, 0.0), entry, deeper, image);
        assert!((across - 1.0).abs() < 1e-6, "{across}");
        // A metre across: partly.
        let metre = cloud_history_clamp_weight(camera(here + Vec3::X, 0.0), entry, deeper, image);
        assert!(metre > 0.01 && metre < 0.2, "{metre}");
    }

    #[test]
    fn a_new_march_is_averaged_in_only_where_the_history_is_the_pixel_s_own() {
        // Read at a texel's centre, not clamped: a quarter.
        let still = cloud_fresh_weight(0.0, Vec2::new(12.5, 7.5));
        assert!((still - CLOUD_FRESH_WEIGHT).abs() < 1e-6);
        // A tenth of a texel off: in between; a quarter or more, or clamped: 1.
        let near = cloud_fresh_weight(0.0, Vec2::new(12.6, 7.5));
        assert!(near > CLOUD_FRESH_WEIGHT && near < 1.0, "{near}");
        assert!((cloud_fresh_weight(0.0, Vec2::new(12.75, 7.5)) - 1.0).abs() < 1e-6);
        assert!((cloud_fresh_weight(0.0, Vec2::new(12.0, 7.0)) - 1.0).abs() < 1e-6);
        assert!((cloud_fresh_weight(1.0, Vec2::new(12.5, 7.5)) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn successive_marches_of_a_pixel_fall_between_each_other_s_steps() {
        // Eight rounds' offsets: in [0, 1), none within 1/20 (a twentieth of a
        // step) of another.
        let offsets: Vec<f32> = (0..8).map(cloud_march_round_offset).collect();
        assert!(offsets[0].abs() < f32::EPSILON);
        for (i, a) in offsets.iter().enumerate() {
            assert!((0.0..1.0).contains(a));
            for b in &offsets[..i] {
                assert!((a - b).abs() > 0.05, "{offsets:?}");
            }
        }
        assert!((0.0..1.0).contains(&cloud_march_round_offset(u64::MAX)));
    }

    #[test]
    fn the_history_is_clamped_to_the_fresh_neighbourhood_with_a_margin() {
        let low = Vec4::new(0.2, 0.2, 0.2, 0.5);
        let high = Vec4::new(0.6, 0.6, 0.6, 0.9);
        // Inside the range, or within its margin: kept.
        let inside = Vec4::new(0.3, 0.65, 0.1 + 0.2, 0.95);
        assert_eq!(cloud_history_clamped(inside, low, high), inside);
        // A cloud the frame before saw where now there is clear sky: pulled to the
        // fresh range's edge plus its margin.
        let ghost = Vec4::new(0.9, 0.9, 0.9, 1.0);
        let clamped = cloud_history_clamped(ghost, low, high);
        assert!(
            (clamped - Vec4::new(0.7, 0.7, 0.7, 1.0))
                .abs()
                .max_element()
                < 1e-6
        );
        // An even neighbourhood keeps the slack.
        let even = Vec4::splat(0.5);
        let near = cloud_history_clamped(Vec4::splat(0.51), even, even);
        assert!((near - Vec4::splat(0.51)).abs().max_element() < 1e-6);
        let far = cloud_history_clamped(Vec4::ZERO, even, even);
        assert!(
            (far - Vec4::splat(0.5 - CLOUD_HISTORY_SLACK))
                .abs()
                .max_element()
                < 1e-6
        );
    }

    #[test]
    fn the_history_is_read_where_the_camera_before_saw_the_point() {
        let camera = crate::Camera {
            position_m: Vec3::new(0.0, 2.0, 0.0),
            forward: Vec3::NEG_Z,
            up: Vec3::Y,
            ..crate::Camera::default()
        };
        let view_proj = crate::drawing::render::view_projection(&camera, 16.0 / 9.0);
        // Straight ahead: the image's centre; behind: none; far to the side: none.
        let ahead = cloud_history_uv(view_proj, Vec3::new(0.0, 2.0, -2000.0)).expect("seen");
        assert!((ahead - Vec2::splat(0.5)).length() < 1e-4, "{ahead}");
        assert!(cloud_history_uv(view_proj, Vec3::new(0.0, 2.0, 2000.0)).is_none());
        assert!(cloud_history_uv(view_proj, Vec3::new(2000.0, 2.0, -10.0)).is_none());
        // Up is up the image (v down): a point above the axis has v < ½.
        let up = cloud_history_uv(view_proj, Vec3::new(0.0, 400.0, -2000.0)).expect("seen");
        assert!(up.y < 0.5 && (up.x - 0.5).abs() < 1e-4, "{up}");
    }

    #[test]
    fn the_map_s_values_are_spread_evenly() {
        let map = cloud_coverage_map();
        let mut histogram = [0usize; 8];
        for &b in &map {
            histogram[usize::from(b) / 32] += 1;
        }
        let each = map.len() / 8;
        assert!(histogram.iter().all(|&h| h == each), "{histogram:?}");
        assert_eq!(map, cloud_coverage_map(), "deterministic");
        // It tiles: the last column continues into the first (neighbours differ by
        // little, as inside).
        let n = CLOUD_MAP_PX as usize;
        let jump = |a: usize, b: usize| (i32::from(map[a]) - i32::from(map[b])).abs();
        let seam: i32 = (0..n).map(|y| jump(y * n + n - 1, y * n)).sum();
        let inside: i32 = (0..n).map(|y| jump(y * n + n / 2, y * n + n / 2 + 1)).sum();
        assert!(seam < 2 * inside, "seam {seam} against inside {inside}");
    }

    #[test]
    fn looking_up_the_layer_covers_its_coverage_of_the_sky() {
        let noise = cloud_noise();
        for kind in CloudKind::ALL {
            for coverage in [0.125f32, 0.375, 0.625, 0.875] {
                let layer = CloudLayer::typical(kind, coverage);
                let n = 120;
                let mut covered = 0;
                for i in 0..n * n {
                    let ground = Vec2::new((i % n) as f32, (i / n) as f32) * 97.0;
                    // A vertical column's optical depth through the layer.
                    let steps = 64;
                    let dy = layer.thickness_m / steps as f32;
                    let tau: f32 = (0..steps)
                        .map(|k| {
                            let h = (k as f32 + 0.5) / steps as f32;
                            let p =
                                Vec3::new(ground.x, layer.base_m + h * layer.thickness_m, ground.y);
                            kind.extinction_per_m() * noise.density(&layer, Vec2::ZERO, p) * dy
                        })
                        .sum();
                    if tau > 0.5 {
                        covered += 1;
                    }
                }
                let share = covered as f32 / (n * n) as f32;
                assert!(
                    (share - coverage).abs() < 0.1,
                    "{kind:?} at {coverage}: {share} of the columns are clouded"
                );
            }
        }
    }

    #[test]
    fn profiles_rise_from_the_base_and_fall_to_the_top() {
        for kind in CloudKind::ALL {
            assert!(cloud_profile(kind, 0.0) < 1e-6 && cloud_profile(kind, 1.0) < 1e-6);
            assert!(cloud_profile(kind, -0.1) == 0.0 && cloud_profile(kind, 1.1) == 0.0);
            let peak = (0..=100)
                .map(|i| cloud_profile(kind, i as f32 / 100.0))
                .fold(0.0, f32::max);
            assert!(peak > 0.99, "{kind:?}: {peak}");
        }
        // Cumulus is bottom-heavy (flat base, rounded top); stratus a thin sheet.
        let mass = |kind, lo: f32, hi: f32| -> f32 {
            (0..100)
                .map(|i| lo + (hi - lo) * (i as f32 + 0.5) / 100.0)
                .map(|h| cloud_profile(kind, h))
                .sum()
        };
        assert!(mass(CloudKind::Cumulus, 0.0, 0.5) > 2.0 * mass(CloudKind::Cumulus, 0.5, 1.0));
        assert!(
            mass(CloudKind::Cumulonimbus, 0.5, 1.0) > 0.6 * mass(CloudKind::Cumulonimbus, 0.0, 0.5)
        );
    }

    #[test]
    fn the_two_lobes_average_one_and_glow_toward_the_sun() {
        let n = 100_000;
        let mean: f64 = (0..n)
            .map(|i| {
                f64::from(cloud_phase(
                    (-1.0 + 2.0 * (f64::from(i) + 0.5) / f64::from(n)) as f32,
                ))
            })
            .sum::<f64>()
            / f64::from(n);
        assert!((mean - 1.0).abs() < 2e-3, "{mean}");
        assert!(cloud_phase(1.0) > 20.0 * cloud_phase(0.0));
        assert!(
            cloud_phase(-1.0) > cloud_phase(0.0),
            "a little back-scatter"
        );
    }

    #[test]
    fn the_octaves_start_from_single_scattering_and_reach_deeper() {
        // Octave 0 is Beer and the phase function; the others add light that goes
        // deeper: behind an optical depth of 8 it is most of what is left.
        let single = |c: f32, t: f32| cloud_phase(c) * (-t).exp();
        for c in [-0.9f32, 0.0, 0.9] {
            let all = cloud_sun_light(c, 0.0);
            assert!(all > single(c, 0.0), "{c}: more light with the octaves");
            assert!(all < 2.0 * cloud_phase(c).max(1.0) + 1e-3, "{c}: {all}");
            let deep = cloud_sun_light(c, 8.0);
            assert!(deep > 50.0 * single(c, 8.0), "{c}: {deep} deep in");
        }
    }

    #[test]
    fn clouds_shade_their_coverage_of_the_ground() {
        let map = cloud_noise();
        let sun = Vec3::new(0.3, 0.8, 0.2).normalize();
        for coverage in [0.0f32, 0.3, 0.7, 1.0] {
            let layer = CloudLayer::typical(CloudKind::Cumulus, coverage);
            let n = 100;
            let shaded = (0..n * n)
                .filter(|i| {
                    let p = Vec3::new((i % n) as f32 * 113.0, 0.0, (i / n) as f32 * 113.0);
                    cloud_sun_transmittance(map, &layer, Vec2::ZERO, p, sun) < 0.5
                })
                .count() as f32
                / (n * n) as f32;
            assert!(
                (shaded - coverage).abs() < 0.12,
                "{coverage}: {shaded} of the ground in the clouds' shadow"
            );
        }
        // Above the layer the sun is not dimmed.
        let layer = CloudLayer::typical(CloudKind::Nimbostratus, 1.0);
        let above = Vec3::new(0.0, layer.top_m() + 10.0, 0.0);
        assert!((cloud_sun_transmittance(map, &layer, Vec2::ZERO, above, sun) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_path_s_optical_depth_is_its_extinction_summed() {
        let map = cloud_noise();
        // A full nimbostratus deck from 0 to 2 500 m: inside it the extinction is
        // up to its most, outside none; a level path of 100 m inside sums it.
        let layer = CloudLayer {
            base_m: 0.0,
            thickness_m: 2_500.0,
            coverage: 1.0,
            kind: CloudKind::Nimbostratus,
            transition_band_m: 0.0,
        };
        let at = Vec3::new(10.0, 1_200.0, 10.0);
        let sigma = cloud_extinction_at(map, &layer, Vec2::ZERO, at);
        assert!(sigma > 0.01 && sigma <= 0.05 + 1e-6, "{sigma}");
        assert!(cloud_extinction_at(map, &layer, Vec2::ZERO, Vec3::new(0.0, 3_000.0, 0.0)) == 0.0);
        let tau = cloud_optical_depth(map, &layer, Vec2::ZERO, at, Vec3::X, 1.0);
        assert!((tau - sigma).abs() < 0.02 * sigma, "{tau} against {sigma}");
        // Straight up out of the layer: only the part inside counts.
        let up = cloud_optical_depth(map, &layer, Vec2::ZERO, at, Vec3::Y, 10_000.0);
        let inside = cloud_optical_depth(map, &layer, Vec2::ZERO, at, Vec3::Y, 1_300.0);
        assert!((up - inside).abs() < 0.02 * inside, "{up} {inside}");
        // The drift wraps.
        let d = cloud_drift_m(Vec3::new(10.0, 0.0, -5.0), 2_000.0);
        assert!(
            (d.x - 8_000.0).abs() < 1e-2 && (d.y - 2_000.0).abs() < 1e-2,
            "{d}"
        );
    }

    #[test]
    fn a_ray_crosses_the_layer_where_it_is() {
        // From the ground straight up through 1000–2500 m.
        assert_eq!(cloud_slab(0.0, 1.0, 1_000.0, 2_500.0), (1_000.0, 2_500.0));
        // Level from the ground: never.
        let (a, b) = cloud_slab(0.0, 0.0, 1_000.0, 2_500.0);
        assert!(b <= a);
        // From inside, level: the longest path marched from inside.
        let (a, b) = cloud_slab(1_500.0, 0.0, 1_000.0, 2_500.0);
        assert!(a.abs() < 1e-3 && (b - CLOUD_INSIDE_PATH_M).abs() < 1.0);
        // From below, nearly level: the longest path.
        let (a, b) = cloud_slab(0.0, 0.05, 1_000.0, 2_500.0);
        assert!((b - a - CLOUD_MAX_PATH_M).abs() < 1.0, "{a} {b}");
        // From above looking down at 30°: enters at the top.
        let (a, b) = cloud_slab(3_000.0, -0.5, 1_000.0, 2_500.0);
        assert!(
            (a - 1_000.0).abs() < 1e-2 && (b - 4_000.0).abs() < 1e-1,
            "{a} {b}"
        );
    }

    #[test]
    fn the_weather_implies_its_deck() {
        use crate::{PrecipitationKind as K, Weather};
        let w = |kind, rate| Weather {
            kind,
            intensity_mm_per_h: rate,
            air_temperature_c: if matches!(kind, K::Rain) { 10.0 } else { -5.0 },
            ..Weather::default()
        };
        for (weather, kind) in [
            (w(K::Rain, 0.3), CloudKind::Stratus),
            (w(K::Rain, 4.0), CloudKind::Nimbostratus),
            (w(K::Rain, 40.0), CloudKind::Cumulonimbus),
            (w(K::DrySnow, 2.0), CloudKind::Nimbostratus),
            (w(K::DrySnow, 0.0), CloudKind::Cumulus),
        ] {
            assert_eq!(
                CloudLayer::implied_by(&weather, 0.9).kind,
                kind,
                "{weather:?}"
            );
        }
    }

    #[test]
    fn layers_are_checked() {
        assert!(
            CloudLayer::typical(CloudKind::Cumulus, 0.4)
                .validate()
                .is_ok()
        );
        for bad in [
            CloudLayer {
                coverage: 1.5,
                ..CloudLayer::typical(CloudKind::Stratus, 0.5)
            },
            CloudLayer {
                thickness_m: 0.0,
                ..CloudLayer::typical(CloudKind::Stratus, 0.5)
            },
            CloudLayer {
                base_m: f32::NAN,
                ..CloudLayer::typical(CloudKind::Stratus, 0.5)
            },
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }
}
