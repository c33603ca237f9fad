//! Errors: bad input (a scene file, an option, a problem plcp refuses). The
//! outcome of a solve is a status in the analysis, never an error.

use thiserror::Error;

/// What is wrong with the input.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FramesError {
    /// A scene file is malformed or describes an impossible frame. Displayed on
    /// one line as `file:line: key: message`.
    #[error("{file}:{line}: {key}: {message}")]
    Scene {
        /// The file name as given.
        file: String,
        /// 1-based line of the offending key (0 when unknown).
        line: usize,
        /// The key, with the table it belongs to, e.g. `member "AB" to`.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A scene file is not valid TOML, has a key no table accepts, a value of
    /// the wrong type, or is not UTF-8. Displayed on one line as
    /// `file:line:column: key: message` (1-based; the column counts characters).
    #[error("{file}:{line}:{column}: {key}: {message}")]
    Syntax {
        /// The file name as given.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The key (an unknown key itself), or `(syntax)`, `(encoding)`.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A file could not be read or written.
    #[error("{file}: {message}")]
    Io {
        /// The file name.
        file: String,
        /// The system's message.
        message: String,
    },
    /// An option out of its range (command line or API).
    #[error("invalid {what}: {why}")]
    Invalid {
        /// Which option.
        what: String,
        /// Why.
        why: String,
    },
    /// plcp refused the problem or the settings (for example Lemke on the
    /// singular free block of a statically indeterminate frame).
    #[error(transparent)]
    Plcp(#[from] plcp::PlcpError),
}

impl FramesError {
    pub(crate) fn invalid(what: impl Into<String>, why: impl Into<String>) -> Self {
        FramesError::Invalid {
            what: what.into(),
            why: why.into(),
        }
    }
}
