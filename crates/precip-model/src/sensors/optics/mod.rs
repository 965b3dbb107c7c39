//! What a camera or a LiDAR sees through the precipitation: extinction and
//! backscatter coefficients at 550, 905 and 1550 nm, and the meteorological optical
//! range, for a weather (its size spectra) or from the particles in the air now.
//!
//! ## Extinction
//!
//! A particle of diameter `D` removes `Q_ext·πD²/4` of a beam. Its efficiency is van
//! de Hulst's (1957, *Light Scattering by Small Particles*, §11.22) anomalous
//! diffraction `Q_ext(ρ) = 2 − (4/ρ)·sin ρ + (4/ρ²)·(1 − cos ρ)`, `ρ = 2x·(n − 1)`,
//! `x = πD/λ` ([`extinction_efficiency`]): drops, flakes and sand are thousands of
//! wavelengths across, so `Q_ext = 2` (the extinction paradox) and their extinction
//! does not depend on the wavelength; 10 µm dust is not, and sees 7 % less at 1550
//! nm than at 550. Sums over the size spectra of [`crate::physics::raindrop`] (Marshall–Palmer)
//! and [`crate::physics::snowfall`] (Gunn–Marshall in melted diameter, the flake's diameter
//! from the seed's `ρ = C/D`), grains at their one diameter.
//!
//! ## Backscatter
//!
//! - **Drops** are spheres far larger than the wavelength: geometric optics (van de
//!   Hulst ch. 12). Straight back come the ray reflected at the front (`p = 0`:
//!   `a²·R₀/4` per steradian) and the axial ray reflected once inside (`p = 2`:
//!   `a²·(1 − R₀)²·R₀/(4/n − 2)²`, attenuated by `e^(−2αD)` on its way through the
//!   drop, `α = 4πk/λ`), with `R₀ = ((n − 1)/(n + 1))²` ([`drop_backscatter_m2_sr`]).
//!   Water's index is Hale & Querry's (1973, *Appl. Opt.* 12(3)); water absorbs
//!   strongly at 1550 nm (a 1.2 mm e-folding length), so a rain of millimetre drops
//!   returns mostly its front reflection there. Rain's lidar ratio comes out near
//!   250 sr at 550 nm. The glory (a wave effect of exact spheres) is left out: real
//!   drops of a millimetre and more are flattened by their fall, which spoils it.
//! - **Snowflakes** are aggregates of thin ice crystals whose faces, not the flake's
//!   outline, send light back: their backscatter is that of ice crystals, whose
//!   measured lidar ratio (extinction over backscatter) is 29 ± 12 sr (Chen, Chiang &
//!   Nee 2002, *Appl. Opt.* 41(30), cirrus at 532 nm) — [`ICE_LIDAR_RATIO_SR`]; so
//!   snow sends back about nine times what rain does for the same extinction, as
//!   LiDARs in snow find. Ice's absorption at 1550 nm over a crystal's few tens of µm
//!   is neglected.
//! - **Sand and dust** are irregular mineral grains: the measured lidar ratio of
//!   Saharan dust, 55 ± 5 sr (Tesche et al. 2009, *J. Geophys. Res.* 114, SAMUM,
//!   532 nm; it changes little to 1064 nm) — [`DUST_LIDAR_RATIO_SR`].
//!
//! ## Meteorological optical range
//!
//! The length of air that lets through 5 % of a beam of white light (WMO-No. 8):
//! `MOR = ln 20/σ(550 nm)` ([`meteorological_optical_range_m`]), capped at
//! [`crate::weather::visibility::CLEAR_AIR_VISIBILITY_M`]. (The fog of the renderer keeps
//! Koschmieder's 2 % contrast, `3.912/σ`.)
//!
//! ## From the particles in the air
//!
//! [`Optics::live`] takes the particles a backend holds now: the camera volume's
//! particles are the spectrum's sizes simulated one by one
//! ([`crate::weather::visibility`]'s module docs), a sample of the air around the camera, so
//! their mean cross-sections times the weather's number density of those sizes give
//! the resolved part; the sizes too small to simulate keep their spectrum's part.
//! After the weather changes, the particles not yet re-born keep their old kind and
//! size, and the optics follow them.

use crate::particles::kind::Spectrum;
use crate::particles::particle::{Particle, ParticleKind, ParticleSource};
use crate::weather::Weather;
use crate::weather::visibility::CLEAR_AIR_VISIBILITY_M;

/// A LiDAR's or camera's band.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Band {
    /// Green light, 550 nm: the eye and the meteorological optical range.
    Visible,
    /// 905 nm: most automotive LiDARs (silicon detectors).
    NearInfrared,
    /// 1550 nm: eye-safe fibre-laser LiDARs.
    ShortwaveInfrared,
}

impl Band {
    /// Every band, shortest first.
    pub const ALL: [Self; 3] = [Self::Visible, Self::NearInfrared, Self::ShortwaveInfrared];

    /// The wavelength, nm.
    #[must_use]
    pub const fn wavelength_nm(self) -> f32 {
        match self {
            Self::Visible => 550.0,
            Self::NearInfrared => 905.0,
            Self::ShortwaveInfrared => 1550.0,
        }
    }

    /// The band of a wavelength in nm, if it is one of [`Band::ALL`].
    #[must_use]
    pub fn of_wavelength_nm(nm: f32) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|b| (b.wavelength_nm() - nm).abs() < 0.5)
    }

    /// Its position in [`Band::ALL`].
    #[must_use]
    pub const fn index(self) -> usize {
        self as usize
    }
}

/// What a particle is made of, for its optics (a kind's:
/// [`ParticleKind::material`]; WGSL twin: `MATERIAL_*` in `kind.wgsl`).
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Material {
    /// Liquid water.
    Water,
    /// Ice.
    Ice,
    /// Quartz-like mineral.
    Mineral,
}

/// Complex refractive index `n + i·k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefractiveIndex {
    /// Real part.
    pub n: f32,
    /// Imaginary part (absorption).
    pub k: f32,
}

impl Material {
    /// The refractive index in `band`: water from Hale & Querry (1973), ice from
    /// Warren & Brandt (2008, *J. Geophys. Res.* 113), quartz's ordinary ray from
    /// Ghosh (1999, *Opt. Commun.* 163) (its absorption is not used: mineral
    /// backscatter is measured, [`DUST_LIDAR_RATIO_SR`]).
    #[must_use]
    pub const fn refractive_index(self, band: Band) -> RefractiveIndex {
        let (n, k) = match (self, band) {
            (Self::Water, Band::Visible) => (1.333, 1.96e-9),
            (Self::Water, Band::NearInfrared) => (1.328, 4.86e-7),
            (Self::Water, Band::ShortwaveInfrared) => (1.318, 9.9e-5),
            (Self::Ice, Band::Visible) => (1.311, 2.9e-9),
            (Self::Ice, Band::NearInfrared) => (1.303, 3.3e-7),
            (Self::Ice, Band::ShortwaveInfrared) => (1.296, 5.6e-4),
            (Self::Mineral, Band::Visible) => (1.546, 0.0),
            (Self::Mineral, Band::NearInfrared) => (1.536, 0.0),
            (Self::Mineral, Band::ShortwaveInfrared) => (1.528, 0.0),
        };
        RefractiveIndex { n, k }
    }
}

/// Measured lidar ratio of ice crystals, sr (Chen, Chiang & Nee 2002).
pub const ICE_LIDAR_RATIO_SR: f32 = 29.0;

/// Measured lidar ratio of mineral dust, sr (Tesche et al. 2009).
pub const DUST_LIDAR_RATIO_SR: f32 = 55.0;

/// `ln 20`: the 5 % transmission of the meteorological optical range.
pub const MOR_LOG_CONTRAST: f32 = 2.995_732_3;

/// Van de Hulst's anomalous-diffraction extinction efficiency of a sphere of
/// diameter `diameter_m` and real index `n` at `wavelength_nm`.
#[must_use]
pub fn extinction_efficiency(diameter_m: f32, n: f32, wavelength_nm: f32) -> f32 {
    let x = std::f32::consts::PI * diameter_m / (wavelength_nm * 1.0e-9);
    let rho = 2.0 * x * (n - 1.0);
    if rho < 1.0e-3 {
        // The series: ρ²/2 (Rayleigh-like limit of the approximation).
        return 0.5 * rho * rho;
    }
    2.0 - 4.0 / rho * rho.sin() + 4.0 / (rho * rho) * (1.0 - rho.cos())
}

/// Extinction cross-section of a particle, m².
#[must_use]
pub fn extinction_cross_section_m2(kind: ParticleKind, diameter_m: f32, band: Band) -> f32 {
    let index = kind.material().refractive_index(band);
    extinction_efficiency(diameter_m, index.n, band.wavelength_nm())
        * std::f32::consts::FRAC_PI_4
        * diameter_m
        * diameter_m
}

/// Geometric-optics backscatter of a water drop, m²/sr: the front reflection and
/// the once-reflected axial ray (module docs).
#[must_use]
pub fn drop_backscatter_m2_sr(diameter_m: f32, band: Band) -> f32 {
    let RefractiveIndex { n, k } = Material::Water.refractive_index(band);
    let r0 = ((n - 1.0) / (n + 1.0)).powi(2);
    let a2 = 0.25 * diameter_m * diameter_m;
    let absorption_per_m = 4.0 * std::f32::consts::PI * k / (band.wavelength_nm() * 1.0e-9);
    let front = a2 * r0 / 4.0;
    let axial = a2 * (1.0 - r0).powi(2) * r0 / (4.0 / n - 2.0).powi(2)
        * (-2.0 * absorption_per_m * diameter_m).exp();
    front + axial
}

/// Backscatter cross-section of a particle, m²/sr.
#[must_use]
pub fn backscatter_cross_section_m2_sr(kind: ParticleKind, diameter_m: f32, band: Band) -> f32 {
    match kind.material() {
        Material::Water => drop_backscatter_m2_sr(diameter_m, band),
        Material::Ice => extinction_cross_section_m2(kind, diameter_m, band) / ICE_LIDAR_RATIO_SR,
        Material::Mineral => {
            extinction_cross_section_m2(kind, diameter_m, band) / DUST_LIDAR_RATIO_SR
        }
    }
}

/// `ln 20/σ`, m, capped at the clear air's range.
#[must_use]
pub fn meteorological_optical_range_m(extinction_per_m: f32) -> f32 {
    if extinction_per_m > MOR_LOG_CONTRAST / CLEAR_AIR_VISIBILITY_M {
        MOR_LOG_CONTRAST / extinction_per_m
    } else {
        CLEAR_AIR_VISIBILITY_M
    }
}

/// The optics of the air in one band.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BandOptics {
    /// Extinction coefficient, per m.
    pub extinction_per_m: f32,
    /// Backscatter coefficient, per m per sr.
    pub backscatter_per_m_sr: f32,
}

impl BandOptics {
    /// Extinction over backscatter, sr (`None` where nothing scatters).
    #[must_use]
    pub fn lidar_ratio_sr(&self) -> Option<f32> {
        (self.backscatter_per_m_sr > 0.0).then(|| self.extinction_per_m / self.backscatter_per_m_sr)
    }

    /// The fraction of a beam that goes out `range_m` and comes back: `e^(−2σr)`
    /// (two-way Beer–Lambert).
    #[must_use]
    pub fn two_way_transmittance(&self, range_m: f32) -> f32 {
        (-2.0 * self.extinction_per_m * range_m.max(0.0)).exp()
    }

    fn add(&mut self, other: Self, weight: f32) {
        self.extinction_per_m += weight * other.extinction_per_m;
        self.backscatter_per_m_sr += weight * other.backscatter_per_m_sr;
    }
}

/// Where an [`Optics`] comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OpticsSource {
    /// The weather's size spectra.
    Spectra,
    /// The particles in the camera volume now (this many), plus the spectra's sizes
    /// too small to simulate.
    LiveParticles {
        /// Camera-volume particles counted.
        sampled: u32,
    },
}

/// The lidar ratio (extinction over backscatter) of liquid-water fog and cloud
/// droplets, sr (O'Connor, Illingworth & Hogan 2004, J. Atmos. Oceanic Technol. 21:
/// 18.8 sr, nearly constant over the droplet sizes of water clouds).
pub const FOG_LIDAR_RATIO_SR: f32 = 18.8;

/// Extinction and backscatter in every band, and the meteorological optical range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Optics {
    /// Per band, in [`Band::ALL`]'s order.
    pub bands: [BandOptics; 3],
    /// Where the numbers come from.
    pub source: OpticsSource,
}

impl Optics {
    /// One band.
    #[must_use]
    pub const fn band(&self, band: Band) -> BandOptics {
        self.bands[band.index()]
    }

    /// The meteorological optical range, m (from 550 nm).
    #[must_use]
    pub fn meteorological_optical_range_m(&self) -> f32 {
        meteorological_optical_range_m(self.band(Band::Visible).extinction_per_m)
    }

    /// These optics with a fog layer's droplets added where `at_m` lies in it:
    /// its extinction `B` in every band (droplets of a few µm and more have an
    /// extinction efficiency of 2 from the visible to 1.5 µm) and backscatter
    /// `B/S`, `S` = [`FOG_LIDAR_RATIO_SR`].
    #[must_use]
    pub fn in_fog(
        mut self,
        fog: Option<crate::drawing::fog_layer::FogLayer>,
        at_m: glam::Vec3,
    ) -> Self {
        if let Some(fog) = fog.filter(|f| at_m.y < f.top_m) {
            let b = fog.extinction_per_m();
            for band in &mut self.bands {
                band.extinction_per_m += b;
                band.backscatter_per_m_sr += b / FOG_LIDAR_RATIO_SR;
            }
        }
        self
    }

    /// These optics with a cloud's droplets added where `at_m` lies in one of
    /// `layers` (drifted by `drift_m`): its extinction there in every band and
    /// backscatter over [`FOG_LIDAR_RATIO_SR`], as [`Optics::in_fog`]'s.
    #[must_use]
    pub fn in_cloud(
        mut self,
        layers: &crate::drawing::clouds::CloudLayers,
        drift_m: glam::Vec2,
        at_m: glam::Vec3,
    ) -> Self {
        if !layers.is_empty() {
            let sigma = layers.extinction_at(crate::drawing::clouds::cloud_noise(), drift_m, at_m);
            for band in &mut self.bands {
                band.extinction_per_m += sigma;
                band.backscatter_per_m_sr += sigma / FOG_LIDAR_RATIO_SR;
            }
        }
        self
    }

    /// The optics of `weather`'s size spectra (all sizes).
    #[must_use]
    pub fn of_weather(weather: &Weather) -> Self {
        let parts = SpectrumParts::of(weather);
        Self {
            bands: parts.total,
            source: OpticsSource::Spectra,
        }
    }

    /// The optics from the particles a backend holds (module docs): the camera
    /// volume's particles stand for the sizes simulated one by one at `weather`'s
    /// density of them; the sizes below keep the spectra's part. Without camera-volume
    /// particles, the spectra's.
    #[must_use]
    pub fn live(weather: &Weather, particles: &[Particle]) -> Self {
        Self::from_sums(weather, &CrossSectionSums::of_particles(particles))
    }

    /// [`Optics::live`] from the camera volume's cross-sections summed (on the host,
    /// or on the GPU by `optics_sums`: [`CrossSectionSums::of_partials`]).
    #[must_use]
    pub fn from_sums(weather: &Weather, sums: &CrossSectionSums) -> Self {
        let parts = SpectrumParts::of(weather);
        if sums.sampled == 0 {
            return Self {
                bands: parts.total,
                source: OpticsSource::Spectra,
            };
        }
        let per_particle = weather.simulated_number_density_per_m3() / sums.sampled as f32;
        let mut bands = parts.unresolved;
        for (band, sum) in bands.iter_mut().zip(sums.bands) {
            band.add(sum, per_particle);
        }
        Self {
            bands,
            source: OpticsSource::LiveParticles {
                sampled: sums.sampled,
            },
        }
    }
}

/// The cross-sections of the camera volume's particles summed per band (m², m²/sr,
/// in [`BandOptics`]' fields), and how many were counted: what [`Optics::from_sums`]
/// needs of the particles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CrossSectionSums {
    /// Per band, in [`Band::ALL`]'s order.
    pub bands: [BandOptics; 3],
    /// Camera-volume particles counted.
    pub sampled: u32,
}

impl CrossSectionSums {
    /// The sums over `particles`, in order (the CPU reference).
    #[must_use]
    pub fn of_particles(particles: &[Particle]) -> Self {
        let mut sums = Self::default();
        for p in particles
            .iter()
            .filter(|p| p.source() == ParticleSource::CameraVolume && p.diameter_m > 0.0)
        {
            sums.sampled += 1;
            for band in Band::ALL {
                sums.bands[band.index()].add(
                    BandOptics {
                        extinction_per_m: extinction_cross_section_m2(p.kind(), p.diameter_m, band),
                        backscatter_per_m_sr: backscatter_cross_section_m2_sr(
                            p.kind(),
                            p.diameter_m,
                            band,
                        ),
                    },
                    1.0,
                );
            }
        }
        sums
    }

    /// The sums of the GPU's per-workgroup partials (`optics_sums`), added in order
    /// in double precision, so a backend's answer does not depend on its scheduling.
    #[must_use]
    pub fn of_partials(partials: &[OpticsPartial]) -> Self {
        let mut extinction = [0f64; 3];
        let mut backscatter = [0f64; 3];
        let mut sampled = 0u32;
        for p in partials {
            for b in 0..3 {
                extinction[b] += f64::from(p.extinction_m2[b]);
                backscatter[b] += f64::from(p.backscatter_m2_sr[b]);
            }
            sampled = sampled.saturating_add(p.sampled);
        }
        Self {
            bands: std::array::from_fn(|b| BandOptics {
                extinction_per_m: extinction[b] as f32,
                backscatter_per_m_sr: backscatter[b] as f32,
            }),
            sampled,
        }
    }
}

/// One workgroup's sums of `optics_sums` (64 particles): the cross-sections of its
/// camera-volume particles per band, and their count.
///
/// WGSL twin: `OpticsPartial` in `shaders/optics.wgsl` (32 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct OpticsPartial {
    /// Extinction cross-sections per band, m².
    pub extinction_m2: [f32; 3],
    /// Particles counted.
    pub sampled: u32,
    /// Backscatter cross-sections per band, m²/sr.
    pub backscatter_m2_sr: [f32; 3],
    /// Unused.
    pub reserved: u32,
}
const _: () = assert!(size_of::<OpticsPartial>() == 32);

/// A weather's spectra summed: all of it, and the part below the sizes simulated.
struct SpectrumParts {
    total: [BandOptics; 3],
    unresolved: [BandOptics; 3],
}

/// Bins of the numerical sums over a spectrum.
const SPECTRUM_BINS: u32 = 2000;
/// The sums run to this many mean sizes (`1/Λ`): the rest is `e^(−30)` of the count.
const SPECTRUM_REACH: f32 = 30.0;

impl SpectrumParts {
    fn of(weather: &Weather) -> Self {
        let mut parts = Self {
            total: [BandOptics::default(); 3],
            unresolved: [BandOptics::default(); 3],
        };
        for kind in ParticleKind::ALL {
            match kind.spectrum_in(weather) {
                Some(Spectrum::Exponential {
                    n0_per_m3_mm,
                    slope_per_mm,
                    support_mm,
                    simulated_from_mm,
                    simulated_to_mm,
                }) => parts.add_spectrum(
                    kind,
                    (n0_per_m3_mm, slope_per_mm, support_mm),
                    |d_mm| kind.diameter_at_spectral_size_m(d_mm),
                    |d_mm| !(simulated_from_mm..=simulated_to_mm).contains(&d_mm),
                ),
                Some(Spectrum::OneSize {
                    diameter_m,
                    n_per_m3,
                }) => {
                    for band in Band::ALL {
                        parts.total[band.index()].add(
                            BandOptics {
                                extinction_per_m: extinction_cross_section_m2(
                                    kind, diameter_m, band,
                                ),
                                backscatter_per_m_sr: backscatter_cross_section_m2_sr(
                                    kind, diameter_m, band,
                                ),
                            },
                            n_per_m3,
                        );
                    }
                }
                None => {}
            }
        }
        parts
    }

    /// Adds `∫ N0·e^(−Λd)·C(D(d)) dd` (d in mm, N0 per m³ per mm) over the
    /// spectrum's support (to [`SPECTRUM_REACH`] mean sizes past its start) by the
    /// midpoint rule, to the total and, where `unresolved(d)`, to the unresolved part.
    fn add_spectrum(
        &mut self,
        kind: ParticleKind,
        (n0_per_m3_mm, slope_per_mm, (from_mm, to_mm)): (f32, f32, (f32, f32)),
        diameter_m: impl Fn(f32) -> f32,
        unresolved: impl Fn(f32) -> bool,
    ) {
        if slope_per_mm <= 0.0 || !slope_per_mm.is_finite() {
            return;
        }
        let end_mm = (from_mm + SPECTRUM_REACH / slope_per_mm).min(to_mm);
        let step_mm = (end_mm - from_mm) / SPECTRUM_BINS as f32;
        for i in 0..SPECTRUM_BINS {
            let d_mm = from_mm + (i as f32 + 0.5) * step_mm;
            let count_per_m3 = n0_per_m3_mm * (-slope_per_mm * d_mm).exp() * step_mm;
            let size_m = diameter_m(d_mm);
            for band in Band::ALL {
                let one = BandOptics {
                    extinction_per_m: extinction_cross_section_m2(kind, size_m, band),
                    backscatter_per_m_sr: backscatter_cross_section_m2_sr(kind, size_m, band),
                };
                self.total[band.index()].add(one, count_per_m3);
                if unresolved(d_mm) {
                    self.unresolved[band.index()].add(one, count_per_m3);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
