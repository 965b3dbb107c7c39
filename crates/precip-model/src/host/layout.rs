//! Blocks that cross to the GPU besides the particles and the uniform blocks of
//! their own modules: the grids the kernels read ([`Frames`]) and the scene's
//! vertex ([`SceneVertex`]).

use bytemuck::{Pod, Zeroable};
use precip_cover::GridFrame;

/// The grids the particle kernels read.
///
/// WGSL twin: `Frames` in `shaders/layout.wgsl` (96 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Frames {
    /// The ground height map's grid.
    pub ground: GridFrame,
    /// The cover grid (deposit texels).
    pub cover: GridFrame,
    /// The water bodies' wave grid ([`crate::physics::water_waves`]).
    pub waves: GridFrame,
}
const _: () = assert!(size_of::<Frames>() == 96);

/// Vertex layout of the scene: position (3 × f32), normal (3 × f32), uv (2 × f32),
/// snow eligibility (f32); 36 bytes. WGSL: `SceneVertex` in render_scene.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct SceneVertex {
    /// Position, m.
    pub position_m: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Texture coordinates.
    pub uv: [f32; 2],
    /// Snow eligibility, `[0, 1]`.
    pub eligibility: f32,
}
const _: () = assert!(size_of::<SceneVertex>() == 36);
