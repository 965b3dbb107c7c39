//! The samplers of drawing, as the wgpu backend describes them (wgpu-hal's defaults:
//! nearest mip, LOD 0–32, no anisotropy): the shadow map's comparison sampler, the
//! flake's clamped linear sampler and the materials' repeating linear sampler.

use ash::vk;
use precip_model::BackendError;

use crate::device::Device;
use crate::error::map_vk;

/// The three samplers, made once per device.
#[derive(Debug)]
pub struct Samplers {
    /// Less-or-equal comparison, linear.
    pub shadow: vk::Sampler,
    /// Linear, clamped.
    pub flake: vk::Sampler,
    /// Linear, repeating.
    pub material: vk::Sampler,
}

fn sampler(
    device: &Device,
    name: &str,
    address: vk::SamplerAddressMode,
    compare: Option<vk::CompareOp>,
) -> Result<vk::Sampler, BackendError> {
    let info = vk::SamplerCreateInfo::default()
        .mag_filter(vk::Filter::LINEAR)
        .min_filter(vk::Filter::LINEAR)
        .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
        .address_mode_u(address)
        .address_mode_v(address)
        .address_mode_w(address)
        .compare_enable(compare.is_some())
        .compare_op(compare.unwrap_or(vk::CompareOp::NEVER))
        .min_lod(0.0)
        .max_lod(32.0);
    // SAFETY: a valid device and create info.
    let s = unsafe { device.raw.create_sampler(&info, None) }
        .map_err(|e| map_vk("creating a sampler", e))?;
    device.name(s, name);
    Ok(s)
}

impl Samplers {
    /// Creates the samplers.
    pub fn new(device: &Device) -> Result<Self, BackendError> {
        use vk::SamplerAddressMode as A;
        Ok(Self {
            shadow: sampler(
                device,
                "precip shadow",
                A::CLAMP_TO_EDGE,
                Some(vk::CompareOp::LESS_OR_EQUAL),
            )?,
            flake: sampler(device, "precip flake", A::CLAMP_TO_EDGE, None)?,
            material: sampler(device, "precip material", A::REPEAT, None)?,
        })
    }

    /// Destroys them (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once.
        unsafe {
            for s in [self.shadow, self.flake, self.material] {
                device.raw.destroy_sampler(s, None);
            }
        }
    }
}
