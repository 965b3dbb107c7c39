//! [`shade_texel`]: coverage, masks and wet darkening composed for a surface shader
//! (seed 003, equations 15–17; WGSL twin `cover_shading` in shading.wgsl).
//!
//! ## Reading of the seed
//!
//! Equation 15 gives `A_M = T_M.g − A_S` and `M_M = T_M.r − M_S`, and the text says a
//! mask value is the threshold at which a point becomes covered (or bare). We read
//! `A_M ≤ 0` as *covered* and `M_M ≤ 0` as *melted bare*, with a soft edge of width
//! `mask_edge` so patch borders are not aliased. The thresholds are rescaled by
//! `1 + edge` so that `A_S = 0` shows no snow anywhere and `A_S = 1` shows it
//! everywhere. Wet darkening multiplies the ground by `1 − R_d·wetness`.
//!
//! ## Beyond the seed: a natural cover
//!
//! The seed's `A_S` grows linearly with depth to full cover at 30 mm; we take Niu &
//! Yang's (2007) depletion curve instead ([`snow_cover_fraction`]), which knows the
//! surface's roughness (grass shows through thin snow, a roof does not) and the
//! pack's density (melt opens the cover as the pack densifies). A surface point
//! compares it not with its texel's mask alone but with the mask moved by value
//! noise finer than a texel ([`sub_texel_threshold`]), so patch borders follow
//! neither texels nor triangles; the edge is 0.2 of the mask's range, so thin snow
//! at a border lets the surface show through.
//!
//! Sand and dust that settled ([`CoverTexel::dust_kg_m2`]) tint the bare surface
//! under the snow: grains scattered at random hide `1 − e^(−m/m₀)` of it
//! ([`settled_grain_cover`]; a layer of mass `m` of grains of diameter `d` projects
//! `3m/(2ρd)` of area per area, so `m₀ = 2ρd/3`: 0.35 kg/m² for 0.2 mm sand, 0.02
//! for 10 µm dust; [`GRAINS_COVERING_KG_M2`] takes 0.1, between them).

use crate::params::CoverParams;
use crate::surface::Surface;
use crate::texel::CoverTexel;

/// What a surface shader needs from the cover at one point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverShading {
    /// Opacity of the snow layer over the surface, `[0, 1]` (`C_out.a`).
    pub snow_alpha: f32,
    /// Factor on the bare surface's colour for wetness, `[1 − R_d, 1]`.
    pub ground_darkening: f32,
    /// Snow depth for displacement, metres.
    pub depth_m: f32,
    /// `A_M`: accumulation mask result (≤ 0: covered).
    pub accumulation_mask_result: f32,
    /// `M_M`: melt mask result (≤ 0: melted bare).
    pub melt_mask_result: f32,
}

/// The mass of settled grains that hides `1 − 1/e` of a surface, kg/m² (module docs).
pub const GRAINS_COVERING_KG_M2: f32 = 0.1;

/// The fraction of a surface that settled sand and dust hide (module docs).
/// WGSL twin: `settled_grain_cover` in `shaders/shading.wgsl`.
#[must_use]
pub fn settled_grain_cover(dust_kg_m2: f32) -> f32 {
    1.0 - (-dust_kg_m2.max(0.0) / GRAINS_COVERING_KG_M2).exp()
}

/// Density of new snow in the depletion curve, kg/m³ (Niu & Yang 2007).
pub const NEW_SNOW_DENSITY_KG_M3: f32 = 100.0;

/// The fraction of a surface of roughness length `roughness_m` that snow of
/// `depth_m` and `density_kg_m3` covers (Niu & Yang 2007, *J. Geophys. Res.* 112,
/// D21101, eq. 4): `f = tanh(h / (2.5·z₀·(ρ/ρ_new)^m))`, `ρ_new` =
/// [`NEW_SNOW_DENSITY_KG_M3`], `m` the depletion exponent. Continuous and increasing
/// in depth from 0 at no snow towards 1; a denser pack of the same depth (older or
/// melting snow) covers less, so melt opens the cover before the last snow goes.
/// The density is clamped to `[30, 917]` kg/m³. WGSL twin: same name
/// (shading.wgsl).
#[must_use]
pub fn snow_cover_fraction(
    depth_m: f32,
    density_kg_m3: f32,
    roughness_m: f32,
    exponent: f32,
) -> f32 {
    // Not above zero, or NaN: no snow.
    if depth_m.is_nan() || depth_m <= 0.0 {
        return 0.0;
    }
    let density = density_kg_m3.clamp(30.0, 917.0);
    let scale_m = 2.5 * roughness_m.max(1.0e-4) * (density / NEW_SNOW_DENSITY_KG_M3).powf(exponent);
    (depth_m / scale_m).tanh()
}

/// `A_S`: the fraction of the area the accumulated snow covers
/// ([`snow_cover_fraction`] with the texel's depth, its pack's density and its
/// surface's roughness length).
#[must_use]
pub fn accumulated_fraction(texel: &CoverTexel, params: &CoverParams) -> f32 {
    let density = if texel.depth_mm > 0.0 {
        1000.0 * texel.swe_mm / texel.depth_mm
    } else {
        NEW_SNOW_DENSITY_KG_M3
    };
    snow_cover_fraction(
        texel.depth_mm * 1.0e-3,
        density,
        Surface::from_raw(texel.surface).snow_roughness_m(),
        params.cover_depletion_exponent,
    )
}

/// Wavelengths of the two octaves of [`sub_texel_threshold`]'s noise, m.
pub const THRESHOLD_NOISE_WAVELENGTHS_M: [f32; 2] = [0.6, 0.15];
/// How far [`sub_texel_threshold`] moves a mask value, at most (each way).
pub const THRESHOLD_NOISE_AMPLITUDE: f32 = 0.2;

/// An integer hash of a lattice point to `[0, 1)`: the point's two words mixed, then
/// the PCG output permutation (O'Neill 2014, RXS-M-XS); the same bits in WGSL.
#[must_use]
fn lattice_value(i: i32, j: i32) -> f32 {
    let state = ((i as u32).wrapping_mul(0x8da6_b343) ^ (j as u32).wrapping_mul(0xd816_3841))
        .wrapping_mul(747_796_405)
        .wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (((word >> 22) ^ word) >> 8) as f32 / 16_777_216.0
}

/// Value noise in `[0, 1]` at `(x, z)` in lattice units: the lattice's values
/// blended with the quintic fade, so it is continuous with continuous slope.
/// WGSL twin: same name (shading.wgsl).
#[must_use]
pub fn value_noise(x: f32, z: f32) -> f32 {
    let (fx, fz) = (x.floor(), z.floor());
    let (i, j) = (fx as i32, fz as i32);
    let fade = |t: f32| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let (u, v) = (fade(x - fx), fade(z - fz));
    let a = lattice_value(i, j) + (lattice_value(i + 1, j) - lattice_value(i, j)) * u;
    let b = lattice_value(i, j + 1) + (lattice_value(i + 1, j + 1) - lattice_value(i, j + 1)) * u;
    a + (b - a) * v
}

/// Wavelength of [`cover_warp_m`]'s noise, in texels of the cover grid.
pub const COVER_WARP_WAVELENGTH_TEXELS: f32 = 1.5;

/// How far a surface point moves the place it reads the cover at, m: two value
/// noises (one per axis) over `COVER_WARP_WAVELENGTH_TEXELS` texels, each in
/// `±½` texel, so the interpolated depth's contours — where a drift or a bare
/// patch ends — wander off the grid's lines instead of tracing its texels.
/// Continuous. WGSL twin: same name (shading.wgsl).
#[must_use]
pub fn cover_warp_m(xz_m: [f32; 2], cell_m: [f32; 2]) -> [f32; 2] {
    let scale = [
        cell_m[0] * COVER_WARP_WAVELENGTH_TEXELS,
        cell_m[1] * COVER_WARP_WAVELENGTH_TEXELS,
    ];
    let (u, v) = (
        xz_m[0] / scale[0].max(1.0e-3),
        xz_m[1] / scale[1].max(1.0e-3),
    );
    [
        (value_noise(u, v) - 0.5) * cell_m[0],
        (value_noise(u + 53.0, v + 91.0) - 0.5) * cell_m[1],
    ]
}

/// The accumulation threshold a surface point compares its coverage with: the
/// texel's mask (interpolated between texels) moved by two octaves of value noise
/// finer than a texel ([`THRESHOLD_NOISE_WAVELENGTHS_M`]), so a patch's border wanders
/// within and across texels and triangles instead of following them. Continuous in
/// `xz_m`. WGSL twin: same name (shading.wgsl).
#[must_use]
pub fn sub_texel_threshold(mask: f32, xz_m: [f32; 2]) -> f32 {
    let [coarse, fine] = THRESHOLD_NOISE_WAVELENGTHS_M;
    let n = (2.0 * value_noise(xz_m[0] / coarse, xz_m[1] / coarse)
        + value_noise(xz_m[0] / fine + 17.0, xz_m[1] / fine + 31.0))
        / 3.0;
    mask + THRESHOLD_NOISE_AMPLITUDE * 2.0 * (n - 0.5)
}

/// `M_S`: the fraction of the pack's peak that has melted.
#[must_use]
pub fn melted_fraction(texel: &CoverTexel) -> f32 {
    if texel.peak_swe_mm > 0.0 {
        (1.0 - texel.swe_mm / texel.peak_swe_mm).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Composes the cover of one texel, using its own threshold masks.
#[must_use]
pub fn shade_texel(texel: &CoverTexel, params: &CoverParams) -> CoverShading {
    shade_with_masks(texel, texel.accumulation_mask, texel.melt_mask, params)
}

/// Composes the cover with mask values `(T_M.g, T_M.r)` given by the caller (a shader
/// samples a finer mask texture per fragment).
#[must_use]
pub fn shade_with_masks(
    texel: &CoverTexel,
    mask_g: f32,
    mask_r: f32,
    params: &CoverParams,
) -> CoverShading {
    let edge = params.mask_edge;
    let a_s = accumulated_fraction(texel, params);
    let m_s = melted_fraction(texel);
    let a_m = mask_g - a_s;
    let m_m = mask_r - m_s;
    let covered = ((a_s * (1.0 + edge) - mask_g) / edge).clamp(0.0, 1.0);
    let remaining = ((mask_r + edge - m_s * (1.0 + edge)) / edge).clamp(0.0, 1.0);
    CoverShading {
        snow_alpha: covered * remaining,
        ground_darkening: 1.0 - params.wet_darkening * texel.wetness.clamp(0.0, 1.0),
        depth_m: texel.depth_mm * 1.0e-3,
        accumulation_mask_result: a_m,
        melt_mask_result: m_m,
    }
}

/// The albedo of the ground at a texel as a whole, for light it sends back to the sky
/// and to falling drops (what a raindrop refracts, `precip_model`'s drop
/// environment): the bare surface's `bare_albedo` where no snow shows, the snow's
/// ([`crate::melt::snow_albedo`], greying with age) over the share
/// [`shade_texel`] shows, `ρ = ρ_bare + (A − ρ_bare)·α`. WGSL twin: `ground_albedo`
/// (shading.wgsl).
#[must_use]
pub fn ground_albedo(texel: &CoverTexel, params: &CoverParams, bare_albedo: f32) -> f32 {
    let shown = shade_texel(texel, params).snow_alpha;
    let snow = crate::melt::snow_albedo(texel.age_days, params.albedo_decay_per_day);
    bare_albedo + (snow - bare_albedo) * shown
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ground_s_albedo_goes_from_bare_to_the_snow_s_as_snow_covers_it() {
        let p = CoverParams::default();
        let bare = CoverTexel {
            accumulation_mask: 0.5,
            melt_mask: 0.5,
            ..CoverTexel::default()
        };
        assert!((ground_albedo(&bare, &p, 0.2) - 0.2).abs() < 1e-6);
        let mut deep = bare;
        deep.depth_mm = 500.0;
        deep.swe_mm = 50.0;
        deep.peak_swe_mm = 50.0;
        assert!(
            (ground_albedo(&deep, &p, 0.2) - 0.8).abs() < 1e-4,
            "fresh snow: 0.8"
        );
        deep.age_days = 30.0;
        let old = ground_albedo(&deep, &p, 0.2);
        assert!((0.4..0.8).contains(&old), "old snow greys: {old}");
        // Thin snow at a texel whose threshold it just passes shows in part.
        let mut thin = bare;
        thin.accumulation_mask = 0.1;
        thin.depth_mm = 3.0;
        thin.swe_mm = 0.3;
        thin.peak_swe_mm = 0.3;
        let a = ground_albedo(&thin, &p, 0.2);
        assert!(a > 0.2 && a < 0.8, "thin snow: {a}");
    }

    #[test]
    fn settled_grains_hide_the_surface_as_their_layer_grows() {
        assert!(settled_grain_cover(0.0).abs() < 1e-7);
        assert!(
            (settled_grain_cover(GRAINS_COVERING_KG_M2) - (1.0 - (-1.0f32).exp())).abs() < 1e-6
        );
        assert!(settled_grain_cover(1.0) > 0.99);
        assert!(settled_grain_cover(-1.0).abs() < 1e-7);
    }

    #[test]
    fn no_snow_shows_nothing_full_snow_shows_everywhere() {
        let p = CoverParams::default();
        for g in [0.0, 0.01, 0.5, 0.99, 1.0] {
            let bare = CoverTexel {
                accumulation_mask: g,
                melt_mask: g,
                ..CoverTexel::default()
            };
            assert!(shade_texel(&bare, &p).snow_alpha.abs() < f32::MIN_POSITIVE);
            let deep = CoverTexel {
                depth_mm: 1000.0,
                swe_mm: 100.0,
                peak_swe_mm: 100.0,
                ..bare
            };
            assert!((shade_texel(&deep, &p).snow_alpha - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn a_texel_is_covered_once_a_s_passes_its_threshold_and_bare_once_m_s_passes_its_own() {
        let p = CoverParams::default();
        let t = CoverTexel {
            accumulation_mask: 0.3,
            melt_mask: 0.6,
            swe_mm: 10.0,
            peak_swe_mm: 10.0,
            ..CoverTexel::default()
        };
        // Fresh snow (100 kg/m³) on soil: A_S = tanh(h / 25 mm).
        let at = |depth_mm: f32, melted: f32| {
            let x = CoverTexel {
                depth_mm,
                swe_mm: 0.1 * depth_mm * (1.0 - melted),
                peak_swe_mm: 0.1 * depth_mm,
                ..t
            };
            shade_texel(&x, &p).snow_alpha
        };
        // A_S·(1 + ε) below the mask: bare; ε above it: covered.
        assert!(at(2.0, 0.0) < 0.01);
        assert!(at(25.0, 0.0) > 0.99);
        assert!(at(100.0, 0.3) > 0.99);
        assert!(at(100.0, 0.8) < 0.01);
    }

    #[test]
    fn the_depletion_curve_is_niu_and_yang_s() {
        // tanh(h / (2.5·z₀·(ρ/100)^m)) at the table's values.
        let f = snow_cover_fraction(0.025, 100.0, 0.01, 1.0);
        assert!((f - 1.0f32.tanh()).abs() < 1e-6, "{f}");
        let dense = snow_cover_fraction(0.025, 300.0, 0.01, 1.0);
        assert!((dense - (1.0f32 / 3.0).tanh()).abs() < 1e-6, "{dense}");
        assert!(snow_cover_fraction(0.0, 100.0, 0.01, 1.0).abs() < f32::MIN_POSITIVE);
        assert!(snow_cover_fraction(-1.0, 100.0, 0.01, 1.0).abs() < f32::MIN_POSITIVE);
        assert!(snow_cover_fraction(1.0, 100.0, 0.01, 1.0) > 0.999);
        // Half a lawn shows through 2 cm of fresh snow; a roof is white.
        let grass = snow_cover_fraction(0.02, 100.0, Surface::Grass.snow_roughness_m(), 1.0);
        let roof = snow_cover_fraction(0.02, 100.0, Surface::Roof.snow_roughness_m(), 1.0);
        assert!(grass < 0.6 && roof > 0.9, "{grass} {roof}");
    }

    proptest::proptest! {
        #[test]
        fn coverage_is_continuous_and_monotonic_in_depth(
            depth_mm in 0.0f32..500.0,
            step_mm in 0.0f32..1.0,
            density in 50.0f32..600.0,
            surface in 0u32..6,
        ) {
            let z0 = Surface::from_raw(surface).snow_roughness_m();
            let a = snow_cover_fraction(depth_mm * 1e-3, density, z0, 1.0);
            let b = snow_cover_fraction((depth_mm + step_mm) * 1e-3, density, z0, 1.0);
            proptest::prop_assert!((0.0..=1.0).contains(&a));
            proptest::prop_assert!(b >= a);
            // Slope at most 1/(2.5·z₀·ρ/ρ_new) per metre: 1 mm moves it at most 0.08.
            proptest::prop_assert!(b - a <= step_mm * 1e-3 / (2.5 * z0 * density.clamp(30.0, 917.0) / 100.0) + 1e-6);
        }

        #[test]
        fn the_threshold_is_continuous_across_texels_and_lattice_lines(
            x in -500.0f32..500.0,
            z in -500.0f32..500.0,
            dx in -0.001f32..0.001,
            dz in -0.001f32..0.001,
            mask in 0.0f32..1.0,
        ) {
            let a = sub_texel_threshold(mask, [x, z]);
            let b = sub_texel_threshold(mask, [x + dx, z + dz]);
            // The fade's slope is at most 15/8 per lattice unit; the fine octave's
            // lattice is 0.15 m: at most 2·0.2·(1/3)·(15/8)/0.15·|d|·√2 + the coarse.
            proptest::prop_assert!((a - b).abs() <= 3.0 * (dx.abs() + dz.abs()) + 1e-4, "{a} {b}");
            proptest::prop_assert!((a - mask).abs() <= THRESHOLD_NOISE_AMPLITUDE + 1e-6);
        }
    }

    #[test]
    fn the_warp_stays_within_half_a_texel_and_is_continuous() {
        let cell = [1.0, 0.5];
        for i in 0..5_000 {
            let x = i as f32 * 0.173 - 400.0;
            let z = (i / 70) as f32 * 0.311 - 10.0;
            let w = cover_warp_m([x, z], cell);
            assert!(
                w[0].abs() <= 0.5 * cell[0] && w[1].abs() <= 0.5 * cell[1],
                "{w:?}"
            );
            let n = cover_warp_m([x + 1.0e-3, z - 1.0e-3], cell);
            assert!(
                (n[0] - w[0]).abs() + (n[1] - w[1]).abs() < 1.0e-2,
                "{w:?} {n:?}"
            );
        }
    }

    #[test]
    fn the_noise_spreads_over_its_range() {
        let values: Vec<f32> = (0..10_000)
            .map(|i| value_noise(i as f32 * 0.37, (i / 100) as f32 * 0.53))
            .collect();
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        assert!((mean - 0.5).abs() < 0.05, "{mean}");
        assert!(values.iter().all(|v| (0.0..=1.0).contains(v)));
        assert!(values.iter().any(|v| *v < 0.1) && values.iter().any(|v| *v > 0.9));
    }

    #[test]
    fn wet_ground_is_darker() {
        let p = CoverParams::default();
        let wet = CoverTexel {
            wetness: 1.0,
            ..CoverTexel::default()
        };
        assert!((shade_texel(&wet, &p).ground_darkening - (1.0 - p.wet_darkening)).abs() < 1e-6);
        assert!((shade_texel(&CoverTexel::default(), &p).ground_darkening - 1.0).abs() < 1e-6);
    }
}
