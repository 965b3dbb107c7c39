//! Helpers for image tests: pixels, luma, projection, sRGB.

use glam::{Vec2, Vec3};
use precip_model::drawing::render::view_projection;
use precip_model::{Image, View};

/// The RGB of pixel `(x, y)`.
pub fn rgb(image: &Image, x: u32, y: u32) -> [u8; 3] {
    let i = 4 * (y * image.width_px + x) as usize;
    [image.rgba8[i], image.rgba8[i + 1], image.rgba8[i + 2]]
}

/// Mean of the channels of pixel `(x, y)`, 0–255.
pub fn luma(image: &Image, x: u32, y: u32) -> f32 {
    let [r, g, b] = rgb(image, x, y);
    (f32::from(r) + f32::from(g) + f32::from(b)) / 3.0
}

/// Mean luma over the square of half-side `r` around `(x, y)` (clipped).
pub fn mean_luma(image: &Image, centre: (u32, u32), r: u32) -> f32 {
    let (mut sum, mut n) = (0.0, 0.0);
    for y in centre.1.saturating_sub(r)..=(centre.1 + r).min(image.height_px - 1) {
        for x in centre.0.saturating_sub(r)..=(centre.0 + r).min(image.width_px - 1) {
            sum += luma(image, x, y);
            n += 1.0;
        }
    }
    sum / n
}

/// Where world point `p` lands in the image, px (y down), if in front of the camera.
pub fn project(view: &View, p: Vec3) -> Option<Vec2> {
    let aspect = view.width_px as f32 / view.height_px as f32;
    let clip = view_projection(&view.camera, aspect) * p.extend(1.0);
    if clip.w <= 0.0 {
        return None;
    }
    let ndc = clip.truncate() / clip.w;
    Some(Vec2::new(
        (ndc.x * 0.5 + 0.5) * view.width_px as f32,
        (0.5 - ndc.y * 0.5) * view.height_px as f32,
    ))
}

/// The pixel of world point `p`, if it is inside the image.
pub fn pixel_of(view: &View, p: Vec3) -> Option<(u32, u32)> {
    let s = project(view, p)?;
    (s.x >= 0.0 && s.y >= 0.0 && s.x < view.width_px as f32 && s.y < view.height_px as f32)
        .then_some((s.x as u32, s.y as u32))
}

/// sRGB byte to linear.
pub fn linear(byte: u8) -> f32 {
    let c = f32::from(byte) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The largest per-channel difference between two images of the same size.
pub fn max_difference(a: &Image, b: &Image) -> u8 {
    assert_eq!((a.width_px, a.height_px), (b.width_px, b.height_px));
    a.rgba8
        .iter()
        .zip(&b.rgba8)
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

/// Writes `image` under `target/test-images/` for a person to look at (best effort).
pub fn keep(image: &Image, name: &str) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/test-images");
    if std::fs::create_dir_all(&dir).is_ok() {
        let _ = image::save_buffer(
            dir.join(format!("{name}.png")),
            &image.rgba8,
            image.width_px,
            image.height_px,
            image::ExtendedColorType::Rgba8,
        );
    }
}
