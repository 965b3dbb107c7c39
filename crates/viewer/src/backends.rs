//! Which backend draws: wgpu (Vulkan, Metal, DX12 or GL underneath) or precip's own
//! Vulkan backend (ash). Both run the same WGSL and draw the same frames.

use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::{Backend, BackendError};

/// A GPU backend the viewer can use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BackendName {
    /// `precip-gpu-wgpu`.
    Wgpu,
    /// `precip-gpu-vk` (raw Vulkan through ash).
    Vk,
}

/// What the Vulkan validation layer reported (shared with the backend; readable
/// after it is dropped, leak reports included).
pub type ValidationLog = precip_gpu_vk::Messages;

/// Opens `name` for headless frames. The Vulkan backend runs with the validation
/// layer when `PRECIP_VK_VALIDATION=1`; its log comes back for the caller to print.
pub fn open_headless(
    name: BackendName,
) -> Result<(Box<dyn Backend>, Option<ValidationLog>), BackendError> {
    Ok(match name {
        BackendName::Wgpu => (Box::new(WgpuBackend::new()?), None),
        BackendName::Vk => {
            let backend = VkBackend::new(vk_validation())?;
            let log = vk_validation().then(|| backend.validation_log());
            (Box::new(backend), log)
        }
    })
}

/// Whether `PRECIP_VK_VALIDATION=1` asks for the Vulkan validation layer.
#[must_use]
pub fn vk_validation() -> bool {
    std::env::var("PRECIP_VK_VALIDATION").as_deref() == Ok("1")
}
