//! The WGSL drawing formulas equal the Rust ones (sprite corners, tetrahedron vertices
//! and normals; snow streaks; the snow cover's depletion curve and sub-texel threshold), read back
//! through the `probe_drawing` test kernel.

use glam::Vec3;
use precip_gpu::recipe::ProbeDrawing;
use precip_gpu::shaders::Program;
use precip_model::cover::{cover_warp_m, snow_cover_fraction, sub_texel_threshold, value_noise};
use precip_model::drawing::clouds::{
    CloudKind, cloud_density, cloud_detail, cloud_detail_atlas, cloud_detail_point,
    cloud_fresh_pixel, cloud_history_clamp_weight, cloud_history_clamped, cloud_history_uv,
    cloud_map_uv, cloud_march_slot,
};
use precip_model::drawing::land_borders::land_class_pick;
use precip_model::drawing::multiplicity::drawn_weight;
use precip_model::drawing::unresolved_streaks::{UnresolvedStreaks, streak_grain, streak_h};
use precip_model::drawing::{
    defocus_blur_m, defocused, drop_environment_factor, flake_sun_phase,
    raindrop_tetrahedron_sized, snow_sprite_corners_turned, snow_streak_corners,
};
use precip_model::particles::rng::{particle_key, random_unit};

use crate::common;

fn inputs() -> Vec<ProbeDrawing> {
    let r = |i: u32, d: u32| random_unit(particle_key(7, i, 0), d);
    let v3 = |i: u32, d: u32, scale: f32| {
        Vec3::new(r(i, d) - 0.5, r(i, d + 1) - 0.5, r(i, d + 2) - 0.5) * scale
    };
    let mut out: Vec<ProbeDrawing> = (0..500)
        .map(|i| ProbeDrawing {
            centre_m: v3(i, 0, 100.0).to_array(),
            side_m: 0.001 + r(i, 3) * 0.5,
            camera_m: v3(i, 4, 100.0).to_array(),
            spin_rad: r(i, 7) * 12.0 - 6.0,
            velocity_mps: v3(i, 8, 20.0).to_array(),
            tumble: 0.3 + 0.7 * r(i, 11),
            h_m: r(i, 12) * 2.0,
            a_m: r(i, 13) * 0.2,
            cover: [30.0 + r(i, 14) * 600.0, 0.5 + 2.0 * r(i, 15)],
        })
        .collect();
    // The fallbacks: a camera straight above, a velocity along X.
    out.push(ProbeDrawing {
        centre_m: [1.0, 2.0, 3.0],
        camera_m: [1.0, 50.0, 3.0],
        velocity_mps: [7.0, 0.0, 0.0],
        ..out[0]
    });
    // Land classes on ties (fractions ½ between the pixels: inputs 501–506, of
    // corners (0,2,1,0) … (2,0,2,0), the last two classes in columns, at
    // fractions (½, ½) and (½, 0.3)).
    for k in 0..6 {
        let z = if k % 2 == 0 { 2.0 } else { 1.2 };
        out.push(ProbeDrawing {
            centre_m: [2.0, 0.5, z],
            ..out[0]
        });
    }
    out
}

#[test]
fn wgsl_drawing_equals_rust_drawing() {
    let inputs = inputs();
    for (name, backend) in common::gpu_backends("wgsl_drawing_equals_rust_drawing") {
        let gpu = backend.device();
        let bytes = common::run_probe(
            gpu,
            Program::ProbeDrawing,
            bytemuck::cast_slice(&inputs),
            inputs.len() as u32,
            (inputs.len() * 26 * 16) as u64,
        );
        let got: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        for (i, q) in inputs.iter().enumerate() {
            let centre = Vec3::from(q.centre_m);
            let sprite = snow_sprite_corners_turned(
                centre,
                Vec3::from(q.camera_m),
                q.side_m,
                q.spin_rad,
                q.tumble,
            )
            .expect("camera away from the centre");
            let tetra =
                raindrop_tetrahedron_sized(centre, Vec3::from(q.velocity_mps), q.h_m, q.a_m)
                    .expect("moving");
            let expected = sprite
                .iter()
                .chain(&tetra.vertices)
                .chain(&tetra.normals)
                .copied();
            for (k, want) in expected.enumerate() {
                let g = got[26 * i + k];
                let have = Vec3::new(g[0], g[1], g[2]);
                // The four face normals (values 8–11) of a drop's thin tetrahedron are
                // cross products of nearly parallel edges: a driver that fuses a
                // multiply and an add (NVIDIA's does; lavapipe does not) moves them
                // by up to 6·10⁻⁵ (H200: input 50, value 10), a hundredth of a degree.
                let normal = (8..12).contains(&k);
                let tolerance = if normal { 2e-4 } else { 1e-5 } * (1.0 + want.abs().max_element());
                assert!(
                    (have - want).abs().max_element() <= tolerance,
                    "{name}: input {i} value {k}: WGSL {have} vs Rust {want}"
                );
            }
            let cover = got[26 * i + 12];
            let want = [
                snow_cover_fraction(q.h_m, q.cover[0], q.a_m, q.cover[1]),
                sub_texel_threshold(q.tumble, [centre.x, centre.z]),
                value_noise(centre.x, centre.z),
                drawn_weight(i as u32, 2.0 * q.side_m),
            ];
            for (k, want) in want.into_iter().enumerate() {
                assert!(
                    (cover[k] - want).abs() <= 2e-5,
                    "{name}: input {i} cover value {k}: WGSL {} vs Rust {want}",
                    cover[k]
                );
            }
            let (streak, _) = snow_streak_corners(
                centre,
                Vec3::from(q.camera_m),
                q.side_m,
                (q.spin_rad, q.tumble),
                Vec3::from(q.velocity_mps),
                1.0 / 60.0,
            )
            .expect("camera away from the centre");
            let blur = defocus_blur_m(q.a_m, 10.0, 50.0 * q.h_m);
            let sprite = defocused(q.side_m, 0.8, blur, 2);
            let streak_opacity = defocused(q.side_m, 0.8, blur, 1).1;
            let g = got[26 * i + 17];
            for (k, want) in [blur, sprite.0, sprite.1, streak_opacity]
                .into_iter()
                .enumerate()
            {
                assert!(
                    (g[k] - want).abs() <= 1e-5 * (1.0 + want.abs()),
                    "{name}: input {i} defocus value {k}: WGSL {} vs Rust {want}",
                    g[k]
                );
            }
            let warp = cover_warp_m([centre.x, centre.z], [q.a_m + 0.1, q.side_m + 0.1]);
            let g = got[26 * i + 18];
            assert!(
                (g[0] - warp[0]).abs() <= 2e-5 && (g[1] - warp[1]).abs() <= 2e-5,
                "{name}: input {i} cover warp: WGSL {g:?} vs Rust {warp:?}"
            );
            let phase = flake_sun_phase(q.spin_rad / 6.0);
            assert!(
                (g[2] - phase).abs() <= 1e-5 * (1.0 + phase),
                "{name}: input {i} flake phase: WGSL {} vs Rust {phase}",
                g[2]
            );
            // Three acos, steep near ±1: lavapipe's differ from Rust's by 2·10⁻⁵.
            let drop = drop_environment_factor(q.spin_rad / 6.0, q.tumble);
            assert!(
                (g[3] - drop).abs() <= 2e-4 * (1.0 + drop),
                "{name}: input {i} drop environment: WGSL {} vs Rust {drop}",
                g[3]
            );
            // A drop's oscillation, a cloud column, a layer's map offset.
            let g = got[26 * i + 20];
            let hz = precip_model::drawing::drop_oscillation_hz(q.a_m / 20.0);
            let bright = precip_model::drawing::drop_oscillation_brightness(q.spin_rad);
            let column = precip_model::drawing::clouds::cloud_column(q.tumble, q.side_m);
            let offset = precip_model::drawing::clouds::cloud_layer_map_offset_m(i as u32 % 3);
            assert!(
                (g[0] - hz).abs() <= 1e-5 * hz
                    && (g[1] - bright).abs() <= 1e-4
                    && (g[2] - column).abs() <= 1e-6
                    && (g[3] - (offset.x + offset.y)).abs() <= 1e-3,
                "{name}: input {i} oscillation, column, offset: WGSL {g:?} vs Rust {hz} {bright} {column} {offset}"
            );
            // The clouds' march slot and the history's uv.
            let g = got[26 * i + 19];
            let slot = cloud_march_slot(glam::UVec2::new(
                centre.x.abs() as u32,
                centre.z.abs() as u32,
            ));
            assert_eq!(g[0] as u32, slot, "{name}: input {i} march slot");
            let c = Vec3::from(q.camera_m) / 100.0;
            let camera = glam::Mat4::from_cols(
                glam::Vec4::X,
                glam::Vec4::Y,
                glam::Vec4::new(0.0, 0.0, 1.0, -1.0),
                glam::Vec4::new(c.x, c.y, 0.0, 0.0),
            );
            match cloud_history_uv(camera, centre) {
                Some(uv) => assert!(
                    g[3] > 0.5 && (g[1] - uv.x).abs() <= 1e-5 && (g[2] - uv.y).abs() <= 1e-5,
                    "{name}: input {i} history: WGSL {g:?} vs Rust {uv}"
                ),
                None => assert!(g[3] < 0.5, "{name}: input {i} history: WGSL {g:?} vs none"),
            }
            // The fresh image's pixel and the history's clamp.
            let g = got[26 * i + 21];
            let fresh = cloud_fresh_pixel(
                glam::UVec2::new(centre.x.abs() as u32, centre.z.abs() as u32),
                i as u32 % 16,
            );
            let clamped = cloud_history_clamped(
                glam::Vec4::new(q.tumble, 0.0, 0.0, q.spin_rad),
                glam::Vec4::splat(0.3),
                glam::Vec4::splat(0.6),
            );
            assert!(
                g[0] as u32 == fresh.x
                    && g[1] as u32 == fresh.y
                    && (g[2] - clamped.x).abs() <= 1e-6
                    && (g[3] - clamped.w).abs() <= 1e-6,
                "{name}: input {i} fresh pixel, clamp: WGSL {g:?} vs Rust {fresh} {clamped}"
            );
            let weight = cloud_history_clamp_weight(
                camera,
                centre,
                centre + Vec3::from(q.velocity_mps),
                glam::Vec2::new(320.0, 180.0),
            );
            let g = got[26 * i + 22];
            assert!(
                (g[0] - weight).abs() <= 1e-4,
                "{name}: input {i} clamp weight: WGSL {} vs Rust {weight}",
                g[0]
            );
            let fresh_weight = precip_model::drawing::clouds::cloud_fresh_weight(
                q.tumble - 0.3,
                glam::Vec2::new(centre.x, centre.z),
            );
            assert!(
                (g[1] - fresh_weight).abs() <= 1e-4,
                "{name}: input {i} fresh weight: WGSL {} vs Rust {fresh_weight}",
                g[1]
            );
            let uv = glam::Vec2::new(centre.x, centre.z) / 60.0 + 0.5;
            let map_weight = precip_model::drawing::clouds::cloud_shadow_map_weight(uv);
            let point = precip_model::drawing::clouds::cloud_shadow_map_point_m(
                glam::Vec2::new(q.camera_m[0], q.camera_m[2]),
                glam::UVec2::new(centre.x.abs() as u32, centre.z.abs() as u32),
            );
            assert!(
                (g[2] - map_weight).abs() <= 1e-5 && (g[3] - (point.x + point.y)).abs() <= 1e-2,
                "{name}: input {i} shadow map: WGSL {g:?} vs Rust {map_weight} {point}"
            );
            // The clouds' detail atlas and density.
            let camera_xz = glam::Vec2::new(q.camera_m[0], q.camera_m[2]);
            let (uv, w) = cloud_detail_atlas(cloud_detail_point(centre, camera_xz));
            let detail = cloud_detail(
                glam::Vec4::new(q.side_m, q.tumble, q.a_m, q.spin_rad / 6.0),
                w,
            );
            let g = got[26 * i + 23];
            assert!(
                (g[0] - uv.x).abs() <= 1e-5
                    && (g[1] - uv.y).abs() <= 1e-5
                    && (g[2] - w).abs() <= 1e-3
                    && (g[3] - detail).abs() <= 1e-3,
                "{name}: input {i} cloud detail: WGSL {g:?} vs Rust {uv} {w} {detail}"
            );
            let density = cloud_density(
                CloudKind::ALL[i % 4],
                q.tumble,
                q.side_m,
                q.a_m * 5.0,
                q.h_m / 2.0,
            );
            let map_uv = cloud_map_uv(centre, camera_xz);
            let g = got[26 * i + 24];
            assert!(
                (g[0] - density).abs() <= 1e-4
                    && (g[1] - map_uv.x).abs() <= 1e-6
                    && (g[2] - map_uv.y).abs() <= 1e-6,
                "{name}: input {i} cloud density: WGSL {g:?} vs Rust {density} {map_uv}"
            );
            // The unresolved streaks' grain.
            let grain = UnresolvedStreaks {
                scale: q.tumble,
                reach_m: 100.0 * q.a_m + 1.0,
                near_m: q.h_m,
                length_px: 5.0,
                velocity_mps: Vec3::ZERO,
            };
            let h = streak_h(4.0 * q.side_m);
            let variance = grain.variance(centre.x.abs() + 1.0);
            let along = glam::Vec2::new(q.velocity_mps[0], q.velocity_mps[1]).normalize();
            let pixel = 10.0 * glam::Vec2::new(centre.x, centre.z);
            let g = got[26 * i + 25];
            // A pixel within a rounding of a cell's edge may fall in either cell.
            let g_value = streak_grain(pixel, along, 20.0 * q.side_m + 1.0, i as u32);
            let near_edge = [(1e-3, 0.0), (-1e-3, 0.0), (0.0, 1e-3), (0.0, -1e-3)]
                .iter()
                .map(|&(a, c)| {
                    let p = pixel + along * a + along.perp() * c;
                    streak_grain(p, along, 20.0 * q.side_m + 1.0, i as u32)
                })
                .any(|v| (g[2] - v).abs() <= 1e-5);
            assert!(
                (g[0] - h).abs() <= 1e-4 * (1.0 + h.abs())
                    && (g[1] - variance).abs() <= 1e-4 * (1.0 + variance.abs())
                    && ((g[2] - g_value).abs() <= 1e-5 || near_edge),
                "{name}: input {i} unresolved streaks: WGSL {g:?} vs Rust {h} {variance} {g_value}"
            );
            let k = i as u32;
            let corners = [k % 3, (k / 3) % 3, (k / 9) % 3, (k / 27) % 3];
            let f = (glam::Vec2::new(centre.x, centre.z).abs() * 0.25).fract();
            assert_eq!(
                g[3] as u32,
                land_class_pick(corners, f),
                "{name}: input {i} land class among {corners:?} at {f}"
            );
            for (k, (want, uv)) in streak.iter().enumerate() {
                let g = got[26 * i + 13 + k];
                let have = Vec3::new(g[0], g[1], g[2]);
                let tolerance = 1e-5 * (1.0 + want.abs().max_element());
                assert!(
                    (have - *want).abs().max_element() <= tolerance && (g[3] - uv[1]).abs() <= 1e-3,
                    "{name}: input {i} streak corner {k}: WGSL {g:?} vs Rust {want} {uv:?}"
                );
            }
        }
    }
}
