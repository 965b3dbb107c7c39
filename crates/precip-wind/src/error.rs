//! Typed errors of the wind crate.

/// What was wrong with a wind description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WindError {
    /// A numeric field was non-finite or outside its allowed range.
    #[error("wind field `{field}` = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// The field's name, as in the struct.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
}

/// Checks that `value` is finite and inside `[min, max]`.
pub(crate) fn check_range(
    field: &'static str,
    value: f32,
    min: f32,
    max: f32,
    allowed: &'static str,
) -> Result<(), WindError> {
    if value.is_finite() && value >= min && value <= max {
        Ok(())
    } else {
        Err(WindError::OutOfRange {
            field,
            value: f64::from(value),
            allowed,
        })
    }
}
