//! Several cloud layers at once (docs/model.md (6.15)): up to
//! [`MAX_CLOUD_LAYERS`] layers, lowest first and none overlapping — CIGI 3.3's cloud
//! layers 1–3, or a user's scattered cumulus under an overcast sheet.
//!
//! Each layer reads the one coverage map shifted by its own offset
//! ([`cloud_layer_map_offset_m`]), so two layers' clouds stand independently of each
//! other; every layer drifts with the same mean wind. What a single layer does, the
//! layers do together: the sun reaching a point passes every layer above it (the
//! product of their transmittances), a path's optical depth is the sum of its parts
//! in each layer, and a point lies in at most one layer.
//!
//! WGSL twins: `cloud_layer_map_offset_m` (drawing.wgsl); the march over the layers in
//! `march_clouds` (render_clouds.wgsl).

use glam::{Vec2, Vec3};

use super::{
    CLOUD_MAP_PERIOD_M, CloudLayer, cloud_extinction_at, cloud_optical_depth,
    cloud_sun_transmittance,
};
use crate::BackendError;

/// The most cloud layers drawn at once (CIGI 3.3 has three).
pub const MAX_CLOUD_LAYERS: usize = 3;

/// Where layer `index` reads the coverage map, m, added to the wind's drift: layer 0
/// at the map's origin, each next one shifted along a direction that never returns
/// to a multiple of the map's 12 km period within three layers, so no two layers'
/// clouds stand one above the other.
#[must_use]
pub fn cloud_layer_map_offset_m(index: u32) -> Vec2 {
    let i = index as f32;
    Vec2::new(
        (i * 4_100.0).rem_euclid(CLOUD_MAP_PERIOD_M),
        (i * 7_300.0).rem_euclid(CLOUD_MAP_PERIOD_M),
    )
}

/// Up to [`MAX_CLOUD_LAYERS`] cloud layers, lowest first, none overlapping another.
/// Empty: no clouds (the overcast sky, at no cost).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CloudLayers {
    layers: [Option<CloudLayer>; MAX_CLOUD_LAYERS],
}

impl CloudLayers {
    /// No clouds.
    pub const NONE: Self = Self {
        layers: [None; MAX_CLOUD_LAYERS],
    };

    /// One layer.
    #[must_use]
    pub const fn one(layer: CloudLayer) -> Self {
        Self {
            layers: [Some(layer), None, None],
        }
    }

    /// The layers in `layers`, in any order: sorted by base and checked (each
    /// layer's values, at most [`MAX_CLOUD_LAYERS`] of them, none reaching into the
    /// next one up).
    pub fn new(layers: &[CloudLayer]) -> Result<Self, BackendError> {
        if layers.len() > MAX_CLOUD_LAYERS {
            return Err(BackendError::Setup {
                field: "render.cloud_layers",
                problem: format!(
                    "holds {} layers: at most {MAX_CLOUD_LAYERS} are drawn at once; merge or drop some",
                    layers.len()
                ),
            });
        }
        let mut sorted = layers.to_vec();
        sorted.sort_by(|a, b| a.base_m.total_cmp(&b.base_m));
        let mut out = Self::NONE;
        for (slot, layer) in out.layers.iter_mut().zip(sorted) {
            *slot = Some(layer);
        }
        out.validate()?;
        Ok(out)
    }

    /// Checks each layer ([`CloudLayer::validate`]) and that each lies wholly below
    /// the next.
    pub fn validate(&self) -> Result<(), BackendError> {
        let mut below: Option<CloudLayer> = None;
        for layer in self.iter() {
            layer.validate()?;
            if let Some(lower) = below
                && layer.base_m < lower.top_m()
            {
                return Err(BackendError::Setup {
                    field: "render.cloud_layers",
                    problem: format!(
                        "a layer based at {} m starts inside the one below it ({} – {} m): raise its base to {} m or more, or thin the lower layer",
                        layer.base_m,
                        lower.base_m,
                        lower.top_m(),
                        lower.top_m()
                    ),
                });
            }
            below = Some(*layer);
        }
        Ok(())
    }

    /// The layers, lowest first.
    pub fn iter(&self) -> impl Iterator<Item = &CloudLayer> {
        self.layers.iter().flatten()
    }

    /// The layers with their slot's map offset ([`cloud_layer_map_offset_m`]) plus
    /// `drift_m`, lowest first.
    pub fn with_offsets(&self, drift_m: Vec2) -> impl Iterator<Item = (&CloudLayer, Vec2)> {
        self.iter()
            .zip(0u32..)
            .map(move |(layer, i)| (layer, drift_m + cloud_layer_map_offset_m(i)))
    }

    /// How many layers.
    #[must_use]
    pub fn len(&self) -> usize {
        self.iter().count()
    }

    /// No layer.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.layers[0].is_none()
    }

    /// The lowest layer: the one the precipitation falls from.
    #[must_use]
    pub fn lowest(&self) -> Option<CloudLayer> {
        self.layers[0]
    }

    /// The layer whose `[base, top]` holds the height `y_m`, else the one whose
    /// transition band gives it the largest share ([`CloudLayer::band_share`]),
    /// with its map offset plus `drift_m`.
    #[must_use]
    pub fn containing(&self, y_m: f32, drift_m: Vec2) -> Option<(CloudLayer, Vec2)> {
        self.with_offsets(drift_m)
            .find(|(l, _)| (l.base_m..=l.top_m()).contains(&y_m))
            .or_else(|| {
                self.with_offsets(drift_m)
                    .filter(|(l, _)| l.band_share(y_m) > 0.0)
                    .max_by(|a, b| a.0.band_share(y_m).total_cmp(&b.0.band_share(y_m)))
            })
            .map(|(l, o)| (*l, o))
    }

    /// The share of the sun's light that reaches `p` through every layer
    /// ([`cloud_sun_transmittance`] of each, multiplied).
    #[must_use]
    pub fn sun_transmittance(
        &self,
        noise: &super::CloudNoise,
        drift_m: Vec2,
        p: Vec3,
        to_sun: Vec3,
    ) -> f32 {
        self.with_offsets(drift_m)
            .map(|(layer, offset)| cloud_sun_transmittance(noise, layer, offset, p, to_sun))
            .product()
    }

    /// The clouds' extinction at `p`, per m (0 outside every layer).
    #[must_use]
    pub fn extinction_at(&self, noise: &super::CloudNoise, drift_m: Vec2, p: Vec3) -> f32 {
        self.containing(p.y, drift_m)
            .map_or(0.0, |(layer, offset)| {
                cloud_extinction_at(noise, &layer, offset, p)
            })
    }

    /// The clouds' optical depth from `origin` along the unit `dir` for `length_m`:
    /// the sum of [`cloud_optical_depth`] over the layers.
    #[must_use]
    pub fn optical_depth(
        &self,
        noise: &super::CloudNoise,
        drift_m: Vec2,
        origin: Vec3,
        dir: Vec3,
        length_m: f32,
    ) -> f32 {
        self.with_offsets(drift_m)
            .map(|(layer, offset)| cloud_optical_depth(noise, layer, offset, origin, dir, length_m))
            .sum()
    }
}

impl From<Option<CloudLayer>> for CloudLayers {
    fn from(layer: Option<CloudLayer>) -> Self {
        layer.map_or(Self::NONE, Self::one)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{CloudKind, cloud_noise};
    use super::*;

    fn cumulus_under_stratus() -> CloudLayers {
        CloudLayers::new(&[
            CloudLayer {
                base_m: 4_000.0,
                thickness_m: 500.0,
                coverage: 0.6,
                kind: CloudKind::Stratus,
                transition_band_m: 0.0,
            },
            CloudLayer::typical(CloudKind::Cumulus, 0.5),
        ])
        .expect("valid")
    }

    #[test]
    fn layers_are_sorted_and_may_not_overlap_or_be_too_many() {
        let two = cumulus_under_stratus();
        let bases: Vec<f32> = two.iter().map(|l| l.base_m).collect();
        assert_eq!(bases, [1_000.0, 4_000.0]);
        assert_eq!(two.len(), 2);
        assert_eq!(two.lowest().map(|l| l.kind), Some(CloudKind::Cumulus));
        let cumulus = CloudLayer::typical(CloudKind::Cumulus, 0.5);
        let overlapping = CloudLayer {
            base_m: 2_000.0,
            ..cumulus
        };
        let e = CloudLayers::new(&[cumulus, overlapping]).expect_err("overlap");
        assert!(e.to_string().contains("raise its base to 2500"), "{e}");
        let e = CloudLayers::new(&[cumulus; 4]).expect_err("four");
        assert!(e.to_string().contains("at most 3"), "{e}");
        let bad = CloudLayer {
            coverage: 1.5,
            ..cumulus
        };
        assert!(CloudLayers::new(&[bad]).is_err());
        assert!(CloudLayers::NONE.is_empty());
        assert_eq!(CloudLayers::from(Some(cumulus)), CloudLayers::one(cumulus));
        assert_eq!(CloudLayers::from(None), CloudLayers::NONE);
    }

    #[test]
    fn each_layer_reads_its_own_part_of_the_map() {
        assert_eq!(cloud_layer_map_offset_m(0), Vec2::ZERO);
        // Layers 1 and 2 stand kilometres apart on the 12 km torus from layer 0 and
        // from each other (in x and in z).
        let torus_gap = |a: f32, b: f32| {
            let d = (a - b).rem_euclid(CLOUD_MAP_PERIOD_M);
            d.min(CLOUD_MAP_PERIOD_M - d)
        };
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let (a, b) = (cloud_layer_map_offset_m(i), cloud_layer_map_offset_m(j));
            assert!(torus_gap(a.x, b.x) > 2_000.0 && torus_gap(a.y, b.y) > 2_000.0);
        }
        // So two equal layers' cloudy columns are independent: over a 200 × 200
        // lattice half-covered layers share about a quarter of the columns.
        let map = cloud_noise();
        let layer = CloudLayer::typical(CloudKind::Cumulus, 0.5);
        let (mut both, mut n) = (0usize, 0usize);
        for i in 0..200 {
            for k in 0..200 {
                let p = Vec3::new(i as f32 * 60.0, 1_200.0, k as f32 * 60.0);
                let lower = cloud_extinction_at(map, &layer, cloud_layer_map_offset_m(0), p) > 0.0;
                let upper = cloud_extinction_at(map, &layer, cloud_layer_map_offset_m(1), p) > 0.0;
                both += usize::from(lower && upper);
                n += 1;
            }
        }
        let share = both as f32 / n as f32;
        assert!((0.1..0.3).contains(&share), "{share}");
    }

    #[test]
    fn the_layers_dim_the_sun_and_add_their_depths_together() {
        let map = cloud_noise();
        let two = cumulus_under_stratus();
        let drift = Vec2::new(300.0, -50.0);
        let up = Vec3::new(0.3, 0.9, 0.1).normalize();
        let mut product_checked = 0;
        for i in 0..40 {
            let p = Vec3::new(i as f32 * 337.0, 0.0, i as f32 * 211.0);
            let each: Vec<f32> = two
                .with_offsets(drift)
                .map(|(l, o)| cloud_sun_transmittance(map, l, o, p, up))
                .collect();
            let all = two.sun_transmittance(map, drift, p, up);
            assert!((all - each[0] * each[1]).abs() < 1e-6);
            assert!(all <= each[0] + 1e-6 && all <= each[1] + 1e-6);
            product_checked += usize::from(each[0] < 0.99 && each[1] < 0.99);
            let depth = two.optical_depth(map, drift, p, up, 20_000.0);
            let parts: f32 = two
                .with_offsets(drift)
                .map(|(l, o)| cloud_optical_depth(map, l, o, p, up, 20_000.0))
                .sum();
            assert!((depth - parts).abs() <= 1e-4 * parts.max(1.0));
        }
        assert!(product_checked > 0, "no point under clouds of both layers");
        // A point inside the upper layer takes its extinction, between them none.
        let inside = two.containing(4_200.0, drift).expect("in the stratus");
        assert_eq!(inside.0.kind, CloudKind::Stratus);
        assert_eq!(inside.1, drift + cloud_layer_map_offset_m(1));
        assert!(two.extinction_at(map, drift, Vec3::new(0.0, 3_000.0, 0.0)) <= 0.0);
    }
}
