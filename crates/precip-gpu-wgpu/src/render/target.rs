//! Offscreen targets: an sRGB colour texture and a depth buffer of the view's size
//! (with the splat's sums of that size), and reading the colour back as an [`Image`].

use precip_model::{BackendError, Image};

use precip_gpu::Simulation;
use precip_gpu::bind_groups::GroupLayout;
use precip_gpu::frame_resources::{TARGET_GROUPS, splat_sums_bytes};

use super::frame::{Bindable, FrameResources};
use super::layouts::RenderLayouts;
use super::pipelines::DEPTH_FORMAT;
use crate::device::GpuDevice;
use crate::gpu::Hal;
use crate::transfer::read_buffer;

/// The offscreen colour format: what `read_image` returns (RGBA8, sRGB).
pub const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// A single-level 2D texture of `width × height`.
fn texture_2d(
    gpu: &GpuDevice,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// The camera's depth buffer of a size, and the splat's sums of that size with the
/// bind groups that read them (the splat kernel tests against this depth).
#[derive(Debug)]
pub struct DepthBuffer {
    /// Width, height, px.
    pub size: (u32, u32),
    /// Its view.
    pub view: wgpu::TextureView,
    /// The splat kernel's group (this depth and the sums) and the resolve draw's
    /// (the sums), by table name.
    groups: Vec<(&'static str, wgpu::BindGroup)>,
}

impl DepthBuffer {
    /// A depth buffer of `(width, height)` with its splat sums and the target's groups
    /// (`precip_gpu::frame_resources::TARGET_GROUPS`), beside `frame`.
    pub fn new(
        gpu: &GpuDevice,
        layouts: &RenderLayouts,
        (width, height): (u32, u32),
        frame: &FrameResources,
        sim: &Simulation<Hal>,
    ) -> Result<Self, BackendError> {
        let texture = texture_2d(
            gpu,
            "precip depth",
            (width, height),
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        // Zeroed at creation; the resolve zeroes what it reads.
        let sums = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("precip splat sums"),
            size: splat_sums_bytes((width, height)),
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let with = Bindable {
            sim,
            target: Some((&view, &sums)),
        };
        let groups = frame.bind_groups(&gpu.device, layouts, &TARGET_GROUPS, &with)?;
        Ok(Self {
            size: (width, height),
            view,
            groups,
        })
    }

    /// The group made for `table`, if it is one of the target's.
    #[must_use]
    pub fn group(&self, table: &GroupLayout) -> Option<&wgpu::BindGroup> {
        self.groups
            .iter()
            .find(|(name, _)| *name == table.name)
            .map(|(_, g)| g)
    }
}

/// The offscreen colour target.
#[derive(Debug)]
pub struct ColourTarget {
    /// Width, height, px.
    pub size: (u32, u32),
    /// The texture.
    pub texture: wgpu::Texture,
    /// Its view.
    pub view: wgpu::TextureView,
}

impl ColourTarget {
    /// An sRGB RGBA8 target of `width × height`.
    #[must_use]
    pub fn new(gpu: &GpuDevice, width: u32, height: u32) -> Self {
        let texture = texture_2d(
            gpu,
            "precip image",
            (width, height),
            OFFSCREEN_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Self {
            size: (width, height),
            texture,
            view,
        }
    }

    /// Copies the image back (rows top to bottom).
    pub fn read(&self, gpu: &GpuDevice) -> Result<Image, BackendError> {
        read_texture(gpu, &self.texture)
    }
}

/// Copies a 2D texture (made with `COPY_SRC`) back, rows top to bottom, bytes in the
/// texture's own layout (tests and tools); an [`Image`]'s `rgba8` holds the bytes
/// (4 a pixel for RGBA8, 8 for RGBA16F).
pub fn read_texture(gpu: &GpuDevice, texture: &wgpu::Texture) -> Result<Image, BackendError> {
    let (width, height) = (texture.width(), texture.height());
    let row = width * texture.format().block_copy_size(None).unwrap_or(4);
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("precip image copy"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("precip image copy"),
        });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);
    let bytes = read_buffer(gpu, &buffer, u64::from(padded) * u64::from(height))?;
    let mut rgba8 = Vec::with_capacity((row * height) as usize);
    for r in 0..height as usize {
        let start = r * padded as usize;
        rgba8.extend_from_slice(&bytes[start..start + row as usize]);
    }
    Ok(Image {
        width_px: width,
        height_px: height,
        rgba8,
    })
}
