//! The built-in coastal scene (`precip --coast`; `precip demo --coast --out FILE`
//! writes it as a GLB): the open sea (`"water": "sea"`) running 60 km out to the
//! horizon west of a sand beach (`"surface": "sand"`) that slopes 1 : 14 into it, a
//! concrete breakwater wall (`"surface": "asphalt"`) and a timber pier on posts
//! reaching out over the water, grass rising behind the beach, and the demo's house
//! on it. The sea's mesh is a grid whose cells grow geometrically away from the
//! shore and the pier (1.5 m at the waterline, hundreds of metres at the horizon),
//! so the waves move its vertices where they show and it costs little far out.
//!
//! Axes as everywhere: metres, Y up; the sea lies toward −x, the land toward +x.

use glam::{Vec2, Vec3};
use serde_json::json;

use crate::demo::house_meshes;
use crate::glb::{GlbMesh, height_grid as grid, write_glb};

/// How far the sea runs out from the shore and along it, m.
pub const SEA_REACH_M: f32 = 60_000.0;
/// The beach: a point under the sea (x, m) and its height below the sea's level,
/// and its landward edge and height above it (a 1 : 14 slope).
pub const BEACH: ((f32, f32), (f32, f32)) = ((-40.0, -2.0), (30.0, 3.0));
/// Where the seabed (the beach's slope, on under the sea) ends, x m: 20 m deep.
pub const SEABED_END_M: f32 = -300.0;
/// Half the length of the shore the land covers along z, m.
pub const SHORE_HALF_M: f32 = 110.0;
/// The breakwater wall: x range, z range, top height, m.
pub const BREAKWATER: ((f32, f32), (f32, f32), f32) = ((-90.0, 12.0), (60.0, 68.0), 3.0);
/// The pier: x range, z range of its deck, the deck's top, m.
pub const PIER: ((f32, f32), (f32, f32), f32) = ((-70.0, 8.0), (-45.0, -41.0), 2.5);
/// Where the land's house stands (x, z), m.
pub const HOUSE_AT: Vec2 = Vec2::new(62.0, 0.0);
/// A view from the beach out to sea: the eye and where it looks, m.
pub const BEACH_VIEW: (Vec3, Vec3) = (Vec3::new(-4.0, 2.8, -18.0), Vec3::new(-150.0, 1.5, 6.0));

/// The ground's height at (x, z) (the beach, then the land behind it), m.
#[must_use]
pub fn land_height_m(x: f32, z: f32) -> f32 {
    let ((x0, h0), (x1, h1)) = BEACH;
    if x <= x1 {
        h0 + (h1 - h0) * (x - x0) / (x1 - x0)
    } else {
        // Grass rising gently behind the beach, with a swell, level round the house.
        let rise = h1 + 0.04 * (x - x1) + 0.8 * (x / 17.0).sin() * (z / 23.0).cos();
        let pad = (Vec2::new(x, z).distance(HOUSE_AT) - 8.0).clamp(0.0, 6.0) / 6.0;
        let level = h1 + 0.04 * (HOUSE_AT.x - x1);
        level + (rise - level) * pad
    }
}

/// Positions along an axis from the shore out: `step_m` first, each step `growth`
/// times the last, to `reach_m`.
fn graded(step_m: f32, growth: f32, reach_m: f32) -> Vec<f32> {
    let mut out = vec![0.0];
    let mut step = step_m;
    while *out.last().unwrap_or(&reach_m) < reach_m {
        let next = out.last().copied().unwrap_or_default() + step;
        out.push(next.min(reach_m));
        step *= growth;
    }
    out
}

/// A box between `lo` and `hi`, m, its faces' normals outward.
fn cuboid(name: &str, lo: Vec3, hi: Vec3, colour: [f32; 4]) -> GlbMesh {
    let mut m = GlbMesh {
        name: name.to_owned(),
        base_colour: colour,
        ..GlbMesh::default()
    };
    let centre = 0.5 * (lo + hi);
    let half = 0.5 * (hi - lo);
    for n in [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ] {
        let u = if n.y.abs() > 0.5 { Vec3::X } else { Vec3::Y };
        let v = n.cross(u);
        let start = m.positions.len() as u32;
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let p = centre + (n + u * su + v * sv) * half;
            m.positions.push(p.to_array());
            m.normals.push(n.to_array());
        }
        // u × v = n × u × ... : wind so the face's normal is n.
        let (a, b, c, d) = (start, start + 1, start + 2, start + 3);
        if u.cross(v).dot(n) > 0.0 {
            m.indices.extend_from_slice(&[a, b, c, a, c, d]);
        } else {
            m.indices.extend_from_slice(&[a, c, b, a, d, c]);
        }
    }
    m
}

/// Joins boxes into one mesh.
fn joined(name: &str, parts: Vec<GlbMesh>) -> GlbMesh {
    let mut m = GlbMesh {
        name: name.to_owned(),
        base_colour: parts.first().map_or([0.5; 4], |p| p.base_colour),
        ..GlbMesh::default()
    };
    for p in parts {
        let base = m.positions.len() as u32;
        m.positions.extend(p.positions);
        m.normals.extend(p.normals);
        m.indices.extend(p.indices.iter().map(|i| i + base));
    }
    m
}

/// The coastal scene's meshes.
#[must_use]
pub fn coast_meshes() -> Vec<GlbMesh> {
    // The sea: from over the beach's top (where the shore's run-up can reach; dry,
    // it sinks under the sand) out to the horizon, finest at the waterline and
    // around z = 0 (the beach and the pier).
    let out = graded(1.5, 1.045, SEA_REACH_M);
    let xs: Vec<f32> = out
        .iter()
        .rev()
        .map(|d| 5.0 - d)
        .chain((1..=17).map(|i| 5.0 + 1.5 * i as f32))
        .collect();
    let along = graded(1.5, 1.045, SEA_REACH_M);
    let zs: Vec<f32> = along
        .iter()
        .rev()
        .map(|d| -d)
        .chain(along.iter().skip(1).copied())
        .collect();
    let mut sea = grid("sea", &xs, &zs, |_, _| 0.0);
    sea.base_colour = [0.1, 0.2, 0.25, 1.0];
    sea.node_extras = Some(json!({ "water": "sea" }));

    // Under the sea 5 m a cell, on the beach 2 m.
    let beach_xs: Vec<f32> = (0..52)
        .map(|i| SEABED_END_M + 5.0 * i as f32)
        .chain((0..=35).map(|i| BEACH.0.0 + 2.0 * i as f32))
        .collect();
    let shore_zs: Vec<f32> = (0..=55).map(|j| -SHORE_HALF_M + 4.0 * j as f32).collect();
    let mut beach = grid("beach", &beach_xs, &shore_zs, land_height_m);
    beach.base_colour = [0.66, 0.56, 0.38, 1.0];
    beach.node_extras = Some(json!({ "surface": "sand" }));

    let land_xs: Vec<f32> = (0..=30).map(|i| BEACH.1.0 + 3.0 * i as f32).collect();
    let mut land = grid("land", &land_xs, &shore_zs, land_height_m);
    land.base_colour = [0.24, 0.3, 0.16, 1.0];
    land.node_extras = Some(json!({ "surface": "grass" }));

    let ((wx0, wx1), (wz0, wz1), top) = BREAKWATER;
    let mut wall = cuboid(
        "breakwater",
        Vec3::new(wx0, -8.0, wz0),
        Vec3::new(wx1, top, wz1),
        [0.45, 0.45, 0.43, 1.0],
    );
    wall.node_extras = Some(json!({ "surface": "asphalt" }));

    let ((px0, px1), (pz0, pz1), deck) = PIER;
    let timber = [0.33, 0.24, 0.16, 1.0];
    let mut pier_parts = vec![cuboid(
        "deck",
        Vec3::new(px0, deck - 0.3, pz0),
        Vec3::new(px1, deck, pz1),
        timber,
    )];
    let mut x = px0 + 0.5;
    while x < px1 {
        for z in [pz0 + 0.3, pz1 - 0.3] {
            pier_parts.push(cuboid(
                "post",
                Vec3::new(x - 0.15, -6.0, z - 0.15),
                Vec3::new(x + 0.15, deck - 0.3, z + 0.15),
                timber,
            ));
        }
        x += 6.0;
    }
    let mut pier = joined("pier", pier_parts);
    pier.node_extras = Some(json!({ "surface": "roof" }));

    let mut meshes = vec![sea, beach, land, wall, pier];
    let floor = land_height_m(HOUSE_AT.x, HOUSE_AT.y);
    meshes.extend(house_meshes(Vec3::new(HOUSE_AT.x, floor, HOUSE_AT.y)));
    meshes
}

/// The coastal scene as GLB bytes (the same bytes every time).
#[must_use]
pub fn coast_glb() -> Vec<u8> {
    write_glb(&coast_meshes(), "precip coastal scene")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_beach_runs_into_the_sea_and_the_sea_to_the_horizon() {
        let ((x0, h0), (x1, h1)) = BEACH;
        assert!(h0 < 0.0 && h1 > 0.0, "the waterline crosses the beach");
        assert!(land_height_m(x0, 0.0) < 0.0 && land_height_m(x1 + 40.0, 0.0) > h1);
        let meshes = coast_meshes();
        let sea = meshes.iter().find(|m| m.name == "sea").expect("a sea");
        let (lo, hi) = sea
            .positions
            .iter()
            .fold((f32::MAX, f32::MIN), |(lo, hi), p| {
                (lo.min(p[0]), hi.max(p[0]))
            });
        assert!(lo <= -SEA_REACH_M + 5.0 && hi > 0.0, "{lo} … {hi}");
        // Fine at the waterline, and few vertices in all.
        let waterline = land_height_m(0.0, 0.0);
        assert!(waterline > 0.0);
        assert!(sea.positions.len() < 80_000, "{}", sea.positions.len());
        let near: Vec<f32> = sea
            .positions
            .iter()
            .filter(|p| p[2] == 0.0 && p[0] > -30.0)
            .map(|p| p[0])
            .collect();
        assert!(near.len() > 15, "{near:?}");
        // Every mesh's winding faces its normals.
        for m in &meshes {
            for t in m.indices.chunks_exact(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from(m.positions[i as usize]));
                let n = Vec3::from(m.normals[t[0] as usize]);
                let face = (b - a).cross(c - a);
                assert!(face.dot(n) >= 0.0, "{}: {face} against {n}", m.name);
            }
        }
    }
}
