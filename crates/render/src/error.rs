//! Errors of the renderer; every message names the file (and, for scenes, the line and key) and says what to do.

/// What went wrong while loading or rendering a scene.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A problem in the scene file, with its location.
    #[error("{path}:{line}: {message}")]
    Scene { path: String, line: usize, message: String },
    /// Bad input outside the scene text (meshes, textures, tables).
    #[error("{0}")]
    Input(String),
    #[error("{0}")]
    Io(#[from] std::io::Error),
}
