//! Offscreen targets: an sRGB colour image and a depth buffer of the view's size
//! with their framebuffer, and reading the colour back as a [`precip_model::Image`].

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use precip_model::BackendError;

use crate::buffer::Buffer;
use crate::commands::submit;
use crate::device::Device;
use crate::image::{COLOUR, DEPTH_FORMAT, Image, ImageSpec};

use super::frame::framebuffer;

/// The offscreen colour format: what `read_image` returns (RGBA8, sRGB), as wgpu's
/// `Rgba8UnormSrgb`.
pub const OFFSCREEN_FORMAT: vk::Format = vk::Format::R8G8B8A8_SRGB;

/// A depth buffer of `size`.
pub fn depth_buffer(device: &Device, (width, height): (u32, u32)) -> Result<Image, BackendError> {
    Image::new(
        device,
        &ImageSpec {
            name: "depth",
            extent: UVec3::new(width, height, 1),
            format: DEPTH_FORMAT,
            // Sampled: the splat kernel tests against it.
            usage: vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED,
        },
    )
}

/// The offscreen target: colour, depth, framebuffer.
#[derive(Debug)]
pub struct OffscreenTarget {
    /// The colour image (ends each frame in `TRANSFER_SRC_OPTIMAL`).
    pub colour: Image,
    /// The depth buffer.
    pub depth: Image,
    /// Both, for the camera pass.
    pub framebuffer: vk::Framebuffer,
}

impl OffscreenTarget {
    /// A target of `size` for the offscreen camera pass `pass`.
    pub fn new(
        device: &Device,
        pass: vk::RenderPass,
        size: (u32, u32),
    ) -> Result<Self, BackendError> {
        let colour = Image::new(
            device,
            &ImageSpec {
                name: "image",
                extent: UVec3::new(size.0, size.1, 1),
                format: OFFSCREEN_FORMAT,
                usage: vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC,
            },
        )?;
        let depth = match depth_buffer(device, size) {
            Ok(d) => d,
            Err(e) => {
                colour.destroy(device);
                return Err(e);
            }
        };
        match framebuffer(device, pass, &[colour.view, depth.view], size) {
            Ok(framebuffer) => {
                device.name(framebuffer, "precip offscreen framebuffer");
                Ok(Self {
                    colour,
                    depth,
                    framebuffer,
                })
            }
            Err(e) => {
                colour.destroy(device);
                depth.destroy(device);
                Err(e)
            }
        }
    }

    /// Width and height, px.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        self.colour.size()
    }

    /// Copies the image back, rows top to bottom (waits; the frame must have been
    /// submitted).
    pub fn read(&self, device: &Device) -> Result<precip_model::Image, BackendError> {
        let (width, height) = self.size();
        let bytes = u64::from(width) * u64::from(height) * 4;
        let staging = Buffer::new(
            device,
            "image read-back",
            bytes,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )?;
        let region = vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: COLOUR.aspect_mask,
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(vk::Extent3D {
                width,
                height,
                depth: 1,
            });
        let result = submit(device, |cb| {
            // SAFETY: `cb` is recording; the camera pass left the image in
            // TRANSFER_SRC_OPTIMAL and made its writes visible to transfers.
            unsafe {
                device.raw.cmd_copy_image_to_buffer(
                    cb,
                    self.colour.raw,
                    vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                    staging.raw,
                    &[region],
                );
            }
        })
        .and_then(|f| f.wait(device))
        .and_then(|()| staging.read(bytes as usize));
        staging.destroy(device);
        Ok(precip_model::Image {
            width_px: width,
            height_px: height,
            rgba8: result?,
        })
    }

    /// Frees everything (no pending work may use it).
    pub fn destroy(self, device: &Device) {
        // SAFETY: no pending work uses the framebuffer; destroyed once.
        unsafe { device.raw.destroy_framebuffer(self.framebuffer, None) };
        self.colour.destroy(device);
        self.depth.destroy(device);
    }
}
