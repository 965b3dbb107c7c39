//! The rotation oscillation of seeds 000/001 (docs/model.md §1), with a direction that
//! survives 0. WGSL twin: `advance_rotation` in `shaders/physics.wgsl`.
//!
//! Each offset component moves `|r| ← |r| ± k_vel·dt`; leaving `[0, 2·k_rot]` it is
//! clamped to the bound and turns round. The seed keeps the direction in the sign of
//! `r`, which is lost at 0 (`−0.0 ≥ 0` in IEEE arithmetic): we keep the magnitude in
//! `rotation_rad` and the direction in a flag bit.

/// One axis's offset after `dt_s`: returns `(|r'|, increasing')`.
#[must_use]
pub fn advance_rotation(
    magnitude_rad: f32,
    increasing: bool,
    amplitude_rad: f32,
    speed_rad_per_s: f32,
    dt_s: f32,
) -> (f32, bool) {
    let step = speed_rad_per_s * dt_s;
    let moved = if increasing {
        magnitude_rad + step
    } else {
        magnitude_rad - step
    };
    let top = 2.0 * amplitude_rad;
    if moved > top {
        (top, false)
    } else if moved < 0.0 {
        (0.0, true)
    } else {
        (moved, increasing)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn bounces_at_both_ends_including_zero() {
        // Start exactly at 0, going down: the seed's sign trick would lose this.
        let (m, inc) = advance_rotation(0.0, false, 0.5, 1.0, 0.1);
        assert!(
            m.abs() < f32::MIN_POSITIVE && inc,
            "clamped at 0 and turned up"
        );
        let (m, inc) = advance_rotation(m, inc, 0.5, 1.0, 0.1);
        assert!((m - 0.1).abs() < 1e-6 && inc, "and it does go up from 0");
        let (m, inc) = advance_rotation(0.95, true, 0.5, 1.0, 0.1);
        assert!(
            (m - 1.0).abs() < 1e-6 && !inc,
            "clamped at 2·k_rot and turned down"
        );
        let (m, _) = advance_rotation(m, inc, 0.5, 1.0, 0.1);
        assert!((m - 0.9).abs() < 1e-6);
    }

    proptest! {
        #[test]
        fn stays_in_range_and_keeps_oscillating(amplitude in 0.0f32..std::f32::consts::PI, speed in 0.01f32..10.0, dt in 0.001f32..0.05, start in 0.0f32..1.0) {
            let mut m = start * 2.0 * amplitude;
            let mut inc = false;
            let mut turns = 0;
            // Two turns need up to 8·amplitude of travel; a case slower than 200 000
            // steps for that is left out (it used to be cut short and then fail).
            let needed = (8.0 * amplitude / (speed * dt)).ceil() as usize + 4;
            prop_assume!(needed <= 200_000);
            let steps = needed;
            for _ in 0..steps {
                let (next, next_inc) = advance_rotation(m, inc, amplitude, speed, dt);
                prop_assert!((0.0..=2.0 * amplitude).contains(&next));
                turns += usize::from(next_inc != inc);
                m = next;
                inc = next_inc;
            }
            prop_assert!(turns >= 2, "it turned {turns} times");
        }
    }
}
