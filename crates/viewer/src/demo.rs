//! The built-in demo scene, written by this code as a small GLB (shipped as
//! `assets/demo.glb`; `precip demo --out FILE` writes it again): hilly terrain
//! carrying a `_SNOW_MASK` (a heated patio stays bare), the gabled house of
//! `precip_model::scene::builtin` (its walls' material says `"snow": false`; the ground under
//! its eaves is sheltered), a road whose node says `"snow": false`, and fence posts
//! whose tops hold snow by slope. It shows every mask convention of docs/architecture.md §6,
//! and every surface: grass terrain, an asphalt road with a 2 % camber and a sag
//! that holds a puddle in rain, roofing, a pond (`"water": true`) in a hollow, and a
//! patch of loose sand up-wind of the house (`"surface": "sand"`) that the wind
//! lifts grains from in sand and dust weather.

use glam::{Vec2, Vec3};
use precip_model::scene::builtin::{HousePlan, house};
use serde_json::json;

use crate::glb::{GlbMesh, height_grid, write_glb};

/// The shipped demo file.
pub const DEMO_GLB: &[u8] = include_bytes!("../assets/demo.glb");

/// Side of the terrain, m.
pub const TERRAIN_SIDE_M: f32 = 80.0;
/// The road runs along Z over these X, m.
pub const ROAD_X_M: (f32, f32) = (11.0, 15.0);
/// The heated patio: centre (x, z) and radius, m.
pub const PATIO: (Vec2, f32) = (Vec2::new(-9.0, 7.0), 2.5);
/// The sag in the road: its lowest point's z and its depth, m.
pub const ROAD_SAG: (f32, f32) = (6.0, 0.15);
/// The pond: centre (x, z), radius of its hollow, m.
pub const POND: (Vec2, f32) = (Vec2::new(-20.0, 16.0), 7.0);
/// Depth of the pond's hollow below the pond's surface at the centre, m.
const POND_HOLLOW_M: f32 = 0.9;
/// A patch of loose sand up-wind of the house (x range, z range), m: the grains
/// a sandstorm or a dust haze lifts come from it (`"surface": "sand"`).
pub const SAND_PATCH: ((f32, f32), (f32, f32)) = ((-30.0, -18.0), (-6.0, 4.0));
/// Height of the pond's surface above the terrain's undisturbed level there, m.
const POND_LEVEL_M: f32 = -0.2;

fn road_sag_m(x: f32, z: f32) -> f32 {
    let road_mid = 0.5 * (ROAD_X_M.0 + ROAD_X_M.1);
    let band = 1.0 - (((x - road_mid).abs() - 4.0) / 3.0).clamp(0.0, 1.0);
    ROAD_SAG.1 * (-((z - ROAD_SAG.0) / 4.0).powi(2)).exp() * band
}

fn pond_hollow_m(x: f32, z: f32) -> f32 {
    let d = Vec2::new(x, z).distance(POND.0) / POND.1;
    (POND_HOLLOW_M - POND_LEVEL_M) * (-(d * d * d * d) * 2.5).exp()
}

/// Height of the pond's surface, m.
#[must_use]
pub fn pond_level_m() -> f32 {
    undisturbed_height_m(POND.0.x, POND.0.y) + POND_LEVEL_M
}

/// Terrain height at (x, z): two hills and a gentle swell, flattened around the
/// house and along the road, with the road's sag and the pond's hollow.
#[must_use]
pub fn terrain_height_m(x: f32, z: f32) -> f32 {
    undisturbed_height_m(x, z) - road_sag_m(x, z) - pond_hollow_m(x, z)
}

/// The terrain without the sag and the hollow: two hills and a gentle swell over a
/// site graded to drain, flattened around the house and along the road. The graded
/// plane falls 2 % toward −z and lies 20 cm below the house's floor, which sits on a
/// level pad (5 m round its centre) from which the ground falls away to the plane
/// by 9 m; only hollows then hold water (the road's sag, the pond, dips of the
/// swell).
fn undisturbed_height_m(x: f32, z: f32) -> f32 {
    let hill =
        |cx: f32, cz: f32, h: f32, r2: f32| h * (-((x - cx).powi(2) + (z - cz).powi(2)) / r2).exp();
    let raw = hill(-24.0, -22.0, 5.0, 160.0)
        + hill(26.0, 24.0, 3.5, 120.0)
        + 0.6 * (x / 9.0).sin() * (z / 11.0).cos();
    let r = (x * x + z * z).sqrt();
    let near_house = (r - 9.0).clamp(0.0, 8.0) / 8.0;
    let road_mid = 0.5 * (ROAD_X_M.0 + ROAD_X_M.1);
    let near_road = ((x - road_mid).abs() - 3.0).clamp(0.0, 6.0) / 6.0;
    let plane = 0.02 * z - 0.2;
    let off_pad = ((r - 5.0) / 4.0).clamp(0.0, 1.0);
    raw * near_house * near_road + off_pad * plane
}

fn grid(
    name: &str,
    (x0, x1): (f32, f32),
    (z0, z1): (f32, f32),
    (nx, nz): (u32, u32),
    lift_m: f32,
) -> GlbMesh {
    let steps = |a: f32, b: f32, n: u32| -> Vec<f32> {
        (0..=n).map(|i| a + (b - a) * i as f32 / n as f32).collect()
    };
    height_grid(name, &steps(x0, x1, nx), &steps(z0, z1, nz), |x, z| {
        terrain_height_m(x, z) + lift_m
    })
}

fn post(name: &str, at: Vec2) -> GlbMesh {
    let (w, h) = (0.12, 1.2);
    let base = terrain_height_m(at.x, at.y);
    let mut m = GlbMesh {
        name: name.to_owned(),
        base_colour: [0.35, 0.25, 0.15, 1.0],
        ..GlbMesh::default()
    };
    let faces: [(Vec3, Vec3, Vec3); 5] = [
        (Vec3::Y, Vec3::X, Vec3::Z),
        (Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::NEG_X, Vec3::NEG_Z, Vec3::Y),
        (Vec3::Z, Vec3::NEG_X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::X, Vec3::Y),
    ];
    let centre = Vec3::new(at.x, base + h / 2.0, at.y);
    let half = Vec3::new(w, h, w) / 2.0;
    for (n, u, v) in faces {
        let start = m.positions.len() as u32;
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let p = centre + n * half + u * half * su + v * half * sv;
            m.positions.push(p.to_array());
            m.normals.push(n.to_array());
            m.uvs.push([0.5 + 0.5 * su, 0.5 + 0.5 * sv]);
        }
        // Wind so the face's normal is n (u × v = n for the faces above).
        let (a, b, c, d) = (start, start + 1, start + 2, start + 3);
        if u.cross(v).dot(n) > 0.0 {
            m.indices.extend_from_slice(&[a, b, c, a, c, d]);
        } else {
            m.indices.extend_from_slice(&[a, c, b, a, d, c]);
        }
    }
    m
}

/// The pond's surface: a flat disc at [`pond_level_m`] over the hollow (the
/// terrain above that level hides its rim), its colour the bottom's.
fn pond() -> GlbMesh {
    let level = pond_level_m();
    let mut m = GlbMesh {
        name: "pond".to_owned(),
        base_colour: [0.22, 0.2, 0.12, 1.0],
        node_extras: Some(json!({ "water": true })),
        ..GlbMesh::default()
    };
    let segments = 48u32;
    m.positions.push([POND.0.x, level, POND.0.y]);
    m.normals.push([0.0, 1.0, 0.0]);
    for k in 0..segments {
        let a = k as f32 / segments as f32 * std::f32::consts::TAU;
        let r = POND.1;
        m.positions
            .push([POND.0.x + r * a.cos(), level, POND.0.y + r * a.sin()]);
        m.normals.push([0.0, 1.0, 0.0]);
        // Counter-clockwise seen from above (+Y): centre, next, this.
        let (this, next) = (1 + k, 1 + (k + 1) % segments);
        m.indices.extend_from_slice(&[0, next, this]);
    }
    m
}

/// The demo's meshes.
#[must_use]
pub fn demo_meshes() -> Vec<GlbMesh> {
    let half = TERRAIN_SIDE_M / 2.0;
    let mut terrain = grid("terrain", (-half, half), (-half, half), (64, 64), 0.0);
    terrain.base_colour = [0.24, 0.3, 0.16, 1.0];
    terrain.snow_mask = terrain
        .positions
        .iter()
        .map(|p| {
            let d = Vec2::new(p[0], p[2]).distance(PATIO.0);
            if d < PATIO.1 { 0.0 } else { 1.0 }
        })
        .collect();
    terrain.node_extras = Some(json!({ "surface": "grass" }));
    let mut road = grid("road", ROAD_X_M, (-half, half), (4, 80), 0.04);
    // A 2 % camber from the crown down to both edges.
    let road_mid = 0.5 * (ROAD_X_M.0 + ROAD_X_M.1);
    for p in &mut road.positions {
        p[1] -= 0.02 * (p[0] - road_mid).abs();
    }
    road.base_colour = [0.12, 0.12, 0.13, 1.0];
    road.node_extras = Some(json!({ "snow": false, "surface": "asphalt" }));

    let mut sand = grid("sand", SAND_PATCH.0, SAND_PATCH.1, (24, 20), 0.03);
    sand.base_colour = [0.62, 0.5, 0.32, 1.0];
    sand.node_extras = Some(json!({ "surface": "sand" }));

    let mut meshes = vec![terrain, road, sand, pond()];
    meshes.extend(house_meshes(Vec3::ZERO));
    for (k, z) in [-12.0f32, -6.0, 0.0, 6.0, 12.0].into_iter().enumerate() {
        meshes.push(post(&format!("post {k}"), Vec2::new(ROAD_X_M.0 - 1.0, z)));
    }
    // Untextured: no texture coordinates (the Khronos validator flags unused ones).
    for m in &mut meshes {
        m.uvs.clear();
    }
    meshes
}

/// The house of `precip_model::scene::builtin` (its walls' material says
/// `"snow": false`, its roof's `"surface": "roof"`) moved by `shift_m`, without
/// its ground.
#[must_use]
pub fn house_meshes(shift_m: Vec3) -> Vec<GlbMesh> {
    house(&HousePlan::default())
        .meshes
        .into_iter()
        .filter(|m| m.name != "ground")
        .map(|mesh| GlbMesh {
            name: format!("house {}", mesh.name),
            positions: mesh
                .positions_m
                .iter()
                .map(|p| (*p + shift_m).to_array())
                .collect(),
            normals: mesh.normals.iter().map(|n| n.to_array()).collect(),
            uvs: Vec::new(),
            snow_mask: Vec::new(),
            base_colour: mesh.material.base_colour,
            material_extras: match mesh.name.as_str() {
                "walls" => Some(json!({ "snow": false })),
                "roof" => Some(json!({ "surface": "roof" })),
                _ => None,
            },
            node_extras: None,
            indices: mesh.indices,
        })
        .collect()
}

/// The demo as GLB bytes (deterministic: the same bytes every time).
#[must_use]
pub fn demo_glb() -> Vec<u8> {
    write_glb(&demo_meshes(), "precip demo scene")
}
