//! `crawltrace._crawltrace`, the extension module behind the `crawltrace` Python package (pyo3):
//! `trace` (an image file, its bytes, or a numpy array → a `Drawing`) and `reconstruct` (a point
//! set → curves and outliers, the Crawl through Neighbors of Parakkat & Muthuganapathy, CGF
//! 2016). Options carry the command line's names and checks, errors its one-line messages, and
//! the GIL is released while the library works. The Python side (`crawltrace/__init__.py`) adds
//! the argument conversion of `reconstruct` and the documentation.
#![forbid(unsafe_code)]

mod image_array;
mod options;

use std::path::PathBuf;

use crawltrace::stages::flatten::flatten_path;
use crawltrace::{
    export, trace, trace_bytes, trace_file, ExportOptions, OutputFormat, Point, Traced,
};
use image::DynamicImage;
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyMemoryView, PyString};

use options::TraceArguments;

pyo3::create_exception!(
    _crawltrace,
    CrawltraceError,
    PyValueError,
    "Bad input to crawltrace: a file that cannot be read or is not an image, a blank page, an \
     option out of range, an array of the wrong shape or type. The message is one line, as the \
     command line prints it."
);

/// The error as a Python exception.
fn error(message: impl ToString) -> PyErr {
    CrawltraceError::new_err(message.to_string())
}

/// One curve: its vertices as an `(N, 2)` float64 array of `x, y` and whether it is closed (a
/// closed curve does not repeat its first vertex). Curves of `reconstruct` also have the input
/// indices of their points (`indices`); traced curves have `indices = None`.
#[pyclass(frozen, module = "crawltrace")]
struct Curve {
    points: Py<PyArray2<f64>>,
    closed: bool,
    indices: Option<Py<PyArray1<i64>>>,
}

#[pymethods]
impl Curve {
    /// The vertices, an `(N, 2)` float64 array of `x, y`.
    #[getter]
    fn points(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        self.points.clone_ref(py)
    }

    /// Whether the last vertex connects back to the first.
    #[getter]
    fn closed(&self) -> bool {
        self.closed
    }

    /// For curves of `reconstruct`: the input index of each vertex (int64); else `None`.
    #[getter]
    fn indices(&self, py: Python<'_>) -> Option<Py<PyArray1<i64>>> {
        self.indices.as_ref().map(|indices| indices.clone_ref(py))
    }

    fn __len__(&self, py: Python<'_>) -> usize {
        self.points.bind(py).shape()[0]
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let kind = if self.closed { "closed" } else { "open" };
        format!("<Curve {kind}, {} points>", self.__len__(py))
    }
}

/// An `(N, 2)` array of the points.
fn points_array(py: Python<'_>, points: &[Point]) -> Py<PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    Array2::from_shape_vec((points.len(), 2), flat)
        .expect("two coordinates a point")
        .into_pyarray(py)
        .unbind()
}

/// A traced drawing: its curves in pixel coordinates (x to the right, y down, pixel centres at
/// +0.5), its size in pixels and physically, and its SVG and DXF text.
#[pyclass(frozen, module = "crawltrace")]
struct Drawing {
    traced: Traced,
    export: ExportOptions,
}

#[pymethods]
impl Drawing {
    /// Width of the image in pixels.
    #[getter]
    fn width(&self) -> f64 {
        self.traced.drawing.width
    }

    /// Height of the image in pixels.
    #[getter]
    fn height(&self) -> f64 {
        self.traced.drawing.height
    }

    /// The pixel density the image file records (pixels per inch), or `None`.
    #[getter]
    fn image_dpi(&self) -> Option<f64> {
        self.traced.image_dpi
    }

    /// The pixels per inch the outputs use: from `size`, `dpi`, the image's own density, else 96.
    #[getter]
    fn dpi(&self) -> f64 {
        self.export.physical_size(&self.traced).dpi
    }

    /// The unit of the outputs' sizes and DXF coordinates, `"mm"` or `"in"`.
    #[getter]
    fn units(&self) -> &'static str {
        self.export.physical_size(&self.traced).units.name()
    }

    /// The measured pen width in pixels.
    #[getter]
    fn pen_width(&self) -> f64 {
        self.traced.report.stroke_width
    }

    /// The curves, top to bottom then left to right, Béziers flattened within the fitting
    /// tolerance (`simplify`), in pixels.
    #[getter]
    fn curves(&self, py: Python<'_>) -> PyResult<Vec<Py<Curve>>> {
        let tolerance = self.traced.report.tolerance;
        self.traced
            .drawing
            .paths
            .iter()
            .map(|path| {
                let curve = Curve {
                    points: points_array(py, &flatten_path(path, tolerance)),
                    closed: path.closed,
                    indices: None,
                };
                Py::new(py, curve)
            })
            .collect()
    }

    /// The SVG document: `width`/`height` in mm or inches, `viewBox` and paths in pixels.
    fn to_svg(&self, py: Python<'_>) -> String {
        self.write(py, OutputFormat::Svg)
    }

    /// The DXF R2000 document: one LWPOLYLINE per curve in mm or inches, y pointing up.
    fn to_dxf(&self, py: Python<'_>) -> String {
        self.write(py, OutputFormat::Dxf)
    }

    fn __repr__(&self) -> String {
        let paths = &self.traced.drawing.paths;
        format!(
            "<Drawing {}×{} px, {} curves ({} closed)>",
            self.width(),
            self.height(),
            paths.len(),
            paths.iter().filter(|path| path.closed).count()
        )
    }
}

impl Drawing {
    fn write(&self, py: Python<'_>, format: OutputFormat) -> String {
        let options = ExportOptions {
            format,
            ..self.export
        };
        py.detach(|| export(&self.traced, &options))
    }
}

/// What `trace` was given.
enum Source {
    File(PathBuf),
    Bytes(Vec<u8>),
    Image(DynamicImage),
}

/// Reads the first argument of `trace`: a numpy array, bytes-like data, or a path.
fn source(object: &Bound<'_, PyAny>) -> PyResult<Source> {
    if let Ok(array) = object.cast::<PyUntypedArray>() {
        return Ok(Source::Image(image_array::to_image(array)?));
    }
    if let Ok(bytes) = object.cast::<PyBytes>() {
        return Ok(Source::Bytes(bytes.as_bytes().to_vec()));
    }
    if let Ok(bytes) = object.cast::<PyByteArray>() {
        return Ok(Source::Bytes(bytes.to_vec()));
    }
    if object.cast::<PyMemoryView>().is_ok() {
        let bytes = object.call_method0("tobytes")?;
        return Ok(Source::Bytes(bytes.cast::<PyBytes>()?.as_bytes().to_vec()));
    }
    let is_path = object.cast::<PyString>().is_ok() || object.hasattr("__fspath__")?;
    if is_path {
        return Ok(Source::File(object.extract()?));
    }
    Err(PyTypeError::new_err(format!(
        "trace() takes a path, bytes or a numpy array, not {}",
        object.get_type().name()?
    )))
}

/// Traces a line drawing; see `crawltrace.trace` for the arguments.
#[pyfunction]
#[pyo3(signature = (
    source_, /, *, threshold=None, adaptive=false, invert=false, spacing=None,
    method="strokes", smooth=true, simplify=None, stroke_width=None, color="#000000",
    dpi=None, size=None, units=None,
))]
#[allow(clippy::too_many_arguments)] // the options of `crawltrace trace`, by name
fn trace_drawing(
    py: Python<'_>,
    source_: &Bound<'_, PyAny>,
    threshold: Option<i64>,
    adaptive: bool,
    invert: bool,
    spacing: Option<f64>,
    method: &str,
    smooth: bool,
    simplify: Option<f64>,
    stroke_width: Option<f64>,
    color: &str,
    dpi: Option<f64>,
    size: Option<&str>,
    units: Option<&str>,
) -> PyResult<Drawing> {
    let arguments = TraceArguments {
        threshold,
        adaptive,
        invert,
        spacing,
        method,
        smooth,
        simplify,
        stroke_width,
        color,
        dpi,
        size,
        units,
    };
    let (options, export) = arguments.check().map_err(error)?;
    let traced = match source(source_)? {
        Source::File(path) => py
            .detach(|| trace_file(&path, &options))
            .map_err(|e| error(format!("{}: {e}", path.display())))?,
        Source::Bytes(bytes) => py.detach(|| trace_bytes(bytes, &options)).map_err(error)?,
        Source::Image(image) => py.detach(|| trace(&image, &options)).map_err(error)?,
    };
    Ok(Drawing { traced, export })
}

/// What `reconstruct` returns: the curves, and the indices of the outliers.
type CurvesAndOutliers<'py> = (Vec<Py<Curve>>, Bound<'py, PyArray1<i64>>);

/// Reconstructs curves from an `(N, 2)` float64 array; see `crawltrace.reconstruct`.
#[pyfunction]
fn reconstruct_points<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
) -> PyResult<CurvesAndOutliers<'py>> {
    let array = points.as_array();
    if array.ncols() != 2 {
        return Err(error(format!(
            "points: must be an (N, 2) array of x, y; got shape ({}, {})",
            array.nrows(),
            array.ncols()
        )));
    }
    let points: Vec<Point> = array
        .rows()
        .into_iter()
        .map(|row| Point::new(row[0], row[1]))
        .collect();
    let reconstruction = py
        .detach(|| crawltrace::reconstruct(&points))
        .map_err(error)?;
    let index = |i: usize| i64::try_from(i).expect("an array index fits in i64");
    let curves = reconstruction
        .curves
        .iter()
        .map(|curve| {
            let vertices: Vec<Point> = curve.indices.iter().map(|&i| points[i]).collect();
            let indices: Vec<i64> = curve.indices.iter().copied().map(index).collect();
            let curve = Curve {
                points: points_array(py, &vertices),
                closed: curve.closed,
                indices: Some(indices.into_pyarray(py).unbind()),
            };
            Py::new(py, curve)
        })
        .collect::<PyResult<_>>()?;
    let outliers: Vec<i64> = reconstruction.outliers.iter().copied().map(index).collect();
    Ok((curves, outliers.into_pyarray(py)))
}

#[pymodule]
fn _crawltrace(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("CrawltraceError", module.py().get_type::<CrawltraceError>())?;
    module.add_class::<Curve>()?;
    module.add_class::<Drawing>()?;
    module.add_function(wrap_pyfunction!(trace_drawing, module)?)?;
    module.add_function(wrap_pyfunction!(reconstruct_points, module)?)?;
    Ok(())
}
