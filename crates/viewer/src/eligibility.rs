//! Snow eligibility from glTF `extras` (DESIGN.md §6, rule 2): `{"snow": false}`,
//! `{"snow": true}` or `{"snow": 0.0..1.0}` on a material, mesh or node.

/// The `snow` value of an `extras` object: `Ok(None)` when absent (or `extras` is not
/// an object), `Err` with a message when present but not a boolean or number in [0, 1].
pub fn snow_extra(extras: &gltf::json::Extras) -> Result<Option<f32>, String> {
    let Some(raw) = extras else {
        return Ok(None);
    };
    let value: serde_json::Value = serde_json::from_str(raw.get()).map_err(|e| e.to_string())?;
    match value.get("snow") {
        None => Ok(None),
        Some(serde_json::Value::Bool(b)) => Ok(Some(if *b { 1.0 } else { 0.0 })),
        Some(serde_json::Value::Number(n)) => match n.as_f64() {
            Some(x) if (0.0..=1.0).contains(&x) => Ok(Some(x as f32)),
            _ => Err(format!("extras.snow = {n} must be in [0, 1]")),
        },
        Some(other) => Err(format!(
            "extras.snow = {other} must be true, false or a number in [0, 1]"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn extras(json: &str) -> gltf::json::Extras {
        Some(serde_json::value::RawValue::from_string(json.to_owned()).expect("json"))
    }

    #[test]
    fn reads_the_conventions() {
        assert_eq!(snow_extra(&None), Ok(None));
        assert_eq!(snow_extra(&extras(r#"{"other": 1}"#)), Ok(None));
        assert_eq!(snow_extra(&extras(r#"{"snow": false}"#)), Ok(Some(0.0)));
        assert_eq!(snow_extra(&extras(r#"{"snow": true}"#)), Ok(Some(1.0)));
        assert_eq!(snow_extra(&extras(r#"{"snow": 0.25}"#)), Ok(Some(0.25)));
        assert!(snow_extra(&extras(r#"{"snow": 2}"#)).is_err());
        assert!(snow_extra(&extras(r#"{"snow": "yes"}"#)).is_err());
        assert_eq!(snow_extra(&extras("[1, 2]")), Ok(None));
    }
}
