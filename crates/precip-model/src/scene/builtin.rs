//! A small built-in scene: a gabled house on a plane (the rendering example, tests
//! and the viewer's fallback). The roof overhangs the walls so the ground under the
//! eaves is sheltered; walls are vertical (no snow by slope); the roof is pitched at
//! 30° (full snow by slope).

use glam::{Vec2, Vec3};

use crate::scene::{Material, Mesh, Scene};

/// The house's measurements, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HousePlan {
    /// Side of the square ground plane.
    pub ground_side_m: f32,
    /// Along X (the ridge's direction).
    pub width_m: f32,
    /// Along Z.
    pub depth_m: f32,
    /// Walls' height.
    pub wall_height_m: f32,
    /// Roof pitch from horizontal, degrees.
    pub roof_pitch_deg: f32,
    /// How far the roof reaches past the walls, horizontally.
    pub overhang_m: f32,
}

impl Default for HousePlan {
    fn default() -> Self {
        Self {
            ground_side_m: 40.0,
            width_m: 8.0,
            depth_m: 6.0,
            wall_height_m: 3.0,
            roof_pitch_deg: 30.0,
            overhang_m: 1.0,
        }
    }
}

impl HousePlan {
    /// Height of the ridge, m.
    #[must_use]
    pub fn ridge_height_m(&self) -> f32 {
        self.wall_height_m + 0.5 * self.depth_m * self.roof_pitch_deg.to_radians().tan()
    }

    /// Height of the eaves' edge, m.
    #[must_use]
    pub fn eave_height_m(&self) -> f32 {
        self.wall_height_m - self.overhang_m * self.roof_pitch_deg.to_radians().tan()
    }
}

/// Appends a planar polygon (a fan from its first corner) with a flat normal facing
/// `outward`, vertices not shared with other faces.
fn face(mesh: &mut Mesh, corners: &[Vec3], outward: Vec3) {
    let normal = (corners[1] - corners[0])
        .cross(corners[2] - corners[0])
        .normalize();
    let mut corners = corners.to_vec();
    let normal = if normal.dot(outward) < 0.0 {
        corners.reverse();
        -normal
    } else {
        normal
    };
    let base = mesh.positions_m.len() as u32;
    for c in &corners {
        mesh.positions_m.push(*c);
        mesh.normals.push(normal);
        // Planar UVs, 1 per 2 m, from the two largest axes of the face.
        let uv = if normal.y.abs() > 0.5 {
            Vec2::new(c.x, c.z)
        } else if normal.x.abs() > normal.z.abs() {
            Vec2::new(c.z, -c.y)
        } else {
            Vec2::new(c.x, -c.y)
        };
        mesh.uvs.push(uv * 0.5);
    }
    for k in 1..corners.len() as u32 - 1 {
        mesh.indices
            .extend_from_slice(&[base, base + k, base + k + 1]);
    }
}

fn mesh(name: &str, colour: [f32; 3]) -> Mesh {
    Mesh {
        name: name.to_owned(),
        material: Material {
            base_colour: [colour[0], colour[1], colour[2], 1.0],
            base_colour_texture: None,
        },
        ..Mesh::default()
    }
}

/// The house of `plan` on its ground plane.
#[must_use]
pub fn house(plan: &HousePlan) -> Scene {
    let g = plan.ground_side_m / 2.0;
    let mut ground = mesh("ground", [0.23, 0.26, 0.16]);
    face(
        &mut ground,
        &[
            Vec3::new(-g, 0.0, -g),
            Vec3::new(g, 0.0, -g),
            Vec3::new(g, 0.0, g),
            Vec3::new(-g, 0.0, g),
        ],
        Vec3::Y,
    );

    let (x, z, h) = (plan.width_m / 2.0, plan.depth_m / 2.0, plan.wall_height_m);
    let ridge = plan.ridge_height_m();
    let mut walls = mesh("walls", [0.62, 0.5, 0.38]);
    for (corners, out) in [
        ([(-x, -z), (x, -z)], Vec3::NEG_Z),
        ([(x, z), (-x, z)], Vec3::Z),
    ] {
        let [(x0, z0), (x1, z1)] = corners;
        face(
            &mut walls,
            &[
                Vec3::new(x0, 0.0, z0),
                Vec3::new(x1, 0.0, z1),
                Vec3::new(x1, h, z1),
                Vec3::new(x0, h, z0),
            ],
            out,
        );
    }
    // Gable ends: a wall up to the eaves and the triangle up to the ridge.
    for (sx, out) in [(-x, Vec3::NEG_X), (x, Vec3::X)] {
        face(
            &mut walls,
            &[
                Vec3::new(sx, 0.0, -z),
                Vec3::new(sx, 0.0, z),
                Vec3::new(sx, h, z),
                Vec3::new(sx, ridge, 0.0),
                Vec3::new(sx, h, -z),
            ],
            out,
        );
    }

    let mut roof = mesh("roof", [0.42, 0.14, 0.1]);
    let (rx, rz, eave) = (
        x + plan.overhang_m,
        z + plan.overhang_m,
        plan.eave_height_m(),
    );
    for (sz, out) in [
        (-rz, Vec3::new(0.0, 1.0, -1.0)),
        (rz, Vec3::new(0.0, 1.0, 1.0)),
    ] {
        face(
            &mut roof,
            &[
                Vec3::new(-rx, eave, sz),
                Vec3::new(rx, eave, sz),
                Vec3::new(rx, ridge, 0.0),
                Vec3::new(-rx, ridge, 0.0),
            ],
            out,
        );
    }
    Scene {
        meshes: vec![ground, walls, roof],
    }
}

/// The default house on a 40 m plane.
#[must_use]
pub fn house_on_plane() -> Scene {
    house(&HousePlan::default())
}

/// [`house_on_plane`] with a pond before its south side: a 16 × 10 m water body
/// (`Surface::Water`) 2 cm above the plane, from `z = 4` to `14` m.
#[must_use]
pub fn house_with_pond() -> Scene {
    let mut scene = house_on_plane();
    scene.meshes.push(Mesh {
        name: "pond".into(),
        positions_m: vec![
            Vec3::new(-8.0, 0.02, 4.0),
            Vec3::new(8.0, 0.02, 4.0),
            Vec3::new(8.0, 0.02, 14.0),
            Vec3::new(-8.0, 0.02, 14.0),
        ],
        indices: vec![0, 2, 1, 0, 3, 2],
        surface: Some(precip_cover::Surface::Water),
        ..Mesh::default()
    });
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_house_is_a_valid_scene_with_snow_on_the_roof_only() {
        let (scene, report) = house_on_plane().prepare().expect("valid");
        assert_eq!(report.degenerate_triangles, 0);
        let by_name = |n: &str| scene.meshes.iter().find(|m| m.name == n).expect(n);
        assert!(
            by_name("walls")
                .snow_eligibility
                .iter()
                .all(|e| e.abs() < 1e-6)
        );
        assert!(by_name("roof").snow_eligibility.iter().all(|e| *e > 0.99));
        assert!(by_name("ground").snow_eligibility.iter().all(|e| *e > 0.99));
        assert!(by_name("roof").normals.iter().all(|n| n.y > 0.8));
        let (lo, hi) = scene.bounds_m().expect("vertices");
        assert!(lo.y.abs() < 1e-6 && (hi.y - HousePlan::default().ridge_height_m()).abs() < 1e-5);
    }
}
