//! The weather of an OpenSCENARIO 1.x file over time (`--scenario FILE.xosc`).
//!
//! The storyboard's `Init` gives the weather from the start and its stories' events
//! change it at the simulation times their triggers name ([`timeline`]); each
//! `EnvironmentAction` holds an `Environment` ([`environment`]) or a
//! `CatalogReference` to one in an environment catalog ([`catalogs`]). Every
//! attribute may be a parameter: `$name` from the `ParameterDeclarations` of the
//! file, the story, the maneuver or the catalog entry, or a 1.2 expression `${…}`
//! ([`parameters`], [`expressions`]). What cannot be used is an error naming the
//! file, element and attribute; what is read but not applied (an event waiting on
//! something other than time) is a note ([`Scenario::notes`]). Parsed as a DOM with
//! `roxmltree` (a small, well-kept, read-only XML tree: a storyboard and catalogs
//! need walking, which a streaming reader makes awkward).

pub mod apply;
pub mod catalogs;
pub mod environment;
pub mod expressions;
pub mod parameters;
pub mod timeline;

use std::path::{Path, PathBuf};

pub use environment::{
    FULL_INTENSITY_MM_PER_H, ScenarioWeather, cloud_layer_of, environment_weather,
};
pub use timeline::{Scenario, TimedWeather};

/// A scenario whose weather cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{file}: {detail}")]
    Read {
        /// The file.
        file: PathBuf,
        /// Why.
        detail: String,
    },
    /// The XML is broken.
    #[error("{file}: not well-formed XML: {detail}")]
    Xml {
        /// The file.
        file: PathBuf,
        /// Where and why.
        detail: String,
    },
    /// No `Environment` with a `Weather`.
    #[error(
        "{file}: no Environment/Weather element: give the scenario an EnvironmentAction with a Weather"
    )]
    NoWeather {
        /// The file.
        file: PathBuf,
    },
    /// An attribute is missing, not a number, or out of range.
    #[error("{file}: {element}@{attribute} = {value:?}: {problem}")]
    Attribute {
        /// The file.
        file: PathBuf,
        /// The element.
        element: &'static str,
        /// The attribute.
        attribute: &'static str,
        /// What it says.
        value: String,
        /// What is wrong and what is allowed.
        problem: String,
    },
    /// A parameter declaration cannot be resolved.
    #[error("{file}: {problem}")]
    Parameter {
        /// The file.
        file: PathBuf,
        /// What is wrong.
        problem: String,
    },
    /// A catalog reference cannot be followed.
    #[error("{file}: {problem}")]
    Catalog {
        /// The file.
        file: PathBuf,
        /// What is wrong.
        problem: String,
    },
    /// The weather it describes is not physical (precip_model's validation).
    #[error("{file}: {0}", file = .1.display())]
    Weather(precip_model::WeatherError, PathBuf),
}

/// Reads the OpenSCENARIO file `file`.
pub fn load_scenario(file: &Path) -> Result<Scenario, ScenarioError> {
    let text = std::fs::read_to_string(file).map_err(|e| ScenarioError::Read {
        file: file.to_path_buf(),
        detail: e.to_string(),
    })?;
    scenario_from_text(&text, file)
}

/// Reads OpenSCENARIO text (`file` names it in errors; catalogs are found from its
/// folder).
pub fn scenario_from_text(text: &str, file: &Path) -> Result<Scenario, ScenarioError> {
    let doc = roxmltree::Document::parse(text).map_err(|e| ScenarioError::Xml {
        file: file.to_path_buf(),
        detail: e.to_string(),
    })?;
    timeline::scenario_of(doc.root_element(), file)
}

#[cfg(test)]
mod tests;
