//! [`SceneFileError`]: what is wrong with a scene file, and where — the
//! file, the line and the dotted key.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use hooke_core::{BuildError, ParameterError};
use thiserror::Error;

use crate::SceneError;

/// A scene file that cannot become a [`crate::Scene`]: the file, the line
/// (when known), the dotted key path (e.g. `bodies[1].stretch.stiffness`)
/// and what is wrong.
///
/// Its message reads `file:line: key: problem`, e.g.
/// `scenes/cloth.toml:14: bodies[0].stretch.stiffness: got -5, expected a
/// finite number ≥ 0 (N/m)`.
#[derive(Debug, Error)]
#[error("{}: {kind}", self.location())]
pub struct SceneFileError {
    /// The scene file.
    pub file: PathBuf,
    /// The line, from 1, when the problem has one.
    pub line: Option<usize>,
    /// The dotted key path of the value at fault; empty for the whole file.
    pub key: String,
    /// What is wrong (boxed, to keep results that carry this error small).
    pub kind: Box<ErrorKind>,
}

impl SceneFileError {
    /// `file:line: key`, leaving out what is unknown.
    fn location(&self) -> String {
        let mut at = self.file.display().to_string();
        if let Some(line) = self.line {
            at.push_str(&format!(":{line}"));
        }
        if !self.key.is_empty() {
            at.push_str(&format!(": {}", self.key));
        }
        at
    }
}

/// The kinds of problem a [`SceneFileError`] reports.
#[derive(Debug, Error)]
pub enum ErrorKind {
    /// The scene file could not be read.
    #[error("cannot read the file: {0}")]
    Io(std::io::Error),
    /// Text that is not TOML.
    #[error("not valid TOML: {0}")]
    Syntax(String),
    /// An unknown key, a value of the wrong type or a missing key, in the
    /// words of the TOML reader (`unknown field `x`, expected one of …`).
    #[error("{0}")]
    Schema(String),
    /// A value of the right type outside its range, an unknown name, or
    /// keys that contradict each other.
    #[error("got {value}, expected {expected}")]
    Invalid {
        /// The value given.
        value: String,
        /// What the value must be.
        expected: String,
    },
    /// A body the builders reject (for example a degenerate mesh element).
    #[error("{0}")]
    Scene(SceneError),
    /// A system the system builder rejects.
    #[error("{0}")]
    Build(BuildError),
    /// Integrator parameters the integrator rejects.
    #[error("{0}")]
    Integrator(ParameterError),
}

/// The text of a scene file and where it came from: makes errors with line
/// numbers from byte spans.
pub(crate) struct Source<'a> {
    /// The file's text.
    pub(crate) text: &'a str,
    /// The file's path, for errors.
    pub(crate) file: &'a Path,
}

impl Source<'_> {
    /// The 1-based line holding byte `offset` (the last line past the end).
    pub(crate) fn line(&self, offset: usize) -> usize {
        let bytes = self.text.as_bytes();
        let end = offset.min(bytes.len());
        1 + bytes[..end].iter().filter(|&&b| b == b'\n').count()
    }

    /// An error at `span` (if known) for `key`.
    pub(crate) fn error(
        &self,
        span: Option<Range<usize>>,
        key: impl Into<String>,
        kind: ErrorKind,
    ) -> SceneFileError {
        SceneFileError {
            file: self.file.to_owned(),
            line: span.map(|s| self.line(s.start)),
            key: key.into(),
            kind: Box::new(kind),
        }
    }

    /// An [`ErrorKind::Invalid`] error: `value` at `span` is not what
    /// `expected` says.
    pub(crate) fn invalid(
        &self,
        span: Range<usize>,
        key: impl Into<String>,
        value: impl fmt::Display,
        expected: impl Into<String>,
    ) -> SceneFileError {
        self.error(
            Some(span),
            key,
            ErrorKind::Invalid {
                value: value.to_string(),
                expected: expected.into(),
            },
        )
    }

    /// A builder's [`SceneError`] for the table at `span` and `key`.
    pub(crate) fn scene(&self, error: SceneError, span: Range<usize>, key: &str) -> SceneFileError {
        self.error(Some(span), key, ErrorKind::Scene(error))
    }

    /// A TOML reader's error at `path` (from `serde_path_to_error`) below
    /// the key `prefix`: the path made dotted, and a missing key named in
    /// it.
    pub(crate) fn serde(
        &self,
        prefix: &str,
        error: serde_path_to_error::Error<toml::de::Error>,
    ) -> SceneFileError {
        let mut key = prefix.to_owned();
        for segment in error.path().iter() {
            let text = segment.to_string();
            // The value inside a `Spanned` is reached through a private key.
            if text.starts_with("$__serde_spanned") {
                continue;
            }
            if !key.is_empty() && !text.starts_with('[') {
                key.push('.');
            }
            key.push_str(&text);
        }
        let inner = error.into_inner();
        let message = inner.message().to_owned();
        if let Some(missing) = message
            .strip_prefix("missing field `")
            .and_then(|rest| rest.split('`').next())
        {
            if !key.is_empty() {
                key.push('.');
            }
            key.push_str(missing);
        }
        self.error(inner.span(), key, ErrorKind::Schema(message))
    }
}
