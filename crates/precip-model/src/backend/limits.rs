//! What a device allows, checked once here for every GPU backend, so the same input is
//! refused by each with the same typed error: particles, the ground and cover grids
//! (each one storage binding), the scene's vertex and index buffers, its textures and
//! the size of a frame.

use crate::backend::camera::View;
use crate::backend::error::BackendError;
use crate::backend::setup::Setup;
use crate::host::SceneVertex;
use crate::particles::particle::Particle;
use crate::scene::gpu_scene::PackedScene;

/// Bytes of one cover texel on the GPU.
const COVER_TEXEL_BYTES: u64 = size_of::<precip_cover::CoverTexel>() as u64;

/// A device's limits, in the terms precip checks.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DeviceLimits {
    /// The device, for messages.
    pub device: String,
    /// The largest storage buffer one binding may hold, bytes.
    pub max_storage_binding_bytes: u64,
    /// The largest buffer, bytes.
    pub max_buffer_bytes: u64,
    /// The largest 2D texture or render target side, px.
    pub max_texture_side_px: u32,
}

fn too_large(field: &'static str, bytes: u64, max: u64, what: &str, advice: &str) -> BackendError {
    BackendError::Setup {
        field,
        problem: format!("needs {bytes} bytes but this device allows {max} ({what}): {advice}"),
    }
}

impl DeviceLimits {
    /// The most particles one configuration holds.
    #[must_use]
    pub fn max_particles(&self) -> u64 {
        (self.max_storage_binding_bytes.min(self.max_buffer_bytes) / size_of::<Particle>() as u64)
            .min(u64::from(u32::MAX))
    }

    /// Checks `setup` (validated in full: [`Setup::validate`]) against the device.
    pub fn check_setup(&self, setup: &Setup) -> Result<(), BackendError> {
        let limit = format!(
            "{} bytes a storage binding on {}, {} bytes a particle",
            self.max_storage_binding_bytes,
            self.device,
            size_of::<Particle>()
        );
        setup.validate(self.max_particles(), &limit)?;
        let binding = self.max_storage_binding_bytes.min(self.max_buffer_bytes);
        let cover = setup.cover.frame.texel_count() as u64 * COVER_TEXEL_BYTES;
        if cover > binding {
            return Err(too_large(
                "cover.frame",
                cover,
                binding,
                "one storage binding",
                "use fewer cover texels",
            ));
        }
        let ground = setup.ground.frame.texel_count() as u64 * 4;
        if ground > binding {
            return Err(too_large(
                "ground.frame",
                ground,
                binding,
                "one storage binding",
                "use fewer ground texels",
            ));
        }
        if let Some(scene) = &setup.scene {
            for mesh in &scene.meshes {
                let side = self.max_texture_side_px;
                if let Some(t) = &mesh.material.base_colour_texture
                    && (t.width_px > side || t.height_px > side)
                {
                    return Err(BackendError::Setup {
                        field: "scene",
                        problem: format!(
                            "{}'s base-colour texture is {}×{} px but this device takes at most {side} a side: downscale it",
                            mesh.name, t.width_px, t.height_px
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    /// Checks the packed scene's vertex and index buffers against the device.
    pub fn check_packed_scene(&self, packed: &PackedScene) -> Result<(), BackendError> {
        let advice = "raise render.tessellation_edge_m or lower render.max_scene_triangles";
        let vertices = packed.vertices.len() as u64 * size_of::<SceneVertex>() as u64;
        if vertices > self.max_buffer_bytes {
            return Err(too_large(
                "scene",
                vertices,
                self.max_buffer_bytes,
                "vertex bytes in one buffer",
                advice,
            ));
        }
        let indices = packed.indices.len() as u64 * 4;
        if indices > self.max_buffer_bytes {
            return Err(too_large(
                "scene",
                indices,
                self.max_buffer_bytes,
                "index bytes in one buffer",
                advice,
            ));
        }
        Ok(())
    }

    /// Checks that a frame of `view`'s size fits the device.
    pub fn check_view(&self, view: &View) -> Result<(), BackendError> {
        crate::drawing::render::validate_view(view)?;
        let max = self.max_texture_side_px;
        if view.width_px > max || view.height_px > max {
            return Err(BackendError::InvalidView(format!(
                "{}×{} px exceeds this device's largest render target ({max} px a side): render smaller",
                view.width_px, view.height_px
            )));
        }
        Ok(())
    }
}
