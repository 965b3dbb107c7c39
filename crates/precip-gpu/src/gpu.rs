//! [`Gpu`]: the device calls a backend implements, and nothing else. The executor
//! ([`crate::executor`]) runs the plan over them, so what a configuration
//! allocates, how it is bound, what a step uploads and dispatches and what a query
//! reads back is written once, here, for every backend; `precip-gpu-wgpu` and
//! `precip-gpu-vk` each implement these calls in a file of the same name
//! (`gpu.rs`), in the spirit of wgpu-hal's `Device` and `CommandEncoder`.
//!
//! Resources are owned by the executor and handed back with the `destroy_*` calls
//! (a no-op where the API frees on drop), on every path, errors included.

use precip_model::BackendError;

use crate::bind_groups::GroupLayout;
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
    /// Workgroups `(x, y)`.
    pub workgroups: (u32, u32),
}

/// The device calls of a GPU backend.
pub trait Gpu {
    /// A buffer.
    type Buffer: std::fmt::Debug;
    /// A 3D `Rgba32Float` texture read with `textureLoad`.
    type Volume: std::fmt::Debug;
    /// A bind group's layout (a descriptor set layout).
    type GroupLayout: std::fmt::Debug;
    /// A bind group (a descriptor set).
    type BindGroup: std::fmt::Debug;
    /// A compute pipeline with its layout.
    type Kernel: std::fmt::Debug;

    /// What the device allows (checked at configure).
    fn limits(&self) -> precip_model::DeviceLimits;

    /// Bytes a dynamic uniform offset is a multiple of.
    fn uniform_alignment(&self) -> u64;

    /// How many submissions may be in flight at once, each with its own ring of
    /// uniform blocks (1 where writes are ordered with submissions, as on wgpu).
    fn slots(&self) -> u32;

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

    /// The layout of `table`.
    fn group_layout(&mut self, table: &GroupLayout) -> Result<Self::GroupLayout, BackendError>;

    /// The kernel `entry_point` of `program`, with one group of `layout`.
    fn kernel(
        &mut self,
        program: Program,
        entry_point: &'static str,
        layout: &Self::GroupLayout,
    ) -> Result<Self::Kernel, BackendError>;

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

    /// Hands back a buffer once nothing submitted uses it.
    fn destroy_buffer(&mut self, buffer: Self::Buffer);
    /// Hands back a volume.
    fn destroy_volume(&mut self, volume: Self::Volume);
    /// Hands back a bind group.
    fn destroy_bind_group(&mut self, group: Self::BindGroup);
    /// Hands back a kernel.
    fn destroy_kernel(&mut self, kernel: Self::Kernel);
    /// Hands back a layout.
    fn destroy_group_layout(&mut self, layout: Self::GroupLayout);
}
