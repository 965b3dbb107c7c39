//! How many workgroups a kernel is dispatched over: the arithmetic every GPU
//! backend and the frame's uniform block ([`crate::drawing::render::RenderParams`])
//! share.

/// Invocations per workgroup of every kernel (`@workgroup_size(64)`).
pub const WORKGROUP_SIZE: u32 = 64;

/// Most workgroups along one dispatch dimension (WebGPU's guaranteed minimum).
pub const MAX_WORKGROUPS_PER_DIMENSION: u32 = 65_535;

/// Workgroups `(x, y)` covering `count` invocations in a 2D dispatch (WGSL:
/// `linear_index`), so counts beyond 65535 × 64 fit.
#[must_use]
pub fn dispatch_size(count: u32) -> (u32, u32) {
    let groups = count.div_ceil(WORKGROUP_SIZE).max(1);
    if groups <= MAX_WORKGROUPS_PER_DIMENSION {
        (groups, 1)
    } else {
        let y = groups.div_ceil(MAX_WORKGROUPS_PER_DIMENSION);
        (groups.div_ceil(y), y)
    }
}

/// Workgroups of the culling kernels for `particle_count` particles: every
/// workgroup of the 2D dispatch, padding included (`RenderParams.counts.z`).
#[must_use]
pub fn cull_groups(particle_count: u32) -> u32 {
    let (x, y) = dispatch_size(particle_count);
    x * y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dispatch_covers_every_count() {
        for count in [
            0u32, 1, 64, 65, 4_194_240, 4_194_241, 10_000_000, 67_108_864,
        ] {
            let (x, y) = dispatch_size(count);
            assert!(x <= MAX_WORKGROUPS_PER_DIMENSION && y <= MAX_WORKGROUPS_PER_DIMENSION);
            assert!(
                u64::from(x) * u64::from(y) * 64 >= u64::from(count),
                "{count}"
            );
        }
    }
}
