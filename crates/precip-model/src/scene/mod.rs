//! [`Scene`]: the neutral triangle scene every backend draws and the ground map is
//! rendered from (docs/architecture.md §1, §6). The viewer fills it from glTF; tests and the
//! built-in demo build it in code.
//!
//! [`Scene::prepare`] validates at the boundary, once: non-finite vertices, indices
//! beyond the vertex count, attribute arrays of the wrong length and broken textures
//! are typed errors naming the mesh; degenerate (zero-area) triangles are dropped and
//! counted in the [`SceneReport`]; missing normals are computed (area-weighted);
//! missing snow eligibility comes from the slope (docs/architecture.md §6, rule 3).

pub mod builtin;
pub mod displacement;
pub mod gpu_scene;
pub mod land_cover;
pub mod terrain;
pub mod tessellate;
pub mod top_down;

pub use land_cover::{LandClass, LandCover, LandCoverError};
pub use terrain::{SharedTerrain, Terrain, TerrainError};

use glam::{Vec2, Vec3};

/// Slope (from horizontal) up to which a surface holds full snow, degrees.
pub const FULL_SNOW_SLOPE_DEG: f32 = 30.0;
/// Slope from which a surface holds no snow, degrees (walls, steep roofs).
pub const NO_SNOW_SLOPE_DEG: f32 = 50.0;

/// A base-colour texture, RGBA8 sRGB, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextureRgba8 {
    /// Width, px.
    pub width_px: u32,
    /// Height, px.
    pub height_px: u32,
    /// `4 · width · height` bytes.
    pub rgba8: Vec<u8>,
}

/// A mesh's material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Linear RGBA base colour (multiplies the texture).
    pub base_colour: [f32; 4],
    /// Optional base-colour texture.
    pub base_colour_texture: Option<TextureRgba8>,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            base_colour: [0.8, 0.8, 0.8, 1.0],
            base_colour_texture: None,
        }
    }
}

/// A triangle mesh in world coordinates (metres, Y up).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// A name for messages (glTF node/mesh name).
    pub name: String,
    /// Vertex positions, m.
    pub positions_m: Vec<Vec3>,
    /// Vertex normals; empty: computed.
    pub normals: Vec<Vec3>,
    /// Texture coordinates; empty: all zero.
    pub uvs: Vec<Vec2>,
    /// Triangle list indices; empty: the vertices in order, three a triangle.
    pub indices: Vec<u32>,
    /// Per-vertex snow eligibility in `[0, 1]`; empty: from the slope.
    pub snow_eligibility: Vec<f32>,
    /// What the mesh is made of (glTF `extras.surface`, or `extras.water: true`);
    /// `None`: paved where it may hold no snow, else soil.
    pub surface: Option<precip_cover::Surface>,
    /// The open sea (glTF `extras.water: "sea"`, a water body too): drawn with the
    /// wind's waves ([`crate::drawing::sea`]).
    pub sea: bool,
    /// The material.
    pub material: Material,
}

/// A scene: its meshes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Scene {
    /// The meshes.
    pub meshes: Vec<Mesh>,
}

/// What is wrong with a scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// Nothing to draw.
    #[error("the scene has no triangles: give at least one mesh with a non-degenerate triangle")]
    Empty,
    /// A vertex attribute is not finite.
    #[error(
        "mesh `{mesh}`: vertex {vertex} has a non-finite {attribute}; fix or remove that vertex"
    )]
    NonFinite {
        /// The mesh.
        mesh: String,
        /// The vertex.
        vertex: usize,
        /// Which attribute.
        attribute: &'static str,
    },
    /// An index points past the vertices.
    #[error("mesh `{mesh}`: index {index} is beyond its {vertex_count} vertices")]
    IndexOutOfRange {
        /// The mesh.
        mesh: String,
        /// The index.
        index: u32,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// Indices are not whole triangles.
    #[error("mesh `{mesh}`: {count} indices are not a whole number of triangles")]
    NotTriangles {
        /// The mesh.
        mesh: String,
        /// The index count.
        count: usize,
    },
    /// An attribute array has the wrong length.
    #[error("mesh `{mesh}`: {attribute} has {got} values for {expected} vertices")]
    AttributeLength {
        /// The mesh.
        mesh: String,
        /// Which attribute.
        attribute: &'static str,
        /// Its length.
        got: usize,
        /// The vertex count.
        expected: usize,
    },
    /// A texture's bytes do not match its size.
    #[error(
        "mesh `{mesh}`: base-colour texture {width}×{height} has {got} bytes, expected {expected}"
    )]
    Texture {
        /// The mesh.
        mesh: String,
        /// Width, px.
        width: u32,
        /// Height, px.
        height: u32,
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}

/// What `prepare` changed or dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SceneReport {
    /// Triangles kept.
    pub triangles: usize,
    /// Zero-area triangles dropped.
    pub degenerate_triangles: usize,
    /// Meshes with no triangle left, dropped.
    pub empty_meshes: usize,
    /// Meshes whose normals were computed.
    pub computed_normals: usize,
    /// Meshes whose eligibility came from the slope.
    pub slope_eligibility: usize,
}

/// Snow eligibility from a surface normal: 1 up to [`FULL_SNOW_SLOPE_DEG`], 0 from
/// [`NO_SNOW_SLOPE_DEG`] (and on downward faces), smooth between.
#[must_use]
pub fn slope_eligibility(normal: Vec3) -> f32 {
    let up = normal.normalize_or_zero().y;
    let full = FULL_SNOW_SLOPE_DEG.to_radians().cos();
    let none = NO_SNOW_SLOPE_DEG.to_radians().cos();
    let t = ((up - none) / (full - none)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn check_len(
    mesh: &str,
    attribute: &'static str,
    got: usize,
    expected: usize,
) -> Result<(), SceneError> {
    if got == 0 || got == expected {
        Ok(())
    } else {
        Err(SceneError::AttributeLength {
            mesh: mesh.to_owned(),
            attribute,
            got,
            expected,
        })
    }
}

impl Mesh {
    /// A water body: a mesh tagged water (a pond, a lake), drawn with its depths and
    /// its mirror, not covered by snow.
    #[must_use]
    pub fn is_water_body(&self) -> bool {
        self.surface == Some(precip_cover::Surface::Water)
    }

    /// The open sea: a water body tagged `"water": "sea"`.
    #[must_use]
    pub fn is_sea(&self) -> bool {
        self.sea && self.is_water_body()
    }

    /// Validates and completes one mesh; `None` when no triangle is left.
    fn prepare(mut self, report: &mut SceneReport) -> Result<Option<Self>, SceneError> {
        let n = self.positions_m.len();
        let name = self.name.clone();
        check_len(&name, "normals", self.normals.len(), n)?;
        check_len(&name, "uvs", self.uvs.len(), n)?;
        check_len(&name, "snow_eligibility", self.snow_eligibility.len(), n)?;
        let non_finite = |vertex: usize, attribute: &'static str| SceneError::NonFinite {
            mesh: name.clone(),
            vertex,
            attribute,
        };
        if let Some(v) = self.positions_m.iter().position(|p| !p.is_finite()) {
            return Err(non_finite(v, "position"));
        }
        if let Some(v) = self.normals.iter().position(|p| !p.is_finite()) {
            return Err(non_finite(v, "normal"));
        }
        if let Some(v) = self.uvs.iter().position(|p| !p.is_finite()) {
            return Err(non_finite(v, "uv"));
        }
        if let Some(v) = self.snow_eligibility.iter().position(|e| !e.is_finite()) {
            return Err(non_finite(v, "snow eligibility"));
        }
        if let Some(t) = &self.material.base_colour_texture {
            let expected = 4 * t.width_px as usize * t.height_px as usize;
            if t.rgba8.len() != expected || expected == 0 {
                return Err(SceneError::Texture {
                    mesh: name,
                    width: t.width_px,
                    height: t.height_px,
                    got: t.rgba8.len(),
                    expected,
                });
            }
        }
        if self.indices.is_empty() {
            self.indices = (0..n as u32).collect();
        }
        if !self.indices.len().is_multiple_of(3) {
            return Err(SceneError::NotTriangles {
                mesh: name,
                count: self.indices.len(),
            });
        }
        if let Some(&index) = self.indices.iter().find(|&&i| i as usize >= n) {
            return Err(SceneError::IndexOutOfRange {
                mesh: name,
                index,
                vertex_count: n,
            });
        }
        let mut kept = Vec::with_capacity(self.indices.len());
        for t in self.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| self.positions_m[i as usize]);
            if (b - a).cross(c - a).length_squared() > 0.0 {
                kept.extend_from_slice(t);
            } else {
                report.degenerate_triangles += 1;
            }
        }
        self.indices = kept;
        if self.indices.is_empty() {
            report.empty_meshes += 1;
            return Ok(None);
        }
        report.triangles += self.indices.len() / 3;
        if self.normals.is_empty() {
            let mut normals = vec![Vec3::ZERO; n];
            for t in self.indices.chunks_exact(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| self.positions_m[i as usize]);
                let area_normal = (b - a).cross(c - a);
                for &i in t {
                    normals[i as usize] += area_normal;
                }
            }
            self.normals = normals
                .into_iter()
                .map(|v| v.normalize_or(Vec3::Y))
                .collect();
            report.computed_normals += 1;
        }
        if self.uvs.is_empty() {
            self.uvs = vec![Vec2::ZERO; n];
        }
        if self.snow_eligibility.is_empty() {
            self.snow_eligibility = self
                .normals
                .iter()
                .map(|&normal| slope_eligibility(normal))
                .collect();
            report.slope_eligibility += 1;
        } else {
            for e in &mut self.snow_eligibility {
                *e = e.clamp(0.0, 1.0);
            }
        }
        Ok(Some(self))
    }
}

/// A scene that [`Scene::prepare`] validated and completed: every mesh has finite
/// positions, in-range indices, unit normals, texture coordinates and eligibility for
/// every vertex. Only `prepare` makes one, so a [`crate::Setup`] cannot carry an
/// unprepared scene to a backend; it reads as a [`Scene`] (`Deref`) and cannot be
/// changed in place. It may stand on a [`Terrain`] ([`PreparedScene::on_terrain`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedScene {
    scene: Scene,
    terrain: Option<SharedTerrain>,
}

impl std::ops::Deref for PreparedScene {
    type Target = Scene;
    fn deref(&self) -> &Scene {
        &self.scene
    }
}

impl PreparedScene {
    /// The scene, to change and prepare again (without its terrain).
    #[must_use]
    pub fn into_scene(self) -> Scene {
        self.scene
    }

    /// The scene standing on `terrain` (validated when it was made): the ground
    /// map takes the top-most of both ([`crate::GroundMap::from_scene_and_terrain`])
    /// and the GPU backends draw the terrain as a clipmap under the meshes.
    #[must_use]
    pub fn on_terrain(mut self, terrain: SharedTerrain) -> Self {
        self.terrain = Some(terrain);
        self
    }

    /// The terrain it stands on.
    #[must_use]
    pub fn terrain(&self) -> Option<&SharedTerrain> {
        self.terrain.as_ref()
    }
}

impl Scene {
    /// Validates the scene and completes every mesh (see the module docs).
    pub fn prepare(self) -> Result<(PreparedScene, SceneReport), SceneError> {
        let mut report = SceneReport::default();
        let mut meshes = Vec::with_capacity(self.meshes.len());
        for mesh in self.meshes {
            if let Some(m) = mesh.prepare(&mut report)? {
                meshes.push(m);
            }
        }
        if meshes.is_empty() {
            return Err(SceneError::Empty);
        }
        Ok((
            PreparedScene {
                scene: Self { meshes },
                terrain: None,
            },
            report,
        ))
    }

    /// Axis-aligned bounds `(min, max)` of the vertices of all but the sea, m (the
    /// land and the shore the cover grid and the shadow map cover: the open sea
    /// may run to the horizon); a scene of sea alone: its bounds; `None` for no
    /// vertices.
    #[must_use]
    pub fn land_bounds_m(&self) -> Option<(Vec3, Vec3)> {
        bounds_of(self.meshes.iter().filter(|m| !m.is_sea())).or_else(|| self.bounds_m())
    }

    /// Axis-aligned bounds `(min, max)` of all vertices, m; `None` for no vertices.
    #[must_use]
    pub fn bounds_m(&self) -> Option<(Vec3, Vec3)> {
        bounds_of(self.meshes.iter())
    }
}

fn bounds_of<'a>(meshes: impl Iterator<Item = &'a Mesh>) -> Option<(Vec3, Vec3)> {
    let mut points = meshes.flat_map(|m| m.positions_m.iter().copied());
    let first = points.next()?;
    Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(name: &str, up: bool) -> Mesh {
        // A 2 m square: flat (normal +Y) or a wall (normal +Z).
        let positions_m = if up {
            vec![
                Vec3::ZERO,
                Vec3::new(0.0, 0.0, 2.0),
                Vec3::new(2.0, 0.0, 2.0),
                Vec3::new(2.0, 0.0, 0.0),
            ]
        } else {
            vec![
                Vec3::ZERO,
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(2.0, 2.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
            ]
        };
        Mesh {
            name: name.into(),
            positions_m,
            indices: vec![0, 1, 2, 0, 2, 3],
            ..Mesh::default()
        }
    }

    #[test]
    fn flat_ground_holds_snow_and_walls_do_not() {
        let (scene, report) = Scene {
            meshes: vec![quad("ground", true), quad("wall", false)],
        }
        .prepare()
        .expect("valid");
        assert_eq!(report.triangles, 4);
        assert_eq!(report.computed_normals, 2);
        assert!(
            scene.meshes[0]
                .normals
                .iter()
                .all(|n| (*n - Vec3::Y).length() < 1e-6)
        );
        assert!(
            scene.meshes[0]
                .snow_eligibility
                .iter()
                .all(|&e| (e - 1.0).abs() < 1e-6)
        );
        assert!(
            scene.meshes[1]
                .snow_eligibility
                .iter()
                .all(|&e| e.abs() < 1e-6)
        );
        assert_eq!(
            scene.bounds_m(),
            Some((Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0)))
        );
    }

    #[test]
    fn slope_eligibility_is_smooth_between_30_and_50_degrees() {
        let at = |deg: f32| {
            slope_eligibility(Vec3::new(
                deg.to_radians().sin(),
                deg.to_radians().cos(),
                0.0,
            ))
        };
        assert!((at(0.0) - 1.0).abs() < 1e-6 && (at(29.0) - 1.0).abs() < 1e-6);
        assert!(at(40.0) > 0.2 && at(40.0) < 0.8);
        assert!(at(51.0).abs() < 1e-6 && at(90.0).abs() < 1e-6);
        assert!(
            slope_eligibility(Vec3::NEG_Y).abs() < 1e-6,
            "ceilings hold none"
        );
    }

    #[test]
    fn bad_meshes_are_named_errors_and_degenerate_triangles_are_dropped() {
        let mut nan = quad("nan", true);
        nan.positions_m[2].x = f32::NAN;
        assert!(matches!(
            Scene { meshes: vec![nan] }.prepare(),
            Err(SceneError::NonFinite { vertex: 2, .. })
        ));
        let mut far = quad("far", true);
        far.indices[4] = 9;
        let err = Scene { meshes: vec![far] }.prepare().unwrap_err();
        assert!(
            err.to_string().contains("far") && err.to_string().contains("index 9"),
            "{err}"
        );
        let mut ragged = quad("ragged", true);
        ragged.indices.pop();
        assert!(matches!(
            Scene {
                meshes: vec![ragged]
            }
            .prepare(),
            Err(SceneError::NotTriangles { .. })
        ));
        let mut short = quad("short", true);
        short.uvs = vec![Vec2::ZERO; 2];
        assert!(matches!(
            Scene {
                meshes: vec![short]
            }
            .prepare(),
            Err(SceneError::AttributeLength { .. })
        ));
        let mut textured = quad("textured", true);
        textured.material.base_colour_texture = Some(TextureRgba8 {
            width_px: 2,
            height_px: 2,
            rgba8: vec![0; 15],
        });
        assert!(matches!(
            Scene {
                meshes: vec![textured]
            }
            .prepare(),
            Err(SceneError::Texture { .. })
        ));
        assert!(matches!(Scene::default().prepare(), Err(SceneError::Empty)));

        let mut degenerate = quad("degenerate", true);
        degenerate.indices.extend_from_slice(&[0, 0, 1, 1, 2, 1]);
        let (_, report) = Scene {
            meshes: vec![degenerate],
        }
        .prepare()
        .expect("valid");
        assert_eq!((report.triangles, report.degenerate_triangles), (2, 2));
        let line = Mesh {
            name: "line".into(),
            positions_m: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            ..Mesh::default()
        };
        assert!(matches!(
            Scene { meshes: vec![line] }.prepare(),
            Err(SceneError::Empty)
        ));
    }
}
