//! What can go wrong loading a scene or running the viewer.

use std::path::PathBuf;

/// A scene file that cannot be shown.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be read or parsed as glTF.
    #[error("{file}: not a loadable glTF 2.0 file: {detail}")]
    Gltf {
        /// The file.
        file: PathBuf,
        /// What the glTF reader said.
        detail: String,
    },
    /// The file is glTF but some part of it is broken.
    #[error("{file}: {problem}")]
    Invalid {
        /// The file.
        file: PathBuf,
        /// What is wrong, naming the mesh/accessor.
        problem: String,
    },
    /// Nothing in the file can be drawn.
    #[error("{file}: no triangles to show ({detail}); export the scene's meshes as triangles")]
    NoTriangles {
        /// The file.
        file: PathBuf,
        /// What was skipped.
        detail: String,
    },
    /// The scene's geometry failed precip's checks.
    #[error("{file}: {source}")]
    Scene {
        /// The file.
        file: PathBuf,
        /// The check that failed.
        source: precip_model::SceneError,
    },
    /// Writing a file failed.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}
