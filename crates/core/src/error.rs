//! The library's error type: every failure names the input at fault and what is wrong with it.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or writing a file failed; the message names the file and the system's reason.
    #[error("{}: {err}", path.display())]
    Io { path: PathBuf, err: std::io::Error },
    #[error("{}: malformed scene file: {message}", path.display())]
    SceneSyntax { path: PathBuf, message: String },
    #[error("invalid scene: `{field}` {problem}")]
    InvalidField { field: String, problem: String },
    #[error("{}: {problem}", path.display())]
    BadFile { path: PathBuf, problem: String },
    #[error("unknown built-in scene `{0}` (known: pool, shore, reef, objects, glass, underwater)")]
    UnknownScene(String),
    #[error("unknown technique `{0}`; `caustics techniques` lists them")]
    UnknownTechnique(String),
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
    /// What was asked for does not exist here (an intermediate buffer of a scene without water,
    /// object 5 of three).
    #[error("{0}")]
    Unavailable(String),
}

impl Error {
    pub fn field(field: impl Into<String>, problem: impl Into<String>) -> Self {
        Error::InvalidField {
            field: field.into(),
            problem: problem.into(),
        }
    }

    pub fn bad_file(path: impl Into<PathBuf>, problem: impl Into<String>) -> Self {
        Error::BadFile {
            path: path.into(),
            problem: problem.into(),
        }
    }

    pub fn io(path: impl Into<PathBuf>, err: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            err,
        }
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
