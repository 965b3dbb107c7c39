//! Typed errors of the cover crate.

/// What was wrong with a cover description or input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CoverError {
    /// A numeric parameter was non-finite or outside its range.
    #[error("cover parameter `{field}` = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// The parameter's name.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// Two grids or arrays that must have the same size do not.
    #[error(
        "{what} has {got} texels but the cover grid has {expected}: give one value per cover texel"
    )]
    SizeMismatch {
        /// Which input.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The grid's texel count.
        expected: usize,
    },
}

/// Checks that `value` is finite and inside `[min, max]`.
pub(crate) fn check_range(
    field: &'static str,
    value: f32,
    min: f32,
    max: f32,
    allowed: &'static str,
) -> Result<(), CoverError> {
    if value.is_finite() && value >= min && value <= max {
        Ok(())
    } else {
        Err(CoverError::OutOfRange {
            field,
            value: f64::from(value),
            allowed,
        })
    }
}
