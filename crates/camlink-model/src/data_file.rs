//! Data files a model names (a spline's CSV points): where they may be.
//!
//! A model file is shared between people, so opening one must not read
//! the reader's other files. A data file resolves against the model's
//! folder and must stay inside it (after following every symbolic link)
//! unless the user opts in with [`LoadOptions::allow_outside_data`]. The
//! reading itself (regular files only, a size cap, short escaped excerpts
//! in errors) is [`camlink_core::curve::read_points_csv`].

use std::cell::RefCell;
use std::path::{Path, PathBuf};

/// How a model is loaded.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// The folder data files resolve against; `None`: the model file's
    /// folder ([`crate::load_str`]: the folder of its `source`, the current
    /// folder for a bare name).
    pub base_dir: Option<PathBuf>,
    /// Read data files outside that folder too (absolute paths, `..`,
    /// symbolic links that leave it).
    pub allow_outside_data: bool,
}

/// The data files of one load: where they resolve and which were read.
#[derive(Debug)]
pub(crate) struct DataFiles {
    base: PathBuf,
    allow_outside: bool,
    /// Canonical paths of the files read, in order.
    read: RefCell<Vec<PathBuf>>,
}

impl DataFiles {
    pub(crate) fn new(base: &Path, allow_outside: bool) -> Self {
        DataFiles {
            base: base.to_path_buf(),
            allow_outside,
            read: RefCell::new(Vec::new()),
        }
    }

    /// The path to read for the name `name` written in the model, after
    /// checking that it stays in the model's folder; records it as read.
    pub(crate) fn resolve(&self, name: &str) -> Result<PathBuf, String> {
        let path = self.base.join(name);
        let real = std::fs::canonicalize(&path)
            .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        if !self.allow_outside {
            let folder = if self.base.as_os_str().is_empty() {
                Path::new(".")
            } else {
                &self.base
            };
            let folder = std::fs::canonicalize(folder)
                .map_err(|e| format!("{}: cannot read: {e}", folder.display()))?;
            if !real.starts_with(&folder) {
                return Err(format!(
                    "'{name}' is outside the model's folder {}; data files are read from \
                     that folder and below only (pass --allow-outside-data, or \
                     allow_outside=True in Python, to read it anyway)",
                    folder.display()
                ));
            }
        }
        self.read.borrow_mut().push(real.clone());
        Ok(real)
    }

    /// The canonical paths of the files read, in order.
    pub(crate) fn into_read(self) -> Vec<PathBuf> {
        self.read.into_inner()
    }
}
