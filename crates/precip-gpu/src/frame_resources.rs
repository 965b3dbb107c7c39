//! The resources table of the frame: every buffer, texture and sampler drawing adds
//! to a configuration ([`frame_buffers`], [`frame_textures`], [`Sampler`]), the two
//! a target of a given size adds ([`TargetResource`]), and which one fills each
//! binding of the frame's groups ([`FRAME_GROUPS`], [`TARGET_GROUPS`]). The
//! renderer ([`crate::renderer`]) makes them from these tables through the device
//! calls ([`crate::Gpu`]); what exists, how large, with what contents and bound
//! where is decided here, once.

use precip_model::Setup;
use precip_model::drawing::clouds::{
    CLOUD_DETAIL_ATLAS_PX, CLOUD_MAP_PX, CLOUD_SHADOW_MAP_PX, cloud_noise,
};
use precip_model::drawing::render::RenderParams;
use precip_model::drawing::sea::sea_depth_map;
use precip_model::drawing::shore::ShoreFrames;
use precip_model::drawing::{FLAKE_TEXTURE_PX, snowflake_opacity};

use crate::bind_groups::{
    CLOUD_FRESH, CLOUD_IMAGE, CLOUD_IMAGE_B, CLOUD_SHADOW_KERNEL, COVER_TEXTURE, CULL, GroupLayout,
    OCEAN_KERNEL, PARTICLE_DEPTH, PARTICLE_IMAGE, REFLECTIONS, RENDER_FRAME, RENDER_LIGHT,
    SHORE_KERNEL, SNOW_QUADS, SNOW_QUADS_KERNEL, SPLAT, SPLAT_RESOLVE,
};
use crate::recipe::{
    DRAWN_LIST_BYTES_PER_PARTICLE, FrameDraws, GROUP_COUNT_BYTES, OCEAN_ATLAS_PX,
    OCEAN_SPECTRA_BYTES, SNOW_QUAD_BYTES, SPLAT_BYTES_PER_PIXEL, cull_bindings as cb, cull_groups,
    render_bindings as rb, snow_quad_bytes,
};
use crate::resources::{BufferUsage, SimBuffer};

/// A buffer drawing adds to a configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrameBuffer {
    /// The frame's [`RenderParams`], written by the host every frame, bound as a
    /// uniform block and as read-only storage at a dynamic offset (a ring of them
    /// where frames are in flight).
    RenderParams,
    /// The cull kernels' per-workgroup counts.
    GroupCounts,
    /// The drawn lists (sprites, streaks, splats).
    Drawn,
    /// How each particle is drawn this frame.
    DrawnKinds,
    /// [`FrameDraws`]: the two indirect draws and the splat count.
    Draws,
    /// The albedo of the ground the drops refract (`drop_ground` kernel).
    DropGround,
    /// The sea's spectra, transformed in place by the ocean kernels.
    OceanSpectra,
    /// Each snow sprite instance's quad this frame (`recipe::SNOW_QUAD_BYTES`
    /// each, up to `recipe::SNOW_QUAD_CAPACITY`).
    SnowQuads,
    /// The shore's grid: a header, two states, faces and sources
    /// ([`ShoreFrames::initial_buffer`]), stepped by the shore's kernels and read by
    /// the sea's draw; 16 bytes without a shore.
    Shore,
}

/// A row of the frame's buffers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameBufferSpec {
    /// Which.
    pub buffer: FrameBuffer,
    /// A label for debuggers.
    pub label: &'static str,
    /// Bytes (of one block for [`BufferUsage::FrameBlocks`]: one per slot).
    pub bytes: u64,
    /// Usage.
    pub usage: BufferUsage,
    /// What it holds at first (`None`: undefined).
    pub contents: Option<Vec<u8>>,
}

/// The frame's buffers for `particle_count` particles and the sea's `shore`, with
/// the snow quads kept or not (`snow_quads`, `RenderSettings::snow_quads`: off, one
/// quad, the least a binding of them holds, so every corner past the first
/// instance's makes its own).
#[must_use]
pub fn frame_buffers(
    particle_count: u32,
    shore: Option<&ShoreFrames>,
    snow_quads: bool,
) -> [FrameBufferSpec; 9] {
    let count = u64::from(particle_count);
    let spec = |buffer, label, bytes: u64, usage| FrameBufferSpec {
        buffer,
        label,
        bytes: bytes.max(16),
        usage,
        contents: None,
    };
    let shore_words = shore.map_or_else(|| vec![[0.0f32; 4]], ShoreFrames::initial_buffer);
    let shore_bytes: Vec<u8> = bytemuck::cast_slice(&shore_words).to_vec();
    [
        spec(
            FrameBuffer::RenderParams,
            "precip render params",
            size_of::<RenderParams>() as u64,
            BufferUsage::FrameBlocks,
        ),
        spec(
            FrameBuffer::GroupCounts,
            "precip cull groups",
            u64::from(cull_groups(particle_count)) * GROUP_COUNT_BYTES,
            BufferUsage::Storage,
        ),
        spec(
            FrameBuffer::Drawn,
            "precip drawn",
            count * DRAWN_LIST_BYTES_PER_PARTICLE,
            BufferUsage::Storage,
        ),
        spec(
            FrameBuffer::DrawnKinds,
            "precip drawn kinds",
            count * 4,
            BufferUsage::Storage,
        ),
        spec(
            FrameBuffer::Draws,
            "precip draws",
            FrameDraws::BYTES,
            BufferUsage::Indirect,
        ),
        spec(
            FrameBuffer::SnowQuads,
            "precip snow quads",
            if snow_quads {
                snow_quad_bytes(particle_count)
            } else {
                SNOW_QUAD_BYTES
            },
            BufferUsage::Storage,
        ),
        spec(
            FrameBuffer::DropGround,
            "precip drop ground",
            8,
            BufferUsage::Storage,
        ),
        spec(
            FrameBuffer::OceanSpectra,
            "precip ocean spectra",
            OCEAN_SPECTRA_BYTES,
            BufferUsage::Storage,
        ),
        FrameBufferSpec {
            buffer: FrameBuffer::Shore,
            label: "precip shore",
            bytes: shore_bytes.len() as u64,
            usage: BufferUsage::Storage,
            contents: Some(shore_bytes),
        },
    ]
}

/// A texture drawing adds to a configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrameTexture {
    /// The sun's depth map: drawn by the shadow pass, sampled by the scene.
    ShadowMap,
    /// The cover's first filtered texture (depth mm, SWE mm, peak SWE mm, wetness).
    CoverA,
    /// The second (accumulation mask, melt mask, age days, puddle ratio).
    CoverB,
    /// The third (sand and dust settled, kg/m²).
    CoverC,
    /// The flake's opacity.
    Flake,
    /// The clouds' coverage map.
    CloudMap,
    /// The clouds' detail: the slices of a tiling 3D noise side by side.
    CloudDetail,
    /// The clouds' shadow map: written by a kernel while a layer is drawn, sampled
    /// by the lit draws.
    CloudShadow,
    /// The sea's displacement atlas: written by `ocean_resolve` while a sea is
    /// drawn, read by its draw.
    OceanDisplacement,
    /// The sea's slope atlas (slopes and the Jacobian), likewise.
    OceanSlope,
    /// The water's depth under the sea's level over the ground grid
    /// (`precip_model::drawing::sea::sea_depth_map`): where the waves shoal.
    SeaDepth,
}

/// A texel format of the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexelFormat {
    /// 32-bit float depth.
    Depth32Float,
    /// Four 16-bit floats (filterable, a storage format).
    Rgba16Float,
    /// One 8-bit unsigned normalised channel.
    R8Unorm,
    /// Four 8-bit unsigned normalised channels (linear).
    Rgba8Unorm,
    /// Four 8-bit sRGB channels (base colour textures, the offscreen image).
    Rgba8UnormSrgb,
    /// Four 8-bit sRGB channels, blue first (a window's usual format: the copy of
    /// such a target).
    Bgra8UnormSrgb,
}

impl TexelFormat {
    /// Bytes of a texel.
    #[must_use]
    pub const fn texel_bytes(self) -> u32 {
        match self {
            Self::Depth32Float | Self::Rgba8Unorm | Self::Rgba8UnormSrgb | Self::Bgra8UnormSrgb => {
                4
            }
            Self::Rgba16Float => 8,
            Self::R8Unorm => 1,
        }
    }
}

/// How a frame texture is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureUsage {
    /// A depth attachment, then sampled.
    DepthAttachment,
    /// Written by a kernel as a storage texture and sampled by the draws (and copied
    /// back by tools): kept in one layout for both.
    StorageAndSampled,
    /// Filled once from the host, then sampled.
    Sampled,
    /// The frame's colour target (drawn into, then copied back).
    ColourTarget,
    /// A copy of the colour target or of the camera's depth (copied into each
    /// frame, then sampled).
    CopyOfTarget,
    /// Drawn into by a render pass, then sampled by a later one (the particles'
    /// image); it rests ready to be sampled.
    DrawnThenSampled,
}

/// A row of the frame's textures.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextureSpec {
    /// Which.
    pub texture: FrameTexture,
    /// A label for debuggers.
    pub label: &'static str,
    /// Width and height, texels.
    pub size: [u32; 2],
    /// Format.
    pub format: TexelFormat,
    /// Usage.
    pub usage: TextureUsage,
    /// Texels to fill it with (tightly packed rows), if any.
    pub contents: Option<Vec<u8>>,
}

/// The frame's textures for `setup`: the shadow map at its resolution, the cover's
/// three textures over its grid, the flake's opacity.
#[must_use]
pub fn frame_textures(setup: &Setup) -> Vec<TextureSpec> {
    let shadow = setup.render.shadow_map_px;
    let texels = setup.cover.frame.texels;
    let cover = |texture, label| TextureSpec {
        texture,
        label,
        size: [texels.x, texels.y],
        format: TexelFormat::Rgba16Float,
        usage: TextureUsage::StorageAndSampled,
        contents: None,
    };
    vec![
        TextureSpec {
            texture: FrameTexture::ShadowMap,
            label: "precip shadow map",
            size: [shadow, shadow],
            format: TexelFormat::Depth32Float,
            usage: TextureUsage::DepthAttachment,
            contents: None,
        },
        cover(FrameTexture::CoverA, "precip cover a"),
        cover(FrameTexture::CoverB, "precip cover b"),
        cover(FrameTexture::CoverC, "precip cover c"),
        TextureSpec {
            texture: FrameTexture::Flake,
            label: "precip flake opacity",
            size: [FLAKE_TEXTURE_PX, FLAKE_TEXTURE_PX],
            format: TexelFormat::R8Unorm,
            usage: TextureUsage::Sampled,
            contents: Some(snowflake_opacity(FLAKE_TEXTURE_PX)),
        },
        TextureSpec {
            texture: FrameTexture::CloudMap,
            label: "precip cloud coverage map",
            size: [CLOUD_MAP_PX, CLOUD_MAP_PX],
            format: TexelFormat::R8Unorm,
            usage: TextureUsage::Sampled,
            contents: Some(cloud_noise().coverage.clone()),
        },
        TextureSpec {
            texture: FrameTexture::CloudDetail,
            label: "precip cloud detail",
            size: [CLOUD_DETAIL_ATLAS_PX, CLOUD_DETAIL_ATLAS_PX],
            format: TexelFormat::Rgba8Unorm,
            usage: TextureUsage::Sampled,
            contents: Some(cloud_noise().detail.clone()),
        },
        TextureSpec {
            texture: FrameTexture::CloudShadow,
            label: "precip cloud shadow map",
            size: [CLOUD_SHADOW_MAP_PX, CLOUD_SHADOW_MAP_PX],
            format: TexelFormat::Rgba16Float,
            usage: TextureUsage::StorageAndSampled,
            contents: None,
        },
        TextureSpec {
            texture: FrameTexture::OceanDisplacement,
            label: "precip ocean displacement",
            size: OCEAN_ATLAS_PX,
            format: TexelFormat::Rgba16Float,
            usage: TextureUsage::StorageAndSampled,
            contents: None,
        },
        TextureSpec {
            texture: FrameTexture::OceanSlope,
            label: "precip ocean slope",
            size: OCEAN_ATLAS_PX,
            format: TexelFormat::Rgba16Float,
            usage: TextureUsage::StorageAndSampled,
            contents: None,
        },
        sea_depth(setup),
    ]
}

/// The sea's depth map over the ground grid; one deep texel without a sea.
fn sea_depth(setup: &Setup) -> TextureSpec {
    let frame = setup.ground.frame;
    let depths = setup
        .scene
        .as_ref()
        .map(|s| sea_depth_map(s, frame))
        .unwrap_or_default();
    let (size, contents) = if depths.is_empty() {
        ([1, 1], vec![u8::MAX])
    } else {
        ([frame.texels.x, frame.texels.y], depths)
    };
    TextureSpec {
        texture: FrameTexture::SeaDepth,
        label: "precip sea depth",
        size,
        format: TexelFormat::R8Unorm,
        usage: TextureUsage::Sampled,
        contents: Some(contents),
    }
}

/// A sampler of the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sampler {
    /// Linear, clamped to the edge.
    LinearClamp,
    /// The shadow map's: a less-or-equal comparison, linear.
    ShadowComparison,
    /// Linear, repeating (the materials' base colour).
    LinearRepeat,
}

/// What a target of a given size adds (made again when the size changes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TargetResource {
    /// The camera's depth buffer (an attachment, read by the splat kernel).
    CameraDepth,
    /// The splat's sums, [`SPLAT_BYTES_PER_PIXEL`] a pixel, zero at first (the
    /// resolve zeroes what it reads).
    SplatSums,
    /// The frame as the scene pass left it ([`crate::frame::PassWork::CopyTarget`]),
    /// in the target's format, for the next frame's reflections.
    SceneCopy,
    /// The camera's depth as the scene pass left it, likewise.
    DepthCopy,
    /// The particles' image ([`crate::frame::ColourTarget::Particles`]):
    /// `Rgba16Float`, [`precip_model::ParticleResolution::drawn_size`] of the
    /// target (1 × 1 where particles are drawn at the frame's resolution).
    ParticleImage,
    /// Its depth buffer ([`crate::frame::DepthTarget::Particles`]), of its size.
    ParticleDepth,
    /// The water bodies' mirror image ([`crate::frame::ColourTarget::Mirror`]):
    /// `Rgba16Float`, the target's size over
    /// [`precip_model::drawing::water_mirror::MIRROR_DOWNSCALE`] (1 × 1 where the
    /// scene has no water body at a level).
    MirrorImage,
    /// Its depth buffer ([`crate::frame::DepthTarget::Mirror`]), of its size.
    MirrorDepth,
    /// The clouds' image ([`crate::frame::ColourTarget::Clouds`]): `Rgba16Float`,
    /// [`CLOUD_DOWNSCALE`] times smaller along each side than the target; written on
    /// alternate frames with [`TargetResource::CloudImageB`], each read as the frame
    /// before's by the other's pass.
    CloudImage,
    /// The clouds' second image ([`crate::frame::ColourTarget::CloudsB`]), alike.
    CloudImageB,
    /// Its depth buffer ([`crate::frame::DepthTarget::Clouds`]), of its size.
    CloudDepth,
    /// The clouds' fresh image ([`crate::frame::ColourTarget::CloudsFresh`]):
    /// `Rgba16Float`, [`precip_model::drawing::clouds::CLOUD_MARCH_BLOCK_PX`] times
    /// smaller along each side than the clouds' image: the one pixel of each
    /// block a frame marches, which the clouds' pass takes and clamps the rest's
    /// history to.
    CloudFresh,
    /// Its depth buffer ([`crate::frame::DepthTarget::CloudsFresh`]), of its size.
    CloudFreshDepth,
}

/// A texture a target of one size adds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TargetTextureSpec {
    /// Which.
    pub resource: TargetResource,
    /// A label for debuggers.
    pub label: &'static str,
    /// Width and height, texels.
    pub size: (u32, u32),
    /// Format.
    pub format: TexelFormat,
    /// Usage.
    pub usage: TextureUsage,
}

/// The textures a `size` target adds: the camera's depth, the copies of the scene
/// (in `copy_format`) and of the depth, the particles' image at `particles` (1 × 1
/// at the frame's resolution: unused), the water bodies' mirror image
/// (1 × 1 unless `mirrors`), the clouds' two images (a quarter of the side: a cloud
/// layer may come while running) and their fresh image (a quarter of that), each
/// image with its depth buffer.
#[must_use]
pub fn target_textures(
    size: (u32, u32),
    copy_format: TexelFormat,
    particles: precip_model::ParticleResolution,
    mirrors: bool,
) -> [TargetTextureSpec; 12] {
    use TargetResource as R;
    use TexelFormat::{Depth32Float, Rgba16Float};
    use TextureUsage::{CopyOfTarget, DepthAttachment, DrawnThenSampled};
    let particle_size = match particles {
        precip_model::ParticleResolution::Full => (1, 1),
        reduced => reduced.drawn_size(size),
    };
    let downscale = precip_model::drawing::water_mirror::MIRROR_DOWNSCALE;
    let mirror_size = if mirrors {
        (size.0.div_ceil(downscale), size.1.div_ceil(downscale))
    } else {
        (1, 1)
    };
    let cloud_size = (
        size.0.div_ceil(CLOUD_DOWNSCALE),
        size.1.div_ceil(CLOUD_DOWNSCALE),
    );
    let block = precip_model::drawing::clouds::CLOUD_MARCH_BLOCK_PX;
    let fresh_size = (cloud_size.0.div_ceil(block), cloud_size.1.div_ceil(block));
    let spec = |resource, label, size, format, usage| TargetTextureSpec {
        resource,
        label,
        size,
        format,
        usage,
    };
    [
        spec(
            R::CameraDepth,
            "precip depth",
            size,
            Depth32Float,
            DepthAttachment,
        ),
        spec(
            R::SceneCopy,
            "precip scene copy",
            size,
            copy_format,
            CopyOfTarget,
        ),
        spec(
            R::DepthCopy,
            "precip depth copy",
            size,
            Depth32Float,
            CopyOfTarget,
        ),
        spec(
            R::ParticleImage,
            "precip particle image",
            particle_size,
            Rgba16Float,
            DrawnThenSampled,
        ),
        spec(
            R::ParticleDepth,
            "precip particle depth",
            particle_size,
            Depth32Float,
            DepthAttachment,
        ),
        spec(
            R::MirrorImage,
            "precip mirror image",
            mirror_size,
            Rgba16Float,
            DrawnThenSampled,
        ),
        spec(
            R::MirrorDepth,
            "precip mirror depth",
            mirror_size,
            Depth32Float,
            DepthAttachment,
        ),
        spec(
            R::CloudImage,
            "precip cloud image",
            cloud_size,
            Rgba16Float,
            DrawnThenSampled,
        ),
        spec(
            R::CloudImageB,
            "precip cloud image b",
            cloud_size,
            Rgba16Float,
            DrawnThenSampled,
        ),
        spec(
            R::CloudDepth,
            "precip cloud depth",
            cloud_size,
            Depth32Float,
            DepthAttachment,
        ),
        spec(
            R::CloudFresh,
            "precip cloud fresh image",
            fresh_size,
            Rgba16Float,
            DrawnThenSampled,
        ),
        spec(
            R::CloudFreshDepth,
            "precip cloud fresh depth",
            fresh_size,
            Depth32Float,
            DepthAttachment,
        ),
    ]
}

/// Frame pixels along each side per pixel of the clouds' image.
pub const CLOUD_DOWNSCALE: u32 = 4;

/// Bytes of the splat sums of a `width × height` target.
#[must_use]
pub fn splat_sums_bytes((width, height): (u32, u32)) -> u64 {
    u64::from(width) * u64::from(height) * SPLAT_BYTES_PER_PIXEL
}

/// What fills a binding of the frame's groups.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameBound {
    /// A buffer of the simulation.
    Sim(SimBuffer),
    /// A buffer of the frame.
    Buffer(FrameBuffer),
    /// A texture, sampled.
    Texture(FrameTexture),
    /// A texture, written by a kernel.
    StorageTexture(FrameTexture),
    /// A sampler.
    Sampler(Sampler),
    /// A resource of the target.
    Target(TargetResource),
}

/// A group of the frame as data: its layout's table and what fills each binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameGroupFill {
    /// The layout.
    pub layout: &'static GroupLayout,
    /// Binding number and what fills it, one per binding of the layout.
    pub bound: &'static [(u32, FrameBound)],
}

/// The groups made once per configuration (the material group is the scene's).
pub const FRAME_GROUPS: [FrameGroupFill; 9] = [
    FrameGroupFill {
        layout: &RENDER_FRAME,
        bound: &[
            (rb::PARAMS, FrameBound::Buffer(FrameBuffer::RenderParams)),
            (
                rb::PARAMS_SWITCHES,
                FrameBound::Buffer(FrameBuffer::RenderParams),
            ),
            (rb::GROUND_HEIGHT, FrameBound::Sim(SimBuffer::Ground)),
            (rb::WAVES, FrameBound::Sim(SimBuffer::Waves)),
            (rb::PARTICLES, FrameBound::Sim(SimBuffer::Particles)),
            (rb::DRAWN, FrameBound::Buffer(FrameBuffer::Drawn)),
            (rb::COVER_A, FrameBound::Texture(FrameTexture::CoverA)),
            (rb::COVER_B, FrameBound::Texture(FrameTexture::CoverB)),
            (rb::COVER_C, FrameBound::Texture(FrameTexture::CoverC)),
            (rb::COVER_SAMPLER, FrameBound::Sampler(Sampler::LinearClamp)),
            (rb::DROP_GROUND, FrameBound::Buffer(FrameBuffer::DropGround)),
            (rb::CLOUD_MAP, FrameBound::Texture(FrameTexture::CloudMap)),
            (
                rb::CLOUD_DETAIL,
                FrameBound::Texture(FrameTexture::CloudDetail),
            ),
            (
                rb::CLOUD_SAMPLER,
                FrameBound::Sampler(Sampler::LinearRepeat),
            ),
            (
                rb::CLOUD_SHADOW,
                FrameBound::Texture(FrameTexture::CloudShadow),
            ),
            (
                rb::OCEAN_DISPLACEMENT,
                FrameBound::Texture(FrameTexture::OceanDisplacement),
            ),
            (
                rb::OCEAN_SLOPE,
                FrameBound::Texture(FrameTexture::OceanSlope),
            ),
            (rb::SEA_DEPTH, FrameBound::Texture(FrameTexture::SeaDepth)),
            (rb::SHORE, FrameBound::Buffer(FrameBuffer::Shore)),
        ],
    },
    FrameGroupFill {
        layout: &SHORE_KERNEL,
        bound: &[
            (rb::PARAMS, FrameBound::Buffer(FrameBuffer::RenderParams)),
            (
                rb::PARAMS_SWITCHES,
                FrameBound::Buffer(FrameBuffer::RenderParams),
            ),
            (rb::SHORE_CELLS, FrameBound::Buffer(FrameBuffer::Shore)),
        ],
    },
    FrameGroupFill {
        layout: &OCEAN_KERNEL,
        bound: &[
            (rb::PARAMS, FrameBound::Buffer(FrameBuffer::RenderParams)),
            (
                rb::PARAMS_SWITCHES,
                FrameBound::Buffer(FrameBuffer::RenderParams),
            ),
            (
                rb::OCEAN_SPECTRA,
                FrameBound::Buffer(FrameBuffer::OceanSpectra),
            ),
            (
                rb::OCEAN_DISPLACEMENT_OUT,
                FrameBound::StorageTexture(FrameTexture::OceanDisplacement),
            ),
            (
                rb::OCEAN_SLOPE_OUT,
                FrameBound::StorageTexture(FrameTexture::OceanSlope),
            ),
        ],
    },
    FrameGroupFill {
        layout: &CLOUD_SHADOW_KERNEL,
        bound: &[
            (rb::PARAMS, FrameBound::Buffer(FrameBuffer::RenderParams)),
            (
                rb::PARAMS_SWITCHES,
                FrameBound::Buffer(FrameBuffer::RenderParams),
            ),
            (rb::CLOUD_MAP, FrameBound::Texture(FrameTexture::CloudMap)),
            (
                rb::CLOUD_DETAIL,
                FrameBound::Texture(FrameTexture::CloudDetail),
            ),
            (
                rb::CLOUD_SAMPLER,
                FrameBound::Sampler(Sampler::LinearRepeat),
            ),
            (
                rb::CLOUD_SHADOW_OUT,
                FrameBound::StorageTexture(FrameTexture::CloudShadow),
            ),
        ],
    },
    FrameGroupFill {
        layout: &SNOW_QUADS,
        bound: &[(rb::SNOW_QUADS, FrameBound::Buffer(FrameBuffer::SnowQuads))],
    },
    FrameGroupFill {
        layout: &SNOW_QUADS_KERNEL,
        bound: &[
            (rb::SPLAT_DRAWS, FrameBound::Buffer(FrameBuffer::Draws)),
            (
                rb::SNOW_QUADS_OUT,
                FrameBound::Buffer(FrameBuffer::SnowQuads),
            ),
        ],
    },
    FrameGroupFill {
        layout: &RENDER_LIGHT,
        bound: &[
            (rb::SHADOW_MAP, FrameBound::Texture(FrameTexture::ShadowMap)),
            (
                rb::SHADOW_SAMPLER,
                FrameBound::Sampler(Sampler::ShadowComparison),
            ),
            (rb::FLAKE_OPACITY, FrameBound::Texture(FrameTexture::Flake)),
            (rb::FLAKE_SAMPLER, FrameBound::Sampler(Sampler::LinearClamp)),
        ],
    },
    FrameGroupFill {
        layout: &CULL,
        bound: &[
            (cb::PARAMS, FrameBound::Buffer(FrameBuffer::RenderParams)),
            (cb::PARTICLES, FrameBound::Sim(SimBuffer::Particles)),
            (
                cb::GROUP_COUNTS,
                FrameBound::Buffer(FrameBuffer::GroupCounts),
            ),
            (cb::DRAWN, FrameBound::Buffer(FrameBuffer::Drawn)),
            (cb::DRAWS, FrameBound::Buffer(FrameBuffer::Draws)),
            (cb::DRAWN_KINDS, FrameBound::Buffer(FrameBuffer::DrawnKinds)),
            (cb::SNOW_QUADS, FrameBound::Buffer(FrameBuffer::SnowQuads)),
        ],
    },
    FrameGroupFill {
        layout: &COVER_TEXTURE,
        bound: &[
            (rb::PARAMS, FrameBound::Buffer(FrameBuffer::RenderParams)),
            (rb::COVER, FrameBound::Sim(SimBuffer::Cover)),
            (
                rb::DROP_GROUND_OUT,
                FrameBound::Buffer(FrameBuffer::DropGround),
            ),
            (
                rb::COVER_A_OUT,
                FrameBound::StorageTexture(FrameTexture::CoverA),
            ),
            (
                rb::COVER_B_OUT,
                FrameBound::StorageTexture(FrameTexture::CoverB),
            ),
            (
                rb::COVER_C_OUT,
                FrameBound::StorageTexture(FrameTexture::CoverC),
            ),
        ],
    },
];

/// The groups made for a target's size (the splat kernel's, its resolve's, the
/// reflections', the reduced particles' and their composite's).
pub const TARGET_GROUPS: [FrameGroupFill; 8] = [
    FrameGroupFill {
        layout: &SPLAT,
        bound: &[
            (
                rb::SPLAT_SCENE_DEPTH,
                FrameBound::Target(TargetResource::CameraDepth),
            ),
            (
                rb::SPLAT_SUMS,
                FrameBound::Target(TargetResource::SplatSums),
            ),
            (rb::SPLAT_DRAWS, FrameBound::Buffer(FrameBuffer::Draws)),
        ],
    },
    FrameGroupFill {
        layout: &SPLAT_RESOLVE,
        bound: &[(
            rb::RESOLVED_SUMS,
            FrameBound::Target(TargetResource::SplatSums),
        )],
    },
    FrameGroupFill {
        layout: &REFLECTIONS,
        bound: &[
            (
                rb::SCENE_COPY,
                FrameBound::Target(TargetResource::SceneCopy),
            ),
            (
                rb::DEPTH_COPY,
                FrameBound::Target(TargetResource::DepthCopy),
            ),
            (
                rb::MIRROR_IMAGE,
                FrameBound::Target(TargetResource::MirrorImage),
            ),
        ],
    },
    FrameGroupFill {
        layout: &PARTICLE_DEPTH,
        bound: &[
            (
                rb::PARTICLE_SCENE_DEPTH,
                FrameBound::Target(TargetResource::CameraDepth),
            ),
            (rb::SNOW_QUADS, FrameBound::Buffer(FrameBuffer::SnowQuads)),
        ],
    },
    FrameGroupFill {
        layout: &CLOUD_IMAGE,
        bound: &[(
            rb::CLOUD_IMAGE,
            FrameBound::Target(TargetResource::CloudImage),
        )],
    },
    FrameGroupFill {
        layout: &CLOUD_IMAGE_B,
        bound: &[(
            rb::CLOUD_IMAGE,
            FrameBound::Target(TargetResource::CloudImageB),
        )],
    },
    FrameGroupFill {
        layout: &CLOUD_FRESH,
        bound: &[(
            rb::CLOUD_FRESH,
            FrameBound::Target(TargetResource::CloudFresh),
        )],
    },
    FrameGroupFill {
        layout: &PARTICLE_IMAGE,
        bound: &[
            (
                rb::RESOLVED_SUMS,
                FrameBound::Target(TargetResource::SplatSums),
            ),
            (
                rb::PARTICLE_IMAGE,
                FrameBound::Target(TargetResource::ParticleImage),
            ),
        ],
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bind_groups::BindingKind;

    #[test]
    fn every_binding_of_each_frame_group_is_filled_once_by_its_kind() {
        for fill in FRAME_GROUPS.iter().chain(&TARGET_GROUPS) {
            assert_eq!(
                fill.bound.len(),
                fill.layout.bindings.len(),
                "{}",
                fill.layout.name
            );
            for b in fill.layout.bindings {
                let bound: Vec<_> = fill
                    .bound
                    .iter()
                    .filter(|(k, _)| *k == b.binding)
                    .map(|(_, r)| *r)
                    .collect();
                assert_eq!(bound.len(), 1, "{} binding {}", fill.layout.name, b.binding);
                let fits = matches!(
                    (b.kind, bound[0]),
                    (
                        BindingKind::Uniform { .. } | BindingKind::Storage { .. },
                        FrameBound::Sim(_) | FrameBound::Buffer(_),
                    ) | (
                        BindingKind::Storage { .. },
                        FrameBound::Target(TargetResource::SplatSums),
                    ) | (
                        BindingKind::Texture { .. },
                        FrameBound::Texture(_)
                            | FrameBound::Target(
                                TargetResource::CameraDepth
                                    | TargetResource::SceneCopy
                                    | TargetResource::DepthCopy
                                    | TargetResource::ParticleImage
                                    | TargetResource::MirrorImage
                                    | TargetResource::CloudImage
                                    | TargetResource::CloudImageB
                                    | TargetResource::CloudFresh
                            ),
                    ) | (
                        BindingKind::StorageTextureRgba16Float,
                        FrameBound::StorageTexture(_)
                    ) | (BindingKind::Sampler { .. }, FrameBound::Sampler(_))
                );
                assert!(
                    fits,
                    "{} binding {}: {:?}",
                    fill.layout.name, b.binding, bound[0]
                );
            }
        }
    }

    #[test]
    fn a_target_s_textures_are_one_row_each_and_sized_by_their_settings() {
        use precip_model::ParticleResolution;
        let size = (1279, 719);
        let full = target_textures(
            size,
            TexelFormat::Bgra8UnormSrgb,
            ParticleResolution::Full,
            false,
        );
        for row in &full {
            let rows = full.iter().filter(|t| t.resource == row.resource).count();
            assert_eq!(rows, 1, "{:?}", row.resource);
            assert_ne!(
                row.resource,
                TargetResource::SplatSums,
                "a buffer, not a texture"
            );
        }
        let size_of = |rows: &[TargetTextureSpec], r| {
            rows.iter()
                .find(|t| t.resource == r)
                .map(|t| t.size)
                .expect("a row")
        };
        assert_eq!(size_of(&full, TargetResource::CameraDepth), size);
        assert_eq!(size_of(&full, TargetResource::SceneCopy), size);
        // Unused images are a texel.
        assert_eq!(size_of(&full, TargetResource::ParticleImage), (1, 1));
        assert_eq!(size_of(&full, TargetResource::MirrorImage), (1, 1));
        // The clouds' image is always a quarter of the side (a layer may come).
        assert_eq!(size_of(&full, TargetResource::CloudImage), (320, 180));
        assert_eq!(size_of(&full, TargetResource::CloudImageB), (320, 180));
        // Its fresh image a quarter of that.
        assert_eq!(size_of(&full, TargetResource::CloudFresh), (80, 45));
        assert_eq!(size_of(&full, TargetResource::CloudFreshDepth), (80, 45));
        let reduced = target_textures(
            size,
            TexelFormat::Rgba8UnormSrgb,
            ParticleResolution::Half,
            true,
        );
        assert_eq!(size_of(&reduced, TargetResource::ParticleImage), (640, 360));
        assert_eq!(size_of(&reduced, TargetResource::ParticleDepth), (640, 360));
        assert_eq!(size_of(&reduced, TargetResource::MirrorImage), (640, 360));
        assert_eq!(size_of(&reduced, TargetResource::MirrorDepth), (640, 360));
        assert_eq!(
            reduced
                .iter()
                .find(|t| t.resource == TargetResource::SceneCopy)
                .map(|t| t.format),
            Some(TexelFormat::Rgba8UnormSrgb)
        );
    }

    #[test]
    fn the_frame_is_sized_from_the_configuration() {
        let setup = Setup::over_flat_ground(20.0, 8, 10.0, 300);
        let buffers = frame_buffers(300, None, true);
        let bytes_of = |buffers: &[FrameBufferSpec], which| {
            buffers.iter().find(|b| b.buffer == which).map(|b| b.bytes)
        };
        assert_eq!(
            bytes_of(&buffers, FrameBuffer::Drawn),
            Some(300 * DRAWN_LIST_BYTES_PER_PARTICLE)
        );
        // A quad for each particle's most copies; one (the least a binding
        // holds) when they are not kept.
        assert_eq!(
            bytes_of(&buffers, FrameBuffer::SnowQuads),
            Some(300 * 4 * SNOW_QUAD_BYTES)
        );
        let without = frame_buffers(300, None, false);
        assert_eq!(
            bytes_of(&without, FrameBuffer::SnowQuads),
            Some(SNOW_QUAD_BYTES)
        );
        let textures = frame_textures(&setup);
        for t in &textures {
            if let Some(c) = &t.contents {
                assert_eq!(
                    c.len() as u32,
                    t.size[0] * t.size[1] * t.format.texel_bytes(),
                    "{:?}",
                    t.texture
                );
            }
        }
        let cover = textures.iter().find(|t| t.texture == FrameTexture::CoverA);
        assert_eq!(cover.map(|t| t.size), Some([8, 8]));
        assert_eq!(splat_sums_bytes((4, 2)), 8 * SPLAT_BYTES_PER_PIXEL);
    }
}
