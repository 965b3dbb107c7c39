//! Drawing formulas of seeds 000/001 (docs/model.md §5), CPU forms: the snow sprite, the
//! raindrop tetrahedron, view-cone culling, the seed's Blinn–Phong lighting and fog.
//!
//! These are the Rust halves of the renderer's WGSL (drawing.wgsl); tests pin them to
//! hand-computed cases so the shaders can be checked against them.
//!
//! ## Sub-pixel particles
//!
//! A particle whose sprite (flake side × snow scale) or streak (length `k·s·|v|`) is
//! shorter than `min_px` pixels ([`sub_pixel`]) is not rasterised: the splat kernel
//! adds its ink — the opacity × px² its enlarged sprite or streak would have covered,
//! [`splat_ink`] — to the pixels around its centre. At the hand-over the sprite is
//! exactly `min_px` wide at full opacity, so its ink and the splat's are equal: a
//! particle crossing the threshold does not pop.

pub mod clouds;
mod drop_environment;
mod drop_oscillation;
pub mod far_ground;
pub mod fog_layer;
pub mod frame_rate_control;
pub mod land_borders;
pub mod multiplicity;
pub mod render;
pub mod sea;
pub mod shadow_cache;
pub mod shadow_fit;
pub mod shore;
pub mod unresolved_streaks;
pub mod water_look;
pub mod water_mirror;

use glam::Vec3;

pub use drop_environment::{
    BARE_GROUND_ALBEDO, DROP_GROUND_RADIUS_M, DROP_GROUND_SAMPLES_PER_SIDE, DROP_HALF_FIELD_RAD,
    DROP_REFRACTED_SHARE, OVERCAST_GROUND_RADIANCE_PER_ALBEDO, drop_environment_factor,
    drop_field_shares, drop_ground_albedo, drop_ground_offset_m,
};
pub use drop_oscillation::{
    DROP_OSCILLATION_CONTRAST, WATER_SURFACE_TENSION_N_PER_M, drop_oscillation_brightness,
    drop_oscillation_hz,
};

/// The four corners of a camera-facing snow sprite of side `side_m` centred at
/// `centre_m`, seen from `camera_m`, in strip order V0 V1 V2 V3 (texture coordinates
/// T0 (1,0), T1 (1,1), T2 (0,0), T3 (0,1)).
///
/// `N = n(O − P)`, `A = n(Y × N)`, `B = n(N × A)`, `V0 = P + ½s(A − B)`,
/// `V1 = V0 + sB`, `V2 = V0 − sA`, `V3 = V1 − sA`. Where the camera looks straight
/// down or up (`Y ∥ N`), Z stands in for Y. `None` when the camera is at the centre.
#[must_use]
pub fn snow_sprite_corners(centre_m: Vec3, camera_m: Vec3, side_m: f32) -> Option<[Vec3; 4]> {
    snow_sprite_corners_turned(centre_m, camera_m, side_m, 0.0, 1.0)
}

/// The sprite of [`snow_sprite_corners`] turned by `spin_rad` in its plane and with its
/// `B` side foreshortened by `tumble ∈ (0, 1]`: how a tumbling flake's silhouette
/// changes (the seeds' r0/r rotation, which seed 003 names as missing). `A' = cos·A +
/// sin·B`, `B' = tumble·(cos·B − sin·A)`, then the seed's corners with `A'`, `B'`.
///
/// WGSL twin: `snow_sprite_corner` in drawing.wgsl.
#[must_use]
pub fn snow_sprite_corners_turned(
    centre_m: Vec3,
    camera_m: Vec3,
    side_m: f32,
    spin_rad: f32,
    tumble: f32,
) -> Option<[Vec3; 4]> {
    let n = (camera_m - centre_m).try_normalize()?;
    let (a, b) = turned_sprite_sides(n, spin_rad, tumble)?;
    let v0 = centre_m + 0.5 * side_m * (a - b);
    let v1 = v0 + side_m * b;
    let v2 = v0 - side_m * a;
    let v3 = v1 - side_m * a;
    Some([v0, v1, v2, v3])
}

/// The sides `A'`, `B'` of a sprite facing the camera along `n` (unit), turned by
/// `spin_rad` and foreshortened by `tumble` ([`snow_sprite_corners_turned`]); `None`
/// for no `n`.
fn turned_sprite_sides(n: Vec3, spin_rad: f32, tumble: f32) -> Option<(Vec3, Vec3)> {
    let a = Vec3::Y
        .cross(n)
        .try_normalize()
        .or_else(|| Vec3::Z.cross(n).try_normalize())?;
    let b = n.cross(a).normalize();
    let (sin, cos) = spin_rad.sin_cos();
    Some((cos * a + sin * b, tumble * (cos * b - sin * a)))
}

/// A flake's quad as two sides: corner `k`, of `uv` [`SNOW_SPRITE_UV`]`[k]` =
/// `(u, v)`, is `centre + (u − ½)·across + (v − ½)·along`, its texture's `v` that `v`
/// times `stretch` ([`snow_streak_texture_v`] reads it). What the renderer computes
/// once for each flake drawn and each of its four corners reads
/// ([`snow_quad_axes`]).
///
/// WGSL twin: `SnowQuadAxes` in drawing.wgsl.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnowQuadAxes {
    /// The side from corner 2 to corner 0 (`u` 0 → 1), m.
    pub across_m: Vec3,
    /// The side from corner 0 to corner 1 (`v` 0 → 1), m.
    pub along_m: Vec3,
    /// The quad's length over its width: 1 for a sprite, more for a streak.
    pub stretch: f32,
}

impl SnowQuadAxes {
    /// Corner `k` (`0..4`, strip order) of the quad centred at `centre_m`, with its
    /// `uv` (`uv.y ∈ [0, stretch]`). WGSL twin: `snow_quad_corner`.
    #[must_use]
    pub fn corner(&self, centre_m: Vec3, k: usize) -> (Vec3, [f32; 2]) {
        let [u, v] = SNOW_SPRITE_UV[k % 4];
        let position = centre_m + (u - 0.5) * self.across_m + (v - 0.5) * self.along_m;
        (position, [u, v * self.stretch])
    }
}

/// A flake as a camera exposing for `exposure_s` records it, as the two sides of its
/// quad ([`SnowQuadAxes`]): the sprite of side `side_m` swept along its motion across
/// the view during the exposure, `M = T·(v − n(n·v))` (`n` toward the camera). When
/// the sweep is at least half a side the sprite becomes a streak: a quad `side` wide
/// and `side + |M|` long along `M`, whose ends are the flake's halves and whose middle
/// is the flake's centre line smeared (the fragment reads `uv.y` through
/// [`snow_streak_texture_v`]); its opacity is divided by the stretch
/// `(side + |M|)/side`, so its ink stays the flake's. Below that the turned sprite
/// stands (stretch 1: `across = s·A'`, `along = s·B'` of
/// [`snow_sprite_corners_turned`], whose corners these are). `None` for a flake at the
/// camera.
///
/// WGSL twin: `snow_quad_axes` in drawing.wgsl.
#[must_use]
pub fn snow_quad_axes(
    centre_m: Vec3,
    camera_m: Vec3,
    side_m: f32,
    (spin_rad, tumble): (f32, f32),
    velocity_mps: Vec3,
    exposure_s: f32,
) -> Option<SnowQuadAxes> {
    let n = (camera_m - centre_m).try_normalize()?;
    let sweep = exposure_s * (velocity_mps - n * n.dot(velocity_mps));
    let length = sweep.length();
    // Short (or NaN): the turned sprite.
    if length.is_nan() || length < 0.5 * side_m {
        let (a, b) = turned_sprite_sides(n, spin_rad, tumble)?;
        return Some(SnowQuadAxes {
            across_m: side_m * a,
            along_m: side_m * b,
            stretch: 1.0,
        });
    }
    let along = sweep / length;
    let across = n.cross(along).normalize();
    let stretch = (side_m + length) / side_m;
    Some(SnowQuadAxes {
        across_m: side_m * across,
        along_m: stretch * side_m * along,
        stretch,
    })
}

/// A snow streak's corners in strip order, each with its `uv`.
pub type StreakCorners = [(Vec3, [f32; 2]); 4];

/// The corners of [`snow_quad_axes`]'s quad in strip order, each with its `uv`
/// (`uv.y ∈ [0, stretch]`), and the stretch, or `None` for a flake at the camera.
///
/// WGSL twin: `snow_streak_corner` in drawing.wgsl.
#[must_use]
pub fn snow_streak_corners(
    centre_m: Vec3,
    camera_m: Vec3,
    side_m: f32,
    spin_tumble: (f32, f32),
    velocity_mps: Vec3,
    exposure_s: f32,
) -> Option<(StreakCorners, f32)> {
    let axes = snow_quad_axes(
        centre_m,
        camera_m,
        side_m,
        spin_tumble,
        velocity_mps,
        exposure_s,
    )?;
    Some((
        std::array::from_fn(|k| axes.corner(centre_m, k)),
        axes.stretch,
    ))
}

/// The flake texture's `v` for a streak's `v ∈ [0, stretch]`: the first half side
/// as it is, the last half side as the texture's last half, the middle its centre
/// line. WGSL twin: `snow_streak_texture_v` (drawing.wgsl).
#[must_use]
pub fn snow_streak_texture_v(v: f32, stretch: f32) -> f32 {
    if v < 0.5 {
        v
    } else if v > stretch - 0.5 {
        v - (stretch - 1.0)
    } else {
        0.5
    }
}

/// A flake's in-plane spin and tumble from its rotation state: orientation
/// `o = r0 + r`, spin `o.y + o.z`, tumble `max(|cos o.x|, 0.3)`.
///
/// WGSL twin: `flake_spin_tumble` in drawing.wgsl.
#[must_use]
pub fn flake_spin_tumble(rotation0_rad: Vec3, rotation_rad: Vec3) -> (f32, f32) {
    let o = rotation0_rad + rotation_rad;
    (o.y + o.z, o.x.cos().abs().max(MIN_TUMBLE))
}

/// The narrowest a tumbling flake's sprite gets, relative to its side.
pub const MIN_TUMBLE: f32 = 0.3;

/// How big a sprite is drawn: the flake's diameter times `scale` (the seed's designer
/// size), but never under `min_px` pixels; a sprite enlarged to `min_px` keeps the
/// light of the flake it stands for (opacity × area ratio), not less than
/// `min_opacity`. `pixel_angle_rad` is the angle one pixel spans at the image centre.
/// Returns `(side_m, opacity)`.
///
/// WGSL twin: `snow_sprite_sizing` in drawing.wgsl.
#[must_use]
pub fn snow_sprite_sizing(
    diameter_m: f32,
    distance_m: f32,
    pixel_angle_rad: f32,
    sizing: &SpriteSizing,
) -> (f32, f32) {
    let side = diameter_m * sizing.snow_scale;
    let min_side = sizing.min_px * pixel_angle_rad * distance_m;
    if side >= min_side {
        (side, 1.0)
    } else {
        let ratio = side / min_side;
        (min_side, (ratio * ratio).max(sizing.min_opacity))
    }
}

/// How particles are sized on screen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpriteSizing {
    /// Sprite side per flake diameter (the seed's designer size s).
    pub snow_scale: f32,
    /// Smallest sprite or streak width, px.
    pub min_px: f32,
    /// Lowest opacity of an enlarged sprite (a look, not physics: 0, the default,
    /// keeps each sub-pixel flake's own ink).
    pub min_opacity: f32,
}

impl Default for SpriteSizing {
    fn default() -> Self {
        Self {
            snow_scale: 3.0,
            min_px: 1.5,
            min_opacity: 0.0,
        }
    }
}

/// A raindrop's streak as a camera exposing for `exposure_s` records it
/// (Garg & Nayar 2007, *Vision and rain*, IJCV 75(1)): the drop moves
/// `h = max(T·|v|, D)` during the exposure and is `D` wide, and it lies over each point
/// of its streak for `D/|v|` of the exposure, so the streak's opacity is
/// `(π/2)·D/h` on the tetrahedron's silhouette (`h·a/2`): its ink is the drop's
/// projected area `π·D²/4` however long the exposure (energy-conserving; capped at
/// opaque). A base under `min_px` pixels is widened to it with the opacity scaled
/// down by the same factor, so the ink stays (no floor: a sub-pixel drop adds its
/// area, not a pixel). Returns `(h_m, a_m, opacity)`.
///
/// WGSL twin: `raindrop_sizing` in drawing.wgsl.
#[must_use]
pub fn raindrop_sizing(
    speed_mps: f32,
    diameter_m: f32,
    distance_m: f32,
    pixel_angle_rad: f32,
    sizing: &SpriteSizing,
    exposure_s: f32,
) -> (f32, f32, f32) {
    let d = diameter_m.max(1.0e-5);
    let h = (exposure_s * speed_mps).max(d);
    let opacity = (std::f32::consts::FRAC_PI_2 * d / h).min(1.0);
    let min_a = sizing.min_px * pixel_angle_rad * distance_m;
    if d >= min_a {
        (h, d, opacity)
    } else {
        (h, min_a, opacity * d / min_a)
    }
}

/// The blur circle of a thin lens of aperture `aperture_m` focused at
/// `focus_distance_m`, measured at `distance_m` (m across at the particle): the
/// blur angle `A·|1/d − 1/d_f|` times `d`. 0 in focus and for a pinhole.
/// WGSL twin: `defocus_blur_m` (drawing.wgsl).
#[must_use]
pub fn defocus_blur_m(aperture_m: f32, focus_distance_m: f32, distance_m: f32) -> f32 {
    aperture_m * (1.0 - distance_m / focus_distance_m.max(1.0e-3)).abs()
}

/// A sprite or streak width `width_m` at `opacity` spread by a blur circle
/// `blur_m`: `width + blur` wide at `opacity·(width/(width + blur))^power`
/// (power 2 for a sprite, which spreads both ways; 1 for a streak's width), so
/// its ink stays. WGSL twin: `defocused` (drawing.wgsl).
#[must_use]
pub fn defocused(width_m: f32, opacity: f32, blur_m: f32, power: i32) -> (f32, f32) {
    let wide = width_m + blur_m.max(0.0);
    if wide <= 0.0 {
        return (width_m, opacity);
    }
    (wide, opacity * (width_m / wide).powi(power))
}

/// Particles nearer the camera than this are not drawn, m (a flake or drop at the
/// lens would fill the view as a blur a real camera does not focus).
pub const NEAR_FADE_START_M: f32 = 0.5;
/// From here on particles are drawn at full opacity, m.
pub const NEAR_FADE_END_M: f32 = 1.5;

/// Opacity factor of a sprite or streak `distance_m` from the camera: 0 before
/// [`NEAR_FADE_START_M`], 1 after [`NEAR_FADE_END_M`], smooth between.
///
/// WGSL twin: `near_fade` in drawing.wgsl.
#[must_use]
pub fn near_fade(distance_m: f32) -> f32 {
    smoothstep(NEAR_FADE_START_M, NEAR_FADE_END_M, distance_m)
}

/// Whether a particle `length_m` long at `distance_m` is drawn below `min_px` pixels
/// (and so is splatted, not rasterised).
///
/// WGSL twin: `sub_pixel` in drawing.wgsl.
#[must_use]
pub fn sub_pixel(length_m: f32, distance_m: f32, pixel_angle_rad: f32, min_px: f32) -> bool {
    length_m < min_px * pixel_angle_rad * distance_m
}

/// What a splatted particle looks like: a sprite of `(side_m, opacity)` from
/// [`snow_sprite_sizing`], or a streak of `(h_m, a_m, opacity)` from
/// [`raindrop_sizing`] (its opacity already times the rain's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SplatShape {
    /// A snow sprite.
    Sprite {
        /// Side, m.
        side_m: f32,
        /// Opacity.
        opacity: f32,
    },
    /// A rain tetrahedron.
    Streak {
        /// Height, m.
        h_m: f32,
        /// Base, m.
        a_m: f32,
        /// Opacity.
        opacity: f32,
    },
}

/// The ink (opacity × px²) of a sprite or streak seen from `distance_m`: a sprite
/// covers side² px at its opacity times the flake texture's mean; a tetrahedron's
/// silhouette about h·a/2.
///
/// WGSL twin: `splat_ink` in drawing.wgsl.
#[must_use]
pub fn splat_ink(shape: SplatShape, distance_m: f32, pixel_angle_rad: f32) -> f32 {
    let px = 1.0 / (pixel_angle_rad * distance_m).max(1.0e-12);
    match shape {
        SplatShape::Sprite { side_m, opacity } => {
            let side_px = side_m * px;
            side_px * side_px * opacity * flake_mean_opacity()
        }
        SplatShape::Streak { h_m, a_m, opacity } => 0.5 * h_m * px * a_m * px * opacity,
    }
}

/// Side of the flake opacity texture both GPU backends make, px.
pub const FLAKE_TEXTURE_PX: u32 = 64;

/// Mean opacity of the flake texture ([`snowflake_opacity`] at
/// [`FLAKE_TEXTURE_PX`]): what a sprite's area is worth in ink.
#[must_use]
pub fn flake_mean_opacity() -> f32 {
    static MEAN: std::sync::OnceLock<f32> = std::sync::OnceLock::new();
    *MEAN.get_or_init(|| {
        let texture = snowflake_opacity(FLAKE_TEXTURE_PX);
        let sum: u64 = texture.iter().map(|&v| u64::from(v)).sum();
        sum as f32 / (255.0 * texture.len() as f32)
    })
}

/// A grey-scale opacity texture of a six-armed dendritic flake, `side_px²` bytes
/// (white opaque, black transparent, rows top to bottom): a soft core, six arms with
/// side branches, fading toward the rim.
#[must_use]
pub fn snowflake_opacity(side_px: u32) -> Vec<u8> {
    let side = side_px.max(2);
    let mut out = Vec::with_capacity((side * side) as usize);
    for y in 0..side {
        for x in 0..side {
            let p = (glam::Vec2::new(x as f32, y as f32) + 0.5) / side as f32 * 2.0 - 1.0;
            let r = p.length();
            let core = 1.0 - smoothstep(0.12, 0.3, r);
            // Distance to the nearest of six arms (angle folded into one 60° sector).
            let sector = std::f32::consts::PI / 3.0;
            let angle = p.y.atan2(p.x).rem_euclid(sector) - 0.5 * sector;
            let along = r * angle.cos();
            let across = (r * angle.sin()).abs();
            let arm = 1.0 - smoothstep(0.03, 0.09, across);
            // Side branches: at 0.45 and 0.7 of the radius, 60° off the arm.
            let branch = [0.45f32, 0.7]
                .iter()
                .map(|&at| {
                    let d = along - at;
                    let off = (d * 0.5 - across * 0.866).abs();
                    if d > 0.0 && d < 0.2 {
                        1.0 - smoothstep(0.02, 0.06, off)
                    } else {
                        0.0
                    }
                })
                .fold(0.0f32, f32::max);
            let rim = 1.0 - smoothstep(0.8, 1.0, r);
            let value = core.max(arm.max(branch) * rim);
            out.push((value.clamp(0.0, 1.0) * 255.0).round() as u8);
        }
    }
    out
}

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Texture coordinates of the sprite's strip V0 V1 V2 V3.
pub const SNOW_SPRITE_UV: [[f32; 2]; 4] = [[1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [0.0, 1.0]];

/// A raindrop's tetrahedron: vertices V0..V3 and the seed's vertex normals N0..N3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RainTetrahedron {
    /// V0 (apex, trailing the drop) and the base V1, V2, V3.
    pub vertices: [Vec3; 4],
    /// N0..N3 (not normalised, as the seed writes them).
    pub normals: [Vec3; 4],
}

/// The tetrahedron of a drop at `centre_m` moving at `velocity_mps` with designer
/// size `size` and speed factor `speed_factor`: height `h = k·s·|v|`, base side
/// `a = 0.1·h`, axis along the velocity (docs/model.md §5). Where the velocity is parallel
/// to X, Z stands in for X. `None` for a drop at rest.
#[must_use]
pub fn raindrop_tetrahedron(
    centre_m: Vec3,
    velocity_mps: Vec3,
    size: f32,
    speed_factor: f32,
) -> Option<RainTetrahedron> {
    let h = speed_factor * size * velocity_mps.length();
    raindrop_tetrahedron_sized(centre_m, velocity_mps, h, 0.1 * h)
}

/// The tetrahedron with height `h_m` and base side `a_m` given (the renderer widens
/// the base of distant drops to a pixel, [`raindrop_sizing`]). `None` for a drop at
/// rest.
///
/// WGSL twin: `raindrop_vertex` in drawing.wgsl.
#[must_use]
pub fn raindrop_tetrahedron_sized(
    centre_m: Vec3,
    velocity_mps: Vec3,
    h: f32,
    a: f32,
) -> Option<RainTetrahedron> {
    let e_y = (-velocity_mps).try_normalize()?;
    let e_z = Vec3::X
        .cross(e_y)
        .try_normalize()
        .or_else(|| Vec3::Z.cross(e_y).try_normalize())?;
    let e_x = e_y.cross(e_z).normalize();
    let r = 3f32.sqrt() / 3.0 * a;
    let v0 = centre_m + h * e_y;
    let v1 = centre_m - 0.5 * r * e_x - 0.5 * a * e_z;
    let v2 = centre_m + r * e_x;
    let v3 = v1 + a * e_z;
    let n = |v: Vec3| v.normalize_or_zero();
    Some(RainTetrahedron {
        vertices: [v0, v1, v2, v3],
        normals: [
            e_y,
            n(v1 - centre_m) + n(v1 - v0),
            e_x + n(v2 - v0),
            n(v3 - centre_m) + n(v3 - v0),
        ],
    })
}

/// The tetrahedron's four faces as vertex numbers, outward-facing order irrelevant
/// (drawn two-sided): triangle list of 12 vertices.
pub const RAIN_TETRAHEDRON_FACES: [u32; 12] = [0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2];

/// The same four faces as one triangle strip of 6 vertices (its triangles 012, 123,
/// 230, 301): what the renderer draws, each vertex's position and normal being its
/// number's alone, so half the corners shade every face. WGSL twin:
/// `rain_tetrahedron_strip_vertex` (drawing.wgsl).
pub const RAIN_TETRAHEDRON_STRIP: [u32; 6] = [0, 1, 2, 3, 0, 1];

/// The right side of the view-cone test, computed once per frame:
/// `(1 + tan²(α/2) + tan²(β/2))^(−1/2)` for horizontal and vertical fields of view.
#[must_use]
pub fn view_cone_cos(horizontal_fov_rad: f32, vertical_fov_rad: f32) -> f32 {
    let (th, tv) = (
        (0.5 * horizontal_fov_rad).tan(),
        (0.5 * vertical_fov_rad).tan(),
    );
    1.0 / (1.0 + th * th + tv * tv).sqrt()
}

/// Whether a particle at `position_m` is drawn: `dot(n(P − C), view_dir) ≥ cone_cos`.
/// The cone circumscribes the frustum, so nothing visible is culled.
#[must_use]
pub fn in_view_cone(position_m: Vec3, camera_m: Vec3, view_dir: Vec3, cone_cos: f32) -> bool {
    (position_m - camera_m)
        .try_normalize()
        .is_some_and(|d| d.dot(view_dir) >= cone_cos)
}

/// The material and light terms of the seed's lighting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lighting {
    /// k_A·I_A.
    pub ambient: f32,
    /// k_D·I_D.
    pub diffuse: f32,
    /// k_S·I_S.
    pub specular: f32,
    /// Shininess s ∈ [0, 128].
    pub shininess: f32,
    /// Shadow colour sc.
    pub shadow_colour: f32,
    /// Shadow density ∈ [0, 1].
    pub shadow_density: f32,
    /// Light attenuation λ.
    pub attenuation: f32,
}

/// Blinn–Phong with a shadow-map visibility `lit ∈ [0, 1]` (docs/model.md §5):
/// `I = λ(k_A I_A + (1 − sh) k_D I_D max(0, L·N) + sh·sc + lit·k_S I_S max(0, H·N)^s)`,
/// `sh = density·(1 − lit)`, `H = n(L + V)`. `normal`, `to_light` and `to_viewer`
/// are unit vectors.
#[must_use]
pub fn blinn_phong(l: &Lighting, normal: Vec3, to_light: Vec3, to_viewer: Vec3, lit: f32) -> f32 {
    let sh = l.shadow_density * (1.0 - lit);
    let half = (to_light + to_viewer).normalize_or_zero();
    l.attenuation
        * (l.ambient
            + (1.0 - sh) * l.diffuse * to_light.dot(normal).max(0.0)
            + sh * l.shadow_colour
            + lit * l.specular * half.dot(normal).max(0.0).powf(l.shininess))
}

/// Asymmetry parameter `g` of a snowflake's single scattering in visible light,
/// diffraction included (ice crystals and their aggregates: 0.75–0.8; docs/model.md
/// (5.7a)).
pub const FLAKE_ASYMMETRY: f32 = 0.75;

/// The share of the sun's diffuse light a snowflake sends at scattering angle `Θ`
/// (`cos_scatter = cos Θ`, 1 straight on, away from the sun): half the
/// Henyey–Greenstein phase function of the delta-Eddington asymmetry
/// `g' = g/(1 + g)` ([`FLAKE_ASYMMETRY`]; the diffraction peak, a fraction `g²` far
/// narrower than a pixel, counted as light that went on unscattered), normalised to
/// a mean of ½ over the sphere like the `|cos|` of a plate lit from either side it
/// replaces: a flake between the camera and the sun glows (4.4× an isotropic
/// scatterer's), one with the sun behind the camera is dimmer (0.28×). Docs/model.md
/// (5.7a).
#[must_use]
pub fn flake_sun_phase(cos_scatter: f32) -> f32 {
    let g = FLAKE_ASYMMETRY / (1.0 + FLAKE_ASYMMETRY);
    let d = 1.0 + g * g - 2.0 * g * cos_scatter.clamp(-1.0, 1.0);
    0.5 * (1.0 - g * g) / (d * d.sqrt())
}

/// Fraction of light that crosses `distance_m` of precipitation of extinction
/// `extinction_per_m` (Beer–Lambert; at the Koschmieder visibility it is 2 %).
#[must_use]
pub fn fog_transmittance(distance_m: f32, extinction_per_m: f32) -> f32 {
    (-extinction_per_m * distance_m.max(0.0)).exp()
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn a_flake_scatters_forward_with_the_mean_of_a_two_sided_plate() {
        // Mean over the sphere: ½ ∫ P(cos Θ) d(cos Θ) over [−1, 1], midpoint rule.
        let n = 20_000;
        let mean = (0..n)
            .map(|i| flake_sun_phase(-1.0 + (i as f32 + 0.5) * 2.0 / n as f32))
            .sum::<f32>()
            / n as f32;
        assert!((mean - 0.5).abs() < 1e-3, "{mean}");
        let g = FLAKE_ASYMMETRY / (1.0 + FLAKE_ASYMMETRY);
        let forward_over_back = flake_sun_phase(1.0) / flake_sun_phase(-1.0);
        assert!(
            (forward_over_back - ((1.0 + g) / (1.0 - g)).powi(3)).abs() < 1e-2,
            "{forward_over_back}"
        );
        assert!(flake_sun_phase(1.0) > 2.0 && flake_sun_phase(-1.0) < 0.15);
        // Monotonic from back to forward.
        let mut last = 0.0;
        for i in 0..=100 {
            let p = flake_sun_phase(-1.0 + 0.02 * i as f32);
            assert!(p >= last);
            last = p;
        }
    }
    use crate::weather::visibility::koschmieder_visibility_m;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn sprite_faces_the_camera_with_side_s() {
        // Camera on +Z: N = Z, A = Y × Z = X, B = Z × X = Y.
        let c = snow_sprite_corners(Vec3::ZERO, Vec3::new(0.0, 0.0, 10.0), 2.0)
            .expect("not degenerate");
        assert!(close(c[0], Vec3::new(1.0, -1.0, 0.0)));
        assert!(close(c[1], Vec3::new(1.0, 1.0, 0.0)));
        assert!(close(c[2], Vec3::new(-1.0, -1.0, 0.0)));
        assert!(close(c[3], Vec3::new(-1.0, 1.0, 0.0)));
        let from_above =
            snow_sprite_corners(Vec3::ZERO, Vec3::new(0.0, 5.0, 0.0), 1.0).expect("fallback axis");
        assert!(
            from_above.iter().all(|v| v.y.abs() < 1e-6),
            "lies flat under a camera straight above"
        );
        assert!(snow_sprite_corners(Vec3::ONE, Vec3::ONE, 1.0).is_none());
    }

    #[test]
    fn tetrahedron_trails_the_velocity_with_an_equilateral_base() {
        let t = raindrop_tetrahedron(Vec3::ZERO, Vec3::new(0.0, -8.0, 0.0), 0.01, 10.0)
            .expect("moving");
        let h = 10.0 * 0.01 * 8.0;
        assert!(
            close(t.vertices[0], Vec3::new(0.0, h, 0.0)),
            "apex above a falling drop"
        );
        let a = 0.1 * h;
        for (i, j) in [(1, 2), (2, 3), (3, 1)] {
            assert!(
                ((t.vertices[i] - t.vertices[j]).length() - a).abs() < 1e-5,
                "base side {i}{j}"
            );
        }
        let centroid = (t.vertices[1] + t.vertices[2] + t.vertices[3]) / 3.0;
        assert!(close(centroid, Vec3::ZERO));
        assert!(close(t.normals[0], Vec3::Y));
        assert!(
            raindrop_tetrahedron(Vec3::ZERO, Vec3::X * 3.0, 0.01, 10.0).is_some(),
            "parallel to X"
        );
        assert!(raindrop_tetrahedron(Vec3::ZERO, Vec3::ZERO, 0.01, 10.0).is_none());
    }

    #[test]
    fn the_rain_strip_draws_the_tetrahedron_s_four_faces() {
        let sorted = |t: &[u32]| {
            let mut t = t.to_vec();
            t.sort_unstable();
            t
        };
        let mut faces: Vec<Vec<u32>> = RAIN_TETRAHEDRON_FACES.chunks(3).map(sorted).collect();
        let mut strip: Vec<Vec<u32>> = RAIN_TETRAHEDRON_STRIP.windows(3).map(sorted).collect();
        faces.sort();
        strip.sort();
        assert_eq!(strip, faces);
    }

    proptest! {
        #[test]
        fn a_still_flake_s_quad_has_the_turned_sprite_s_corners(
            x in -20.0f32..20.0, y in -5.0f32..5.0, z in -20.0f32..20.0,
            side in 0.001f32..0.2, spin in -7.0f32..7.0, tumble in MIN_TUMBLE..1.0,
        ) {
            let camera = Vec3::new(0.3, 1.7, -0.2);
            let centre = camera + Vec3::new(x, y, z);
            prop_assume!(Vec3::new(x, y, z).length() > 0.05);
            let sprite = snow_sprite_corners_turned(centre, camera, side, spin, tumble).expect("away");
            let axes = snow_quad_axes(centre, camera, side, (spin, tumble), Vec3::ZERO, 1.0 / 60.0).expect("away");
            prop_assert!((axes.stretch - 1.0).abs() < f32::EPSILON);
            let tolerance = 1.0e-5 * (1.0 + centre.abs().max_element());
            for (k, corner) in sprite.iter().enumerate() {
                let (position, uv) = axes.corner(centre, k);
                prop_assert!((position - *corner).abs().max_element() < tolerance, "{k}: {position} {corner}");
                let want = SNOW_SPRITE_UV[k];
                prop_assert!((uv[0] - want[0]).abs() + (uv[1] - want[1]).abs() < f32::EPSILON);
            }
        }
    }

    proptest! {
        #[test]
        fn nothing_inside_the_frustum_is_culled(u in -1.0f32..1.0, v in -1.0f32..1.0, depth in 0.1f32..500.0, hfov in 0.2f32..2.5, vfov in 0.2f32..2.5) {
            let cone = view_cone_cos(hfov, vfov);
            let point = Vec3::new(u * (0.5 * hfov).tan(), v * (0.5 * vfov).tan(), -1.0) * depth;
            prop_assert!(in_view_cone(point, Vec3::ZERO, Vec3::NEG_Z, cone - 1e-6));
            prop_assert!(!in_view_cone(-point, Vec3::ZERO, Vec3::NEG_Z, cone), "behind the camera");
        }
    }

    #[test]
    fn lighting_terms() {
        let l = Lighting {
            ambient: 0.2,
            diffuse: 0.6,
            specular: 0.5,
            shininess: 16.0,
            shadow_colour: 0.05,
            shadow_density: 1.0,
            attenuation: 1.0,
        };
        let up = Vec3::Y;
        let lit = blinn_phong(&l, up, up, up, 1.0);
        assert!((lit - (0.2 + 0.6 + 0.5)).abs() < 1e-6);
        let shadowed = blinn_phong(&l, up, up, up, 0.0);
        assert!((shadowed - (0.2 + 0.05)).abs() < 1e-6);
        let grazing = blinn_phong(&l, up, Vec3::X, Vec3::X, 1.0);
        assert!((grazing - 0.2).abs() < 1e-6);
    }

    #[test]
    fn fog_leaves_two_percent_at_the_visibility() {
        let sigma = 0.005;
        let v = koschmieder_visibility_m(sigma);
        assert!((fog_transmittance(v, sigma) - 0.02).abs() < 1e-3);
        assert!((fog_transmittance(0.0, sigma) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_turned_sprite_stays_facing_the_camera_and_keeps_its_size() {
        let (centre, camera) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 6.0, 15.0));
        let seed = snow_sprite_corners(centre, camera, 0.5).expect("not degenerate");
        let same = snow_sprite_corners_turned(centre, camera, 0.5, 0.0, 1.0).expect("ok");
        assert_eq!(seed, same);
        let turned = snow_sprite_corners_turned(centre, camera, 0.5, 0.7, 1.0).expect("ok");
        let n = (camera - centre).normalize();
        for v in turned {
            assert!(
                (v - centre).dot(n).abs() < 1e-5,
                "in the plane facing the camera"
            );
            assert!(((v - centre).length() - 0.5 / 2f32.sqrt()).abs() < 1e-5);
        }
        assert!(!close(turned[0], seed[0]), "spin moves the corners");
        let flat = snow_sprite_corners_turned(centre, camera, 0.5, 0.0, 0.3).expect("ok");
        assert!(
            ((flat[1] - flat[0]).length() - 0.15).abs() < 1e-5,
            "B side × tumble"
        );
        assert!(
            ((flat[0] - flat[2]).length() - 0.5).abs() < 1e-5,
            "A side kept"
        );
        let (spin, tumble) = flake_spin_tumble(Vec3::new(3.0, 0.1, 0.2), Vec3::new(0.0, 0.3, 0.4));
        assert!((spin - 1.0).abs() < 1e-6);
        assert!((tumble - 3f32.cos().abs()).abs() < 1e-6);
        let (_, edge_on) =
            flake_spin_tumble(Vec3::new(std::f32::consts::FRAC_PI_2, 0.0, 0.0), Vec3::ZERO);
        assert!((edge_on - MIN_TUMBLE).abs() < 1e-6);
    }

    #[test]
    fn sprites_and_streaks_never_shrink_under_the_minimum_and_keep_their_light() {
        let sizing = SpriteSizing {
            min_opacity: 0.15,
            ..SpriteSizing::default()
        };
        let pixel = 0.01;
        // A 5 mm flake at 1 m: 1.5 cm sprite, more than 1.5 px (1.5 cm)? equal: full.
        let (side, opacity) = snow_sprite_sizing(0.005, 1.0, pixel, &sizing);
        assert!((side - 0.015).abs() < 1e-6 && (opacity - 1.0).abs() < 1e-6);
        // At 4 m the minimum (6 cm) binds: opacity = (1.5/6)² = 1/16, floored at 0.15.
        let (side, opacity) = snow_sprite_sizing(0.005, 4.0, pixel, &sizing);
        assert!((side - 0.06).abs() < 1e-6);
        assert!((opacity - sizing.min_opacity).abs() < 1e-6);
        let (_, opacity) = snow_sprite_sizing(0.005, 2.0, pixel, &sizing);
        assert!((opacity - 0.25).abs() < 1e-6, "(1.5/3)²");
        // A 3 mm drop at 8 m/s, 1/60 s: h = 13.3 cm, a = 3 mm, opacity (π/2)·3/133.
        let (h, a, o) = raindrop_sizing(8.0, 0.003, 0.1, pixel, &sizing, 1.0 / 60.0);
        let expected = std::f32::consts::FRAC_PI_2 * 0.003 / h;
        assert!((h - 8.0 / 60.0).abs() < 1e-6 && (a - 0.003).abs() < 1e-6);
        assert!((o - expected).abs() < 1e-6, "{o}");
        // At 1 m the base (1.5 cm) is widened five times, the opacity cut by five.
        let (_, a, o1) = raindrop_sizing(8.0, 0.003, 1.0, pixel, &sizing, 1.0 / 60.0);
        assert!((a - 0.015).abs() < 1e-6 && (o1 - expected / 5.0).abs() < 1e-7);
    }

    #[test]
    fn particles_at_the_lens_fade_out() {
        assert!(near_fade(0.0).abs() < 1e-6 && near_fade(NEAR_FADE_START_M).abs() < 1e-6);
        assert!((near_fade(1.0) - 0.5).abs() < 1e-6);
        assert!((near_fade(NEAR_FADE_END_M) - 1.0).abs() < 1e-6);
        assert!((near_fade(30.0) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_particle_crossing_the_splat_threshold_keeps_its_ink() {
        let sizing = SpriteSizing::default();
        let pixel = 1.0e-3;
        let diameter = 0.004;
        let side = diameter * sizing.snow_scale;
        // The distance where the sprite is exactly min_px wide.
        let hand_over = side / (sizing.min_px * pixel);
        let ink_at = |d: f32| {
            let (side_m, opacity) = snow_sprite_sizing(diameter, d, pixel, &sizing);
            splat_ink(SplatShape::Sprite { side_m, opacity }, d, pixel)
        };
        assert!(!sub_pixel(side, hand_over * 0.999, pixel, sizing.min_px));
        assert!(sub_pixel(side, hand_over * 1.001, pixel, sizing.min_px));
        // Just before: the sprite, min_px² × mean texture; just after: the same.
        let before = ink_at(hand_over * 0.999);
        let after = ink_at(hand_over * 1.001);
        let expected = sizing.min_px * sizing.min_px * flake_mean_opacity();
        assert!(
            (before - expected).abs() < 0.01 * expected,
            "{before} {expected}"
        );
        assert!((after - before).abs() < 0.01 * before, "{after} {before}");
        // Farther, the ink falls as 1/d² (the flake's own area) until the floor.
        let far = ink_at(hand_over * 2.0);
        assert!((far - 0.25 * expected).abs() < 0.01 * expected, "{far}");
        // Rain: a streak of min_px length (h) at its hand-over, base min_px.
        let (h, a, o) = raindrop_sizing(8.0, 0.002, 200.0, pixel, &sizing, 1.0 / 60.0);
        let ink = splat_ink(
            SplatShape::Streak {
                h_m: h,
                a_m: a,
                opacity: o,
            },
            200.0,
            pixel,
        );
        assert!(
            (ink - 0.5 * (h / 0.2) * (a / 0.2) * o).abs() < 1e-4,
            "{ink}"
        );
    }

    #[test]
    fn a_flake_is_swept_as_long_as_its_motion_during_the_exposure() {
        let camera = Vec3::new(0.0, 1.7, 0.0);
        let centre = Vec3::new(0.0, 1.7, -2.0);
        let side = 0.01;
        // A blizzard's flake 2 m away crossing the view at 14 m/s for 1/60 s: 23 cm.
        let v = Vec3::new(14.0, -1.0, 0.0);
        let (corners, stretch) =
            snow_streak_corners(centre, camera, side, (0.3, 0.8), v, 1.0 / 60.0).expect("away");
        let sweep = Vec3::new(14.0, -1.0, 0.0) / 60.0;
        assert!(
            (stretch - (side + sweep.length()) / side).abs() < 1e-3,
            "{stretch}"
        );
        // Its length along the sweep is side + |sweep| (10 %), its width a side.
        let length = (corners[1].0 - corners[0].0).length();
        let width = (corners[2].0 - corners[0].0).length();
        assert!(
            (length / (side + sweep.length()) - 1.0).abs() < 0.1,
            "{length}"
        );
        assert!((width - side).abs() < 1e-5);
        // In pixels of 1 mrad: 23 cm at 2 m is about 117 px.
        let px = (length - side) / (2.0 * 1.0e-3);
        let want_px = sweep.length() / (2.0 * 1.0e-3);
        assert!((px / want_px - 1.0).abs() < 0.1, "{px} {want_px}");
        // A flake moving along the line of sight, or barely, is the turned sprite.
        let (_, still) = snow_streak_corners(
            centre,
            camera,
            side,
            (0.3, 0.8),
            Vec3::new(0.0, 0.0, 3.0),
            1.0 / 60.0,
        )
        .expect("away");
        assert!((still - 1.0).abs() < f32::EPSILON);
        // The texture's v: halves at the ends, the centre line between.
        assert!((snow_streak_texture_v(0.2, 5.0) - 0.2).abs() < 1e-6);
        assert!((snow_streak_texture_v(2.5, 5.0) - 0.5).abs() < 1e-6);
        assert!((snow_streak_texture_v(4.8, 5.0) - 0.8).abs() < 1e-6);
        assert!((snow_streak_texture_v(0.7, 1.0) - 0.7).abs() < 1e-6);
    }

    #[test]
    fn defocus_spreads_a_flake_without_changing_its_ink() {
        // f/4 on a 60° lens: f = 20.8 mm, A = 5.2 mm; focused at 10 m.
        let lens = crate::backend::camera::Lens::default();
        let a = lens.aperture_m(60f32.to_radians());
        assert!(
            (a - 0.012 / (30f32.to_radians().tan()) / 4.0).abs() < 1e-6,
            "{a}"
        );
        assert!(defocus_blur_m(a, 10.0, 10.0).abs() < 1e-9, "in focus");
        // At 1 m: A·0.9, 4.7 mm (3 px at 1.6 mrad per px).
        let near = defocus_blur_m(a, 10.0, 1.0);
        assert!((near - 0.9 * a).abs() < 1e-6, "{near}");
        // A pinhole is sharp everywhere.
        let pinhole = crate::backend::camera::Lens {
            f_number: f32::INFINITY,
            ..lens
        };
        assert!(pinhole.aperture_m(1.0).abs() < f32::MIN_POSITIVE);
        for power in [2, 1] {
            let (wide, o) = defocused(0.01, 0.8, near, power);
            assert!((wide - (0.01 + near)).abs() < 1e-7);
            let ink = |w: f32| w.powi(power);
            assert!((ink(wide) * o - ink(0.01) * 0.8).abs() < 1e-6, "ink kept");
        }
    }

    #[test]
    fn a_streak_is_as_long_as_the_exposure_and_holds_the_drop_s_area() {
        let pixel = 1.0e-3;
        for exposure_s in [1.0 / 250.0, 1.0 / 60.0, 1.0 / 15.0] {
            let sizing = SpriteSizing::default();
            for distance_m in [1.0f32, 3.0, 10.0, 40.0] {
                for (diameter_m, speed_mps) in [(0.0005, 2.0), (0.002, 6.5), (0.005, 9.1)] {
                    let (h, a, o) = raindrop_sizing(
                        speed_mps, diameter_m, distance_m, pixel, &sizing, exposure_s,
                    );
                    let px = 1.0 / (pixel * distance_m);
                    // Streak length = speed × exposure, in pixels (10 %).
                    let want_px = speed_mps * exposure_s * px;
                    assert!(((h * px) / want_px - 1.0).abs() < 0.1, "{h} {want_px}");
                    // Ink = the drop's projected area, px² (1 %), at any size on screen.
                    let ink = splat_ink(
                        SplatShape::Streak {
                            h_m: h,
                            a_m: a,
                            opacity: o,
                        },
                        distance_m,
                        pixel,
                    );
                    let area = std::f32::consts::FRAC_PI_4 * (diameter_m * px).powi(2);
                    assert!((ink / area - 1.0).abs() < 0.01, "{ink} vs {area}");
                }
            }
        }
    }

    #[test]
    fn the_flake_texture_is_opaque_at_the_core_clear_at_the_corners_and_six_fold() {
        let n = 64u32;
        let t = snowflake_opacity(n);
        assert_eq!(t.len(), 64 * 64);
        let at = |x: f32, y: f32| {
            let (i, j) = (
                ((x + 1.0) / 2.0 * n as f32) as u32,
                ((y + 1.0) / 2.0 * n as f32) as u32,
            );
            t[(j.min(n - 1) * n + i.min(n - 1)) as usize]
        };
        assert_eq!(at(0.0, 0.0), 255);
        assert_eq!(at(-0.99, -0.99), 0);
        // Arms at 30° + k·60° (one points straight up the sprite); clear between them.
        let r = 0.6f32;
        let arm = |deg: f32| at(r * deg.to_radians().cos(), r * deg.to_radians().sin());
        assert!(arm(30.0) > 200 && arm(90.0) > 200 && arm(150.0) > 200);
        assert!(arm(0.0) < 40 && arm(60.0) < 40);
    }
}
