//! Why a synthesis problem has no mechanism: the kind of failure, the
//! problem field it concerns and what is wrong.

use std::fmt;

/// The kind of a synthesis error (a stable slug for tests and users).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// Two prescribed poses (or precision points) are the same.
    Coincident,
    /// A pivot's three positions lie on a line: its centre is at infinity.
    Collinear,
    /// The data admit no real linkage (a link of zero, infinite or
    /// imaginary length, a singular system).
    NoSolution,
    /// A value is out of its range or not finite.
    Invalid,
}

impl ErrorKind {
    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::Coincident => "coincident",
            ErrorKind::Collinear => "collinear",
            ErrorKind::NoSolution => "no_solution",
            ErrorKind::Invalid => "invalid",
        }
    }
}

/// A synthesis error: its kind, the problem field it concerns (e.g.
/// `synthesis.poses`), and the message.
#[derive(Clone, Debug, PartialEq)]
pub struct SynthError {
    pub kind: ErrorKind,
    pub field: Option<String>,
    pub message: String,
}

impl SynthError {
    pub fn new(kind: ErrorKind, field: impl Into<String>, message: impl Into<String>) -> Self {
        SynthError {
            kind,
            field: Some(field.into()),
            message: message.into(),
        }
    }
}

impl fmt::Display for SynthError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for SynthError {}
