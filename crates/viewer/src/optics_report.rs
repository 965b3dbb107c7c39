//! `precip optics`: a weather's optics in a table — from its size spectra, and from
//! the particles the CPU reference simulates for it ([`precip_model::sensors::optics`]).

use glam::Vec3;
use precip_model::backend::setup::CameraVolumeSetup;
use precip_model::sensors::optics::{Band, Optics};
use precip_model::{Backend, CameraVolume, CpuBackend, Setup, Weather};

/// Particles in the sampled camera volume.
pub const SAMPLE_PARTICLES: u32 = 20_000;
/// The camera volume's half side, m.
pub const SAMPLE_HALF_EXTENT_M: f32 = 10.0;
/// Seconds simulated before the particles are counted.
pub const SAMPLE_SECONDS: u32 = 1;

/// The optics of `weather` from the particles of a CPU reference run: a camera
/// volume of [`SAMPLE_PARTICLES`] over flat ground, stepped [`SAMPLE_SECONDS`].
pub fn sampled_optics(weather: &Weather) -> anyhow::Result<Optics> {
    let mut setup = Setup::over_flat_ground(100.0, 16, 30.0, 0);
    setup.world_emitter = None;
    setup.weather = *weather;
    setup.camera.position_m = Vec3::new(0.0, 1.7 + SAMPLE_HALF_EXTENT_M, 0.0);
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume {
            half_extent_m: Vec3::splat(SAMPLE_HALF_EXTENT_M),
            ..CameraVolume::default()
        },
        particle_count: SAMPLE_PARTICLES,
    });
    let mut backend = CpuBackend::new();
    backend.configure(&setup)?;
    for _ in 0..SAMPLE_SECONDS {
        backend.step(1.0)?;
    }
    Ok(backend.optics()?)
}

/// The table `precip optics` prints.
#[must_use]
pub fn optics_table(weather: &Weather, spectra: &Optics, sampled: &Optics) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:?} {:.2} mm/h at {:.1} °C",
        weather.kind, weather.intensity_mm_per_h, weather.air_temperature_c
    );
    let _ = writeln!(
        out,
        "{:>8}  {:>14} {:>14}  {:>18} {:>18}  {:>12}  {:>14}",
        "band",
        "extinction /m",
        "(particles)",
        "backscatter /m/sr",
        "(particles)",
        "lidar ratio",
        "2-way at 100 m"
    );
    for band in Band::ALL {
        let (a, b) = (spectra.band(band), sampled.band(band));
        let ratio = a
            .lidar_ratio_sr()
            .map_or_else(|| "-".to_owned(), |s| format!("{s:.0} sr"));
        let _ = writeln!(
            out,
            "{:>5} nm  {:>14.4e} {:>14.4e}  {:>18.4e} {:>18.4e}  {:>12}  {:>14.4}",
            band.wavelength_nm(),
            a.extinction_per_m,
            b.extinction_per_m,
            a.backscatter_per_m_sr,
            b.backscatter_per_m_sr,
            ratio,
            a.two_way_transmittance(100.0)
        );
    }
    let _ = writeln!(
        out,
        "meteorological optical range (550 nm, 5 %): {:.0} m from the spectra, {:.0} m from the particles",
        spectra.meteorological_optical_range_m(),
        sampled.meteorological_optical_range_m()
    );
    let _ = writeln!(
        out,
        "(particles: {SAMPLE_PARTICLES} in a {:.0} m camera volume of the CPU reference after {SAMPLE_SECONDS} s, plus the sizes too small to simulate; {:?})",
        2.0 * SAMPLE_HALF_EXTENT_M,
        sampled.source
    );
    out
}

/// Prints the table for `weather`.
pub fn print_optics(weather: &Weather) -> anyhow::Result<()> {
    let spectra = Optics::of_weather(weather);
    let sampled = sampled_optics(weather)?;
    print!("{}", optics_table(weather, &spectra, &sampled));
    Ok(())
}
