//! Splashes: a raindrop that strikes a surface hard enough throws up a secondary
//! droplet, made from the same particle (its slot: no allocation, no budget of its
//! own), drawn by the same machinery. WGSL twin: `shaders/splash.wgsl`.
//!
//! ## The model
//!
//! - **Whether it splashes** — Mundo, Sommerfeld & Tropea (1995, *Int. J.
//!   Multiphase Flow* 21(2)): a drop splashes on a surface when
//!   `K = We^(1/2)·Re^(1/4) > 57.7`, `We = ρ·D·v²/σ`, `Re = ρ·D·v/μ`
//!   ([`splashes`]). At terminal speed, drops from about 0.8 mm up splash; drizzle
//!   does not.
//! - **What flies** — the crown of a splash breaks into droplets of about a quarter
//!   of the drop's diameter, thrown at 20–40 % of the impact speed at 35–65° above
//!   the surface, in every direction round the vertical (Yarin 2006, *Annu. Rev.
//!   Fluid Mech.* 38, and the measurements it reviews). One droplet stands for the
//!   crown: its direction is drawn from the particle's own random stream
//!   ([`crate::particles::rng::draw::SPLASH_AZIMUTH`]…), so splashes are deterministic per seed.
//! - **Water** — a world-emitter drop deposits its water where it strikes (as before)
//!   and the droplet goes on gathering the emitter's water per second while it flies,
//!   landing it where it falls back: every slot stands for its share of the rate for
//!   all its time, so the water that reaches the cover still equals rate × area ×
//!   time ([`crate::particles::step`]).
//! - A droplet splashes no further: when it lands, its slot is re-born as a new drop.

use glam::Vec3;

use crate::particles::particle::{Particle, flags};
use crate::particles::rng::{draw, particle_key, random_unit};
use crate::physics::raindrop::{RAIN_DIAMETER_MIN_MM, raindrop_terminal_speed_mps};
use crate::physics::snowflake::WATER_DENSITY_KG_M3;

/// Mundo et al.'s splash threshold on `K = We^(1/2)·Re^(1/4)`.
pub const SPLASH_THRESHOLD_K: f32 = 57.7;

/// Surface tension of water (20 °C), N/m. WGSL: `water_physics.wgsl`.
pub const SURFACE_TENSION_N_M: f32 = 0.0728;
/// Dynamic viscosity of water (20 °C), Pa·s.
pub const VISCOSITY_PA_S: f32 = 1.0e-3;

/// The Weber number `We = ρ·D·v²/σ` of a drop of `diameter_m` at `speed_mps`
/// (WGSL twin: `weber_number` in `water_physics.wgsl`).
#[must_use]
pub fn weber_number(diameter_m: f32, speed_mps: f32) -> f32 {
    WATER_DENSITY_KG_M3 * diameter_m.max(0.0) * speed_mps * speed_mps / SURFACE_TENSION_N_M
}

/// Height above the surface a droplet starts at, m (clear of the landing test).
pub const SPLASH_LIFT_M: f32 = 0.01;

/// Mundo's `K` of a drop of `diameter_m` striking at `speed_mps`.
#[must_use]
pub fn splash_number(diameter_m: f32, speed_mps: f32) -> f32 {
    let d = diameter_m.max(0.0);
    let v = speed_mps.max(0.0);
    let reynolds = WATER_DENSITY_KG_M3 * d * v / VISCOSITY_PA_S;
    weber_number(d, v).sqrt() * reynolds.sqrt().sqrt()
}

/// Whether `particle`, striking a surface with its velocity, splashes: a raindrop,
/// not itself a splash droplet, above Mundo's threshold.
#[must_use]
pub fn splashes(particle: &Particle) -> bool {
    particle.kind().is_drop()
        && particle.flags & flags::SPLASH == 0
        && splash_number(particle.diameter_m, particle.velocity_mps.length()) > SPLASH_THRESHOLD_K
}

/// The droplet particle `index` (of `seed`) throws up from `surface_m`, where it
/// struck: its water is zeroed (the caller deposited it), its life and generation go
/// on.
#[must_use]
pub fn splash_droplet(seed: u32, index: u32, particle: &Particle, surface_m: Vec3) -> Particle {
    let key = particle_key(seed, index, particle.generation);
    let azimuth = std::f32::consts::TAU * random_unit(key, draw::SPLASH_AZIMUTH);
    let elevation = (35.0 + 30.0 * random_unit(key, draw::SPLASH_ELEVATION)).to_radians();
    let speed = (0.2 + 0.2 * random_unit(key, draw::SPLASH_SPEED)) * particle.velocity_mps.length();
    let (sa, ca) = azimuth.sin_cos();
    let (se, ce) = elevation.sin_cos();
    let diameter_m = 0.25 * particle.diameter_m;
    Particle {
        position_m: surface_m + Vec3::new(0.0, SPLASH_LIFT_M, 0.0),
        velocity_mps: speed * Vec3::new(ce * ca, se, ce * sa),
        terminal_speed_mps: raindrop_terminal_speed_mps(
            (diameter_m * 1.0e3).max(RAIN_DIAMETER_MIN_MM),
        ),
        diameter_m,
        water_kg: 0.0,
        flags: (particle.flags & !flags::LANDED) | flags::SPLASH,
        ..*particle
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drop(diameter_mm: f32) -> Particle {
        let v = raindrop_terminal_speed_mps(diameter_mm);
        Particle {
            velocity_mps: Vec3::new(0.5, -v, 0.0),
            terminal_speed_mps: v,
            diameter_m: diameter_mm * 1e-3,
            flags: 2 << flags::KIND_SHIFT,
            ..Particle::default()
        }
    }

    #[test]
    fn raindrops_splash_from_about_a_millimetre_and_drizzle_does_not() {
        assert!(!splashes(&drop(0.5)), "K = {}", splash_number(0.5e-3, 2.06));
        assert!(splashes(&drop(1.0)), "K = {}", splash_number(1.0e-3, 4.03));
        assert!(splashes(&drop(3.0)));
        let snow = Particle {
            flags: 0,
            ..drop(3.0)
        };
        assert!(!splashes(&snow), "snow does not splash");
    }

    #[test]
    fn a_droplet_flies_up_and_out_and_splashes_no_further() {
        let d = drop(2.0);
        let s = splash_droplet(3, 17, &d, Vec3::new(1.0, 0.5, 2.0));
        assert!(s.velocity_mps.y > 0.0);
        let speed = s.velocity_mps.length() / d.velocity_mps.length();
        assert!((0.2..=0.4).contains(&speed), "{speed}");
        let elevation = (s.velocity_mps.y / s.velocity_mps.length())
            .asin()
            .to_degrees();
        assert!((35.0..=65.0).contains(&elevation), "{elevation}");
        assert!((s.diameter_m - 0.5e-3).abs() < 1e-9 && s.water_kg == 0.0);
        assert!(s.position_m.y > 0.5 && !splashes(&s));
        assert_eq!(
            s,
            splash_droplet(3, 17, &d, Vec3::new(1.0, 0.5, 2.0)),
            "deterministic"
        );
        assert_ne!(
            s.velocity_mps,
            splash_droplet(4, 17, &d, Vec3::new(1.0, 0.5, 2.0)).velocity_mps
        );
    }
}
