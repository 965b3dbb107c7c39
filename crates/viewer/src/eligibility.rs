//! Snow eligibility from glTF `extras` (docs/architecture.md §6, rule 2): `{"snow": false}`,
//! `{"snow": true}` or `{"snow": 0.0..1.0}` on a material, mesh or node; and the
//! surface a mesh is made of: `{"surface": "asphalt" | "soil" | "grass" | "roof" |
//! "water"}` or `{"water": true}` (a pond, a lake) or `{"water": "sea"}` (the open
//! sea, drawn with the wind's waves), with the same precedence (material, then
//! mesh, then the nearest node up the hierarchy).

use precip_model::cover::Surface;

fn extras_object(extras: &gltf::json::Extras) -> Result<Option<serde_json::Value>, String> {
    let Some(raw) = extras else {
        return Ok(None);
    };
    serde_json::from_str(raw.get())
        .map(Some)
        .map_err(|e| e.to_string())
}

/// What a primitive is made of, as its `extras` say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SurfaceTag {
    /// The surface.
    pub surface: Surface,
    /// The open sea (`"water": "sea"`; its surface is water).
    pub sea: bool,
}

impl From<Surface> for SurfaceTag {
    fn from(surface: Surface) -> Self {
        Self {
            surface,
            sea: false,
        }
    }
}

/// The `surface` (or `water: true`, `water: "sea"`) of an `extras` object:
/// `Ok(None)` when absent, `Err` with a message when present but not a known name.
pub fn surface_extra(extras: &gltf::json::Extras) -> Result<Option<SurfaceTag>, String> {
    let Some(value) = extras_object(extras)? else {
        return Ok(None);
    };
    if let Some(water) = value.get("water") {
        return match water {
            serde_json::Value::Bool(true) => Ok(Some(Surface::Water.into())),
            serde_json::Value::String(s) if s == "sea" => Ok(Some(SurfaceTag {
                surface: Surface::Water,
                sea: true,
            })),
            serde_json::Value::Bool(false) => Ok(None),
            other => Err(format!(
                "extras.water = {other} must be true, false or \"sea\""
            )),
        };
    }
    match value.get("surface") {
        None => Ok(None),
        Some(serde_json::Value::String(name)) => Surface::from_name(name)
            .map(|s| Some(s.into()))
            .ok_or_else(|| {
                format!(
                    "extras.surface = \"{name}\" is not a surface: use one of {}",
                    Surface::NAMES.join(", ")
                )
            }),
        Some(other) => Err(format!(
            "extras.surface = {other} must be a string: one of {}",
            Surface::NAMES.join(", ")
        )),
    }
}

/// The `snow` value of an `extras` object: `Ok(None)` when absent (or `extras` is not
/// an object), `Err` with a message when present but not a boolean or number in [0, 1].
pub fn snow_extra(extras: &gltf::json::Extras) -> Result<Option<f32>, String> {
    let Some(value) = extras_object(extras)? else {
        return Ok(None);
    };
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

    #[test]
    fn reads_the_surfaces() {
        assert_eq!(surface_extra(&None), Ok(None));
        assert_eq!(surface_extra(&extras(r#"{"snow": false}"#)), Ok(None));
        assert_eq!(
            surface_extra(&extras(r#"{"surface": "asphalt"}"#)),
            Ok(Some(Surface::Asphalt.into()))
        );
        assert_eq!(
            surface_extra(&extras(r#"{"water": true}"#)),
            Ok(Some(Surface::Water.into()))
        );
        assert_eq!(
            surface_extra(&extras(r#"{"water": "sea"}"#)),
            Ok(Some(SurfaceTag {
                surface: Surface::Water,
                sea: true
            }))
        );
        let unknown = surface_extra(&extras(r#"{"surface": "lava"}"#)).unwrap_err();
        assert!(
            unknown.contains("lava") && unknown.contains("asphalt"),
            "{unknown}"
        );
        assert!(surface_extra(&extras(r#"{"surface": 3}"#)).is_err());
        let yes = surface_extra(&extras(r#"{"water": "yes"}"#)).unwrap_err();
        assert!(yes.contains("\"sea\""), "{yes}");
    }
}
