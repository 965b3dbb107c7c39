//! What the snow has done on the scene, in a line: the headless summary and the
//! window's title (sampled with [`crate::water_summary::WaterSummary`]) report it from
//! the cover read back.

use precip_model::cover::CoverGrid;

/// The snow on the scene's surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SnowSummary {
    /// Mean snow depth over the grid, mm.
    pub mean_depth_mm: f64,
    /// The deepest snow, mm.
    pub deepest_mm: f64,
    /// The steepest face of snow, degrees
    /// ([`CoverGrid::steepest_snow_slope_deg`]).
    pub steepest_deg: f32,
    /// Area where snow is blowing, m².
    pub blowing_area_m2: f64,
    /// Snow the wind brought over the grid's edges minus what it blew off, kg.
    pub drifted_in_kg: f64,
    /// Sand and dust settled on the grid, kg.
    pub dust_kg: f64,
    /// The most sand and dust on one texel, kg/m².
    pub dust_heaviest_kg_m2: f32,
}

impl SnowSummary {
    /// From a cover read back.
    #[must_use]
    pub fn of(cover: &CoverGrid) -> Self {
        let totals = cover.totals();
        Self {
            mean_depth_mm: totals.mean_snow_depth_mm(),
            deepest_mm: totals.max_snow_depth_mm,
            steepest_deg: cover.steepest_snow_slope_deg(),
            blowing_area_m2: totals.blowing_area_m2,
            drifted_in_kg: totals.edge_drifted_kg,
            dust_kg: totals.dust_kg,
            dust_heaviest_kg_m2: cover
                .texels
                .iter()
                .map(|t| t.dust_kg_m2)
                .fold(0.0, f32::max),
        }
    }

    /// Whether the wind lifts snow anywhere.
    #[must_use]
    pub fn blowing(&self) -> bool {
        self.blowing_area_m2 > 0.0
    }

    /// In words, for a title or a summary line.
    #[must_use]
    pub fn describe(&self) -> String {
        let blowing = if self.blowing() {
            format!(", blowing snow over {:.0} m²", self.blowing_area_m2)
        } else {
            String::new()
        };
        let dust = if self.dust_kg > 0.0 {
            format!(
                "; sand and dust settled: {:.1} kg, up to {:.3} kg/m²",
                self.dust_kg, self.dust_heaviest_kg_m2
            )
        } else {
            String::new()
        };
        format!(
            "snow {:.0} mm deep on average, deepest {:.0} mm, steepest face {:.1}°{blowing}{dust}",
            self.mean_depth_mm, self.deepest_mm, self.steepest_deg
        )
    }
}

/// The snow's depth seen from above, one pixel a texel (column = x, row = z, the
/// grid's minimum corner top left), as 16-bit grey in millimetres (65 535 = 65.5 m
/// or deeper): the map a sensor model or a GIS tool reads, written by the headless
/// run as `snow_depth_mm.png`.
#[must_use]
pub fn snow_depth_map_mm(cover: &CoverGrid) -> image::ImageBuffer<image::Luma<u16>, Vec<u16>> {
    let texels = cover.frame.texels;
    image::ImageBuffer::from_fn(texels.x, texels.y, |x, z| {
        let i = (x + texels.x * z) as usize;
        let depth_mm = cover.texels.get(i).map_or(0.0, |t| t.depth_mm);
        image::Luma([depth_mm.round().clamp(0.0, f32::from(u16::MAX)) as u16])
    })
}

#[cfg(test)]
mod tests {
    use precip_model::cover::{
        CoverFeed, CoverGrid, CoverTexel, GridFrame, generate_threshold_masks,
    };

    use super::*;

    #[test]
    fn it_reads_depths_slopes_and_blowing_snow() {
        let frame = GridFrame::centred(
            glam::Vec2::ZERO,
            glam::Vec2::splat(4.0),
            glam::UVec2::splat(4),
        );
        let masks = generate_threshold_masks(&frame, 0, 4.0);
        let mut cover =
            CoverGrid::new(frame, &[1.0; 16], &masks, &[CoverFeed::Particles; 16]).expect("grid");
        cover.texels[5] = CoverTexel {
            swe_mm: 100.0,
            depth_mm: 400.0,
            saltation_kg_per_m_s: 0.01,
            ..cover.texels[5]
        };
        let s = SnowSummary::of(&cover);
        assert!((s.mean_depth_mm - 25.0).abs() < 1e-3, "{s:?}");
        assert!((s.deepest_mm - 400.0).abs() < 1e-3);
        assert!((s.steepest_deg - 0.4f32.atan().to_degrees()).abs() < 1e-2);
        assert!(s.blowing() && s.describe().contains("blowing snow over 1 m²"));
        let map = snow_depth_map_mm(&cover);
        assert_eq!(map.dimensions(), (4, 4));
        assert_eq!(map.get_pixel(1, 1).0, [400]);
        assert_eq!(map.get_pixel(0, 0).0, [0]);
    }
}
