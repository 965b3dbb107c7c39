//! A spinning LiDAR over the scene: its beams, the points its echoes make, and those
//! points as a PLY file (the `lidar_scan` example writes one beside a rendered frame).
//!
//! Each beam reports one point, the stronger echo of the two the backend's beam query
//! returns ([`precip_model::sensors::lidar::BeamReturn::strongest_echo_m`]): the first flake
//! or drop struck, whose reflectance is its backscatter per area
//! (`π·β_p/A_p`: about 0.22 for snow, whose lidar ratio is 29 sr, and 0.02 for
//! rain at 905 nm), or the ground behind it at [`GROUND_REFLECTANCE`] — water (a
//! pond, a puddle, the sea) at its glint's and foam's
//! ([`precip_model::sensors::lidar::water_echo`]: strong straight down, nothing
//! aslant but foam) — seen through the air's two-way transmittance and what the
//! particle leaves of the footprint.
//! An echo weaker than the sensor's detection threshold — a [`RATED_REFLECTANCE`]
//! target at its full range — gives no point: far flakes, which fill a sliver of the
//! widened beam, are not seen; near ones are (the clutter LiDARs show in snow).

use std::io::Write as _;
use std::path::Path;

use glam::Vec3;
use precip_model::sensors::lidar::water_echo::water_reflectance;
use precip_model::sensors::lidar::{Beam, BeamReturn};
use precip_model::sensors::optics::{Band, backscatter_cross_section_m2_sr};

/// The ground's reflectance at the LiDAR's wavelength (soil, grass, asphalt are
/// 0.1–0.4 at 905 nm).
pub const GROUND_REFLECTANCE: f32 = 0.3;

/// The beams' radius where they leave the sensor, m.
pub const APERTURE_RADIUS_M: f32 = 0.01;

/// The weakest target a sensor is specified to see at its full range: a 10 %
/// reflectance (automotive LiDARs quote their range for 10 % targets).
pub const RATED_REFLECTANCE: f32 = 0.1;

/// A spinning LiDAR's pattern.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinningLidar {
    /// Where it sits, m.
    pub origin_m: Vec3,
    /// Channels (rows), spread evenly from `lowest_deg` to `highest_deg`.
    pub channels: u32,
    /// The lowest channel's elevation, degrees.
    pub lowest_deg: f32,
    /// The highest channel's elevation, degrees.
    pub highest_deg: f32,
    /// Beams per turn.
    pub azimuth_steps: u32,
    /// Full divergence of a beam, rad.
    pub divergence_rad: f32,
    /// Range, m.
    pub max_range_m: f32,
}

impl SpinningLidar {
    /// A 32-channel, 1024-step sensor of 3 mrad beams and 120 m range at `origin_m`,
    /// looking from −25° to +15°.
    #[must_use]
    pub fn automotive(origin_m: Vec3) -> Self {
        Self {
            origin_m,
            channels: 32,
            lowest_deg: -25.0,
            highest_deg: 15.0,
            azimuth_steps: 1024,
            divergence_rad: 3.0e-3,
            max_range_m: 120.0,
        }
    }

    /// The weakest echo it detects, reflectance over range² (1/m²).
    #[must_use]
    pub fn detection_threshold(&self) -> f32 {
        RATED_REFLECTANCE / (self.max_range_m * self.max_range_m)
    }

    /// Its beams, channel by channel; azimuth 0 looks along −z, turning toward +x.
    #[must_use]
    pub fn beams(&self) -> Vec<Beam> {
        let rows = self.channels.max(1);
        let mut beams = Vec::with_capacity((rows * self.azimuth_steps) as usize);
        for row in 0..rows {
            let f = if rows > 1 {
                row as f32 / (rows - 1) as f32
            } else {
                0.5
            };
            let elevation =
                (self.lowest_deg + f * (self.highest_deg - self.lowest_deg)).to_radians();
            for step in 0..self.azimuth_steps {
                let azimuth = std::f32::consts::TAU * step as f32 / self.azimuth_steps as f32;
                let direction = Vec3::new(
                    elevation.cos() * azimuth.sin(),
                    elevation.sin(),
                    -elevation.cos() * azimuth.cos(),
                );
                beams.push(Beam {
                    divergence_rad: self.divergence_rad,
                    ..Beam::ray(self.origin_m, direction, self.max_range_m)
                });
            }
        }
        beams
    }
}

/// One point of the cloud.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LidarPoint {
    /// Where, m.
    pub position_m: Vec3,
    /// The echo's strength, reflectance over range² (1/m²).
    pub intensity: f32,
    /// Whether a particle made it (else the ground).
    pub from_particle: bool,
}

/// The reflectance the target of `r` echoes with along `beam` in a wind of
/// `wind_mps`: water's glint and foam, else [`GROUND_REFLECTANCE`].
#[must_use]
pub fn target_reflectance(beam: &Beam, r: &BeamReturn, wind_mps: f32) -> f32 {
    match r.target {
        Some(t) if t.surface == precip_model::cover::Surface::Water => {
            let down = -beam.direction.normalize_or_zero().y;
            water_reflectance(down, wind_mps)
        }
        _ => GROUND_REFLECTANCE,
    }
}

/// The points of `returns` (one per beam of `beams`) in `band` whose echo reaches
/// `detection_threshold` (1/m²; [`SpinningLidar::detection_threshold`]), in a wind
/// of `wind_mps` (water's echo).
#[must_use]
pub fn point_cloud(
    beams: &[Beam],
    returns: &[BeamReturn],
    band: Band,
    detection_threshold: f32,
    wind_mps: f32,
) -> Vec<LidarPoint> {
    beams
        .iter()
        .zip(returns)
        .filter_map(|(beam, r)| {
            let particle_reflectance = r.particle.map_or(0.0, |p| {
                let area = std::f32::consts::FRAC_PI_4 * p.diameter_m * p.diameter_m;
                std::f32::consts::PI * backscatter_cross_section_m2_sr(p.kind, p.diameter_m, band)
                    / area.max(f32::MIN_POSITIVE)
            });
            let ground = target_reflectance(beam, r, wind_mps);
            let (range, from_particle) = r.strongest_echo_m(particle_reflectance, ground)?;
            let intensity = if from_particle {
                particle_reflectance * r.particle.map_or(0.0, |p| p.footprint_share)
            } else {
                ground
                    * r.target.map_or(0.0, |t| t.two_way_transmittance)
                    * (1.0 - r.particle.map_or(0.0, |p| p.footprint_share))
            } / range.max(0.1).powi(2);
            (intensity >= detection_threshold).then_some(LidarPoint {
                position_m: beam.origin_m + beam.direction * range,
                intensity,
                from_particle,
            })
        })
        .collect()
}

/// Writes `points` as an ASCII PLY: `x y z intensity particle` (particle 1 for a
/// flake's or drop's echo, 0 for the ground's).
pub fn write_ply(path: &Path, points: &[LidarPoint]) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "ply")?;
    writeln!(out, "format ascii 1.0")?;
    writeln!(out, "comment precip LiDAR scan: strongest echo per beam")?;
    writeln!(out, "element vertex {}", points.len())?;
    for property in [
        "float x",
        "float y",
        "float z",
        "float intensity",
        "uchar particle",
    ] {
        writeln!(out, "property {property}")?;
    }
    writeln!(out, "end_header")?;
    for p in points {
        writeln!(
            out,
            "{:.4} {:.4} {:.4} {:.6e} {}",
            p.position_m.x,
            p.position_m.y,
            p.position_m.z,
            p.intensity,
            u8::from(p.from_particle)
        )?;
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    use precip_model::ParticleKind;
    use precip_model::sensors::lidar::{EchoOrigin, ParticleEcho, TargetEcho};

    use super::*;

    #[test]
    fn the_pattern_spans_its_channels_and_turn() {
        let lidar = SpinningLidar {
            channels: 3,
            azimuth_steps: 4,
            ..SpinningLidar::automotive(Vec3::Y)
        };
        let beams = lidar.beams();
        assert_eq!(beams.len(), 12);
        assert!((beams[0].direction.y - (-25f32).to_radians().sin()).abs() < 1e-6);
        assert!((beams[11].direction.y - 15f32.to_radians().sin()).abs() < 1e-6);
        // Azimuth 0 looks along −z, a quarter turn along +x.
        assert!(beams[4].direction.z < -0.99 && beams[5].direction.x > 0.99);
    }

    #[test]
    fn a_snowflake_in_front_of_far_ground_is_the_echo_and_the_ply_says_so() {
        let beam = Beam::ray(Vec3::ZERO, Vec3::NEG_Z, 100.0);
        let flake = BeamReturn {
            particle: Some(ParticleEcho {
                range_m: 4.0,
                diameter_m: 0.006,
                kind: ParticleKind::DrySnow,
                origin: EchoOrigin::CameraVolume,
                footprint_share: 0.5,
            }),
            target: Some(TargetEcho {
                range_m: 60.0,
                two_way_transmittance: 0.8,
                surface: precip_model::cover::Surface::Grass,
            }),
        };
        let bare = BeamReturn {
            particle: None,
            ..flake
        };
        let nothing = BeamReturn {
            particle: None,
            target: None,
        };
        let points = point_cloud(
            &[beam, beam, beam],
            &[flake, bare, nothing],
            Band::NearInfrared,
            0.0,
            3.0,
        );
        assert_eq!(points.len(), 2);
        // A 120 m sensor's threshold keeps the flake at 4 m and the ground at 60 m.
        let threshold = SpinningLidar::automotive(Vec3::ZERO).detection_threshold();
        let seen = point_cloud(
            &[beam, beam],
            &[flake, bare],
            Band::NearInfrared,
            threshold,
            3.0,
        );
        assert_eq!(seen.len(), 2);
        // The same flake at 40 m fills 1 % of the footprint's share: not seen.
        let far = BeamReturn {
            particle: flake.particle.map(|p| ParticleEcho {
                range_m: 40.0,
                footprint_share: 0.005,
                ..p
            }),
            target: None,
        };
        assert!(point_cloud(&[beam], &[far], Band::NearInfrared, threshold, 3.0).is_empty());
        assert!(points[0].from_particle && (points[0].position_m.z + 4.0).abs() < 1e-6);
        assert!(!points[1].from_particle && (points[1].position_m.z + 60.0).abs() < 1e-4);
        let path = std::env::temp_dir().join(format!("precip-ply-{}.ply", std::process::id()));
        write_ply(&path, &points).expect("written");
        let text = std::fs::read_to_string(&path).expect("read");
        std::fs::remove_file(&path).ok();
        assert!(text.starts_with("ply\nformat ascii 1.0\n"));
        assert!(text.contains("element vertex 2\n"));
        assert_eq!(text.lines().count(), 10 + 2);
        assert!(text.lines().nth(10).expect("a point").ends_with(" 1"));
    }

    #[test]
    fn water_echoes_to_a_beam_from_above_and_not_to_a_grazing_one() {
        // 30 m to the target, looking straight down and 5° under the horizon.
        let target = |surface| BeamReturn {
            particle: None,
            target: Some(TargetEcho {
                range_m: 30.0,
                two_way_transmittance: 1.0,
                surface,
            }),
        };
        let down = Beam::ray(Vec3::ZERO, Vec3::NEG_Y, 100.0);
        let grazing = Beam::ray(
            Vec3::ZERO,
            Vec3::new(1.0, -5f32.to_radians().tan(), 0.0),
            100.0,
        );
        let threshold = SpinningLidar::automotive(Vec3::ZERO).detection_threshold();
        let water = target(precip_model::cover::Surface::Water);
        let grass = target(precip_model::cover::Surface::Grass);
        let seen = |beam: Beam, r: BeamReturn, wind: f32| {
            point_cloud(&[beam], &[r], Band::NearInfrared, threshold, wind).len()
        };
        assert_eq!(seen(down, water, 5.0), 1);
        assert_eq!(seen(grazing, water, 5.0), 0);
        assert_eq!(seen(grazing, grass, 5.0), 1);
        // A gale's whitecaps echo even aslant.
        assert!(target_reflectance(&grazing, &water, 24.0) > 0.01);
    }
}
