//! Gravity and drag toward the wind (docs/model.md §2), integrated so that any step up to
//! 0.05 s and any terminal speed from 0.3 m/s settles without overshoot.
//! WGSL twin: `drag_velocity` in `shaders/physics.wgsl`.
//!
//! ## The update
//!
//! The acceleration is `a = g + k·|V_f|·V_f` with `V_f = V_w − v` and
//! `k = |g| / V_pmax²` (the seed's `F_d = |V_f|²·m·g/V_pmax²`; the mass cancels). An
//! explicit step oscillates unless `dt < V_pmax/(2|g|)`. We take the **backward-Euler**
//! step `v' = v + dt·a(v')`, which for this drag law has a closed form: with
//! `w = V_w − v'` it reads `w·(1 + dt·k·|w|) = b`, `b = V_w − v − dt·g`, so `w ∥ b` and
//! `|w|` is the positive root of `dt·k·|w|² + |w| − |b| = 0`:
//!
//! ```text
//! |w| = 2|b| / (1 + sqrt(1 + 4·dt·k·|b|)),   w = b·|w|/|b|,   v' = V_w − w
//! ```
//!
//! Backward Euler is monotone for this dissipative law (no overshoot for any dt), and
//! `v = V_w − V_pmax·ŷ·(−1)` — falling at V_pmax through the wind — is its exact fixed
//! point. The position then follows the seed's kinematics with the step's mean
//! acceleration: `P' = P + v·dt + ½·a·dt² = P + ½(v + v')·dt`.

use glam::Vec3;

/// Gravitational acceleration |g|, m/s².
pub const GRAVITY_MPS2: f32 = 9.81;

/// Gravity g as a vector (Y up), m/s².
pub const GRAVITY: Vec3 = Vec3::new(0.0, -GRAVITY_MPS2, 0.0);

/// Smallest terminal speed the integrator is specified for, m/s.
pub const MIN_TERMINAL_SPEED_MPS: f32 = 0.3;

/// Longest step the integrator is specified for, s; backends sub-step longer ones.
pub const MAX_SUBSTEP_S: f32 = 0.05;

/// The acceleration `g + k·|V_f|·V_f` of a particle at velocity `v` in wind `wind`.
#[must_use]
pub fn acceleration(velocity_mps: Vec3, wind_mps: Vec3, terminal_speed_mps: f32) -> Vec3 {
    let relative = wind_mps - velocity_mps;
    let k = GRAVITY_MPS2 / (terminal_speed_mps * terminal_speed_mps);
    GRAVITY + relative * (k * relative.length())
}

/// The velocity after `dt_s` under gravity and drag toward `wind` (backward Euler,
/// closed form; see the module docs).
#[must_use]
pub fn drag_velocity(
    velocity_mps: Vec3,
    wind_mps: Vec3,
    terminal_speed_mps: f32,
    dt_s: f32,
) -> Vec3 {
    let k = GRAVITY_MPS2 / (terminal_speed_mps * terminal_speed_mps);
    let b = wind_mps - velocity_mps - GRAVITY * dt_s;
    let b_len = b.length();
    if b_len <= 0.0 {
        return wind_mps;
    }
    let w_len = 2.0 * b_len / (1.0 + (1.0 + 4.0 * dt_s * k * b_len).sqrt());
    wind_mps - b * (w_len / b_len)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn terminal_fall_is_a_fixed_point() {
        for v in [0.3f32, 1.0, 4.0, 9.2] {
            for wind in [Vec3::ZERO, Vec3::new(7.0, 0.5, -3.0)] {
                let falling = wind - Vec3::Y * v;
                let next = drag_velocity(falling, wind, v, 0.05);
                assert!(
                    (next - falling).length() < 1e-5 * v.max(1.0),
                    "{v} {wind}: {next}"
                );
                assert!(acceleration(falling, wind, v).length() < 1e-4);
            }
        }
    }

    #[test]
    fn a_flake_is_carried_by_the_wind() {
        let wind = Vec3::new(10.0, 0.0, 0.0);
        let mut v = Vec3::ZERO;
        for _ in 0..400 {
            v = drag_velocity(v, wind, 1.0, 0.02);
        }
        assert!((v.x - 10.0).abs() < 0.01 && (v.y + 1.0).abs() < 0.01, "{v}");
    }

    proptest! {
        #[test]
        fn in_still_air_a_flake_settles_at_v_pmax_and_never_overshoots(
            terminal in MIN_TERMINAL_SPEED_MPS..10.0f32,
            dt in 0.001f32..=MAX_SUBSTEP_S,
            start_down in 0.0f32..1.0,
        ) {
            // "Never overshoots" up to f32 rounding: near V_pmax each step contracts the
            // error by only (1 − 2·g·dt/V), so rounding of ~6e-8 per step settles at up to
            // ~V/(2·g·dt) times that, about 3e-5 relative for dt = 1 ms and V = 10 m/s.
            let tolerance = 1e-4;
            let mut v = Vec3::new(0.0, -start_down * terminal, 0.0);
            // Long enough for ~10 relaxation times (V/g) or 400 steps, whichever is more.
            let steps = ((12.0 * terminal / GRAVITY_MPS2 / dt).ceil() as usize).max(400);
            for _ in 0..steps {
                v = drag_velocity(v, Vec3::ZERO, terminal, dt);
                prop_assert!(-v.y <= terminal * (1.0 + tolerance), "overshoot: {} > {}", -v.y, terminal);
                prop_assert!(v.x.abs() < 1e-6 && v.z.abs() < 1e-6);
            }
            prop_assert!((-v.y - terminal).abs() <= 0.01 * terminal, "settled at {} vs {}", -v.y, terminal);
        }

        #[test]
        fn a_flake_thrown_up_or_down_fast_relaxes_without_passing_v_pmax(
            terminal in MIN_TERMINAL_SPEED_MPS..10.0f32,
            dt in 0.001f32..=MAX_SUBSTEP_S,
            start in -30.0f32..30.0,
        ) {
            let mut v = Vec3::new(0.0, start, 0.0);
            let from_above = -start > terminal;
            for _ in 0..2000 {
                v = drag_velocity(v, Vec3::ZERO, terminal, dt);
                if from_above {
                    prop_assert!(-v.y >= terminal * (1.0 - 1e-4));
                } else {
                    prop_assert!(-v.y <= terminal * (1.0 + 1e-4));
                }
            }
        }
    }
}
