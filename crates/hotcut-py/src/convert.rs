//! Numbers between Python and Rust. Points come in as any sequence of 2 or 3 numbers per
//! point (lists, tuples, numpy arrays, Rhino's `Point3d` with `X`, `Y`, `Z`, compas'
//! `Point`); arrays go out as numpy arrays when numpy is installed (and
//! `hotcut.use_numpy(False)` was not called), else as lists, since Rhino's Python may lack
//! numpy and Grasshopper reads lists best.

use std::sync::atomic::{AtomicU8, Ordering};

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// 0: not read yet, 1: numpy when importable, 2: lists (`use_numpy(False)`, or
/// `HOTCUT_ARRAYS=list` in the environment at the first call).
static MODE: AtomicU8 = AtomicU8::new(0);
/// numpy, when it could be imported.
static NUMPY: PyOnceLock<Option<Py<PyModule>>> = PyOnceLock::new();

/// numpy for output arrays, or `None` for lists.
fn numpy(py: Python<'_>) -> Option<Bound<'_, PyModule>> {
    if MODE.load(Ordering::Relaxed) == 0 {
        let lists = std::env::var("HOTCUT_ARRAYS").is_ok_and(|v| v.eq_ignore_ascii_case("list"));
        let _ = MODE.compare_exchange(
            0,
            if lists { 2 } else { 1 },
            Ordering::Relaxed,
            Ordering::Relaxed,
        );
    }
    if MODE.load(Ordering::Relaxed) == 2 {
        return None;
    }
    NUMPY
        .get_or_init(py, || py.import("numpy").ok().map(Bound::unbind))
        .as_ref()
        .map(|m| m.bind(py).clone())
}

/// Whether arrays come out as numpy arrays (`True`) or lists.
#[pyfunction]
fn arrays_are_numpy(py: Python<'_>) -> bool {
    numpy(py).is_some()
}

/// `use_numpy(False)`: arrays come out as lists from now on; `use_numpy(True)`: as numpy
/// arrays when numpy can be imported.
#[pyfunction]
fn use_numpy(flag: bool) {
    MODE.store(if flag { 1 } else { 2 }, Ordering::Relaxed);
}

/// Points read from Python: `dim` is 2 or 3; 2-D points have z = 0.
pub struct Points {
    /// 2 or 3.
    pub dim: usize,
    /// The points.
    pub xyz: Vec<[f64; 3]>,
}

impl Points {
    /// The x, y of every point.
    pub fn xy(&self) -> Vec<[f64; 2]> {
        self.xyz.iter().map(|p| [p[0], p[1]]).collect()
    }
}

fn value_error(what: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{what}: {message}"))
}

/// Whether `obj` is a numpy array (without importing numpy).
fn is_ndarray(obj: &Bound<'_, PyAny>) -> bool {
    let ty = obj.get_type();
    ty.name().is_ok_and(|n| n == "ndarray")
        && ty
            .module()
            .is_ok_and(|m| m.to_string().starts_with("numpy"))
}

/// Points from an (n, 2) or (n, 3) array-like; at least `min` of them, all finite.
pub fn points(obj: &Bound<'_, PyAny>, what: &str, min: usize) -> PyResult<Points> {
    let p = if is_ndarray(obj) {
        points_of_array(obj, what)?
    } else {
        points_of_sequence(obj, what)?
    };
    if p.xyz.len() < min {
        return Err(value_error(
            what,
            format!("at least {min} points are needed, got {}", p.xyz.len()),
        ));
    }
    if let Some(i) = p.xyz.iter().position(|q| !q.iter().all(|c| c.is_finite())) {
        return Err(value_error(what, format!("point {i} is not finite")));
    }
    Ok(p)
}

/// An ndarray read through its bytes: one copy, no Python object per number.
fn points_of_array(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Points> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let a = np.call_method1("ascontiguousarray", (obj, "float64"))?;
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    let (n, dim) = match shape[..] {
        [n, d] if d == 2 || d == 3 => (n, d),
        _ => {
            return Err(value_error(
                what,
                format!("expected an (n, 2) or (n, 3) array, got shape {shape:?}"),
            ))
        }
    };
    let bytes = a.call_method0("tobytes")?;
    let bytes = bytes.cast::<PyBytes>()?.as_bytes();
    let mut xyz = Vec::with_capacity(n);
    for row in bytes.chunks_exact(8 * dim) {
        let mut q = [0.0; 3];
        for (k, c) in row.chunks_exact(8).enumerate() {
            let mut b = [0u8; 8];
            b.copy_from_slice(c);
            q[k] = f64::from_ne_bytes(b);
        }
        xyz.push(q);
    }
    Ok(Points { dim, xyz })
}

/// One point: a sequence of 2 or 3 numbers, or an object with `X`, `Y` (and `Z`), as
/// Rhino's points are.
fn point(item: &Bound<'_, PyAny>, what: &str, i: usize) -> PyResult<(usize, [f64; 3])> {
    // tuples and lists first: asking them for `X` would raise (and cost) an AttributeError
    let plain = item.is_instance_of::<PyTuple>() || item.is_instance_of::<PyList>();
    if plain {
        return coordinates(item, what, i);
    }
    if let (Ok(x), Ok(y)) = (item.getattr("X"), item.getattr("Y")) {
        let z = match item.getattr("Z") {
            Ok(z) => Some(z.extract::<f64>()?),
            Err(_) => None,
        };
        return Ok((
            if z.is_some() { 3 } else { 2 },
            [x.extract()?, y.extract()?, z.unwrap_or(0.0)],
        ));
    }
    coordinates(item, what, i)
}

/// The 2 or 3 numbers of a point given as a sequence.
fn coordinates(item: &Bound<'_, PyAny>, what: &str, i: usize) -> PyResult<(usize, [f64; 3])> {
    let mut q = [0.0; 3];
    let mut d = 0;
    let iter = item.try_iter().map_err(|_| {
        PyTypeError::new_err(format!(
            "{what}: point {i} is not a sequence of 2 or 3 numbers"
        ))
    })?;
    for c in iter {
        if d == 3 {
            return Err(value_error(
                what,
                format!("point {i} has more than 3 coordinates"),
            ));
        }
        q[d] = c?.extract::<f64>().map_err(|_| {
            PyTypeError::new_err(format!("{what}: point {i}: coordinates must be numbers"))
        })?;
        d += 1;
    }
    if d < 2 {
        return Err(value_error(
            what,
            format!("point {i} has {d} coordinate(s), expected 2 or 3"),
        ));
    }
    Ok((d, q))
}

fn points_of_sequence(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Points> {
    let iter = obj
        .try_iter()
        .map_err(|_| PyTypeError::new_err(format!("{what}: expected a sequence of points")))?;
    let mut xyz = Vec::new();
    let mut dim = 0;
    for (i, item) in iter.enumerate() {
        let (d, q) = point(&item?, what, i)?;
        if dim == 0 {
            dim = d;
        } else if d != dim {
            return Err(value_error(
                what,
                format!("point {i} has {d} coordinates, the points before it {dim}"),
            ));
        }
        xyz.push(q);
    }
    Ok(Points {
        dim: dim.max(2),
        xyz,
    })
}

/// One point or vector (2 or 3 numbers).
pub fn vector(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let (d, q) = point(obj, what, 0)?;
    if !q.iter().all(|c| c.is_finite()) {
        return Err(value_error(what, "not finite"));
    }
    Ok(q[..d].to_vec())
}

/// Rows of `dim` numbers as an (n, dim) numpy array, or a list of lists.
pub fn rows(py: Python<'_>, flat: &[f64], dim: usize) -> PyResult<Py<PyAny>> {
    let n = flat.len() / dim.max(1);
    if let Some(np) = numpy(py) {
        let bytes: Vec<u8> = flat.iter().flat_map(|v| v.to_ne_bytes()).collect();
        let a = np
            .call_method1("frombuffer", (PyBytes::new(py, &bytes), "float64"))?
            .call_method1("reshape", ((n, dim),))?
            .call_method0("copy")?;
        return Ok(a.unbind());
    }
    let list = PyList::empty(py);
    for r in flat.chunks_exact(dim.max(1)) {
        list.append(PyList::new(py, r)?)?;
    }
    Ok(list.into_any().unbind())
}

/// Numbers as a 1-D numpy array, or a list.
pub fn row(py: Python<'_>, v: &[f64]) -> PyResult<Py<PyAny>> {
    if let Some(np) = numpy(py) {
        return Ok(np.call_method1("array", (PyList::new(py, v)?,))?.unbind());
    }
    Ok(PyList::new(py, v)?.into_any().unbind())
}

/// A float, or a sequence of floats (a list, tuple or numpy array): `Err(x)` for one number.
pub fn floats(obj: &Bound<'_, PyAny>) -> PyResult<Result<Vec<f64>, f64>> {
    if let Ok(x) = obj.extract::<f64>() {
        return Ok(Err(x));
    }
    if is_ndarray(obj) {
        let list = obj.call_method0("ravel")?.call_method0("tolist")?;
        return Ok(Ok(list.extract()?));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() || obj.try_iter().is_ok() {
        let mut out = Vec::new();
        for v in obj.try_iter()? {
            out.push(v?.extract::<f64>()?);
        }
        return Ok(Ok(out));
    }
    Err(PyTypeError::new_err(
        "expected a number or a sequence of numbers",
    ))
}

/// Deepest nesting of a dict job (a job is a few levels deep; this stops a cycle).
const MAX_DEPTH: usize = 64;

/// A Python value (a dict job, a blade) as JSON, or the pointer and message of the part that is not one.
pub fn to_json(
    obj: &Bound<'_, PyAny>,
    at: &str,
    depth: usize,
) -> Result<serde_json::Value, (String, String)> {
    let mut budget = MAX_VALUES;
    to_json_within(obj, at, depth, &mut budget)
}

/// Most values a dict job or argument may hold (a job is a page of text; this stops a
/// list that holds itself many times over, which has few levels but no end of values).
const MAX_VALUES: usize = 1_000_000;

/// [`to_json`], counting the values converted against `budget`.
fn to_json_within(
    obj: &Bound<'_, PyAny>,
    at: &str,
    depth: usize,
    budget: &mut usize,
) -> Result<serde_json::Value, (String, String)> {
    use serde_json::Value;
    let fail = |m: &str| {
        Err((
            if at.is_empty() {
                "/".into()
            } else {
                at.to_string()
            },
            m.to_string(),
        ))
    };
    if depth > MAX_DEPTH {
        return fail("nested too deeply (a dict that holds itself?)");
    }
    if *budget == 0 {
        return fail(&format!("more than {MAX_VALUES} values: not a job"));
    }
    *budget -= 1;
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(obj.extract().unwrap_or(false)));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(i.into());
        }
        if let Ok(u) = obj.extract::<u64>() {
            return Ok(u.into());
        }
        return fail("an integer too large for a job");
    }
    if obj.is_instance_of::<PyFloat>() {
        let x: f64 = obj.extract().unwrap_or(f64::NAN);
        return match serde_json::Number::from_f64(x) {
            Some(n) => Ok(Value::Number(n)),
            None => fail(&format!("{x} is not a finite number")),
        };
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Value::String(s.to_string()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let Ok(key) = k.cast::<PyString>().map(|k| k.to_string()) else {
                return fail("dict keys must be strings");
            };
            let here = format!("{at}/{}", key.replace('~', "~0").replace('/', "~1"));
            map.insert(key, to_json_within(&v, &here, depth + 1, budget)?);
        }
        return Ok(Value::Object(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, v) in obj
            .try_iter()
            .map_err(|e| (at.to_string(), e.to_string()))?
            .enumerate()
        {
            let v = v.map_err(|e| (at.to_string(), e.to_string()))?;
            out.push(to_json_within(&v, &format!("{at}/{i}"), depth + 1, budget)?);
        }
        return Ok(Value::Array(out));
    }
    // numpy arrays and scalars, and whatever else knows its plain value
    for method in ["tolist", "item"] {
        if obj.hasattr(method).unwrap_or(false) {
            if let Ok(v) = obj.call_method0(method) {
                if !v.is(obj) {
                    return to_json_within(&v, at, depth + 1, budget);
                }
            }
        }
    }
    fail(&format!(
        "a value of type {} is not part of a job (use dicts, lists, strings, numbers)",
        obj.get_type()
            .name()
            .map(|n| n.to_string())
            .unwrap_or_default()
    ))
}

/// A JSON value as Python objects (dicts, lists, numbers, strings, `None`).
pub fn json_to_py(py: Python<'_>, v: &serde_json::Value) -> PyResult<Py<PyAny>> {
    use serde_json::Value;
    Ok(match v {
        Value::Null => py.None(),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any().unbind(),
        Value::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any().unbind(),
            (None, Some(x)) => x.into_pyobject(py)?.into_any().unbind(),
            (None, None) => py.None(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        Value::Array(a) => {
            let list = PyList::empty(py);
            for x in a {
                list.append(json_to_py(py, x)?)?;
            }
            list.into_any().unbind()
        }
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, json_to_py(py, x)?)?;
            }
            d.into_any().unbind()
        }
    })
}

/// Adds `use_numpy` and `arrays_are_numpy`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(use_numpy, m)?)?;
    m.add_function(wrap_pyfunction!(arrays_are_numpy, m)?)
}
