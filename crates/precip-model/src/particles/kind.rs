//! [`ParticleKind`]: what a particle is, and every decision that depends on it, in
//! one table — how a newborn of each kind is drawn ([`draw_species`], from the
//! weather's [`SpeciesParams`]), which deposit channel it lands in, its optical
//! material, whether it splashes, how it is drawn. WGSL twin: `shaders/kind.wgsl`
//! (the same rows, the same names with a `kind_` prefix).
//!
//! What the weather puts in the air of each kind is here too: its share of the
//! weather's rate ([`ParticleKind::rate_in`]), its size spectrum
//! ([`ParticleKind::spectrum_in`]: what is simulated one by one and what only in the
//! haze), its extinction and number density. The visibility, the optics' reference
//! sums, the multiplicity and the unresolved streaks sum these rows over
//! [`ParticleKind::ALL`], so none of them names a kind.
//!
//! A new kind (say, hail) is a variant here and a row in each function below, its
//! WGSL twin, the physics of its size and fall speed (`crate::physics`), and the
//! weather's kind that makes it fall ([`crate::weather::PrecipitationKind`]);
//! `docs/architecture.md` walks through it.

use crate::particles::rng::{draw, random_unit};
use crate::particles::step::StepParams;
use crate::physics::grain::{Grain, grain_settling_speed_mps};
use crate::physics::hail::{
    HAIL_DIAMETER_MAX_MM, HAIL_DIAMETER_MIN_MM, draw_hail_diameter_mm, hail_extinction_per_m,
    hail_number_density_per_m3, hail_spectrum, hailstone_terminal_speed_mps,
};
use crate::physics::raindrop::{
    MARSHALL_PALMER_N0, RAIN_DIAMETER_MAX_MM, RAIN_DIAMETER_MIN_MM, draw_raindrop_diameter_mm,
    marshall_palmer_slope_per_mm, rain_number_density_per_m3, raindrop_terminal_speed_mps,
};
use crate::physics::snowfall::{
    gunn_marshall_intercept, gunn_marshall_slope_per_mm, snow_number_density_per_m3,
};
use crate::physics::snowflake::{
    mean_snowflake_diameter_m, snow_terminal_speed_mps, snow_terminal_speed_range_mps,
    snowflake_diameter_from_melted_m, snowflake_diameter_m,
};
use crate::sensors::optics::Material;
use crate::weather::Weather;
use crate::weather::visibility::{
    melted_diameter_mm, rain_extinction_per_m, snow_extinction_per_m,
};
use bytemuck::{Pod, Zeroable};
use precip_cover::DepositBuffer;

/// What a particle is: four bits of [`super::particle::Particle::flags`] (four of
/// sixteen values taken).
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParticleKind {
    /// A dry snowflake.
    DrySnow = 0,
    /// A wet snowflake.
    WetSnow = 1,
    /// A raindrop.
    Rain = 2,
    /// A grain of sand or dust ([`crate::physics::grain`]).
    Grain = 3,
    /// A hailstone ([`crate::physics::hail`]).
    Hail = 4,
}

impl ParticleKind {
    /// Every kind, in the order of their values.
    pub const ALL: [Self; 5] = [
        Self::DrySnow,
        Self::WetSnow,
        Self::Rain,
        Self::Grain,
        Self::Hail,
    ];

    /// The kind of the four bits' value `bits` (an unknown value reads as a grain).
    #[must_use]
    pub const fn from_bits(bits: u32) -> Self {
        match bits {
            0 => Self::DrySnow,
            1 => Self::WetSnow,
            2 => Self::Rain,
            4 => Self::Hail,
            _ => Self::Grain,
        }
    }

    /// Whether it is snow (rebounds off walls, drawn as a flake, counted as snow).
    #[must_use]
    pub const fn is_snow(self) -> bool {
        matches!(self, Self::DrySnow | Self::WetSnow)
    }

    /// The deposit channel its water (or grains) lands in (`kind_deposit_channel`).
    #[must_use]
    pub const fn deposit_channel(self) -> usize {
        match self {
            // Hail piles as ice and melts as the snow does.
            Self::DrySnow | Self::WetSnow | Self::Hail => DepositBuffer::SNOW,
            Self::Rain => DepositBuffer::RAIN,
            Self::Grain => DepositBuffer::GRAINS,
        }
    }

    /// What it is made of, for its optics (`kind_material`).
    #[must_use]
    pub const fn material(self) -> Material {
        match self {
            Self::DrySnow | Self::WetSnow | Self::Hail => Material::Ice,
            Self::Rain => Material::Water,
            Self::Grain => Material::Mineral,
        }
    }

    /// Whether it is a drop: it may splash where it strikes
    /// ([`crate::physics::splash`]) and is drawn as a streak along its fall
    /// (`kind_is_drop`); the other kinds are drawn as flakes.
    #[must_use]
    pub const fn is_drop(self) -> bool {
        matches!(self, Self::Rain)
    }

    /// Whether striking a water body it rings it: the ripples' crater law is a
    /// drop's ([`crate::physics::water_waves::crater_volume_m3`]); a hailstone's
    /// cavity is not, and its strikes, at the simulated stones' count (about the
    /// physical one, where drops are sampled), shook the 4 cm wave grid into blocks.
    /// GPU only (the reference draws no ripples): `kind_rings_water`.
    #[must_use]
    pub const fn rings_water(self) -> bool {
        !matches!(self, Self::Hail)
    }

    /// Its share of `weather`'s rate: mm/h of water (grains: kg/(m²·h)); 0 when
    /// the weather has none of it ([`crate::PrecipitationKind::share_of`]).
    #[must_use]
    pub fn rate_in(self, weather: &Weather) -> f32 {
        weather.intensity_mm_per_h * weather.kind.share_of(self, weather.air_temperature_c)
    }

    /// How its particles in `weather`'s air are spread in size; `None` where the
    /// weather has none of it.
    #[must_use]
    pub fn spectrum_in(self, weather: &Weather) -> Option<Spectrum> {
        let rate = self.rate_in(weather);
        if rate <= 0.0 {
            return None;
        }
        match self {
            Self::DrySnow | Self::WetSnow => Some(Spectrum::Exponential {
                n0_per_m3_mm: gunn_marshall_intercept(rate),
                slope_per_mm: gunn_marshall_slope_per_mm(rate),
                support_mm: (0.0, f32::INFINITY),
                // Flakes at least as large as the smallest the seed's law draws.
                simulated_from_mm: melted_diameter_mm(
                    0.5 * mean_snowflake_diameter_m(weather.air_temperature_c),
                    self == Self::WetSnow,
                ),
                simulated_to_mm: f32::INFINITY,
            }),
            Self::Rain => Some(Spectrum::Exponential {
                n0_per_m3_mm: MARSHALL_PALMER_N0,
                slope_per_mm: marshall_palmer_slope_per_mm(rate),
                support_mm: (0.0, f32::INFINITY),
                simulated_from_mm: RAIN_DIAMETER_MIN_MM,
                simulated_to_mm: RAIN_DIAMETER_MAX_MM,
            }),
            Self::Grain => weather.grains().map(|g| Spectrum::OneSize {
                diameter_m: g.diameter_m,
                n_per_m3: weather.grain_number_density_per_m3(),
            }),
            Self::Hail => {
                let (n0, slope) = hail_spectrum(rate);
                Some(Spectrum::Exponential {
                    n0_per_m3_mm: n0,
                    slope_per_mm: slope,
                    support_mm: (HAIL_DIAMETER_MIN_MM, HAIL_DIAMETER_MAX_MM),
                    simulated_from_mm: HAIL_DIAMETER_MIN_MM,
                    simulated_to_mm: HAIL_DIAMETER_MAX_MM,
                })
            }
        }
    }

    /// The particle's diameter, m, at its spectrum's size `d_mm` (a flake's melted
    /// diameter, a drop's or grain's own).
    #[must_use]
    pub fn diameter_at_spectral_size_m(self, d_mm: f32) -> f32 {
        match self {
            Self::DrySnow | Self::WetSnow => {
                snowflake_diameter_from_melted_m(d_mm * 1.0e-3, self == Self::WetSnow)
            }
            Self::Rain | Self::Grain | Self::Hail => d_mm * 1.0e-3,
        }
    }

    /// Its fall speed in still air at its spectrum's size `d_mm`, m/s (a flake's:
    /// the middle of its kind's range, whatever its size; a grain's: quartz's).
    #[must_use]
    pub fn fall_speed_at_spectral_size_mps(self, d_mm: f32) -> f32 {
        match self {
            Self::DrySnow | Self::WetSnow => {
                let (lo, hi) = snow_terminal_speed_range_mps(self == Self::WetSnow);
                0.5 * (lo + hi)
            }
            Self::Rain => raindrop_terminal_speed_mps(d_mm),
            Self::Grain => grain_settling_speed_mps(d_mm * 1.0e-3, Grain::SAND.density_kg_m3),
            Self::Hail => hailstone_terminal_speed_mps(d_mm),
        }
    }

    /// Its extinction coefficient in `weather`'s air, per m, over its whole
    /// spectrum (closed forms: [`crate::weather::visibility`]).
    #[must_use]
    pub fn extinction_in(self, weather: &Weather) -> f32 {
        let rate = self.rate_in(weather);
        match self {
            Self::DrySnow | Self::WetSnow => snow_extinction_per_m(rate, self == Self::WetSnow),
            Self::Rain => rain_extinction_per_m(rate),
            Self::Grain => weather.grain_extinction_per_m(),
            Self::Hail => hail_extinction_per_m(rate),
        }
    }

    /// Its particles per m³ in `weather`'s air, all sizes.
    #[must_use]
    pub fn number_density_in(self, weather: &Weather) -> f32 {
        let rate = self.rate_in(weather);
        match self {
            Self::DrySnow | Self::WetSnow => snow_number_density_per_m3(rate),
            Self::Rain => rain_number_density_per_m3(rate),
            Self::Grain => weather.grain_number_density_per_m3(),
            Self::Hail => hail_number_density_per_m3(rate),
        }
    }
}

/// How a kind's particles in the air are spread in size
/// ([`ParticleKind::spectrum_in`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spectrum {
    /// `N(d) = N0·e^(−Λd)` per m³ per mm of the kind's spectral size `d`, mm
    /// ([`ParticleKind::diameter_at_spectral_size_m`]), for the sizes in
    /// `support_mm`; those in `[simulated_from_mm, simulated_to_mm]` are simulated
    /// one by one, the rest is only in the haze.
    Exponential {
        /// `N0`, per m³ per mm.
        n0_per_m3_mm: f32,
        /// `Λ`, per mm.
        slope_per_mm: f32,
        /// The sizes that exist, mm: from 0 to no end for snow and rain; 5–50 mm
        /// for hail (its `N0` holds there alone). Sums over the spectrum run over
        /// these only.
        support_mm: (f32, f32),
        /// The smallest size simulated one by one, mm.
        simulated_from_mm: f32,
        /// The largest, mm (may be infinite).
        simulated_to_mm: f32,
    },
    /// Particles of one size, every one simulated.
    OneSize {
        /// Their diameter, m.
        diameter_m: f32,
        /// Their number per m³.
        n_per_m3: f32,
    },
}

impl Spectrum {
    /// Particles per m³ of the sizes simulated one by one: an exponential's tail
    /// `(N0/Λ)·(e^(−Λ·from) − e^(−Λ·to))`, every grain.
    #[must_use]
    pub fn simulated_per_m3(&self) -> f32 {
        match *self {
            Self::Exponential {
                n0_per_m3_mm,
                slope_per_mm,
                simulated_from_mm,
                simulated_to_mm,
                ..
            } => crate::weather::visibility::exponential_tail_per_m3(
                n0_per_m3_mm,
                slope_per_mm,
                simulated_from_mm,
                simulated_to_mm,
            ),
            Self::OneSize { n_per_m3, .. } => n_per_m3,
        }
    }
}

/// What the weather's kinds need to draw a newborn's species: a block of
/// [`StepParams`] (`species`). WGSL twin: `SpeciesParams` in `shaders/kind.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct SpeciesParams {
    /// Fraction of births that are snow (the rest rain).
    pub snow_fraction: f32,
    /// Marshall–Palmer Λ for the rain part, mm⁻¹.
    pub rain_slope_per_mm: f32,
    /// Sand or dust weather: the grains' mean diameter, m; 0: snow and rain fall.
    pub grain_diameter_m: f32,
    /// The grains' density, kg/m³.
    pub grain_density_kg_m3: f32,
    /// Fraction of births that are hailstones (after the snow's).
    pub hail_fraction: f32,
    /// The hail spectrum's `Λ`, mm⁻¹ ([`crate::physics::hail::hail_spectrum`]).
    pub hail_slope_per_mm: f32,
    /// Unused (`0`).
    pub reserved0: f32,
    /// Unused (`0`).
    pub reserved1: f32,
}
const _: () = assert!(size_of::<SpeciesParams>().is_multiple_of(16));

impl SpeciesParams {
    /// The species of `weather`, whose grains (sand or dust weather's, or those the
    /// wind lifts from the scene) are `grain`.
    #[must_use]
    pub fn of_weather(weather: &Weather, grain: Option<Grain>) -> Self {
        let rain_rate = weather.rain_rate_mm_per_h();
        let hail_rate = ParticleKind::Hail.rate_in(weather);
        Self {
            hail_fraction: weather
                .kind
                .share_of(ParticleKind::Hail, weather.air_temperature_c),
            hail_slope_per_mm: if hail_rate > 0.0 {
                hail_spectrum(hail_rate).1
            } else {
                1.0
            },
            reserved0: 0.0,
            reserved1: 0.0,
            snow_fraction: weather.snow_fraction(),
            rain_slope_per_mm: marshall_palmer_slope_per_mm(if rain_rate > 0.0 {
                rain_rate
            } else {
                1.0
            }),
            grain_diameter_m: grain.map_or(0.0, |g| g.diameter_m),
            grain_density_kg_m3: grain.map_or(0.0, |g| g.density_kg_m3),
        }
    }
}

/// Kind, diameter (m) and terminal speed (m/s) of a newborn particle.
///
/// Sand or dust weather: a grain, `d = d̄·(0.5 + f)`, falling at its settling speed
/// ([`crate::physics::grain::grain_settling_speed_mps`]). Otherwise snow with probability
/// `snow_fraction` (sleet), hail with `hail_fraction` (its stones drawn from the flux
/// as the drops are: [`crate::physics::hail::draw_hail_diameter_mm`]), else rain. Snow: `D = D̄(T)·(0.5 + f)`,
/// `V_pmax` across the dry/wet range. Rain: D from the flux-weighted Marshall–Palmer
/// draw, `V_pmax = v(D)`. WGSL twin: `draw_species` in `shaders/birth.wgsl`.
#[must_use]
pub fn draw_species(key: u32, params: &StepParams) -> (ParticleKind, f32, f32) {
    let species = &params.species;
    if species.grain_diameter_m > 0.0 {
        let diameter = species.grain_diameter_m * (0.5 + random_unit(key, draw::GRAIN_SIZE));
        return (
            ParticleKind::Grain,
            diameter,
            grain_settling_speed_mps(diameter, species.grain_density_kg_m3),
        );
    }
    let which = random_unit(key, draw::KIND);
    if which < species.snow_fraction {
        let wet = params.snow_is_wet != 0;
        let diameter =
            snowflake_diameter_m(params.air_temperature_c, random_unit(key, draw::SNOW_SIZE));
        let speed = snow_terminal_speed_mps(wet, random_unit(key, draw::SNOW_SPEED));
        (snow_kind(params), diameter, speed)
    } else if which < species.snow_fraction + species.hail_fraction {
        let diameter_mm = draw_hail_diameter_mm(key, species.hail_slope_per_mm);
        (
            ParticleKind::Hail,
            diameter_mm * 1.0e-3,
            hailstone_terminal_speed_mps(diameter_mm),
        )
    } else {
        let diameter_mm = draw_raindrop_diameter_mm(key, species.rain_slope_per_mm);
        (
            ParticleKind::Rain,
            diameter_mm * 1.0e-3,
            raindrop_terminal_speed_mps(diameter_mm),
        )
    }
}

/// The snow kind of this weather: wet or dry.
#[must_use]
pub const fn snow_kind(params: &StepParams) -> ParticleKind {
    if params.snow_is_wet != 0 {
        ParticleKind::WetSnow
    } else {
        ParticleKind::DrySnow
    }
}

/// The slowest terminal speed this weather's particles are born with, m/s (the
/// slower of the snow's range floor and the smallest drop's speed, by the kinds that
/// fall). WGSL twin: `slowest_terminal_speed_mps` in `shaders/birth.wgsl`.
#[must_use]
pub fn slowest_terminal_speed_mps(params: &StepParams) -> f32 {
    let species = &params.species;
    if species.grain_diameter_m > 0.0 {
        return grain_settling_speed_mps(
            0.5 * species.grain_diameter_m,
            species.grain_density_kg_m3,
        );
    }
    let mut slowest = f32::INFINITY;
    if species.snow_fraction > 0.0 {
        slowest = slowest.min(snow_terminal_speed_mps(params.snow_is_wet != 0, 0.0));
    }
    if species.hail_fraction > 0.0 {
        slowest = slowest.min(hailstone_terminal_speed_mps(HAIL_DIAMETER_MIN_MM));
    }
    if species.snow_fraction + species.hail_fraction < 1.0 {
        slowest = slowest.min(raindrop_terminal_speed_mps(RAIN_DIAMETER_MIN_MM));
    }
    slowest
}

#[cfg(test)]
mod tests {
    use std::mem::offset_of;

    use super::*;

    /// The value of `const NAME: u32 = …u;` in kind.wgsl.
    fn wgsl_const(name: &str) -> u32 {
        crate::wgsl::u32_const(crate::wgsl::KIND, name)
    }

    /// `SpeciesParams` is checked here rather than with the other blocks
    /// (precip-gpu's `tests/shaders.rs`, which checks where `StepParams` holds it),
    /// so a kind's new field is an edit of this file and `kind.wgsl` only.
    #[test]
    fn species_params_is_its_wgsl_twin() {
        let wgsl = crate::wgsl::KIND;
        let start = wgsl.find("struct SpeciesParams {").expect("declared");
        let end = start + wgsl[start..].find('}').expect("closed");
        // Every member is an f32: 4 bytes apart, in order.
        let members: Vec<&str> = wgsl[start..end]
            .lines()
            .skip(1)
            .filter_map(|l| l.trim().strip_suffix(": f32,"))
            .collect();
        let rust = [
            ("snow_fraction", offset_of!(SpeciesParams, snow_fraction)),
            (
                "rain_slope_per_mm",
                offset_of!(SpeciesParams, rain_slope_per_mm),
            ),
            (
                "grain_diameter_m",
                offset_of!(SpeciesParams, grain_diameter_m),
            ),
            (
                "grain_density_kg_m3",
                offset_of!(SpeciesParams, grain_density_kg_m3),
            ),
            ("hail_fraction", offset_of!(SpeciesParams, hail_fraction)),
            (
                "hail_slope_per_mm",
                offset_of!(SpeciesParams, hail_slope_per_mm),
            ),
            ("reserved0", offset_of!(SpeciesParams, reserved0)),
            ("reserved1", offset_of!(SpeciesParams, reserved1)),
        ];
        assert_eq!(members.len() * 4, size_of::<SpeciesParams>(), "{members:?}");
        assert_eq!(members.len(), rust.len(), "{members:?}");
        for (i, (name, offset)) in rust.into_iter().enumerate() {
            assert_eq!((members[i], 4 * i), (name, offset));
        }
    }

    #[test]
    fn the_kinds_are_their_wgsl_twins() {
        for (name, kind) in [
            "KIND_DRY_SNOW",
            "KIND_WET_SNOW",
            "KIND_RAIN",
            "KIND_GRAIN",
            "KIND_HAIL",
        ]
        .into_iter()
        .zip(ParticleKind::ALL)
        {
            assert_eq!(wgsl_const(name), kind as u32, "{name}");
            assert_eq!(ParticleKind::from_bits(kind as u32), kind);
        }
        for (name, material) in [
            ("MATERIAL_WATER", Material::Water),
            ("MATERIAL_ICE", Material::Ice),
            ("MATERIAL_MINERAL", Material::Mineral),
        ] {
            assert_eq!(wgsl_const(name), material as u32, "{name}");
        }
    }

    #[test]
    fn every_kind_has_a_channel_a_material_and_a_look() {
        for kind in ParticleKind::ALL {
            assert!(kind.deposit_channel() < precip_cover::DEPOSIT_CHANNELS);
            // Snow is ice; drops are water; neither is the other.
            assert!(!(kind.is_snow() && kind.is_drop()), "{kind:?}");
            if kind.is_snow() {
                assert_eq!(kind.material(), Material::Ice);
                assert_eq!(kind.deposit_channel(), DepositBuffer::SNOW);
            }
            if kind.is_drop() {
                assert_eq!(kind.material(), Material::Water);
            }
        }
    }
}
