//! Where a run's rows go: Python's `on_chunk` callback in chunks, and the
//! array the run returns; Ctrl-C watched while the core runs.

use camlink_core::quantity::Quantity;
use camlink_core::run::{Channel, Sink, Stop};
use numpy::ndarray::{Array2, ShapeBuilder};
use numpy::{IntoPyArray, PyArray2};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// Rows buffered between two calls of `on_chunk`, unless the caller says.
pub(crate) const DEFAULT_CHUNK_ROWS: usize = 1024;

/// Most bytes of rows buffered between two calls of `on_chunk`, whatever
/// `chunk_rows` says: a chunk holds at least one row and at most this many
/// bytes of values, so that a wide model's chunk stays small.
const CHUNK_BYTES: usize = 2 << 20;

/// Where a run's rows go: to `on_chunk` every `chunk_rows` rows and, with
/// `keep_rows`, into the array the run returns.
pub(crate) struct Delivery {
    on_chunk: Option<Py<PyAny>>,
    chunk_rows: usize,
    keep_rows: bool,
}

impl Delivery {
    pub(crate) fn new(on_chunk: Option<Py<PyAny>>, chunk_rows: usize, keep_rows: bool) -> Self {
        Delivery {
            on_chunk,
            chunk_rows: chunk_rows.max(1),
            keep_rows,
        }
    }
}

/// Collects rows and hands them to Python in chunks.
pub(crate) struct ChunkSink {
    pub(crate) names: Vec<String>,
    /// What each of `names` measures ([`Quantity::name`]), `"time"` first.
    pub(crate) quantities: Vec<&'static str>,
    /// Rows of the current chunk, row-major.
    chunk: Vec<f64>,
    /// Every row so far, row-major, when `keep_rows`; else empty.
    pub(crate) all: Vec<f64>,
    keep_rows: bool,
    /// Rows per chunk: the caller's `chunk_rows`, capped by [`CHUNK_BYTES`].
    chunk_rows: usize,
    on_chunk: Option<Py<PyAny>>,
    pub(crate) callback_error: Option<PyErr>,
    /// When Python's signal handlers last ran.
    checked: std::time::Instant,
    /// Ticks since the clock was last read.
    ticks: u32,
}

/// Longest wall time between two checks for Ctrl-C and other signals.
const SIGNAL_INTERVAL: std::time::Duration = std::time::Duration::from_millis(50);

impl ChunkSink {
    pub(crate) fn new(delivery: Delivery) -> Self {
        ChunkSink {
            names: Vec::new(),
            quantities: Vec::new(),
            chunk: Vec::new(),
            all: Vec::new(),
            keep_rows: delivery.keep_rows,
            chunk_rows: delivery.chunk_rows,
            on_chunk: delivery.on_chunk,
            callback_error: None,
            checked: std::time::Instant::now(),
            ticks: 0,
        }
    }

    /// Runs Python's signal handlers when [`SIGNAL_INTERVAL`] has passed
    /// since they last ran; stops the run if one raised (Ctrl-C), the
    /// exception going to the caller as for a failing `on_chunk`.
    fn watch_signals(&mut self) -> Result<(), Stop> {
        self.ticks += 1;
        // Reading the clock costs about as much as a small step: every 16th.
        if self.ticks < 16 {
            return Ok(());
        }
        self.ticks = 0;
        if self.checked.elapsed() < SIGNAL_INTERVAL {
            return Ok(());
        }
        self.checked = std::time::Instant::now();
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            // `on_chunk` stays: the rows buffered so far still reach it.
            self.callback_error.get_or_insert(e);
            return Err(Stop("interrupted".into()));
        }
        Ok(())
    }

    fn width(&self) -> usize {
        self.names.len()
    }

    /// Calls `on_chunk` with the buffered rows (if any), column-major, then
    /// moves them to `all` (with `keep_rows`) or drops them.
    pub(crate) fn flush(&mut self) {
        if self.chunk.is_empty() {
            return;
        }
        let result = Python::attach(|py| -> PyResult<()> {
            // Ctrl-C raises KeyboardInterrupt here even without a callback.
            py.check_signals()?;
            if let Some(cb) = &self.on_chunk {
                let rows = to_column_major_array(py, &self.chunk, self.width())?;
                cb.call1(py, (self.names.clone(), rows, self.quantities.clone()))?;
            }
            Ok(())
        });
        if let Err(e) = result {
            self.callback_error.get_or_insert(e);
            self.on_chunk = None;
        }
        if self.keep_rows {
            self.all.extend_from_slice(&self.chunk);
        }
        self.chunk.clear();
    }
}

/// A `rows × width` NumPy array in Fortran order from row-major values.
fn to_column_major_array<'py>(
    py: Python<'py>,
    values: &[f64],
    width: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = values.len().checked_div(width).unwrap_or(0);
    let mut columns = Vec::with_capacity(values.len());
    for k in 0..width {
        columns.extend(values.iter().skip(k).step_by(width));
    }
    let a = Array2::from_shape_vec((rows, width).f(), columns)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?;
    Ok(a.into_pyarray(py))
}

impl Sink for ChunkSink {
    fn begin(&mut self, channels: &[Channel]) {
        self.names = std::iter::once("t".to_string())
            .chain(channels.iter().map(|c| c.name.clone()))
            .collect();
        self.quantities = std::iter::once(Quantity::Time.name())
            .chain(channels.iter().map(|c| c.quantity.name()))
            .collect();
        let width = self.width().max(1);
        self.chunk_rows = self
            .chunk_rows
            .min(CHUNK_BYTES / (width * std::mem::size_of::<f64>()))
            .max(1);
        self.chunk.reserve(self.chunk_rows * width);
    }

    fn row(&mut self, t: f64, values: &[f64]) -> Result<(), Stop> {
        self.chunk.push(t);
        self.chunk.extend_from_slice(values);
        if self.chunk.len() >= self.chunk_rows * self.width() {
            self.flush();
            if self.callback_error.is_some() {
                return Err(Stop("on_chunk raised an exception".into()));
            }
        }
        self.watch_signals()
    }

    fn tick(&mut self) -> Result<(), Stop> {
        self.watch_signals()
    }
}
