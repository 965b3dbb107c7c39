//! The WGSL twins of this crate's Rust, for the GPU programs that join them
//! (`precip-gpu`'s shader assembly reads them from here, beside their Rust twins).

/// `cover.wgsl`: the cover texel, the melt and the cover kernel's update, twin of
/// [`crate::update_texel`].
pub const COVER: &str = include_str!("../shaders/cover.wgsl");
/// `blowing.wgsl`: when the wind lifts snow and how much it carries, twin of
/// [`crate::blowing`].
pub const BLOWING: &str = include_str!("../shaders/blowing.wgsl");
/// `deposit.wgsl`: fixed-point deposits, twin of [`crate::deposit_units`].
pub const DEPOSIT: &str = include_str!("../shaders/deposit.wgsl");
/// `shading.wgsl`: the cover as a surface sees it, twin of [`crate::shade_texel`].
pub const SHADING: &str = include_str!("../shaders/shading.wgsl");
/// `cover_update.wgsl`: kernels `cover_update`, `snow_wind`, `snow_outflow`,
/// `snow_inflow`, `water_outflow` and `water_inflow`, twins of [`crate::drift`] and
/// [`crate::water`].
pub const COVER_UPDATE: &str = include_str!("../shaders/cover_update.wgsl");
