//! [`Surface`]: what a cover texel's ground is made of, and how water behaves on it.
//!
//! The kind comes from the asset (glTF `extras.surface`, docs/architecture.md §6) or, where the
//! asset says nothing, from the snow conventions: ground that may not hold snow
//! (`"snow": false`: roads, heated paving) is paved, the rest is soil.
//!
//! Each kind carries the constants of the surface-water model ([`SurfaceWater`],
//! WGSL twin `surface_water` in `shaders/cover.wgsl`), each from a measured source:
//!
//! - **Film capacity**: water the surface's texture holds without flowing (its
//!   wetting storage). Impervious pavement 0.5 mm, roofing 0.3 mm, bare soil 1 mm,
//!   turf 2 mm: the lower ends of the depression-storage ranges of urban hydrology
//!   (ASCE/WEF *Design and Construction of Urban Stormwater Management Systems*,
//!   1992: 0.4–1.5 mm impervious, 2.5–5 mm pervious, of which the larger depressions
//!   are resolved here by the ground map itself).
//! - **Infiltration capacity**: saturated hydraulic conductivity `K_s`, the
//!   long-time infiltration rate of a ponded surface (Green–Ampt). Loam 3.4 mm/h
//!   (Rawls, Brakensiek & Miller 1983, *J. Hydraul. Eng.* 109(1), table 1); turf over
//!   loam 10 mm/h (root macropores roughly triple it); sand 210 mm/h (same table);
//!   pavement and roofs 0.
//! - **Manning's n** for shallow overland flow: asphalt 0.015, roofing 0.012, bare
//!   soil 0.03, short grass 0.15 (Engman 1986, *J. Irrig. Drain. Eng.* 112(1));
//!   loose sand 0.02 (between fallow soil and smooth bare ground in the same table).
//! - **Roughness height**: how deep standing water must be to top the surface's
//!   texture and show as open water (a puddle's mirror). Asphalt 1 mm (the mean
//!   texture depth of road surfaces is 0.5–1.5 mm, PIARC 1987), roofing 0.5 mm, bare
//!   soil 5 mm (clods), turf 30 mm (the blades of mown grass), sand 2 mm (ripples).
//! - Sand's film capacity, 0.5 mm: what a sand surface holds before water stands is
//!   small, its large pores drain at once.
//!
//! How much a wet surface darkens is the seed's one `R_d`
//! ([`crate::CoverParams::wet_darkening`]): light trapped by total internal
//! reflection in the film (Lekner & Dorf 1988, *Applied Optics* 27(7)).
//!
//! A water body (`extras.water: true` or `"surface": "water"`) takes whatever lands
//! or flows onto it into itself: no cover, no film, no puddle.

/// What a surface is made of.
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Surface {
    /// Bare soil (loam): infiltrates, darkens strongly when wet.
    #[default]
    Soil = 0,
    /// Asphalt or concrete paving: impervious, smooth, glossy when wet.
    Asphalt = 1,
    /// Turf: infiltrates fast, slows overland flow.
    Grass = 2,
    /// Roofing: impervious, smoothest.
    Roof = 3,
    /// A water body (pond, lake, sea): takes in all that lands or flows onto it.
    Water = 4,
    /// Loose sand (dunes, beaches, desert floor): drains fast, and the wind lifts
    /// its grains ([`Surface::erodibility`]).
    Sand = 5,
}

/// The constants of water on one [`Surface`] (see the module docs for sources).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceWater {
    /// Water the surface holds as a film without flowing, mm.
    pub film_capacity_mm: f32,
    /// Infiltration capacity (saturated hydraulic conductivity), mm/h.
    pub infiltration_mm_per_h: f32,
    /// Manning's roughness coefficient for overland flow, s/m^(1/3).
    pub manning_n: f32,
    /// Standing water shows as open water above this depth, mm.
    pub roughness_mm: f32,
}

impl Surface {
    /// Every kind, in `u32` order.
    pub const ALL: [Self; 6] = [
        Self::Soil,
        Self::Asphalt,
        Self::Grass,
        Self::Roof,
        Self::Water,
        Self::Sand,
    ];

    /// The names the asset uses (`extras.surface`), in `u32` order.
    pub const NAMES: [&'static str; 6] = ["soil", "asphalt", "grass", "roof", "water", "sand"];

    /// From the stored `u32` (unknown values read as soil).
    #[must_use]
    pub const fn from_raw(raw: u32) -> Self {
        match raw {
            1 => Self::Asphalt,
            2 => Self::Grass,
            3 => Self::Roof,
            4 => Self::Water,
            5 => Self::Sand,
            _ => Self::Soil,
        }
    }

    /// From an asset's name for it (`"asphalt"`, …; `"concrete"` and `"paving"` are
    /// asphalt, `"turf"` grass); `None` for a name it does not know.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        match name.to_ascii_lowercase().as_str() {
            "soil" | "earth" | "dirt" | "ground" => Some(Self::Soil),
            "asphalt" | "concrete" | "paving" | "pavement" | "road" => Some(Self::Asphalt),
            "grass" | "turf" | "lawn" => Some(Self::Grass),
            "roof" | "roofing" => Some(Self::Roof),
            "water" => Some(Self::Water),
            "sand" | "dune" | "beach" | "desert" => Some(Self::Sand),
            _ => None,
        }
    }

    /// The name the asset uses.
    #[must_use]
    pub const fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The default where an asset names no surface: ground that may hold no snow
    /// (eligibility below ½: roads, heated paving) is paved, the rest soil.
    #[must_use]
    pub fn from_eligibility(eligibility: f32) -> Self {
        if eligibility < 0.5 {
            Self::Asphalt
        } else {
            Self::Soil
        }
    }

    /// How water behaves on it (WGSL twin: `surface_water`).
    #[must_use]
    pub const fn water(self) -> SurfaceWater {
        match self {
            Self::Soil => SurfaceWater {
                film_capacity_mm: 1.0,
                infiltration_mm_per_h: 3.4,
                manning_n: 0.03,
                roughness_mm: 5.0,
            },
            Self::Asphalt => SurfaceWater {
                film_capacity_mm: 0.5,
                infiltration_mm_per_h: 0.0,
                manning_n: 0.015,
                roughness_mm: 1.0,
            },
            Self::Grass => SurfaceWater {
                film_capacity_mm: 2.0,
                infiltration_mm_per_h: 10.0,
                manning_n: 0.15,
                roughness_mm: 30.0,
            },
            Self::Roof => SurfaceWater {
                film_capacity_mm: 0.3,
                infiltration_mm_per_h: 0.0,
                manning_n: 0.012,
                roughness_mm: 0.5,
            },
            Self::Water => SurfaceWater {
                film_capacity_mm: 0.0,
                infiltration_mm_per_h: 0.0,
                manning_n: 0.03,
                roughness_mm: 0.0,
            },
            Self::Sand => SurfaceWater {
                film_capacity_mm: 0.5,
                infiltration_mm_per_h: 210.0,
                manning_n: 0.02,
                roughness_mm: 2.0,
            },
        }
    }

    /// The share of the surface whose loose grains the wind can lift, `[0, 1]`:
    /// 1 for sand, 0 for the rest (soil under vegetation or crust, paving, roofs,
    /// water). Where the friction velocity passes the grains' threshold, sand and
    /// dust rise from it (`precip_model::physics::grain`). WGSL twin: the erodibility words
    /// of the ground buffer (`precip_model::GroundMap::gpu_words`).
    #[must_use]
    pub const fn erodibility(self) -> f32 {
        match self {
            Self::Sand => 1.0,
            Self::Soil | Self::Asphalt | Self::Grass | Self::Roof | Self::Water => 0.0,
        }
    }

    /// The depth of snow the surface holds against the wind, m: snow up to it lies
    /// between the grass blades or the clods and no wind lifts it; only the depth
    /// above it can drift (Liston & Sturm 1998, *J. Glaciology* 44: the vegetation's
    /// snow-holding depth of SnowTran-3D). Turf 0.15 m, the grassland value of
    /// SnowModel's vegetation table (Liston & Elder 2006, *J. Hydrometeorology* 7;
    /// the height of the lawn whose roughness [`Self::snow_roughness_m`] takes);
    /// bare soil, paving, roofs, sand and water 0.01 m, its bare and urban classes.
    /// So a blizzard whitens a lawn before it scours it. WGSL twin:
    /// `surface_snow_holding_depth_m` (blowing.wgsl).
    #[must_use]
    pub const fn snow_holding_depth_m(self) -> f32 {
        match self {
            Self::Grass => 0.15,
            Self::Soil | Self::Asphalt | Self::Roof | Self::Sand | Self::Water => 0.01,
        }
    }

    /// The roughness length `z₀` that snow must bury before it covers the surface
    /// (the snow-cover depletion curve, `crate::shading::snow_cover_fraction`), m.
    /// Bare soil 0.01 m, Niu & Yang's (2007) ground value; turf 0.015 m, a tenth of
    /// a 15 cm lawn's height (the usual `z₀ ≈ h/10` of a canopy); paving, roofs, sand
    /// and water 0.005 m, the "smooth" class of the Davenport–Wieringa roughness
    /// classification (Wieringa et al. 2001, WMO-No. 8 annex). 2 cm of fresh snow
    /// whitens a roof (0.92) while half the lawn shows through (0.49). WGSL twin:
    /// `surface_snow_roughness_m` (shading.wgsl).
    #[must_use]
    pub const fn snow_roughness_m(self) -> f32 {
        match self {
            Self::Soil => 0.01,
            Self::Grass => 0.015,
            Self::Asphalt | Self::Roof | Self::Sand | Self::Water => 0.005,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_raw_values_round_trip() {
        for (i, s) in Surface::ALL.into_iter().enumerate() {
            assert_eq!(s as usize, i);
            assert_eq!(Surface::from_raw(i as u32), s);
            assert_eq!(Surface::from_name(s.name()), Some(s));
        }
        assert_eq!(Surface::from_name("Concrete"), Some(Surface::Asphalt));
        assert_eq!(Surface::from_name("lava"), None);
        assert_eq!(Surface::from_raw(99), Surface::Soil);
        assert_eq!(Surface::from_eligibility(0.0), Surface::Asphalt);
        assert_eq!(Surface::from_eligibility(1.0), Surface::Soil);
    }

    #[test]
    fn pervious_surfaces_infiltrate_and_paving_does_not() {
        assert!(Surface::Soil.water().infiltration_mm_per_h > 0.0);
        assert!(
            Surface::Grass.water().infiltration_mm_per_h
                > Surface::Soil.water().infiltration_mm_per_h
        );
        for s in [Surface::Asphalt, Surface::Roof, Surface::Water] {
            assert!(s.water().infiltration_mm_per_h.abs() < f32::MIN_POSITIVE);
        }
    }
}
