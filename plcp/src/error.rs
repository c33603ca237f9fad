//! Errors: bad input, reported at construction. An algorithm's outcome is a
//! [`Status`](crate::Status) in the [`Path`](crate::Path), never an error.

use thiserror::Error;

/// What is wrong with the input of a problem, a setting or a file.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PlcpError {
    /// A matrix or vector has the wrong size.
    #[error("dimension mismatch: {what} has {found}, expected {expected}")]
    Dimension {
        /// Which input.
        what: String,
        /// What was expected.
        expected: String,
        /// What was found.
        found: String,
    },
    /// An entry is NaN or infinite.
    #[error("non-finite entry in {what} at {position}: {value}")]
    NonFinite {
        /// Which input.
        what: String,
        /// Where, e.g. `(2, 3)` or `[4]`.
        position: String,
        /// The value as read.
        value: f64,
    },
    /// A nonzero entry below the smallest normal number of the working
    /// precision: it would be zero, or lose digits, in that type.
    #[error("{what} entry {position} = {value:e} underflows the working precision {precision}: it is below its smallest normal number {min_normal:e} (it would be traced as zero or with lost digits); rescale the data as a whole or use a wider precision")]
    Underflow {
        /// Which input.
        what: String,
        /// Where, e.g. `(2, 3)` or `[4]`.
        position: String,
        /// The value as given (as read, for files).
        value: f64,
        /// The working precision's name.
        precision: String,
        /// Its smallest positive normal number.
        min_normal: f64,
    },
    /// A scalar argument or setting out of its range.
    #[error("invalid {what}: {why}")]
    Invalid {
        /// Which argument.
        what: String,
        /// Why it is invalid.
        why: String,
    },
    /// The free block of a mixed problem is singular, so it has no reduction
    /// to standard form.
    #[error("the free block ({p} x {p}) is singular (numerical rank {rank}): no reduction to standard form exists; use the Wolfe long form (--method wolfe), which works on the unreduced system")]
    SingularFreeBlock {
        /// Size of the free block.
        p: usize,
        /// Its numerical rank.
        rank: usize,
    },
    /// A file could not be parsed.
    #[error("{file}:{line}:{column}: {message}")]
    Parse {
        /// The file name.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// An I/O failure reading a file.
    #[error("{file}: {message}")]
    Io {
        /// The file name.
        file: String,
        /// The system's message.
        message: String,
    },
}
