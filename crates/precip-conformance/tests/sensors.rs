//! What sensors get, alike on every backend: LiDAR beams against the particles and
//! the ground (each backend's answer equals the CPU reference's on that backend's own
//! particles), and the optics from the particles in the air.

use glam::Vec3;
use precip_conformance::all_subjects;
use precip_model::backend::setup::CameraVolumeSetup;
use precip_model::sensors::lidar::{Beam, BeamParams, BeamQuery, NO_PARTICLE, query_on_cpu};
use precip_model::sensors::optics::{Band, Optics, OpticsSource};
use precip_model::{CameraVolume, ParticleKind, PrecipitationKind, Setup, Weather};

/// Snow around a camera 1.7 m over a 40 m square with a 3 m wall 6 m ahead (−z):
/// 20 000 flakes in a 10 m camera volume (20 per m³), so beams strike flakes often.
fn snow_before_a_wall() -> Setup {
    let mut s = Setup::over_flat_ground(40.0, 80, 15.0, 2_000);
    s.seed = 5;
    s.weather = Weather {
        intensity_mm_per_h: 2.0,
        air_temperature_c: -5.0,
        ..Weather::default()
    };
    s.camera.position_m = Vec3::new(0.0, 1.7, 0.0);
    s.camera.forward = Vec3::NEG_Z;
    s.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume {
            half_extent_m: Vec3::splat(5.0),
            ..CameraVolume::default()
        },
        particle_count: 20_000,
    });
    let frame = s.ground.frame;
    for i in 0..frame.texel_count() {
        let c = frame.texel_centre(i);
        if (c.y + 6.0).abs() < 0.3 {
            s.ground.height_m[i] = 3.0;
        }
    }
    s
}

/// One pencil beam from the camera of [`snow_before_a_wall`] to its wall, 6 m ahead,
/// at 905 nm through air that dims nothing by itself.
fn beam_to_the_wall() -> BeamQuery {
    BeamQuery {
        beams: vec![Beam::ray(Vec3::new(0.0, 1.7, 0.0), Vec3::NEG_Z, 40.0)],
        band: Band::NearInfrared,
        aperture_radius_m: 0.0,
        extinction_per_m: Some(0.0),
        sample_unresolved: false,
    }
}

/// A spinning LiDAR's fan: 16 channels from −15° to +10°, every 3° around.
fn fan(origin_m: Vec3) -> Vec<Beam> {
    let mut beams = Vec::new();
    for channel in 0..16 {
        let elevation = (-15.0 + 25.0 * channel as f32 / 15.0).to_radians();
        for step in 0..120 {
            let azimuth = (3.0 * step as f32).to_radians();
            beams.push(Beam {
                divergence_rad: 3.0e-3,
                ..Beam::ray(
                    origin_m,
                    Vec3::new(
                        elevation.cos() * azimuth.sin(),
                        elevation.sin(),
                        -elevation.cos() * azimuth.cos(),
                    ),
                    40.0,
                )
            });
        }
    }
    beams
}

/// The CPU reference's hits for `query` on `backend`'s own particles, and the
/// validated beams.
fn reference_hits(
    backend: &mut dyn precip_model::Backend,
    query: &BeamQuery,
    setup: &Setup,
) -> (Vec<Beam>, Vec<precip_model::sensors::lidar::BeamHit>) {
    let particles = backend.read_particles().expect("particles");
    let beams = query.validate().expect("valid");
    // The particles in the air under the setup's weather (the rest rest unseen).
    let in_the_air = precip_model::particles::step::stepped_particles(&setup.step_params(
        &setup.weather,
        Vec3::ZERO,
        0.01,
        0.0,
    ));
    let params: BeamParams = query.params(&beams, in_the_air, &setup.ground);
    let hits = query_on_cpu(&beams, &params, &particles, &setup.ground);
    (beams, hits)
}

#[test]
fn beams_strike_the_same_particles_and_targets_as_the_cpu_reference_on_every_backend() {
    let setup = snow_before_a_wall();
    for mut s in all_subjects("beams") {
        s.backend.configure(&setup).expect("configure");
        for _ in 0..3 {
            s.backend.step(0.05).expect("step");
        }
        let query = BeamQuery {
            beams: fan(setup.camera.position_m),
            band: Band::NearInfrared,
            aperture_radius_m: 0.01,
            extinction_per_m: None,
            // The kernel alone: strikes drawn from the spectrum are checked below.
            sample_unresolved: false,
        };
        let returns = s.backend.query_beams(&query).expect("beams");
        assert_eq!(returns.len(), query.beams.len());
        // The reference on this backend's own particles.
        let (beams, reference) = reference_hits(s.backend.as_mut(), &query, &setup);
        let extinction = query.extinction_in(&setup.weather);
        let expected = BeamQuery::returns(&beams, &reference, query.aperture_radius_m, extinction);
        let mut differing = 0;
        for (got, want) in returns.iter().zip(&expected) {
            let same_particle = match (got.particle, want.particle) {
                (Some(a), Some(b)) => {
                    a.diameter_m.to_bits() == b.diameter_m.to_bits()
                        && a.kind == b.kind
                        && (a.range_m - b.range_m).abs() < 1e-4 * b.range_m.max(1.0)
                }
                (None, None) => true,
                _ => false,
            };
            let same_target = match (got.target, want.target) {
                (Some(a), Some(b)) => (a.range_m - b.range_m).abs() < 1e-3,
                (None, None) => true,
                _ => false,
            };
            if !(same_particle && same_target) {
                differing += 1;
            }
        }
        let struck = returns.iter().filter(|r| r.particle.is_some()).count();
        let walls = returns
            .iter()
            .filter(|r| r.target.is_some_and(|t| t.range_m < 7.0 && t.range_m > 5.0))
            .count();
        let flakes = returns
            .iter()
            .filter_map(|r| r.particle)
            .filter(|p| p.kind == ParticleKind::DrySnow)
            .count();
        println!(
            "{}: {} beams, {struck} struck a flake ({flakes} dry snow), {walls} met the wall 6 m ahead, {differing} differ from the CPU reference on its particles",
            s.name,
            returns.len()
        );
        assert!(
            struck > 100 && flakes == struck,
            "{}: {struck} struck",
            s.name
        );
        assert!(walls > 100, "{}: {walls} beams met the wall", s.name);
        // Only grazing strikes (a flake's rim on the cone's edge) may round apart.
        assert!(
            differing * 200 <= returns.len(),
            "{}: {differing} differ",
            s.name
        );
        assert!(reference.iter().any(|h| h.particle_flags == NO_PARTICLE));
        s.check_clean("beams");
    }
}

#[test]
fn optics_from_the_particles_in_the_air_follow_the_weather_on_every_backend() {
    let mut setup = snow_before_a_wall();
    setup.weather = Weather {
        kind: PrecipitationKind::Rain,
        intensity_mm_per_h: 10.0,
        air_temperature_c: 12.0,
        ..Weather::default()
    };
    let spectra = Optics::of_weather(&setup.weather);
    let mut first: Option<Optics> = None;
    for mut s in all_subjects("optics") {
        s.backend.configure(&setup).expect("configure");
        s.backend.step(0.05).expect("step");
        let live = s.backend.optics().expect("optics");
        assert_eq!(live.source, OpticsSource::LiveParticles { sampled: 20_000 });
        for band in Band::ALL {
            let (a, b) = (live.band(band), spectra.band(band));
            println!(
                "{} {band:?}: extinction {:.3e}/m (spectra {:.3e}), backscatter {:.3e}/(m·sr) (spectra {:.3e})",
                s.name,
                a.extinction_per_m,
                b.extinction_per_m,
                a.backscatter_per_m_sr,
                b.backscatter_per_m_sr
            );
            // 20 000 drops drawn from Marshall–Palmer sample its cross-sections to a
            // few per cent.
            let ratio = a.extinction_per_m / b.extinction_per_m;
            assert!(
                (0.95..1.05).contains(&ratio),
                "{} {band:?}: {ratio}",
                s.name
            );
        }
        match &first {
            None => first = Some(live),
            Some(reference) => {
                // The GPU sums the same particles' cross-sections on the device
                // (`optics_sums`): the CPU's within the sums' rounding, every band.
                for band in Band::ALL {
                    let (a, b) = (live.band(band), reference.band(band));
                    assert!(
                        (a.extinction_per_m / b.extinction_per_m - 1.0).abs() < 1e-3
                            && (a.backscatter_per_m_sr / b.backscatter_per_m_sr - 1.0).abs() < 1e-3,
                        "{} {band:?}: {a:?} vs the CPU's {b:?}",
                        s.name
                    );
                }
            }
        }
        s.check_clean("optics");
    }
}

#[test]
fn a_fog_layer_set_while_running_reaches_the_optics_and_the_beams_on_every_backend() {
    use precip_model::drawing::fog_layer::FogLayer;
    use precip_model::sensors::optics::FOG_LIDAR_RATIO_SR;
    let setup = snow_before_a_wall();
    // The camera at 1.7 m: in a 10 m fog, above a 1 m one.
    let deep = FogLayer::new(10.0, 150.0);
    let shallow = FogLayer::new(1.0, 150.0);
    let query = beam_to_the_wall();
    for mut s in all_subjects("fog_layer") {
        s.backend.configure(&setup).expect("configure");
        s.backend.step(0.05).expect("step");
        let clear = s.backend.optics().expect("optics");
        let wall = |s: &mut precip_conformance::Subject| {
            let r = s.backend.query_beams(&query).expect("beams");
            r[0].target
                .expect("the wall 6 m ahead")
                .two_way_transmittance
        };
        let clear_wall = wall(&mut s);
        s.backend.set_fog_layer(Some(deep)).expect("a valid fog");
        let fog = s.backend.optics().expect("optics");
        let b = deep.extinction_per_m();
        for band in Band::ALL {
            let (f, c) = (fog.band(band), clear.band(band));
            assert!(
                (f.extinction_per_m - c.extinction_per_m - b).abs() < 1e-3 * b
                    && (f.backscatter_per_m_sr - c.backscatter_per_m_sr - b / FOG_LIDAR_RATIO_SR)
                        .abs()
                        < 1e-3 * b,
                "{} {band:?}: {f:?} against {c:?} + fog",
                s.name
            );
        }
        // MOR (5 %) from the fog's and the snow's extinction together.
        let mor = fog.meteorological_optical_range_m();
        let expected = 2.996 / (clear.band(Band::Visible).extinction_per_m + b);
        assert!(
            (mor / expected - 1.0).abs() < 0.01 && mor < 150.0,
            "{}: MOR {mor} m against {expected}",
            s.name
        );
        let foggy_wall = wall(&mut s);
        let range = 6.0;
        assert!(
            (foggy_wall / clear_wall - (-2.0 * b * range).exp()).abs() < 0.02,
            "{}: {foggy_wall} against {clear_wall}",
            s.name
        );
        s.backend.set_fog_layer(Some(shallow)).expect("a valid fog");
        let above = s.backend.optics().expect("optics");
        assert_eq!(above.bands, clear.bands, "{}: above the fog", s.name);
        assert!(
            s.backend
                .set_fog_layer(Some(FogLayer::new(10.0, f32::NAN)))
                .is_err(),
            "{}: a NaN visibility is refused",
            s.name
        );
        s.check_clean("fog_layer");
    }
}

#[test]
fn a_cloud_the_camera_is_in_reaches_the_optics_and_the_beams_on_every_backend() {
    use precip_model::drawing::clouds::{
        CloudKind, CloudLayer, CloudLayers, cloud_drift_m, cloud_extinction_at, cloud_noise,
    };
    let setup = snow_before_a_wall();
    // A full nimbostratus deck from 500 m below the ground (the camera, at 1.7 m, a
    // fifth of the way up it).
    let deck = CloudLayer {
        base_m: -500.0,
        thickness_m: 2_500.0,
        coverage: 1.0,
        kind: CloudKind::Nimbostratus,
        transition_band_m: 0.0,
    };
    let query = beam_to_the_wall();
    for mut s in all_subjects("cloud_layer") {
        s.backend.configure(&setup).expect("configure");
        s.backend.step(0.05).expect("step");
        let clear = s.backend.optics().expect("optics");
        let clear_wall = s.backend.query_beams(&query).expect("beams")[0]
            .target
            .expect("the wall")
            .two_way_transmittance;
        // The deck with a stratus sheet above it (the camera in the deck only).
        let sheet = CloudLayer {
            base_m: deck.top_m() + 500.0,
            thickness_m: 400.0,
            coverage: 1.0,
            kind: CloudKind::Stratus,
            transition_band_m: 0.0,
        };
        s.backend
            .set_cloud_layers(CloudLayers::new(&[sheet, deck]).expect("valid layers"))
            .expect("valid layers");
        let cloudy = s.backend.optics().expect("optics");
        // The clock after one step of 0.05 s: the deck drifted with the calm wind.
        let offset = cloud_drift_m(setup.weather.wind.mean_wind_mps, 0.05);
        let sigma = cloud_extinction_at(cloud_noise(), &deck, offset, setup.camera.position_m);
        assert!(sigma > 0.01, "the camera is in the cloud: {sigma}");
        for band in Band::ALL {
            let added = cloudy.band(band).extinction_per_m - clear.band(band).extinction_per_m;
            assert!(
                (added - sigma).abs() < 1e-3 * sigma,
                "{} {band:?}: {added} against {sigma}",
                s.name
            );
        }
        let wall = s.backend.query_beams(&query).expect("beams")[0]
            .target
            .expect("the wall")
            .two_way_transmittance;
        // 6 m to the wall in a cloud of some 0.03 per m: e^(−2·6·σ).
        assert!(
            (wall / clear_wall - (-12.0 * sigma).exp()).abs() < 0.03,
            "{}: {wall} against {clear_wall} at σ {sigma}",
            s.name
        );
        assert!(
            s.backend
                .set_cloud_layers(CloudLayers::one(CloudLayer {
                    coverage: 2.0,
                    ..deck
                }))
                .is_err(),
            "{}: a coverage of 2 is refused",
            s.name
        );
        // 300 m below a deck, in its transition band of 400 m (CIGI's): three
        // quarters of the way out, the air has a quarter of the deck's mean
        // extinction.
        let above = CloudLayer {
            base_m: 301.7,
            transition_band_m: 400.0,
            ..deck
        };
        s.backend
            .set_cloud_layers(CloudLayers::one(above))
            .expect("valid layer");
        let banded = s.backend.optics().expect("optics");
        let quarter = 0.25 * above.mean_extinction_per_m();
        for band in Band::ALL {
            let added = banded.band(band).extinction_per_m - clear.band(band).extinction_per_m;
            assert!(
                (added - quarter).abs() < 1e-3 * quarter,
                "{} {band:?} in the transition band: {added} against {quarter}",
                s.name
            );
        }
        s.check_clean("cloud_layer");
    }
}

#[test]
fn optics_of_snow_and_dust_are_the_cpus_on_every_backend() {
    // The GPU's cross-sections (optics.wgsl) for ice and mineral grains, every band:
    // the CPU reference's sums of the same particles, within the sums' rounding.
    for (kind, temperature_c) in [
        (PrecipitationKind::DrySnow, -5.0),
        (PrecipitationKind::Dust, 25.0),
    ] {
        let mut setup = snow_before_a_wall();
        setup.weather.kind = kind;
        setup.weather.air_temperature_c = temperature_c;
        let mut reference: Option<Optics> = None;
        for mut s in all_subjects("optics of snow and dust") {
            s.backend.configure(&setup).expect("configure");
            s.backend.step(0.05).expect("step");
            let live = s.backend.optics().expect("optics");
            assert!(matches!(live.source, OpticsSource::LiveParticles { .. }));
            match &reference {
                None => reference = Some(live),
                Some(cpu) => {
                    assert_eq!(live.source, cpu.source, "{} {kind:?}", s.name);
                    for band in Band::ALL {
                        let (a, b) = (live.band(band), cpu.band(band));
                        let close = |x: f32, y: f32| (x / y - 1.0).abs() < 1e-3;
                        assert!(
                            close(a.extinction_per_m, b.extinction_per_m)
                                && close(a.backscatter_per_m_sr, b.backscatter_per_m_sr),
                            "{} {kind:?} {band:?}: {a:?} vs the CPU's {b:?}",
                            s.name
                        );
                    }
                }
            }
            s.check_clean("optics of snow and dust");
        }
    }
}

#[test]
fn bad_beam_queries_are_refused_alike_and_queries_hold_no_memory() {
    use precip_model::BackendError;
    let setup = snow_before_a_wall();
    let good = BeamQuery {
        beams: fan(setup.camera.position_m)[..240].to_vec(),
        band: Band::ShortwaveInfrared,
        aperture_radius_m: 0.0,
        extinction_per_m: Some(1.0e-3),
        sample_unresolved: true,
    };
    for mut s in all_subjects("bad beams") {
        assert!(
            matches!(
                s.backend.query_beams(&good),
                Err(BackendError::NotConfigured { .. })
            ),
            "{}: before configure",
            s.name
        );
        s.backend.configure(&setup).expect("configure");
        for bad in [
            BeamQuery {
                beams: Vec::new(),
                ..good.clone()
            },
            BeamQuery {
                beams: vec![Beam::ray(Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), 10.0)],
                ..good.clone()
            },
            BeamQuery {
                beams: vec![Beam::ray(Vec3::ZERO, Vec3::X, 1.0e6)],
                ..good.clone()
            },
            BeamQuery {
                aperture_radius_m: f32::INFINITY,
                ..good.clone()
            },
        ] {
            assert!(
                matches!(
                    s.backend.query_beams(&bad),
                    Err(BackendError::InvalidBeams(_))
                ),
                "{}: {:?} accepted",
                s.name,
                bad.beams.first()
            );
        }
        // Each query frees what it made: the device's allocations come back.
        let first = s.backend.query_beams(&good).expect("beams");
        let before = s.backend.device_memory();
        for _ in 0..10 {
            assert_eq!(
                s.backend.query_beams(&good).expect("beams"),
                first,
                "{}",
                s.name
            );
        }
        let after = s.backend.device_memory();
        if let (Some(b), Some(a)) = (before, after) {
            println!("{}: device memory {b:?} → {a:?} after 10 queries", s.name);
            assert!(
                a.allocations <= b.allocations && a.allocated_bytes <= b.allocated_bytes,
                "{}: {b:?} → {a:?}",
                s.name
            );
        }
        s.check_clean("bad beams");
    }
}

#[test]
fn strikes_drawn_from_the_spectrum_are_the_same_on_every_backend() {
    use precip_model::sensors::lidar::{EchoOrigin, UnresolvedAir};
    let setup = snow_before_a_wall();
    let query = BeamQuery {
        beams: fan(setup.camera.position_m),
        band: Band::NearInfrared,
        aperture_radius_m: 0.01,
        extinction_per_m: None,
        sample_unresolved: true,
    };
    // What every backend's clock and step parameters are after three 0.05 s steps.
    let time_s = (0..3).fold(0.0f64, |t, _| t + f64::from(0.05f32));
    let species = setup.step_params(&setup.weather, Vec3::ZERO, 0.05, 0.0);
    let air = UnresolvedAir::of_configuration(
        &setup,
        &setup.weather,
        species,
        setup.camera.position_m,
        time_s,
    );
    for mut s in all_subjects("drawn strikes") {
        s.backend.configure(&setup).expect("configure");
        for _ in 0..3 {
            s.backend.step(0.05).expect("step");
        }
        let returns = s.backend.query_beams(&query).expect("beams");
        let (beams, reference) = reference_hits(s.backend.as_mut(), &query, &setup);
        let expected = query
            .answer("reference", &beams, &reference, &setup.weather, &air)
            .expect("answered");
        let drawn = returns
            .iter()
            .filter(|r| r.particle.is_some_and(|p| p.origin == EchoOrigin::Spectrum))
            .count();
        let simulated = returns
            .iter()
            .filter(|r| r.particle.is_some_and(|p| p.origin != EchoOrigin::Spectrum))
            .count();
        let differing = returns
            .iter()
            .zip(&expected)
            .filter(|(a, b)| {
                a.particle.map(|p| (p.origin, p.kind)) != b.particle.map(|p| (p.origin, p.kind))
                    || a.particle.zip(b.particle).is_some_and(|(p, q)| {
                        (p.range_m - q.range_m).abs() > 1e-4 * q.range_m.max(1.0)
                    })
            })
            .count();
        println!(
            "{}: {drawn} beams struck a flake drawn from the spectrum, {simulated} a simulated one; {differing} differ from the reference",
            s.name
        );
        // The camera volume holds 20 of the air's 79 flakes per m³ (of the sizes
        // simulated): most strikes are drawn.
        assert!(drawn > simulated && simulated > 50, "{}", s.name);
        assert!(
            differing * 200 <= returns.len(),
            "{}: {differing} differ",
            s.name
        );
        s.check_clean("drawn strikes");
    }
}
