//! The colour of water by wavelength (docs/model.md (13.8)): what the water column
//! absorbs and scatters, how much light comes back up from deep water, and how a
//! spectrum becomes the renderer's linear sRGB (seed 004's spectral radiance to RGB,
//! with a white balance for the chromatic adaptation).
//!
//! - **Absorption** of pure water, Pope & Fry 1997 (10 nm, 380–700 nm), plus the
//!   dissolved organic matter's `a_g(λ) = a_g(440)·e^(−0.014·(λ − 440))` (Bricaud,
//!   Morel & Prieur 1981).
//! - **Scattering** of pure sea water, Morel 1974: `b_w = 0.00288·(λ/500)^(−4.32)`
//!   m⁻¹, half of it backward; suspended particles `b_p(λ) = b_p(550)·(550/λ)`, 1.9 %
//!   of it backward (Petzold's turbid-harbour phase function).
//! - **Deep water's reflectance** just beneath the surface, `R = 0.33·b_b/(a + b_b)`
//!   (Gordon, Brown & Jacobs 1975; Morel & Prieur 1977): clear ocean water reflects
//!   a few per cent of blue light and almost no red.
//! - **To RGB**: the CIE 1931 colour-matching functions by the piecewise Gaussians of
//!   Wyman, Sloan & Shirley 2013, XYZ → linear sRGB (IEC 61966-2-1), each channel
//!   divided by a white reflector's under the same light (a von Kries white balance:
//!   the eye adapted to the daylight, as the seed adapts its colours).

/// The wavelengths of the tables, nm: 380 to 700 every 10.
pub const WAVELENGTHS_NM: [f32; 33] = {
    let mut w = [0.0; 33];
    let mut i = 0;
    while i < 33 {
        w[i] = 380.0 + 10.0 * i as f32;
        i += 1;
    }
    w
};

/// Pure water's absorption at [`WAVELENGTHS_NM`], m⁻¹ (Pope & Fry 1997).
pub const PURE_WATER_ABSORPTION_PER_M: [f32; 33] = [
    0.01137, 0.00851, 0.00663, 0.00473, 0.00454, 0.00495, 0.00635, 0.00922, 0.00979, 0.0106,
    0.0127, 0.0150, 0.0204, 0.0325, 0.0409, 0.0434, 0.0474, 0.0565, 0.0619, 0.0695, 0.0896, 0.1351,
    0.2224, 0.2644, 0.2755, 0.2916, 0.3108, 0.340, 0.410, 0.439, 0.465, 0.516, 0.624,
];

/// What is in the water besides water.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterContent {
    /// The dissolved organic matter's absorption at 440 nm, m⁻¹ (0 in the open
    /// ocean, some 0.1 on coasts, 1 and more in a peaty lake).
    pub organic_absorption_440_per_m: f32,
    /// The suspended particles' scattering at 550 nm, m⁻¹ (0 in the clearest
    /// ocean, about 0.5 on coasts, 5 and more in a muddy river).
    pub particle_scattering_550_per_m: f32,
}

impl WaterContent {
    /// Clear open-ocean water.
    pub const CLEAR: Self = Self {
        organic_absorption_440_per_m: 0.0,
        particle_scattering_550_per_m: 0.0,
    };
    /// Coastal water.
    pub const COASTAL: Self = Self {
        organic_absorption_440_per_m: 0.1,
        particle_scattering_550_per_m: 0.5,
    };

    /// The absorption at `nm`, m⁻¹.
    #[must_use]
    pub fn absorption_per_m(&self, nm: f32) -> f32 {
        pure_water_absorption_per_m(nm)
            + self.organic_absorption_440_per_m * (-0.014 * (nm - 440.0)).exp()
    }

    /// The backscattering at `nm`, m⁻¹.
    #[must_use]
    pub fn backscattering_per_m(&self, nm: f32) -> f32 {
        0.5 * 0.00288 * (nm / 500.0).powf(-4.32)
            + 0.019 * self.particle_scattering_550_per_m * 550.0 / nm
    }

    /// Deep water's reflectance beneath the surface at `nm`: `0.33·b_b/(a + b_b)`.
    #[must_use]
    pub fn deep_reflectance(&self, nm: f32) -> f32 {
        let bb = self.backscattering_per_m(nm);
        0.33 * bb / (self.absorption_per_m(nm) + bb)
    }

    /// The colour deep water sends back up, linear sRGB of a white reflector's 1.
    #[must_use]
    pub fn deep_colour(&self) -> [f32; 3] {
        reflectance_to_rgb(|nm| self.deep_reflectance(nm))
    }

    /// The colour deep water sends out through the surface, as a share of a white
    /// diffuser's under the same light: [`WaterContent::deep_colour`] ×
    /// [`WATER_LEAVING_FACTOR`].
    #[must_use]
    pub fn water_leaving_colour(&self) -> [f32; 3] {
        self.deep_colour().map(|c| c * WATER_LEAVING_FACTOR)
    }

    /// The share of each channel's light that crosses `path_m` of the water, as
    /// one absorption per channel: `−ln(T)/path`, m⁻¹ (a white light; each channel
    /// weighs the wavelengths by its non-negative sensitivity).
    #[must_use]
    pub fn rgb_absorption_per_m(&self, path_m: f32) -> [f32; 3] {
        let (mut through, mut total) = ([0.0f32; 3], [0.0f32; 3]);
        let mut nm = 380.0;
        while nm <= 700.0 {
            let t = (-self.absorption_per_m(nm) * path_m).exp();
            for (c, w) in channel_sensitivity(nm).into_iter().enumerate() {
                through[c] += w * t;
                total[c] += w;
            }
            nm += 2.0;
        }
        std::array::from_fn(|c| -(through[c] / total[c]).max(1.0e-9).ln() / path_m)
    }
}

/// The seabed a coast's shallow water shows: wet sand's albedo, linear sRGB (dry
/// quartz sand reflects 0.3–0.45; wetting darkens it by about half: Lekner & Dorf
/// 1988).
pub const SEABED_ALBEDO: [f32; 3] = [0.22, 0.19, 0.14];

impl WaterContent {
    /// The diffuse attenuation of each channel's light going down and coming back,
    /// m⁻¹: `K ≈ a + b_b` (Gordon 1989, a sun high in the sky), the absorption over
    /// a metre's path ([`WaterContent::rgb_absorption_per_m`]) plus the
    /// backscattering at the channel's middle (600, 550, 450 nm).
    #[must_use]
    pub fn rgb_attenuation_per_m(&self) -> [f32; 3] {
        let a = self.rgb_absorption_per_m(1.0);
        let nm = [600.0, 550.0, 450.0];
        std::array::from_fn(|c| a[c] + self.backscattering_per_m(nm[c]))
    }
}

/// The colour shallow water `depth_m` deep over a bottom sends out, each channel:
/// `R = R∞ + (A − R∞)·e^(−2·K·d)` (Maritorena, Morel & Gentili 1994), with `deep`
/// the deep water's colour, `bottom` the bottom's as seen through the surface (its
/// albedo times [`WATER_LEAVING_FACTOR`]) and `k` the diffuse attenuation.
/// WGSL twin: `sea_shallow_colour`.
#[must_use]
pub fn shallow_colour(deep: [f32; 3], bottom: [f32; 3], k: [f32; 3], depth_m: f32) -> [f32; 3] {
    std::array::from_fn(|c| {
        deep[c] + (bottom[c] - deep[c]) * (-2.0 * k[c] * depth_m.max(0.0)).exp()
    })
}

/// Water-leaving radiance over the reflectance beneath the surface, each as a
/// share of a white diffuser's: `t/(n²·Q)·π ≈ 0.54` (transmission 0.98 up through
/// the surface, `n² = 1.78`, an upwelling light as even as a diffuser's; Austin 1974).
pub const WATER_LEAVING_FACTOR: f32 = 0.54;

/// Pure water's absorption at `nm` (linear between the table's wavelengths, held
/// beyond), m⁻¹.
#[must_use]
pub fn pure_water_absorption_per_m(nm: f32) -> f32 {
    let t = ((nm - 380.0) / 10.0).clamp(0.0, 32.0);
    let i = (t.floor() as usize).min(31);
    let f = t - i as f32;
    PURE_WATER_ABSORPTION_PER_M[i] * (1.0 - f) + PURE_WATER_ABSORPTION_PER_M[i + 1] * f
}

/// One lobe of Wyman, Sloan & Shirley's fit: a Gaussian of width `low` below `mu`,
/// `high` above.
fn lobe(nm: f32, mu: f32, low: f32, high: f32) -> f32 {
    let s = if nm < mu { low } else { high };
    (-0.5 * ((nm - mu) / s).powi(2)).exp()
}

/// The CIE 1931 2° colour-matching functions `(x̄, ȳ, z̄)` at `nm` (Wyman, Sloan &
/// Shirley 2013, their multi-lobe fit).
#[must_use]
pub fn colour_matching(nm: f32) -> [f32; 3] {
    [
        1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7)
            - 0.065 * lobe(nm, 501.1, 20.4, 26.2),
        0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
        1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8),
    ]
}

/// CIE XYZ → linear sRGB (IEC 61966-2-1, D65 white).
const XYZ_TO_SRGB: [[f32; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// The sRGB channels' sensitivities at `nm`: the colour-matching functions through
/// the XYZ → linear sRGB matrix, their negative lobes cut.
#[must_use]
pub fn channel_sensitivity(nm: f32) -> [f32; 3] {
    let c = colour_matching(nm);
    XYZ_TO_SRGB.map(|row| (row[0] * c[0] + row[1] * c[1] + row[2] * c[2]).max(0.0))
}

/// The linear sRGB of `light(λ)` (a flat spectrum's 1 is white), before the
/// white balance.
fn spectrum_to_rgb(light: &dyn Fn(f32) -> f32) -> [f32; 3] {
    let mut xyz = [0.0f32; 3];
    let mut nm = 380.0;
    while nm <= 700.0 {
        let cmf = colour_matching(nm);
        let l = light(nm);
        for (sum, c) in xyz.iter_mut().zip(cmf) {
            *sum += c * l;
        }
        nm += 2.0;
    }
    XYZ_TO_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// The linear sRGB of a surface of spectral reflectance `reflectance(λ)` under a
/// flat light, white balanced (each channel over a white reflector's).
#[must_use]
pub fn reflectance_to_rgb(reflectance: impl Fn(f32) -> f32) -> [f32; 3] {
    let white = spectrum_to_rgb(&|_| 1.0);
    let rgb = spectrum_to_rgb(&reflectance);
    [rgb[0] / white[0], rgb[1] / white[1], rgb[2] / white[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pure_water_absorbs_red_and_least_near_420_nm() {
        let least = WAVELENGTHS_NM
            .iter()
            .copied()
            .min_by(|a, b| {
                pure_water_absorption_per_m(*a).total_cmp(&pure_water_absorption_per_m(*b))
            })
            .unwrap_or(0.0);
        assert!((410.0..=430.0).contains(&least), "{least}");
        assert!(pure_water_absorption_per_m(650.0) > 30.0 * pure_water_absorption_per_m(450.0));
        // Between the table's points, linear.
        let mid = pure_water_absorption_per_m(555.0);
        assert!((mid - 0.5 * (0.0565 + 0.0619)).abs() < 1e-6, "{mid}");
    }

    #[test]
    fn the_colour_matching_fit_has_the_cie_shape() {
        // ȳ peaks at 555 nm at 1; x̄'s lobes at 600 and 442 nm; the three have
        // nearly equal areas (an equal-energy light is white: X = Y = Z).
        let y = colour_matching(555.0)[1];
        assert!((y - 1.0).abs() < 0.01, "{y}");
        let area = |c: usize| {
            (380..=780)
                .map(|nm| colour_matching(nm as f32)[c])
                .sum::<f32>()
        };
        let (x, y, z) = (area(0), area(1), area(2));
        assert!(
            (x / y - 1.0).abs() < 0.02 && (z / y - 1.0).abs() < 0.03,
            "{x} {y} {z}"
        );
        assert!((y - 106.9).abs() < 2.0, "{y}");
    }

    #[test]
    fn white_is_white_and_grey_is_grey() {
        let w = reflectance_to_rgb(|_| 1.0);
        assert!(w.iter().all(|c| (c - 1.0).abs() < 1e-5), "{w:?}");
        let g = reflectance_to_rgb(|_| 0.18);
        assert!(g.iter().all(|c| (c - 0.18).abs() < 1e-5), "{g:?}");
    }

    #[test]
    fn shallow_water_shows_its_bottom_and_fades_to_the_deep_s_colour() {
        let water = WaterContent::COASTAL;
        let deep = water.water_leaving_colour();
        let bottom = SEABED_ALBEDO.map(|a| a * WATER_LEAVING_FACTOR);
        let k = water.rgb_attenuation_per_m();
        // Red dies first; in coastal water the dissolved organic matter takes the
        // blue, so green goes deepest (in clear water blue does).
        assert!(k[0] > k[2] && k[2] > k[1] && k[0] > 0.2, "{k:?}");
        let clear = WaterContent::CLEAR.rgb_attenuation_per_m();
        assert!(clear[0] > clear[1] && clear[1] > clear[2], "{clear:?}");
        assert!(shallow_colour(deep, bottom, k, 0.0).map(f32::to_bits) == bottom.map(f32::to_bits));
        let mid = shallow_colour(deep, bottom, k, 1.5);
        let far = shallow_colour(deep, bottom, k, 60.0);
        for c in 0..3 {
            assert!((far[c] - deep[c]).abs() < 1e-4, "{far:?} {deep:?}");
            assert!(mid[c] < bottom[c] && mid[c] > deep[c], "{mid:?}");
        }
        // Over sand 1.5 m down the water is turquoise: green over red.
        assert!(mid[1] > mid[0], "{mid:?}");
    }

    #[test]
    fn clear_water_is_blue_and_coastal_water_greener_and_brighter() {
        let clear = WaterContent::CLEAR;
        // Pure sea water sends back some 10 % of blue light (Morel & Prieur 1977
        // computed about that for it; natural clear ocean, with a trace of
        // phytoplankton absorbing, 2–5 %), almost no red.
        let r440 = clear.deep_reflectance(440.0);
        assert!((0.05..0.12).contains(&r440), "{r440}");
        assert!(clear.deep_reflectance(650.0) < 0.001);
        let c = clear.deep_colour();
        assert!(c[2] > c[1] && c[1] > c[0], "{c:?}");
        let coastal = WaterContent::COASTAL.deep_colour();
        assert!(
            coastal[1] > c[1] && coastal[1] / coastal[2] > c[1] / c[2],
            "{coastal:?}"
        );
        println!("deep colour: clear {c:?}, coastal {coastal:?}");
        // Through 2 m of clear water, red is absorbed as Pope & Fry's red band, green
        // and blue far less.
        let a = clear.rgb_absorption_per_m(2.0);
        println!("absorption over 2 m: {a:?} per m");
        assert!(
            (0.15..0.6).contains(&a[0]) && a[1] < 0.15 && a[2] < 0.06 && a[2] < a[1],
            "{a:?}"
        );
    }
}
