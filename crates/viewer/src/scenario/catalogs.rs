//! Environment catalogs: a scenario's `CatalogLocations/EnvironmentCatalog/
//! Directory@path` (relative to the scenario's folder) holds `.xosc` files whose
//! `Catalog` elements hold named `Environment`s; an `EnvironmentAction`'s
//! `CatalogReference` names the catalog (`catalogName`) and the entry
//! (`entryName`), and may assign the entry's parameters.

use std::path::{Path, PathBuf};

use roxmltree::Node;

use super::ScenarioError;
use super::environment::{ScenarioWeather, environment_weather};
use super::parameters::Parameters;

/// Where a scenario's environment catalogs are.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Catalogs {
    directories: Vec<PathBuf>,
}

impl Catalogs {
    /// The environment catalogs' directories named under `root`'s
    /// `CatalogLocations`, relative to `folder`.
    pub fn of(
        root: Node<'_, '_>,
        folder: &Path,
        parameters: &Parameters,
        file: &Path,
    ) -> Result<Self, ScenarioError> {
        let mut directories = Vec::new();
        let locations = root
            .children()
            .filter(|c| c.has_tag_name("CatalogLocations"))
            .flat_map(|l| l.children())
            .filter(|c| c.has_tag_name("EnvironmentCatalog"))
            .flat_map(|c| c.children())
            .filter(|c| c.has_tag_name("Directory"));
        for directory in locations {
            let raw = directory.attribute("path").unwrap_or_default();
            let path = parameters
                .resolve(raw)
                .map_err(|problem| ScenarioError::Attribute {
                    file: file.to_path_buf(),
                    element: "EnvironmentCatalog/Directory",
                    attribute: "path",
                    value: raw.to_owned(),
                    problem,
                })?;
            directories.push(folder.join(path));
        }
        Ok(Self { directories })
    }

    /// The weather of the catalog entry `reference` (a `CatalogReference`) names,
    /// its parameters assigned in `caller`'s scope.
    pub fn environment(
        &self,
        reference: Node<'_, '_>,
        caller: &Parameters,
        file: &Path,
    ) -> Result<ScenarioWeather, ScenarioError> {
        let name = |attribute: &'static str| {
            let raw = reference.attribute(attribute).unwrap_or_default();
            caller
                .resolve(raw)
                .map_err(|problem| ScenarioError::Attribute {
                    file: file.to_path_buf(),
                    element: "CatalogReference",
                    attribute,
                    value: raw.to_owned(),
                    problem,
                })
        };
        let (catalog, entry) = (name("catalogName")?, name("entryName")?);
        let catalog_error = |problem: String| ScenarioError::Catalog {
            file: file.to_path_buf(),
            problem,
        };
        for directory in &self.directories {
            let Ok(listing) = std::fs::read_dir(directory) else {
                continue;
            };
            let mut files: Vec<PathBuf> = listing
                .flatten()
                .map(|e| e.path())
                .filter(|p| {
                    p.extension()
                        .is_some_and(|x| x.eq_ignore_ascii_case("xosc"))
                })
                .collect();
            files.sort();
            for path in files {
                let text = std::fs::read_to_string(&path).map_err(|e| ScenarioError::Read {
                    file: path.clone(),
                    detail: e.to_string(),
                })?;
                let doc = roxmltree::Document::parse(&text).map_err(|e| ScenarioError::Xml {
                    file: path.clone(),
                    detail: e.to_string(),
                })?;
                let found = doc
                    .descendants()
                    .filter(|n| {
                        n.has_tag_name("Catalog") && n.attribute("name") == Some(catalog.as_str())
                    })
                    .flat_map(|c| c.children())
                    .find(|n| {
                        n.has_tag_name("Environment") && n.attribute("name") == Some(entry.as_str())
                    });
                if let Some(environment) = found {
                    let own = Parameters::declared_in(environment, &Parameters::default())
                        .map_err(|problem| ScenarioError::Catalog {
                            file: path.clone(),
                            problem,
                        })?;
                    let scope = own
                        .assigned_from(reference, caller)
                        .map_err(&catalog_error)?;
                    return environment_weather(environment, &scope, &path);
                }
            }
        }
        let searched: Vec<String> = self
            .directories
            .iter()
            .map(|d| d.display().to_string())
            .collect();
        Err(catalog_error(format!(
            "CatalogReference catalogName=\"{catalog}\" entryName=\"{entry}\": no such Environment in the .xosc files of {} (the scenario's CatalogLocations/EnvironmentCatalog directories)",
            if searched.is_empty() {
                "no directory".to_owned()
            } else {
                searched.join(", ")
            }
        )))
    }
}
