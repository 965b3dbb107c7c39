//! The open sea as the frame draws it (docs/model.md (13.8)): a mesh tagged
//! `"water": "sea"` is drawn with the wind's waves (`precip_sea::ocean`, on the
//! GPU each frame: three cascades of [`precip_sea::ocean::OCEAN_N`]² points), its
//! colour the water's own by wavelength (`precip_sea::optics`), its foam where the
//! surface folds and where the wind whips up whitecaps. The weather gives the
//! wind (its mean, 10 m above the water); [`SeaSettings`] the rest.
//!
//! Toward the shore the water shoals: a wave breaks when its height reaches
//! [`BREAKER_INDEX`] times the depth (McCowan 1894), so the sea's waves are
//! scaled down to `min(1, γ_b·d/H_s)` of their open-sea height over the depth `d`
//! the scene's bed gives ([`sea_depth_map`]: sea level less the top-most surface of
//! every mesh but the sea), and foam marks the surf where they are cut down. Over
//! the shore's grid the shallow-water solver's water takes the place of the longest
//! waves: the run-up on the beach and the reflection off walls
//! ([`crate::drawing::shore`]).

use glam::Vec4;
use precip_cover::GridFrame;
pub use precip_sea::ocean::SeaSpectrum;
use precip_sea::ocean::{
    PHILLIPS_AMPLITUDE, SeaState, jonswap_peak_rad_per_s, jonswap_rad, whitecap_cover,
};
use precip_sea::optics::{SEABED_ALBEDO, WATER_LEAVING_FACTOR, WaterContent};

use crate::BackendError;
use crate::particles::ground::GroundMap;
use crate::scene::Scene;

/// The breaker index γ_b: the highest wave the depth `d` holds is `γ_b·d`
/// (McCowan 1894, for a solitary wave).
pub const BREAKER_INDEX: f32 = 0.78;

/// The depths [`sea_depth_map`] holds, m: 0 … this, in steps of a 255th (deeper
/// water shoals no wave of a sea the wind raises on a coast).
pub const SEA_DEPTH_RANGE_M: f32 = 25.5;

/// The sea's level: the mean height of its meshes' vertices, m (`None` without a
/// sea).
#[must_use]
pub fn sea_level_m(scene: &Scene) -> Option<f32> {
    let (sum, n) = scene
        .meshes
        .iter()
        .filter(|m| m.is_sea())
        .flat_map(|m| m.positions_m.iter())
        .fold((0.0f64, 0usize), |(s, n), p| (s + f64::from(p.y), n + 1));
    (n > 0).then(|| (sum / n as f64) as f32)
}

/// The water's depth under the sea's level over `frame`, per texel (rows in order),
/// as 8-bit fractions of [`SEA_DEPTH_RANGE_M`]: the level less the bed, the
/// top-most upward face under the level of every mesh but the sea (a pier's deck
/// or a wall's underside is no bed: the seabed under them is); 0 where only land
/// above the level lies; the whole range where no mesh lies under the sea. Empty
/// without a sea.
#[must_use]
pub fn sea_depth_map(scene: &Scene, frame: GridFrame) -> Vec<u8> {
    let Some(level) = sea_level_m(scene) else {
        return Vec::new();
    };
    let land = || scene.meshes.iter().filter(|m| !m.is_sea());
    let bed = GroundMap::top_down(land(), frame, f32::NEG_INFINITY, Some(level));
    let anything = GroundMap::top_down(land(), frame, f32::NEG_INFINITY, None);
    bed.height_m
        .iter()
        .zip(&anything.height_m)
        .map(|(bed, any)| {
            let depth = if bed.is_finite() {
                level - bed
            } else if any.is_finite() {
                0.0
            } else {
                SEA_DEPTH_RANGE_M
            };
            (depth.clamp(0.0, SEA_DEPTH_RANGE_M) / SEA_DEPTH_RANGE_M * 255.0).round() as u8
        })
        .collect()
}

/// The significant wave height `H_s = 4·√m₀` of `state`'s sea, m: JONSWAP's
/// frequency spectrum's zeroth moment over 0.5 … 8 times the peak (the rest holds
/// under 0.1 % of it); Phillips's `4·√(A·π/2)·U²/g` (its variance `A·π·L²/2`,
/// docs/model.md (13.6)).
#[must_use]
pub fn significant_height_m(state: &SeaState) -> f32 {
    let (u, f) = (state.wind_speed_mps, state.fetch_m);
    if let SeaSpectrum::Phillips = state.spectrum {
        return 4.0 * (PHILLIPS_AMPLITUDE * std::f32::consts::FRAC_PI_2).sqrt() * u * u / 9.81;
    }
    if u <= 0.0 || f <= 0.0 {
        return 0.0;
    }
    let peak = jonswap_peak_rad_per_s(u, f);
    let (lo, hi, n) = (0.5 * peak, 8.0 * peak, 400);
    let d = (hi - lo) / n as f32;
    let m0: f32 = (0..n)
        .map(|i| jonswap_rad(lo + (i as f32 + 0.5) * d, u, f, 3.3) * d)
        .sum();
    4.0 * m0.sqrt()
}

/// The open sea's settings: the water and the distance the wind has blown over it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeaSettings {
    /// The distance the wind has blown over open water to the scene, m (JONSWAP's
    /// fetch: 10 km a bay's, 100 km and more the open ocean's).
    pub fetch_m: f32,
    /// The water's depth offshore, m (the waves' speed by the dispersion relation).
    pub depth_m: f32,
    /// The choppy displacement's factor λ, `[0, 2]` (0: round crests, 1: as
    /// Tessendorf's, sharp crests that fold in a gale).
    pub choppiness: f32,
    /// The draw of the waves' phases, `[0, 2²⁴)`.
    pub seed: u32,
    /// What the water holds besides water (its colour).
    pub content: WaterContent,
    /// The spectrum (JONSWAP over the fetch by default).
    pub spectrum: SeaSpectrum,
}

impl Default for SeaSettings {
    fn default() -> Self {
        Self {
            fetch_m: 100_000.0,
            depth_m: 50.0,
            choppiness: 1.0,
            seed: 1,
            content: WaterContent::COASTAL,
            spectrum: SeaSpectrum::Jonswap,
        }
    }
}

/// The most seed [`SeaSettings::seed`] takes (it travels as a float's integer).
pub const MAX_SEA_SEED: u32 = (1 << 24) - 1;

impl SeaSettings {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), BackendError> {
        let bad = |field: &'static str, problem: String| BackendError::Setup { field, problem };
        for (field, value, lo, hi) in [
            ("render.sea.fetch_m", self.fetch_m, 100.0, 1.0e7),
            ("render.sea.depth_m", self.depth_m, 0.5, 1.1e4),
            ("render.sea.choppiness", self.choppiness, 0.0, 2.0),
            (
                "render.sea.content.organic_absorption_440_per_m",
                self.content.organic_absorption_440_per_m,
                0.0,
                20.0,
            ),
            (
                "render.sea.content.particle_scattering_550_per_m",
                self.content.particle_scattering_550_per_m,
                0.0,
                50.0,
            ),
        ] {
            if !(value.is_finite() && (lo..=hi).contains(&value)) {
                return Err(bad(field, format!("= {value} must be in [{lo}, {hi}]")));
            }
        }
        if self.seed > MAX_SEA_SEED {
            return Err(bad(
                "render.sea.seed",
                format!("= {} must be in [0, {MAX_SEA_SEED}]", self.seed),
            ));
        }
        Ok(())
    }

    /// The sea a wind of `wind_mps` (x, z, m/s, 10 m above the water) raises.
    #[must_use]
    pub fn state(&self, wind_mps: [f32; 2]) -> SeaState {
        SeaState {
            spectrum: self.spectrum,
            ..SeaState::of_wind(
                wind_mps,
                self.fetch_m,
                self.depth_m,
                self.choppiness,
                self.seed,
            )
        }
    }

    /// The frame block's rows of the sea (`RenderParams::ocean_wind`, `ocean`,
    /// `sea_colour`, `sea_attenuation`, `sea_bed`, `ocean_spectrum`) in a wind of
    /// `wind_mps`.
    #[must_use]
    pub fn rows(&self, wind_mps: [f32; 2]) -> [Vec4; 6] {
        let s = self.state(wind_mps);
        let colour = self.content.water_leaving_colour();
        let k = self.content.rgb_attenuation_per_m();
        let bed = SEABED_ALBEDO.map(|a| a * WATER_LEAVING_FACTOR);
        [
            Vec4::new(
                s.wind_speed_mps,
                s.fetch_m,
                s.wind_direction[0],
                s.wind_direction[1],
            ),
            Vec4::new(
                s.choppiness,
                s.depth_m,
                s.seed as f32,
                significant_height_m(&s),
            ),
            Vec4::new(
                colour[0],
                colour[1],
                colour[2],
                whitecap_cover(s.wind_speed_mps),
            ),
            Vec4::new(k[0], k[1], k[2], 0.0),
            Vec4::new(bed[0], bed[1], bed[2], 0.0),
            Vec4::new(
                match s.spectrum {
                    SeaSpectrum::Jonswap => 0.0,
                    SeaSpectrum::Phillips => 1.0,
                },
                0.0,
                0.0,
                0.0,
            ),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gale_raises_whitecaps_a_breeze_hardly_any() {
        let sea = SeaSettings::default();
        let [wind, row, colour, _, _, spectrum] = sea.rows([3.0, 4.0]);
        assert!(spectrum.x.abs() < f32::EPSILON);
        assert!((wind.x - 5.0).abs() < 1e-6, "{wind}");
        assert!((wind.z - 0.6).abs() < 1e-6 && (wind.w - 0.8).abs() < 1e-6);
        assert!((row.z - 1.0).abs() < 1e-6, "{row}");
        assert!(colour.w < 0.001, "{colour}");
        let gale = sea.rows([24.0, 0.0])[2].w;
        assert!(gale > 0.05, "{gale}");
        // Coastal water is blue-green and dark: little of the light comes back.
        assert!(
            colour.z > colour.x && colour.max_element() < 0.1,
            "{colour}"
        );
    }

    #[test]
    fn the_significant_height_is_the_spectrum_s() {
        // 15 m/s over 50 km: the closed moment against the wavenumber integral.
        let state = SeaState::of_wind([15.0, 0.0], 50_000.0, 1.0e3, 1.0, 1);
        let got = significant_height_m(&state);
        let want = state.wind_sea().significant_height_m(1.0e-3, 60.0);
        println!("H_s {got:.3} m against {want:.3} m");
        assert!((got / want - 1.0).abs() < 0.03, "{got} {want}");
        let calm = SeaState::of_wind([0.0, 0.0], 50_000.0, 1.0e3, 1.0, 1);
        assert!(significant_height_m(&calm).abs() < f32::EPSILON);
    }

    #[test]
    fn the_depth_map_reads_the_bed_under_the_sea() {
        use crate::scene::Mesh;
        use glam::{UVec2, Vec2, Vec3};
        // A sea at 1 m over a bed sloping from 5 m deep (x = −10) to 1 m above the
        // sea (x = 10), on half the frame; open water on the other half.
        let square = |x0: f32, x1: f32, y0: f32, y1: f32| Mesh {
            positions_m: vec![
                Vec3::new(x0, y0, -10.0),
                Vec3::new(x1, y1, -10.0),
                Vec3::new(x1, y1, 0.0),
                Vec3::new(x0, y0, 0.0),
            ],
            indices: vec![0, 2, 1, 0, 3, 2],
            ..Mesh::default()
        };
        let sea = Mesh {
            surface: Some(precip_cover::Surface::Water),
            sea: true,
            ..square(-10.0, 10.0, 1.0, 1.0)
        };
        // A deck over the deep end, 2 m above the sea: no bed.
        let deck = square(-10.0, -8.0, 3.0, 3.0);
        let (scene, _) = Scene {
            meshes: vec![sea, square(-10.0, 10.0, -4.0, 2.0), deck],
        }
        .prepare()
        .expect("valid");
        assert!((sea_level_m(&scene).expect("a sea") - 1.0).abs() < 1e-6);
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(20.0), UVec2::new(20, 20));
        let map = sea_depth_map(&scene, frame);
        let depth = |i: usize, j: usize| f32::from(map[j * 20 + i]) / 255.0 * SEA_DEPTH_RANGE_M;
        // x = −9.5: bed −3.85, 4.85 m deep; x = 9.5: the bed above the sea.
        assert!((depth(0, 5) - 4.85).abs() < 0.06, "{}", depth(0, 5));
        assert!(depth(19, 5) < 0.01);
        // Where no bed lies: deep.
        assert!(depth(5, 15) > SEA_DEPTH_RANGE_M - 0.01);
        assert!(sea_depth_map(&Scene::default(), frame).is_empty());
    }

    #[test]
    fn bad_settings_are_named() {
        for (bad, field) in [
            (
                SeaSettings {
                    fetch_m: f32::NAN,
                    ..SeaSettings::default()
                },
                "render.sea.fetch_m",
            ),
            (
                SeaSettings {
                    choppiness: 3.0,
                    ..SeaSettings::default()
                },
                "render.sea.choppiness",
            ),
            (
                SeaSettings {
                    seed: 1 << 24,
                    ..SeaSettings::default()
                },
                "render.sea.seed",
            ),
        ] {
            match bad.validate() {
                Err(BackendError::Setup { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{other:?}"),
            }
        }
        assert!(SeaSettings::default().validate().is_ok());
    }
}
