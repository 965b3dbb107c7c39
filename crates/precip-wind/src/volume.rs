//! [`WindVolume`]: the baked 3D grid of gust texels, laid out as the GPU uploads it.

use bytemuck::{Pod, Zeroable};
use glam::{UVec3, Vec3};

use crate::error::{WindError, check_range};
use crate::field::WindField;

/// One texel of the wind volume: an `Rgba32Float` texel of the GPU's 3D texture.
///
/// WGSL twin: `textureLoad(wind_volume, ...)` returns `vec4<f32>(sin_alpha,
/// vertical_mps, 0, 0)` (shaders/wind.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct WindTexel {
    /// `sin α`, α ∈ [0, π] from Perlin noise: so in `[0, 1]`.
    pub sin_alpha: f32,
    /// Vertical gust w, m/s, in `[-vertical_gust_mps, vertical_gust_mps]`.
    pub vertical_mps: f32,
    /// Unused (`0`): keeps the texel an RGBA texel.
    pub reserved: [f32; 2],
}
const _: () = assert!(size_of::<WindTexel>() == 16);

/// Size of the wind volume: texels per axis and the extent in metres it tiles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindVolumeSpec {
    /// Texels along X, Y, Z; each in `2..=256`.
    pub texels: UVec3,
    /// Extent covered by one period of the volume, metres; each in `[1, 100000]`.
    pub extent_m: Vec3,
}

impl Default for WindVolumeSpec {
    /// 64 × 32 × 64 texels over 256 × 128 × 256 m: 4 m per texel.
    fn default() -> Self {
        Self {
            texels: UVec3::new(64, 32, 64),
            extent_m: Vec3::new(256.0, 128.0, 256.0),
        }
    }
}

impl WindVolumeSpec {
    /// Checks sizes; the error names the field.
    pub fn validate(&self) -> Result<(), WindError> {
        for (field, n) in [
            ("texels.x", self.texels.x),
            ("texels.y", self.texels.y),
            ("texels.z", self.texels.z),
        ] {
            if !(2..=256).contains(&n) {
                return Err(WindError::OutOfRange {
                    field,
                    value: f64::from(n),
                    allowed: "2..=256 texels per axis",
                });
            }
        }
        for (field, e) in [
            ("extent_m.x", self.extent_m.x),
            ("extent_m.y", self.extent_m.y),
            ("extent_m.z", self.extent_m.z),
        ] {
            check_range(field, e, 1.0, 1.0e5, "[1, 100000] m")?;
        }
        Ok(())
    }

    /// Size of one texel in metres.
    #[must_use]
    pub fn cell_m(&self) -> Vec3 {
        self.extent_m / self.texels.as_vec3()
    }

    /// Number of texels.
    #[must_use]
    pub fn texel_count(&self) -> usize {
        self.texels.x as usize * self.texels.y as usize * self.texels.z as usize
    }
}

/// The baked wind: the field it came from, its size, and its texels.
///
/// Texel `(i, j, k)` sits at `texels[i + nx·(j + ny·k)]` (X fastest, then Y, then Z:
/// rows of X, images of Z, as a 3D texture upload expects), and its centre is at
/// `((i, j, k) + 0.5) · cell_m` in the volume's periodic frame.
#[derive(Debug, Clone, PartialEq)]
pub struct WindVolume {
    /// The field baked.
    pub field: WindField,
    /// The grid.
    pub spec: WindVolumeSpec,
    /// The texels, X fastest.
    pub texels: Vec<WindTexel>,
}

impl WindVolume {
    /// Bakes `field` into a volume of size `spec` (Perlin noise, periodic).
    pub fn bake(field: &WindField, spec: &WindVolumeSpec) -> Result<Self, WindError> {
        field.validate()?;
        spec.validate()?;
        Ok(Self {
            field: *field,
            spec: *spec,
            texels: crate::bake::bake_texels(field, spec),
        })
    }

    /// The texel at integer coordinates, wrapped periodically.
    #[must_use]
    ///
    /// A volume built by hand whose `texels` do not match its `spec` reads as calm
    /// air where they are missing, rather than panicking.
    pub fn texel_wrapped(&self, i: i32, j: i32, k: i32) -> WindTexel {
        let n = self.spec.texels.as_ivec3();
        if n.min_element() <= 0 {
            return WindTexel::default();
        }
        let (i, j, k) = (i.rem_euclid(n.x), j.rem_euclid(n.y), k.rem_euclid(n.z));
        let index = i as usize + n.x as usize * (j as usize + n.y as usize * k as usize);
        self.texels.get(index).copied().unwrap_or_default()
    }

    /// The texels as bytes, ready for a texture upload.
    #[must_use]
    pub fn as_bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.texels)
    }

    /// Replaces the mean wind without re-baking: the texels do not depend on it.
    pub fn set_mean_wind(&mut self, mean_wind_mps: Vec3) {
        self.field.mean_wind_mps = mean_wind_mps;
    }

    /// The volume for a new wind `field`, and whether its texels changed: re-baked
    /// when the noise changed ([`WindField::needs_rebake`]), else this volume with the
    /// new mean wind (nothing to upload). Every backend's `set_weather` goes through
    /// here.
    pub fn for_field(&self, field: &WindField) -> Result<(Self, bool), WindError> {
        if field.needs_rebake(&self.field) {
            Ok((Self::bake(field, &self.spec)?, true))
        } else {
            let mut same = self.clone();
            same.set_mean_wind(field.mean_wind_mps);
            Ok((same, false))
        }
    }
}

/// The wind's uniform block for the GPU.
///
/// WGSL twin: `WindParams` in `shaders/layout.wgsl` (48 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct WindParams {
    /// Mean wind, m/s.
    pub mean_wind_mps: Vec3,
    /// Gust factor μ.
    pub gust_factor: f32,
    /// Extent of one period of the volume, m.
    pub extent_m: Vec3,
    /// Unused (`0`).
    pub reserved0: f32,
    /// Texels per axis.
    pub texels: UVec3,
    /// Unused (`0`).
    pub reserved1: u32,
}
const _: () = assert!(size_of::<WindParams>() == 48);

impl WindVolume {
    /// The uniform block the GPU samples this volume with.
    #[must_use]
    pub fn gpu_params(&self) -> WindParams {
        WindParams {
            mean_wind_mps: self.field.mean_wind_mps,
            gust_factor: self.field.gust_factor,
            extent_m: self.spec.extent_m,
            reserved0: 0.0,
            texels: self.spec.texels,
            reserved1: 0,
        }
    }
}
