//! The library's error type: every failure names the input at fault and what is wrong with it.

use std::path::PathBuf;

/// Every failure of the library, each worded for the user: what input, and what is wrong.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or writing a file failed; the message names the file and the system's reason.
    #[error("{}: {err}", path.display())]
    Io {
        /// The file read or written.
        path: PathBuf,
        /// The system's reason.
        err: std::io::Error,
    },
    /// A scene file is not valid TOML or does not fit the scene schema (an unknown key, a value of
    /// the wrong type).
    #[error("{}: malformed scene file: {message}", path.display())]
    SceneSyntax {
        /// The scene file; `<name>` for a built-in scene or text not read from a file.
        path: PathBuf,
        /// The TOML reader's message, with the line and column at fault.
        message: String,
    },
    /// A scene's field holds a value the scene model does not accept.
    #[error("invalid scene: `{field}` {problem}")]
    InvalidField {
        /// The field's dotted name as the scene file spells it (`water.depth`, `light.direction`).
        field: String,
        /// What is wrong, as the tail of a sentence (`must be positive, got -1`).
        problem: String,
    },
    /// A file other than a scene file (a mesh, a height field, an image) cannot be used.
    #[error("{}: {problem}", path.display())]
    BadFile {
        /// The file at fault.
        path: PathBuf,
        /// What is wrong with it.
        problem: String,
    },
    /// No built-in scene has this name.
    #[error("unknown built-in scene `{0}` (known: pool, shore, reef, objects, glass, underwater)")]
    UnknownScene(String),
    /// A parameter given outside a scene's fields (a command-line option, a technique's setting, a
    /// function's argument) is malformed or out of range; the message names it.
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
    /// What was asked for does not exist here (an intermediate buffer of a scene without water,
    /// object 5 of three).
    #[error("{0}")]
    Unavailable(String),
}

impl Error {
    /// [`Error::InvalidField`]: the field's dotted name and what is wrong with it.
    pub fn field(field: impl Into<String>, problem: impl Into<String>) -> Self {
        Error::InvalidField {
            field: field.into(),
            problem: problem.into(),
        }
    }

    /// [`Error::BadFile`]: the file and what is wrong with it.
    pub fn bad_file(path: impl Into<PathBuf>, problem: impl Into<String>) -> Self {
        Error::BadFile {
            path: path.into(),
            problem: problem.into(),
        }
    }

    /// [`Error::BadFile`] for a file this build cannot read or write: `what` ("an OBJ mesh") needs
    /// the crate feature `feature`, which the application did not turn on.
    pub fn feature_off(path: impl Into<PathBuf>, what: &str, feature: &str) -> Self {
        Self::bad_file(
            path,
            format!(
                "{what} needs caustics-core's `{feature}` feature, which this build leaves out \
                 (add `features = [\"{feature}\"]` to its dependency)"
            ),
        )
    }

    /// [`Error::Io`]: the file and the system's error reading or writing it.
    pub fn io(path: impl Into<PathBuf>, err: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            err,
        }
    }
}

/// The library's result, failing with [`Error`] unless told otherwise.
pub type Result<T, E = Error> = std::result::Result<T, E>;

// The checks of a scene's numbers, with one wording; each names the field it refuses.

pub(crate) fn finite(field: &str, v: &[f64]) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::field(field, format!("must be finite, got {v:?}")))
    }
}

pub(crate) fn positive(field: &str, v: f64) -> Result<()> {
    finite(field, &[v])?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(Error::field(field, format!("must be positive, got {v}")))
    }
}

pub(crate) fn non_negative(field: &str, v: &[f64]) -> Result<()> {
    finite(field, v)?;
    if v.iter().all(|&x| x >= 0.0) {
        Ok(())
    } else {
        Err(Error::field(
            field,
            format!("must not be negative, got {v:?}"),
        ))
    }
}

pub(crate) fn at_least(field: &str, v: f64, min: f64) -> Result<()> {
    finite(field, &[v])?;
    if v >= min {
        Ok(())
    } else {
        Err(Error::field(
            field,
            format!("must be at least {min}, got {v}"),
        ))
    }
}

pub(crate) fn between(field: &str, v: f64, min: f64, max: f64) -> Result<()> {
    if (min..=max).contains(&v) {
        Ok(())
    } else {
        Err(Error::field(
            field,
            format!("must be between {min} and {max}, got {v}"),
        ))
    }
}
