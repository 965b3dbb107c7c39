#![expect(
    clippy::float_cmp,
    reason = "ranges, sizes and caps the code copies or computes exactly"
)]

use glam::UVec2;
use precip_cover::GridFrame;

use proptest::prelude::*;

use super::*;
use crate::particles::particle::{ParticleSource, pack_flags};
use crate::particles::rng::{particle_key, random_unit};

fn frame(size_m: f32, texels: u32) -> GridFrame {
    GridFrame {
        origin_m: Vec2::splat(-0.5 * size_m),
        size_m: Vec2::splat(size_m),
        texels: UVec2::splat(texels),
        reserved: UVec2::ZERO,
    }
}

fn particle_at(position_m: Vec3, diameter_m: f32) -> Particle {
    Particle {
        position_m,
        diameter_m,
        flags: pack_flags(ParticleKind::Rain, ParticleSource::CameraVolume, [false; 3]),
        ..Particle::zeroed()
    }
}

fn query(beams: Vec<Beam>) -> BeamQuery {
    BeamQuery {
        beams,
        band: Band::NearInfrared,
        aperture_radius_m: 0.0,
        extinction_per_m: Some(0.0),
        sample_unresolved: false,
    }
}

#[test]
fn a_beam_strikes_what_lies_within_its_cone() {
    let beam = Beam {
        divergence_rad: 0.01,
        ..Beam::ray(Vec3::ZERO, Vec3::X, 100.0)
    };
    // At 50 m the cone's radius is 0.25 m: a 2 mm drop 0.25 m off the axis is struck.
    assert_eq!(
        beam_strike_range_m(&beam, 0.0, Vec3::new(50.0, 0.2509, 0.0), 0.002),
        Some(50.0)
    );
    assert_eq!(
        beam_strike_range_m(&beam, 0.0, Vec3::new(50.0, 0.2511, 0.0), 0.002),
        None
    );
    // Behind, or beyond the range.
    assert_eq!(
        beam_strike_range_m(&beam, 0.0, Vec3::new(-1.0, 0.0, 0.0), 0.002),
        None
    );
    assert_eq!(
        beam_strike_range_m(&beam, 0.0, Vec3::new(101.0, 0.0, 0.0), 0.002),
        None
    );
    // The aperture widens it.
    assert!(beam_strike_range_m(&beam, 0.05, Vec3::new(50.0, 0.3, 0.0), 0.002).is_some());
}

#[test]
fn the_hard_target_is_the_ground_where_the_beam_meets_it() {
    let ground = GroundMap::flat(frame(200.0, 400), 1.5, 1.0);
    // From 11.5 m up, 45° down: the ground (1.5 m) at 10·√2 m.
    let beam = Beam::ray(
        Vec3::new(0.0, 11.5, 0.0),
        Vec3::new(1.0, -1.0, 0.0).normalize(),
        100.0,
    );
    let range = hard_target_range_m(&beam, &ground, march_step_m(&ground)).expect("ground ahead");
    assert!((range - 10.0 * 2f32.sqrt()).abs() < 1e-3, "{range}");
    // Level: nothing; too short: nothing; off the map: open sky.
    let level = Beam::ray(Vec3::new(0.0, 11.5, 0.0), Vec3::X, 100.0);
    assert_eq!(hard_target_range_m(&level, &ground, 0.25), None);
    let short = Beam {
        max_range_m: 10.0,
        ..beam
    };
    assert_eq!(hard_target_range_m(&short, &ground, 0.25), None);
    let outside = Beam::ray(Vec3::new(500.0, 10.0, 0.0), Vec3::NEG_Y, 100.0);
    assert_eq!(hard_target_range_m(&outside, &ground, 0.25), None);
}

#[test]
fn a_target_is_labelled_with_the_surface_the_beam_meets() {
    // Water west of x = 0, grass east: beams down either side.
    let mut ground = GroundMap::flat(frame(200.0, 400), 0.0, 1.0);
    ground.surface = (0..400 * 400)
        .map(|k| {
            if k % 400 < 200 {
                precip_cover::Surface::Water
            } else {
                precip_cover::Surface::Grass
            }
        })
        .collect();
    let beams = [
        Beam::ray(Vec3::new(-20.0, 30.0, 0.0), Vec3::NEG_Y, 100.0),
        Beam::ray(Vec3::new(20.0, 30.0, 0.0), Vec3::NEG_Y, 100.0),
    ];
    let hit = |range| BeamHit {
        particle_range_m: 0.0,
        particle_diameter_m: 0.0,
        particle_flags: NO_PARTICLE,
        target_range_m: range,
    };
    let mut returns = BeamQuery::returns(&beams, &[hit(30.0), hit(-1.0)], 0.0, 0.0);
    label_targets(&mut returns, &beams, &ground);
    assert_eq!(
        returns[0].target.map(|t| t.surface),
        Some(precip_cover::Surface::Water)
    );
    assert!(returns[1].target.is_none());
    let mut grass = BeamQuery::returns(&beams[1..], &[hit(30.0)], 0.0, 0.0);
    label_targets(&mut grass, &beams[1..], &ground);
    assert_eq!(
        grass[0].target.map(|t| t.surface),
        Some(precip_cover::Surface::Grass)
    );
}

#[test]
fn a_wall_stops_the_beam_and_hides_the_particles_behind_it() {
    let mut ground = GroundMap::flat(frame(40.0, 40), 0.0, 1.0);
    // A 3 m wall one texel thick at x ∈ [10, 11).
    for z in 0..40 {
        ground.height_m[z * 40 + 30] = 3.0;
    }
    let beam = Beam::ray(Vec3::new(0.0, 1.0, 0.5), Vec3::X, 30.0);
    let beams = query(vec![beam]).validate().expect("valid");
    let behind = particle_at(Vec3::new(15.0, 1.0, 0.5), 0.004);
    let before = particle_at(Vec3::new(5.0, 1.0, 0.5), 0.004);
    let params = query(vec![beam]).params(&beams, 0..2, &ground);
    let hits = query_on_cpu(&beams, &params, &[behind], &ground);
    assert!(
        (hits[0].target_range_m - 10.0).abs() < 1e-3,
        "{:?}",
        hits[0]
    );
    assert_eq!(hits[0].particle_flags, NO_PARTICLE);
    let hits = query_on_cpu(&beams, &params, &[behind, before], &ground);
    assert_eq!(hits[0].particle_range_m, 5.0);
    assert_eq!(hits[0].particle_diameter_m, 0.004);
    let returns = BeamQuery::returns(&beams, &hits, 0.0, 0.01);
    let r = returns[0];
    let p = r.particle.expect("struck");
    assert_eq!(
        (p.kind, p.origin),
        (ParticleKind::Rain, EchoOrigin::CameraVolume)
    );
    assert_eq!(p.footprint_share, 1.0);
    let t = r.target.expect("the wall");
    assert!((t.two_way_transmittance - (-0.2f32).exp()).abs() < 1e-4);
    // A pencil beam's drop blocks all of it: the drop is the echo.
    assert_eq!(r.strongest_echo_m(0.02, 0.5), Some((5.0, true)));
}

#[test]
fn bad_queries_are_refused_with_the_field() {
    let ok = Beam::ray(Vec3::ZERO, Vec3::X, 10.0);
    for (bad, says) in [
        (query(vec![]), "0 beams"),
        (
            query(vec![Beam {
                direction: Vec3::ZERO,
                ..ok
            }]),
            "direction",
        ),
        (
            query(vec![Beam {
                max_range_m: 0.0,
                ..ok
            }]),
            "max_range_m",
        ),
        (
            query(vec![Beam {
                max_range_m: f32::NAN,
                ..ok
            }]),
            "max_range_m",
        ),
        (
            query(vec![Beam {
                divergence_rad: 0.5,
                ..ok
            }]),
            "divergence_rad",
        ),
        (
            query(vec![Beam {
                origin_m: Vec3::INFINITY,
                ..ok
            }]),
            "origin_m",
        ),
        (
            BeamQuery {
                aperture_radius_m: -1.0,
                ..query(vec![ok])
            },
            "aperture",
        ),
        (
            BeamQuery {
                extinction_per_m: Some(f32::NAN),
                ..query(vec![ok])
            },
            "extinction",
        ),
    ] {
        match bad.validate() {
            Err(BackendError::InvalidBeams(message)) => {
                assert!(message.contains(says), "{message}");
            }
            other => panic!("{says}: {other:?}"),
        }
    }
    let normalised = query(vec![Beam::ray(Vec3::ZERO, Vec3::new(0.0, 3.0, 4.0), 1.0)])
        .validate()
        .expect("valid");
    assert!((normalised[0].direction.length() - 1.0).abs() < 1e-6);
}

/// `count` spheres of `diameter_m` uniform in a cube of side `side_m` about 0.
fn uniform_field(count: u32, side_m: f32, diameter_m: f32) -> Vec<Particle> {
    (0..count)
        .map(|i| {
            let key = particle_key(7, i, 0);
            let u = Vec3::new(
                random_unit(key, 0),
                random_unit(key, 1),
                random_unit(key, 2),
            );
            particle_at((u - 0.5) * side_m, diameter_m)
        })
        .collect()
}

/// Directions spread over the sphere (a Fibonacci lattice).
fn directions(count: u32) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..count)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
            let r = (1.0 - y * y).sqrt();
            let phi = golden * i as f32;
            Vec3::new(r * phi.cos(), y, r * phi.sin())
        })
        .collect()
}

#[test]
fn hits_in_a_uniform_field_are_poisson() {
    // 128 000 spheres of 0.2 m in a 40 m cube: n·A = 2/m³·0.0314 m² = 0.0628 per m.
    // Each beam starts at its own random point of the middle 20 m, so beams seldom
    // share the particles near their origins (which would correlate them).
    let (count, side, diameter) = (128_000u32, 40.0f32, 0.2f32);
    let particles = uniform_field(count, side, diameter);
    let ground = GroundMap::flat(frame(1.0, 1), -1.0e4, 1.0);
    let n_per_m3 = count as f32 / side.powi(3);
    for (divergence_rad, aperture_m) in [(0.0f32, 0.0f32), (0.02, 0.05)] {
        let beams: Vec<Beam> = directions(4000)
            .into_iter()
            .enumerate()
            .map(|(i, d)| {
                let key = particle_key(11, i as u32, 0);
                let origin = Vec3::new(
                    random_unit(key, 0),
                    random_unit(key, 1),
                    random_unit(key, 2),
                );
                Beam {
                    divergence_rad,
                    ..Beam::ray((origin - 0.5) * 0.5 * side, d, 9.5)
                }
            })
            .collect();
        let q = BeamQuery {
            aperture_radius_m: aperture_m,
            ..query(beams)
        };
        let beams = q.validate().expect("valid");
        let hits = query_on_cpu(
            &beams,
            &q.params(&beams, 0..count, &ground),
            &particles,
            &ground,
        );
        for r in [2.0f32, 5.0, 9.0] {
            // Expected strikes within r: n·∫π(D/2 + a + t·tan(θ/2))² dt.
            let k = (0.5 * divergence_rad).tan();
            let reach = |t: f32| 0.5 * diameter + aperture_m + t * k;
            let integral = if k > 0.0 {
                (reach(r).powi(3) - reach(0.0).powi(3)) / (3.0 * k)
            } else {
                reach(0.0).powi(2) * r
            };
            let expected = (-n_per_m3 * std::f32::consts::PI * integral).exp();
            let clear = hits
                .iter()
                .filter(|h| h.particle_flags == NO_PARTICLE || h.particle_range_m > r)
                .count() as f32
                / beams.len() as f32;
            let sigma = (expected * (1.0 - expected) / beams.len() as f32).sqrt();
            println!(
                "divergence {divergence_rad} rad, aperture {aperture_m} m: P(no hit within {r} m) = {clear:.4}, Poisson {expected:.4} ± {sigma:.4}"
            );
            assert!(
                (clear - expected).abs() < 4.0 * sigma + 0.005,
                "{clear} vs {expected}"
            );
        }
    }
}

fn unit(v: (f32, f32, f32)) -> Vec3 {
    let v = Vec3::new(v.0, v.1, v.2);
    if v.length_squared() < 1e-4 {
        Vec3::X
    } else {
        v.normalize()
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// The kernel's group bound leaves out no particle a beam of the group strikes.
    #[test]
    fn the_group_bound_keeps_every_struck_particle(
        origin in (-5.0f32..5.0, 0.0f32..3.0, -5.0f32..5.0),
        spread_m in 0.0f32..2.0,
        heading in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        fan_rad in 0.0f32..1.5,
        divergence_rad in 0.0f32..0.1,
        aperture_m in 0.0f32..0.5,
        diameter_m in 0.0f32..0.02,
        seed in 0u32..1000,
    ) {
        let axis = unit(heading);
        let beams: Vec<Beam> = (0..64u32)
            .map(|i| {
                let key = particle_key(seed, i, 1);
                let jitter = Vec3::new(random_unit(key, 0), random_unit(key, 1), random_unit(key, 2)) - 0.5;
                let turn = Vec3::new(random_unit(key, 3), random_unit(key, 4), random_unit(key, 5)) - 0.5;
                Beam {
                    divergence_rad,
                    ..Beam::ray(
                        Vec3::new(origin.0, origin.1, origin.2) + jitter * spread_m,
                        (axis + turn * fan_rad).normalize_or(axis),
                        5.0 + 50.0 * random_unit(key, 6),
                    )
                }
            })
            .collect();
        let bound = beam_group_bound(&beams, aperture_m);
        for k in 0..400u32 {
            // Particles near the beams: a point along a beam, pushed off it.
            let key = particle_key(seed, k, 2);
            let beam = beams[(k % 64) as usize];
            let t = random_unit(key, 0) * beam.max_range_m;
            let off = (Vec3::new(random_unit(key, 1), random_unit(key, 2), random_unit(key, 3)) - 0.5)
                * (0.2 + t * 0.1);
            let centre = beam.origin_m + beam.direction * t + off;
            let struck = beams.iter().any(|b| beam_strike_range_m(b, aperture_m, centre, diameter_m).is_some());
            prop_assert!(
                !struck || group_may_strike(&bound, centre, diameter_m),
                "left out a struck particle at {centre} of {bound:?}"
            );
        }
    }
}

#[test]
fn a_narrow_group_bound_leaves_out_what_lies_aside_and_behind() {
    let beams: Vec<Beam> = (0..64)
        .map(|i| {
            let azimuth = (i as f32 - 31.5) * 0.35f32.to_radians();
            Beam {
                divergence_rad: 3.0e-3,
                ..Beam::ray(Vec3::Y, Vec3::new(azimuth.sin(), 0.0, -azimuth.cos()), 50.0)
            }
        })
        .collect();
    let bound = beam_group_bound(&beams, 0.01);
    // 64 steps of 0.35°: ±11° and a little.
    assert!(
        (bound.half_angle_rad - 11.03f32.to_radians()).abs() < 0.01,
        "{bound:?}"
    );
    assert!(group_may_strike(&bound, Vec3::new(0.0, 1.0, -20.0), 0.005));
    assert!(
        !group_may_strike(&bound, Vec3::new(0.0, 1.0, 20.0), 0.005),
        "behind"
    );
    assert!(
        !group_may_strike(&bound, Vec3::new(20.0, 1.0, -5.0), 0.005),
        "aside"
    );
    assert!(
        !group_may_strike(&bound, Vec3::new(0.0, 1.0, -80.0), 0.005),
        "beyond reach"
    );
}

#[test]
fn hits_the_kernel_never_wrote_are_an_error_not_an_answer() {
    let beams = vec![Beam::ray(Vec3::ZERO, Vec3::X, 10.0); 3];
    let q = query(beams.clone());
    let mut hits = BeamQuery::unwritten_hits(3);
    hits[0].particle_flags = NO_PARTICLE;
    hits[1].particle_flags = NO_PARTICLE;
    match q.answer(
        "test",
        &beams,
        &hits,
        &crate::Weather::default(),
        &still_air(),
    ) {
        Err(BackendError::Device { message, .. }) => {
            assert!(message.contains("left 1 of 3"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    hits[2].particle_flags = NO_PARTICLE;
    assert_eq!(
        q.answer(
            "test",
            &beams,
            &hits,
            &crate::Weather::default(),
            &still_air()
        )
        .expect("answered")
        .len(),
        3
    );
}

fn still_air() -> UnresolvedAir {
    UnresolvedAir::new(
        0.0,
        (Vec3::ZERO, Vec3::ZERO, 0),
        crate::particles::step::StepParams::zeroed(),
        1,
        0.0,
    )
}

#[test]
fn a_fog_layer_dims_the_targets_behind_it_by_its_path_in_it() {
    use crate::drawing::fog_layer::FogLayer;
    // From 10 m up, one beam level (above the 5 m fog: clear), one down at 45° to
    // the ground 10 m below (the last 5 m of height, 5·√2 m of path, in fog).
    let level = Beam::ray(Vec3::new(0.0, 10.0, 0.0), Vec3::X, 50.0);
    let down = Beam::ray(Vec3::new(0.0, 10.0, 0.0), Vec3::new(1.0, -1.0, 0.0), 50.0);
    let beams = query(vec![level, down]).validate().expect("valid");
    let hits = [30.0f32, 10.0 * 2f32.sqrt()]
        .map(|range| BeamHit {
            particle_range_m: 0.0,
            particle_diameter_m: 0.0,
            particle_flags: NO_PARTICLE,
            target_range_m: range,
        })
        .to_vec();
    let fog = FogLayer::new(5.0, 100.0);
    let air = UnresolvedAir {
        fog_layer: Some(fog),
        ..still_air()
    };
    let q = BeamQuery {
        extinction_per_m: Some(0.0),
        ..query(beams.clone())
    };
    let returns = q
        .answer("test", &beams, &hits, &crate::Weather::default(), &air)
        .expect("answered");
    let clear = returns[0].target.expect("target").two_way_transmittance;
    assert!((clear - 1.0).abs() < 1e-6, "above the fog: {clear}");
    let through = returns[1].target.expect("target").two_way_transmittance;
    let expected = (-2.0 * fog.extinction_per_m() * 5.0 * 2f32.sqrt()).exp();
    assert!(
        (through - expected).abs() < 1e-4,
        "{through} against {expected}"
    );
}
