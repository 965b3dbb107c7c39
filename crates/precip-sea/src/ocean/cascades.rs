//! The open sea as a frame draws it (docs/model.md (13.8)): the wind sea of the
//! weather ([`SeaState`]: the wind 10 m above the water, the fetch, the depth, the
//! chop) synthesised on [`OCEAN_CASCADES`] patches of [`OCEAN_N`]² points of
//! different sizes ([`CASCADE_SIZES_M`]), each holding its own band of wavenumbers
//! ([`cascade_band_per_m`]): the largest the swell and the wind's long waves, the
//! next the waves a few metres long, the smallest the ripples — so each wave length
//! is drawn once, and the patches' periods (co-prime-ish ratios, none a multiple of
//! another) never line up into a repetition the eye finds toward the horizon.
//!
//! The GPU's kernels (`ocean_spectrum`, `ocean_fft_rows`, `ocean_fft_columns`,
//! `ocean_resolve` in precip-gpu) compute the same surfaces each frame from the
//! same formulas (ocean.wgsl); [`SeaState::cascade`] is their reference.

use super::spectrum::{WindSea, fully_developed_fetch_m};
use super::synthesis::OceanCascade;

/// Points along each cascade's side (a power of two; the GPU's FFT takes a line of
/// them in one workgroup of `OCEAN_N / 2` invocations).
pub const OCEAN_N: usize = 128;

/// The cascades the sea is drawn from.
pub const OCEAN_CASCADES: usize = 3;

/// The cascades' sides, m, largest first: 263 m holds waves up to a fully developed
/// gale's peak (~250 m), 8.3 m ripples down to 13 cm.
pub const CASCADE_SIZES_M: [f32; OCEAN_CASCADES] = [263.0, 47.0, 8.3];

/// Waves shorter than this are rolled off (`WindSea::shortest_m`), m: capillary
/// waves, which a wind-wave spectrum does not describe.
pub const SHORTEST_WAVE_M: f32 = 0.1;

/// The wind below which the sea's waves point nowhere in particular: its direction
/// is then taken along +x, m/s.
pub const CALM_WIND_MPS: f32 = 0.1;

/// The band of wavenumbers cascade `c` holds, rad/m: from where the one before's
/// grid ends (its Nyquist wavenumber `π·N/L`, the largest disc its square holds)
/// to where its own does (the smallest holds everything beyond).
#[must_use]
pub fn cascade_band_per_m(c: usize) -> (f32, f32) {
    let nyquist = |i: usize| std::f32::consts::PI * OCEAN_N as f32 / CASCADE_SIZES_M[i];
    let lo = if c == 0 { 0.0 } else { nyquist(c - 1) };
    let hi = if c + 1 >= OCEAN_CASCADES {
        f32::INFINITY
    } else {
        nyquist(c)
    };
    (lo, hi)
}

/// The seed of cascade `c`'s amplitudes.
#[must_use]
pub const fn cascade_seed(seed: u32, c: usize) -> u32 {
    seed.wrapping_add(c as u32)
}

/// Which spectrum raises the sea.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeaSpectrum {
    /// JONSWAP over the fetch (a sea still growing, or fully developed past the
    /// fetch that develops it).
    #[default]
    Jonswap,
    /// Phillips as Tessendorf uses it, scaled to Pierson & Moskowitz's fully
    /// developed sea ([`super::PHILLIPS_AMPLITUDE`]); the fetch plays no part.
    Phillips,
}

/// The sea the weather raises.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeaState {
    /// The spectrum.
    pub spectrum: SeaSpectrum,
    /// The wind's speed 10 m above the water, m/s.
    pub wind_speed_mps: f32,
    /// The direction it blows toward, a unit vector on the water (x, z).
    pub wind_direction: [f32; 2],
    /// The distance it has blown over open water, m (JONSWAP's fetch).
    pub fetch_m: f32,
    /// The water's depth, m (the waves' speed).
    pub depth_m: f32,
    /// The choppy displacement's factor λ (0: none, 1: Tessendorf's full lean).
    pub choppiness: f32,
    /// The amplitudes' draw.
    pub seed: u32,
}

impl SeaState {
    /// The sea of a wind `wind_mps` (x, z; m/s) over `fetch_m` of water `depth_m`
    /// deep: its direction along +x in a calm; the fetch no longer than the one that
    /// fully develops the sea ([`fully_developed_fetch_m`]).
    #[must_use]
    pub fn of_wind(
        wind_mps: [f32; 2],
        fetch_m: f32,
        depth_m: f32,
        choppiness: f32,
        seed: u32,
    ) -> Self {
        let speed = wind_mps[0].hypot(wind_mps[1]);
        let wind_direction = if speed > CALM_WIND_MPS {
            [wind_mps[0] / speed, wind_mps[1] / speed]
        } else {
            [1.0, 0.0]
        };
        Self {
            spectrum: SeaSpectrum::Jonswap,
            wind_speed_mps: speed,
            wind_direction,
            fetch_m: fetch_m.min(fully_developed_fetch_m(speed)),
            depth_m,
            choppiness,
            seed,
        }
    }

    /// Its spectrum (JONSWAP over the fetch, or Phillips), the capillaries rolled
    /// off.
    #[must_use]
    pub const fn wind_sea(&self) -> WindSea {
        let mut sea = WindSea::jonswap(self.wind_speed_mps, self.fetch_m, self.wind_direction);
        sea.shortest_m = SHORTEST_WAVE_M;
        if let SeaSpectrum::Phillips = self.spectrum {
            sea.kind = super::SpectrumKind::Phillips {
                amplitude: super::PHILLIPS_AMPLITUDE,
            };
        }
        sea
    }

    /// Cascade `c` (`None` past the last): its patch, its band and its draw.
    #[must_use]
    pub fn cascade(&self, c: usize) -> Option<OceanCascade> {
        let size_m = *CASCADE_SIZES_M.get(c)?;
        OceanCascade::banded(
            &self.wind_sea(),
            OCEAN_N,
            size_m,
            self.depth_m,
            cascade_seed(self.seed, c),
            cascade_band_per_m(c),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cascades_hold_each_wave_length_once() {
        let mut last_hi = 0.0f32;
        for (c, size) in CASCADE_SIZES_M.iter().enumerate() {
            let (lo, hi) = cascade_band_per_m(c);
            assert!(
                lo.to_bits() == last_hi.to_bits(),
                "cascade {c} starts where the one before ends"
            );
            assert!(hi > lo);
            // Its band lies on its grid: its lowest wavenumber spans several cells
            // of its grid (a wave spans few of its patches).
            let dk = std::f32::consts::TAU / size;
            if c > 0 {
                assert!(lo > 4.0 * dk, "{c}: {lo} against a cell of {dk}");
            }
            last_hi = hi;
        }
        assert!(last_hi.is_infinite());
        // No patch a whole multiple of another: their repetitions never coincide.
        for a in CASCADE_SIZES_M {
            for b in CASCADE_SIZES_M {
                let r = a / b;
                assert!(a <= b || (r - r.round()).abs() > 0.05, "{a} / {b}");
            }
        }
    }

    #[test]
    fn the_cascades_together_carry_the_sea_s_variance() {
        // A 12 m/s wind over 100 km: the three cascades' variances add up to the
        // spectrum's, each band's within 10 %.
        let state = SeaState::of_wind([9.6, 7.2], 100_000.0, 200.0, 1.0, 5);
        let sea = state.wind_sea();
        let mut total = 0.0;
        for (c, size) in CASCADE_SIZES_M.iter().enumerate() {
            let cascade = state.cascade(c).expect("a cascade");
            let s = cascade.surface_at(2.0, 1.0);
            let n = s.height_m.len() as f32;
            let variance = s.height_m.iter().map(|h| h * h).sum::<f32>() / n;
            total += variance;
            let (lo, hi) = cascade_band_per_m(c);
            let want = sea.variance_m2(lo.max(std::f32::consts::TAU / size), hi.min(200.0));
            println!("cascade {c}: variance {variance:.3e} m² against the band's {want:.3e}");
            if c > 0 {
                assert!(
                    (variance / want - 1.0).abs() < 0.1,
                    "{c}: {variance} {want}"
                );
            }
        }
        let hs = 4.0 * total.sqrt();
        let want = sea.significant_height_m(std::f32::consts::TAU / CASCADE_SIZES_M[0], 200.0);
        println!("H_s {hs:.2} m against the spectrum's {want:.2} m");
        assert!((hs / want - 1.0).abs() < 0.15, "{hs} {want}");
        assert!(state.cascade(OCEAN_CASCADES).is_none());
    }

    #[test]
    fn a_fetch_past_full_development_raises_the_sea_no_more() {
        // 10 m/s: fully developed past some 160 km; its H_s then Pierson &
        // Moskowitz's 0.21·U₁₉.₅²/g (U₁₉.₅ ≈ 1.075·U₁₀) within 15 % (JONSWAP's peak
        // enhancement γ = 3.3 carries some 13 % more).
        let hs = |fetch_m: f32| {
            let s = SeaState::of_wind([10.0, 0.0], fetch_m, 1.0e3, 1.0, 1);
            s.wind_sea().significant_height_m(1.0e-3, 50.0)
        };
        let developed = fully_developed_fetch_m(10.0);
        assert!((1.5e5..1.7e5).contains(&developed), "{developed}");
        assert!(hs(developed).to_bits() == hs(1.0e6).to_bits());
        assert!(hs(20_000.0) < 0.8 * hs(developed));
        let pm = 0.21 * (1.075f32 * 10.0).powi(2) / 9.81;
        println!(
            "H_s fully developed {:.2} m, Pierson–Moskowitz's {pm:.2} m",
            hs(developed)
        );
        assert!(
            (hs(developed) / pm - 1.0).abs() < 0.15,
            "{} {pm}",
            hs(developed)
        );
    }

    #[test]
    fn a_calm_points_the_waves_along_x_and_raises_none() {
        let calm = SeaState::of_wind([0.0, 0.0], 1.0e5, 50.0, 1.0, 1);
        assert!(calm.wind_direction.map(f32::to_bits) == [1.0f32, 0.0].map(f32::to_bits));
        let s = calm.cascade(0).expect("a cascade").surface_at(1.0, 1.0);
        assert!(s.height_m.iter().all(|h| *h == 0.0));
    }
}

#[cfg(test)]
mod wgsl_twins {
    use super::*;

    #[test]
    fn the_wgsl_constants_are_these() {
        let source = crate::wgsl::OCEAN;
        let constant = |name: &str| -> f32 {
            let line = source
                .lines()
                .find(|l| l.starts_with(&format!("const {name}:")))
                .unwrap_or_else(|| panic!("{name} in ocean.wgsl"));
            let value = line.split('=').nth(1).expect("a value");
            value
                .trim()
                .trim_end_matches(';')
                .trim_end_matches('u')
                .parse()
                .expect("a number")
        };
        assert_eq!(constant("OCEAN_N") as usize, OCEAN_N);
        assert_eq!(constant("OCEAN_CASCADES") as usize, OCEAN_CASCADES);
        assert_eq!(
            constant("SHORTEST_WAVE_M").to_bits(),
            SHORTEST_WAVE_M.to_bits()
        );
        for (c, size) in CASCADE_SIZES_M.iter().enumerate() {
            assert_eq!(
                constant(&format!("OCEAN_CASCADE_{c}_M")).to_bits(),
                size.to_bits()
            );
        }
    }
}
