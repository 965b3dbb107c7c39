#![expect(clippy::float_cmp, reason = "caps and limits the code returns exactly")]

use super::*;
use crate::physics::raindrop::{
    RAIN_DIAMETER_MAX_MM, RAIN_DIAMETER_MIN_MM, marshall_palmer_slope_per_mm,
};
use crate::weather::PrecipitationKind;
use crate::weather::visibility::{rain_extinction_per_m, snow_extinction_per_m};

fn rain(rate_mm_per_h: f32) -> Weather {
    Weather {
        kind: PrecipitationKind::Rain,
        intensity_mm_per_h: rate_mm_per_h,
        air_temperature_c: 10.0,
        ..Weather::default()
    }
}

fn dry_snow(rate_mm_per_h: f32) -> Weather {
    Weather {
        intensity_mm_per_h: rate_mm_per_h,
        ..Weather::default()
    }
}

#[test]
fn anomalous_diffraction_tends_to_two_and_peaks_near_rho_four() {
    // Large against the wavelength: the extinction paradox.
    let q = extinction_efficiency(1.0e-3, 1.333, 550.0);
    assert!((q - 2.0).abs() < 0.01, "{q}");
    // The first maximum of van de Hulst's curve: 3.17 at ρ ≈ 4.09.
    let wavelength_nm = 550.0;
    let d_m = 4.09 / (2.0 * std::f32::consts::PI * 0.333) * wavelength_nm * 1.0e-9;
    let peak = extinction_efficiency(d_m, 1.333, wavelength_nm);
    assert!((peak - 3.17).abs() < 0.02, "{peak}");
    // Small: vanishes.
    assert!(extinction_efficiency(1.0e-9, 1.333, 550.0) < 1.0e-4);
}

#[test]
fn rain_and_snow_extinction_are_the_visibility_modules_and_do_not_depend_on_the_band() {
    for r in [1.0, 10.0, 50.0] {
        let optics = Optics::of_weather(&rain(r));
        let expected = rain_extinction_per_m(r);
        for band in Band::ALL {
            let got = optics.band(band).extinction_per_m;
            assert!(
                (got / expected - 1.0).abs() < 0.01,
                "{r} mm/h {band:?}: {got} vs {expected}"
            );
        }
    }
    for s in [0.5, 2.0] {
        let optics = Optics::of_weather(&dry_snow(s));
        let expected = snow_extinction_per_m(s, false);
        for band in Band::ALL {
            let got = optics.band(band).extinction_per_m;
            assert!(
                (got / expected - 1.0).abs() < 0.01,
                "{s} mm/h {band:?}: {got} vs {expected}"
            );
        }
    }
}

/// The optics' sums over each kind's spectrum agree with the visibility's closed
/// forms, for every kind whose stones or drops are large against the wavelength
/// (hail's spectrum exists from 5 mm alone: summing below it tripled its haze).
#[test]
fn every_kind_s_visible_extinction_is_the_visibility_s() {
    for kind in PrecipitationKind::ALL {
        if kind.default_grain().is_some() {
            continue; // grains are small against the wavelength: not efficiency 2
        }
        for rate in [0.5, 10.0, 30.0] {
            let w = Weather {
                kind,
                intensity_mm_per_h: rate,
                air_temperature_c: kind.default_air_temperature_c(),
                ..Weather::default()
            };
            let got = Optics::of_weather(&w).band(Band::Visible).extinction_per_m;
            let expected = w.extinction_per_m();
            assert!(
                (got / expected - 1.0).abs() < 0.02,
                "{kind} at {rate} mm/h: {got} vs {expected}"
            );
        }
    }
}

#[test]
fn rain_extinction_is_within_half_again_of_carbonneaus_relation() {
    // Carbonneau (1998), the free-space optics link budget's rain: 1.076·R^0.67
    // dB/km, the same at every wavelength (drops ≫ λ).
    for r in [1.0f32, 5.0, 10.0, 25.0, 50.0] {
        let published_per_m = 1.076 * r.powf(0.67) / (10.0 * std::f32::consts::LOG10_E) / 1000.0;
        let ours = Optics::of_weather(&rain(r))
            .band(Band::ShortwaveInfrared)
            .extinction_per_m;
        let ratio = ours / published_per_m;
        println!(
            "rain {r} mm/h: {:.3} /km vs Carbonneau {:.3} /km ({ratio:.2}×)",
            ours * 1e3,
            published_per_m * 1e3
        );
        assert!((0.75..1.5).contains(&ratio), "{r} mm/h: {ratio}");
    }
}

#[test]
fn one_millimetre_an_hour_of_dry_snow_has_a_mor_of_a_few_hundred_metres() {
    // docs/model.md §7: Koschmieder's visibility 0.4–1.2 km; the MOR is ln 20/3.912 of it.
    let mor = Optics::of_weather(&dry_snow(1.0)).meteorological_optical_range_m();
    let ratio = MOR_LOG_CONTRAST / 3.912;
    assert!((400.0 * ratio..=1200.0 * ratio).contains(&mor), "{mor} m");
    // Clear air.
    let clear = Optics::of_weather(&dry_snow(0.0));
    assert_eq!(
        clear.meteorological_optical_range_m(),
        CLEAR_AIR_VISIBILITY_M
    );
    assert_eq!(clear.band(Band::NearInfrared).backscatter_per_m_sr, 0.0);
}

#[test]
fn rain_backscatter_falls_with_water_absorption_and_snow_keeps_the_ice_lidar_ratio() {
    let optics = Optics::of_weather(&rain(10.0));
    let s: Vec<f32> = Band::ALL
        .iter()
        .map(|&b| optics.band(b).lidar_ratio_sr().expect("rain scatters"))
        .collect();
    println!("rain 10 mm/h lidar ratio 550/905/1550 nm: {s:?} sr");
    // Geometric optics of a water sphere without absorption: 2π/(R₀/4 + (1−R₀)²R₀) ≈ 255.
    assert!((240.0..270.0).contains(&s[0]), "{s:?}");
    assert!(s[1] < 1.1 * s[0] && s[1] >= s[0], "{s:?}");
    // At 1550 nm a millimetre drop's inside is dark: about the front reflection.
    assert!(s[2] > 2.0 * s[0], "{s:?}");
    let snow = Optics::of_weather(&dry_snow(1.0));
    for band in Band::ALL {
        let ratio = snow.band(band).lidar_ratio_sr().expect("snow scatters");
        assert!(
            (ratio - ICE_LIDAR_RATIO_SR).abs() < 0.01,
            "{band:?}: {ratio}"
        );
    }
}

#[test]
fn dust_sees_less_extinction_at_longer_wavelengths() {
    let dust = Weather {
        kind: PrecipitationKind::Dust,
        intensity_mm_per_h: 0.5e-3,
        air_temperature_c: 30.0,
        ..Weather::default()
    };
    let optics = Optics::of_weather(&dust);
    let visible = optics.band(Band::Visible).extinction_per_m;
    let swir = optics.band(Band::ShortwaveInfrared).extinction_per_m;
    // The grain module's σ = 3C/(ρd) is Q_ext = 2.
    let q_visible = visible / dust.grain_extinction_per_m() * 2.0;
    assert!((1.9..2.2).contains(&q_visible), "{q_visible}");
    assert!(swir < 0.97 * visible, "{swir} vs {visible}");
    let ratio = optics
        .band(Band::Visible)
        .lidar_ratio_sr()
        .expect("dust scatters");
    assert!((ratio - DUST_LIDAR_RATIO_SR).abs() < 0.01);
}

#[test]
fn the_resolved_part_is_the_simulated_sizes() {
    // Rain: drops below 0.3 mm are unresolved; their share of the extinction is
    // small (∫ d² e^(−Λd) below 0.3 mm).
    let w = rain(10.0);
    let parts = SpectrumParts::of(&w);
    let total = parts.total[0].extinction_per_m;
    let unresolved = parts.unresolved[0].extinction_per_m;
    let slope = marshall_palmer_slope_per_mm(10.0);
    let x = slope * RAIN_DIAMETER_MIN_MM;
    // Share of ∫ d² e^(−Λd) below d0: 1 − e^(−x)(1 + x + x²/2); plus the tail above
    // 6 mm.
    let below = 1.0 - (-x).exp() * (1.0 + x + 0.5 * x * x);
    let y = slope * RAIN_DIAMETER_MAX_MM;
    let above = (-y).exp() * (1.0 + y + 0.5 * y * y);
    let share = unresolved / total;
    assert!(
        (share - (below + above)).abs() < 0.002,
        "{share} vs {}",
        below + above
    );
}

#[test]
fn bands_are_found_by_wavelength() {
    assert_eq!(Band::of_wavelength_nm(905.0), Some(Band::NearInfrared));
    assert_eq!(Band::of_wavelength_nm(1064.0), None);
    assert_eq!(Band::ShortwaveInfrared.index(), 2);
}

#[test]
fn two_way_transmittance_is_beer_lambert_both_ways() {
    let b = BandOptics {
        extinction_per_m: 1.0e-3,
        backscatter_per_m_sr: 0.0,
    };
    assert!((b.two_way_transmittance(500.0) - (-1.0f32).exp()).abs() < 1e-6);
    assert_eq!(b.two_way_transmittance(-3.0), 1.0);
    assert_eq!(b.lidar_ratio_sr(), None);
}
