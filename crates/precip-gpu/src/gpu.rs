//! [`Gpu`]: the device calls a backend implements, and nothing else. The executor
//! ([`crate::executor`]) runs the plan over them, so what a configuration
//! allocates, how it is bound, what a step uploads and dispatches and what a query
//! reads back is written once, here, for every backend; `precip-gpu-wgpu` and
//! `precip-gpu-vk` each implement these calls in a file of the same name
//! (`gpu.rs`), in the spirit of wgpu-hal's `Device` and `CommandEncoder`.
//!
//! The frame is recorded once too ([`crate::renderer`]): as a [`FrameWork`], the
//! frame plan's passes as plain commands (set a kernel or a pipeline, bind a group,
//! dispatch, draw), which [`Gpu::submit_frame`] translates into one command buffer:
//! the backend adds only what its API needs besides (Vulkan's render passes,
//! framebuffers, barriers and image layouts; wgpu's passes).
//!
//! Resources are owned by the executor and handed back with the `destroy_*` calls
//! (a no-op where the API frees on drop), on every path, errors included.

use std::ops::Range;

use precip_model::{BackendError, DeviceMemory};

use crate::bind_groups::GroupLayout;
use crate::frame::{Draw, RenderPassRecipe};
use crate::frame_resources::{Sampler, TexelFormat, TextureUsage};
use crate::resources::BufferUsage;
use crate::shaders::Program;

/// What fills one binding of a bind group.
#[derive(Debug)]
pub enum BindingResource<'a, G: Gpu + ?Sized> {
    /// A buffer: a uniform binding sees the table's block size from offset 0 (a
    /// dynamic one moves with its offset), a storage binding the whole buffer.
    Buffer(&'a G::Buffer),
    /// A 3D texture.
    Volume(&'a G::Volume),
    /// A 2D texture, sampled or loaded.
    Texture(&'a G::Texture),
    /// A 2D texture written by a kernel.
    StorageTexture(&'a G::Texture),
    /// A sampler.
    Sampler(&'a G::Sampler),
}

/// One compute dispatch of a submission.
#[derive(Debug)]
pub struct Dispatch<'a, G: Gpu + ?Sized> {
    /// The kernel.
    pub kernel: &'a G::Kernel,
    /// Its group 0.
    pub group: &'a G::BindGroup,
    /// The group's dynamic offset, if it has a dynamic binding.
    pub offset: Option<u32>,
    /// Workgroups `(x, y)`: the dispatch's, or the most an indirect one may hold.
    pub workgroups: (u32, u32),
    /// An indirect dispatch: the buffer (made [`crate::resources::BufferUsage::Indirect`]) and
    /// the byte offset of its workgroups `(x, y, z)`, written by a kernel before.
    pub indirect: Option<(&'a G::Buffer, u64)>,
}

/// A 2D texture to make.
#[derive(Debug, Clone, Copy)]
pub struct TextureDesc<'a> {
    /// A label for debuggers.
    pub label: &'static str,
    /// Width and height, texels.
    pub size: (u32, u32),
    /// Format.
    pub format: TexelFormat,
    /// Usage (which also fixes the layout it rests in between passes).
    pub usage: TextureUsage,
    /// Texels to fill it with (tightly packed rows), if any.
    pub contents: Option<&'a [u8]>,
}

/// Where a frame is drawn.
#[derive(Debug)]
pub enum Target<'a, G: Gpu + ?Sized> {
    /// A texture of [`TextureUsage::ColourTarget`], read back afterwards.
    Texture(&'a G::Texture),
    /// The backend's window image (a wgpu surface texture, a swapchain image): the
    /// caller presents it.
    Surface(&'a G::Surface),
}

impl<G: Gpu + ?Sized> Clone for Target<'_, G> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<G: Gpu + ?Sized> Copy for Target<'_, G> {}

/// One command of a pass, in order. Groups stay bound until replaced; a draw or a
/// dispatch sees the last pipeline and groups set.
#[derive(Debug)]
pub enum Command<'a, G: Gpu + ?Sized> {
    /// Sets a compute kernel (a pass of kernels).
    Kernel(&'a G::Kernel),
    /// Sets a draw pipeline (a render pass).
    Pipeline(&'a G::DrawPipeline),
    /// Binds `group` at `index`, with one offset per dynamic binding.
    Group {
        /// Its index in the pipeline's layout.
        index: u32,
        /// The group.
        group: &'a G::BindGroup,
        /// Its dynamic offsets, in binding order.
        offsets: &'a [u32],
    },
    /// Dispatches `(x, y)` workgroups of the kernel; its writes are seen by every
    /// later command of the frame.
    Dispatch(u32, u32),
    /// Sets the scene's vertex (`SceneVertex`) and `u32` index buffers.
    Meshes {
        /// Vertices.
        vertices: &'a G::Buffer,
        /// Indices.
        indices: &'a G::Buffer,
    },
    /// Draws `n` vertices, one instance.
    Draw(u32),
    /// Draws this range of indices, one instance.
    DrawIndexed(Range<u32>),
    /// Draws with the arguments at this byte offset of the buffer.
    DrawIndirect(&'a G::Buffer, u64),
}

/// The attachments of a render pass.
#[derive(Debug)]
pub struct Attachments<'a, G: Gpu + ?Sized> {
    /// Its depth texture (its size is the pass's).
    pub depth: &'a G::Texture,
    /// Its colour target where it is not the frame's: a texture of
    /// [`TextureUsage::DrawnThenSampled`], of the depth's size, left ready to be
    /// sampled.
    pub colour: Option<&'a G::Texture>,
    /// What a clearing colour target is cleared to (linear RGBA).
    pub clear_colour: [f32; 4],
    /// What the pass recipe says of them.
    pub recipe: &'static RenderPassRecipe,
    /// Whether a draw of the pass writes depth.
    pub depth_written: bool,
    /// Whether this is the frame's last pass on the frame's target (it leaves the
    /// target ready to be read or presented).
    pub colour_last: bool,
    /// The draws only within this rectangle, px `(x, y, width, height)`, y down,
    /// within the attachments (`None`: all of them); what is cleared is cleared
    /// whole.
    pub scissor: Option<[u32; 4]>,
}

/// What a pass of the frame is.
#[derive(Debug)]
pub enum PassKind<'a, G: Gpu + ?Sized> {
    /// Compute kernels.
    Compute,
    /// A render pass into these attachments (and the target, if the recipe has
    /// colour).
    Render(Attachments<'a, G>),
    /// The colour target copied, whole, into `colour` (of its size and format) and
    /// the depth texture `depth.0` into `depth.1` (both made with
    /// [`crate::frame_resources::TextureUsage::CopyOfTarget`]); the target and the
    /// depth are left as they were, ready for the next render pass.
    CopyTarget {
        /// The colour target's copy.
        colour: &'a G::Texture,
        /// The depth buffer and its copy.
        depth: (&'a G::Texture, &'a G::Texture),
    },
}

/// One pass of a frame as commands.
#[derive(Debug)]
pub struct RecordedPass<'a, G: Gpu + ?Sized> {
    /// Its name.
    pub name: &'static str,
    /// Whether it runs (a skipped pass keeps its place: its timestamps are written
    /// and not reported).
    pub runs: bool,
    /// Compute or render.
    pub kind: PassKind<'a, G>,
    /// Its commands.
    pub commands: Vec<Command<'a, G>>,
}

/// A frame as the executor records it: every pass of the frame plan in order, each
/// timed by two timestamps (`2·i`, `2·i + 1`) where the device has them.
#[derive(Debug)]
pub struct FrameWork<'a, G: Gpu + ?Sized> {
    /// The passes.
    pub passes: Vec<RecordedPass<'a, G>>,
}

/// The device calls of a GPU backend.
pub trait Gpu {
    /// A buffer.
    type Buffer: std::fmt::Debug;
    /// A 3D `Rgba32Float` texture read with `textureLoad`.
    type Volume: std::fmt::Debug;
    /// A 2D texture with its view.
    type Texture: std::fmt::Debug;
    /// A sampler.
    type Sampler: std::fmt::Debug;
    /// A bind group's layout (a descriptor set layout).
    type GroupLayout: std::fmt::Debug;
    /// A bind group (a descriptor set).
    type BindGroup: std::fmt::Debug;
    /// A compute pipeline with its layout.
    type Kernel: std::fmt::Debug;
    /// A render pipeline with its layout.
    type DrawPipeline: std::fmt::Debug;
    /// A window's image to draw into.
    type Surface: std::fmt::Debug;
    /// A colour target's format (pipelines are made per format).
    type ColourFormat: std::fmt::Debug + Copy + PartialEq;

    /// The backend's name (`BackendInfo::name`).
    fn name(&self) -> &'static str;

    /// The device, in words.
    fn describe(&self) -> String;

    /// What the device allows (checked at configure).
    fn limits(&self) -> precip_model::DeviceLimits;

    /// What the device lets a pipeline bind (checked when a backend is made on
    /// it, [`crate::binding_limits`]).
    fn binding_limits(&self) -> crate::binding_limits::BindingLimits;

    /// Bytes a dynamic offset (uniform or storage) is a multiple of.
    fn uniform_alignment(&self) -> u64;

    /// How many submissions may be in flight at once, each with its own ring of
    /// uniform blocks (1 where writes are ordered with submissions, as on wgpu).
    fn slots(&self) -> u32;

    /// The device memory precip holds, where the allocator tells.
    fn device_memory(&self) -> Option<DeviceMemory>;

    /// A buffer of `bytes` bytes holding `contents` (`None`: undefined; the bytes
    /// given are as long as the buffer).
    fn create_buffer(
        &mut self,
        label: &'static str,
        bytes: u64,
        usage: BufferUsage,
        contents: Option<&[u8]>,
    ) -> Result<Self::Buffer, BackendError>;

    /// Writes `bytes` at `offset`, ordered before the next submission. The caller
    /// has made sure no submitted work reads those bytes ([`Gpu::free_slot`],
    /// [`Gpu::settle`]).
    fn write_buffer(
        &mut self,
        buffer: &mut Self::Buffer,
        offset: u64,
        bytes: &[u8],
    ) -> Result<(), BackendError>;

    /// The first `bytes` bytes, after every submission so far has finished.
    fn read_buffer(&mut self, buffer: &Self::Buffer, bytes: u64) -> Result<Vec<u8>, BackendError>;

    /// A 3D texture of `size` texels of 16 bytes holding `texels`.
    fn create_volume(
        &mut self,
        label: &'static str,
        size: [u32; 3],
        texels: &[u8],
    ) -> Result<Self::Volume, BackendError>;

    /// Replaces every texel of `volume`.
    fn write_volume(&mut self, volume: &Self::Volume, texels: &[u8]) -> Result<(), BackendError>;

    /// A 2D texture as `desc` says.
    fn create_texture(&mut self, desc: &TextureDesc<'_>) -> Result<Self::Texture, BackendError>;

    /// Every texel of `texture` (rows tightly packed), after every submission so far
    /// has finished.
    fn read_texture(&mut self, texture: &Self::Texture) -> Result<Vec<u8>, BackendError>;

    /// A sampler of this kind.
    fn create_sampler(&mut self, sampler: Sampler) -> Result<Self::Sampler, BackendError>;

    /// The layout of `table`.
    fn group_layout(&mut self, table: &GroupLayout) -> Result<Self::GroupLayout, BackendError>;

    /// The kernel `entry_point` of `program`, with groups of `layouts` at 0, 1, ….
    fn kernel(
        &mut self,
        program: Program,
        entry_point: &'static str,
        layouts: &[&Self::GroupLayout],
    ) -> Result<Self::Kernel, BackendError>;

    /// The pipeline of `draw` (entry points of [`Program::Render`]) in a pass of
    /// `pass`, with groups of `layouts`, drawing into targets of `colour` (`None`
    /// where the pass has no colour).
    fn draw_pipeline(
        &mut self,
        draw: &Draw,
        pass: &RenderPassRecipe,
        layouts: &[&Self::GroupLayout],
        colour: Option<Self::ColourFormat>,
    ) -> Result<Self::DrawPipeline, BackendError>;

    /// The format of `target`.
    fn colour_format(&self, target: Target<'_, Self>) -> Self::ColourFormat;

    /// The device rasterises and computes on the CPU (lavapipe): what
    /// `precip_model::Mirrors::Auto` spares it, and how many cover tiles a
    /// workgroup takes (`crate::recipe::COVER_TILES_PER_WORKGROUP`).
    fn rasterises_on_cpu(&self) -> bool;

    /// The format of a copy of `target` ([`PassKind::CopyTarget`]), or `None` when
    /// it cannot be copied (a window whose surface allows no copies, a format with no
    /// [`TexelFormat`]): then the passes that read the copy do not run.
    fn copy_format(&self, target: Target<'_, Self>) -> Option<TexelFormat>;

    /// The size of a texture, px.
    fn texture_size(&self, texture: &Self::Texture) -> (u32, u32);

    /// A bind group of `layout` (made from `table`), each binding filled by its entry.
    fn bind_group(
        &mut self,
        layout: &Self::GroupLayout,
        table: &GroupLayout,
        entries: &[(u32, BindingResource<'_, Self>)],
    ) -> Result<Self::BindGroup, BackendError>;

    /// Waits until the uniform blocks of `slot` (`0..slots()`) may be written: the
    /// last submission that used them has finished.
    fn free_slot(&mut self, slot: u32) -> Result<(), BackendError>;

    /// Waits until no submitted work reads what the host writes next; nothing to
    /// wait for where writes are ordered with submissions (wgpu).
    fn settle(&mut self) -> Result<(), BackendError>;

    /// Records `dispatches` in order, each after the last one's writes, and submits
    /// them without waiting. `timed`: a timestamp before the first and after each,
    /// where the device has timestamps ([`Gpu::kernel_times_ms`]).
    fn dispatch(
        &mut self,
        dispatches: &[Dispatch<'_, Self>],
        timed: bool,
    ) -> Result<(), BackendError>;

    /// The milliseconds each dispatch of the last timed submission took, in order;
    /// `None` where the device has no timestamps or nothing was timed.
    fn kernel_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError>;

    /// Records `frame` into `target` and submits it without waiting: the step's
    /// writes are seen by the frame, each dispatch's by every later command, each
    /// pass's attachments by what reads them next, and the next submission waits for
    /// what the frame reads.
    fn submit_frame(
        &mut self,
        frame: &FrameWork<'_, Self>,
        target: Target<'_, Self>,
    ) -> Result<(), BackendError>;

    /// The milliseconds each pass of the last frame took (`2·i + 1` minus `2·i`),
    /// in order; `None` where the device has no timestamps or no frame was drawn.
    fn frame_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError>;

    /// Forgets the timestamps written so far (a new configuration).
    fn forget_times(&mut self);

    /// Whether the device writes timestamps.
    fn has_timestamps(&self) -> bool;

    /// Hands back a buffer once nothing submitted uses it.
    fn destroy_buffer(&mut self, buffer: Self::Buffer);
    /// Hands back a volume.
    fn destroy_volume(&mut self, volume: Self::Volume);
    /// Hands back a texture.
    fn destroy_texture(&mut self, texture: Self::Texture);
    /// Hands back a sampler (by default, dropping it: an API whose objects
    /// free themselves, as wgpu's, needs nothing more; the same for the four
    /// below).
    fn destroy_sampler(&mut self, sampler: Self::Sampler) {
        drop(sampler);
    }
    /// Hands back a bind group.
    fn destroy_bind_group(&mut self, group: Self::BindGroup) {
        drop(group);
    }
    /// Hands back a kernel.
    fn destroy_kernel(&mut self, kernel: Self::Kernel) {
        drop(kernel);
    }
    /// Hands back a draw pipeline.
    fn destroy_draw_pipeline(&mut self, pipeline: Self::DrawPipeline) {
        drop(pipeline);
    }
    /// Hands back a layout.
    fn destroy_group_layout(&mut self, layout: Self::GroupLayout) {
        drop(layout);
    }
}
