//! numpy arrays as the library's strided views, over the arrays' own memory.
//!
//! An array's location is kept as plain numbers ([`Place`]) until the call runs, so that it can
//! move to code that runs without the GIL. The views are built with the library's `from_raw`
//! constructors, which form no Rust reference to the memory: a tangent written into the same
//! interleaved vertex array the positions are read from would otherwise alias them.

use numpy::{Element, PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use tbasis::{Indices, Mesh, Strided, StridedMut};

/// Where an array's elements are: the address of the first, the byte stride, the count.
#[derive(Clone, Copy)]
pub struct Place {
    address: usize,
    stride: usize,
    len: usize,
}

impl Place {
    /// Number of elements.
    pub fn len(&self) -> usize {
        self.len
    }

    /// A view that reads the elements.
    ///
    /// # Safety
    /// The array this place was taken from must stay alive, with the same memory, while the view
    /// is used, and none of its elements may be written meanwhile except through views that share
    /// no byte with this one (the library checks its outputs against its inputs).
    pub unsafe fn read<'a, T: tbasis::Element>(self) -> Strided<'a, T> {
        // SAFETY: [`rows`] and [`indices`] only make places whose `len` elements of `stride` bytes
        // lie inside the array, with `stride` at least the element size; the rest is the caller's.
        unsafe { Strided::from_raw(self.address as *const u8, self.stride, self.len) }
    }

    /// A view that writes the elements.
    ///
    /// # Safety
    /// As for [`Place::read`], and the array must be writable (places of outputs are checked) and
    /// nothing else may read or write the elements while the view lives.
    pub unsafe fn write<'a, T: tbasis::Element>(self) -> StridedMut<'a, T> {
        // SAFETY: as in `read`.
        unsafe { StridedMut::from_raw(self.address as *mut u8, self.stride, self.len) }
    }
}

/// The place of the rows of `array`, a float32 array of shape `(n, WIDTH)`: each row's floats
/// contiguous, rows any positive stride apart (the fields of a structured array qualify).
pub fn rows<const WIDTH: usize>(name: &str, array: &Bound<'_, PyAny>, writable: bool) -> PyResult<Place> {
    let array = array.cast::<PyArray2<f32>>().map_err(|_| {
        PyTypeError::new_err(format!(
            "{name} must be a numpy array of dtype float32 (native byte order) and shape (n, {WIDTH})"
        ))
    })?;
    let (shape, strides) = (array.shape(), array.strides());
    if shape[1] != WIDTH {
        return Err(PyValueError::new_err(format!(
            "{name} must have shape (n, {WIDTH}), not {shape:?}"
        )));
    }
    let len = shape[0];
    if len > 0 && strides[1] != 4 {
        return Err(PyValueError::new_err(format!(
            "{name}: the {WIDTH} floats of a row must be contiguous (strides[1] == 4), not strides {strides:?}"
        )));
    }
    let place = place(name, array.data() as usize, len, strides[0], 4 * WIDTH)?;
    if writable {
        writable_array(name, array.as_any())?;
    }
    Ok(place)
}

/// An index buffer's place and type.
#[derive(Clone, Copy)]
pub enum IndexPlace {
    /// Unindexed.
    None,
    /// uint16 indices.
    U16(Place),
    /// uint32 indices.
    U32(Place),
}

impl IndexPlace {
    /// The library's view of the indices.
    ///
    /// # Safety
    /// As for [`Place::read`].
    pub unsafe fn view<'a>(self) -> Indices<'a> {
        // SAFETY: passed on to the caller.
        unsafe {
            match self {
                IndexPlace::None => Indices::None,
                IndexPlace::U16(place) => Indices::U16(place.read()),
                IndexPlace::U32(place) => Indices::U32(place.read()),
            }
        }
    }
}

/// The place of a one-dimensional uint16 or uint32 array with a positive stride, or unindexed.
pub fn indices(array: Option<&Bound<'_, PyAny>>) -> PyResult<IndexPlace> {
    let Some(array) = array else {
        return Ok(IndexPlace::None);
    };
    if let Ok(array) = array.cast::<PyArray1<u16>>() {
        return Ok(IndexPlace::U16(vector_place(array)?));
    }
    if let Ok(array) = array.cast::<PyArray1<u32>>() {
        return Ok(IndexPlace::U32(vector_place(array)?));
    }
    Err(PyTypeError::new_err(
        "indices must be None or a one-dimensional numpy array of dtype uint16 or uint32 (native byte order)",
    ))
}

fn vector_place<T: Element>(array: &Bound<'_, PyArray1<T>>) -> PyResult<Place> {
    place(
        "indices",
        array.data() as usize,
        array.shape()[0],
        array.strides()[0],
        size_of::<T>(),
    )
}

/// The place of `len` elements of `size` bytes, `stride` bytes apart from `address`.
fn place(name: &str, address: usize, len: usize, stride: isize, size: usize) -> PyResult<Place> {
    // numpy may report any stride along an axis of length 0 or 1, where it is never applied.
    let stride = if len <= 1 {
        size
    } else {
        usize::try_from(stride)
            .ok()
            .filter(|&stride| stride >= size)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "{name}: elements must be at least {size} bytes apart and in increasing address \
                     order, not {stride} bytes"
                ))
            })?
    };
    Ok(Place { address, stride, len })
}

/// Fails unless numpy lets `array` be written.
fn writable_array(name: &str, array: &Bound<'_, PyAny>) -> PyResult<()> {
    if array.getattr("flags")?.getattr("writeable")?.is_truthy()? {
        Ok(())
    } else {
        Err(PyValueError::new_err(format!("{name} is read-only")))
    }
}

/// The places of a mesh's arrays.
#[derive(Clone, Copy)]
pub struct MeshPlaces {
    pub positions: Place,
    pub normals: Place,
    pub texcoords: Option<Place>,
    pub indices: IndexPlace,
}

impl MeshPlaces {
    pub fn new(
        positions: &Bound<'_, PyAny>,
        normals: &Bound<'_, PyAny>,
        texcoords: Option<&Bound<'_, PyAny>>,
        indices: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        Ok(MeshPlaces {
            positions: rows::<3>("positions", positions, false)?,
            normals: rows::<3>("normals", normals, false)?,
            texcoords: texcoords.map(|uvs| rows::<2>("texcoords", uvs, false)).transpose()?,
            indices: self::indices(indices)?,
        })
    }

    /// The library's mesh.
    ///
    /// # Safety
    /// As for [`Place::read`], for every array.
    pub unsafe fn mesh<'a>(self) -> Mesh<'a> {
        // SAFETY: passed on to the caller.
        unsafe {
            let mesh = Mesh::new(self.positions.read(), self.normals.read()).with_indices(self.indices.view());
            match self.texcoords {
                Some(uvs) => mesh.with_texcoords(uvs.read()),
                None => mesh,
            }
        }
    }
}
