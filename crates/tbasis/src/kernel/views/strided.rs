//! Strided, unaligned views over memory the library does not own.
//!
//! Engines hand over interleaved vertex arrays and often want the tangent written into the same
//! array the positions come from. A Rust reference over such memory could alias the output, so
//! these views keep a raw base pointer and read or write each element with `read_unaligned` /
//! `write_unaligned`. Every access is bounds-checked against the element count the view was built
//! with, which is what makes `get`/`set` safe. The one reference formed to caller memory is the
//! slice of a packed, aligned view ([`Strided::packed`], [`StridedMut::packed_mut`]), for as long
//! as the view is borrowed; the calls reach the kernels only after refusing any output that
//! shares a byte with an input (`Error::Overlap`), so no such slice aliases another.

use core::marker::PhantomData;
use core::mem::size_of;

use crate::kernel::error::Error;

mod sealed {
    pub trait Sealed {}
}

/// Plain data a view can read or write: every bit pattern is a valid value.
///
/// ```
/// use tbasis::{Element, Strided};
///
/// fn last<T: Element>(view: &Strided<T>) -> Option<T> {
///     (!view.is_empty()).then(|| view.get(view.len() - 1))
/// }
/// assert_eq!(last(&Strided::from_slice(&[7u16, 8])), Some(8));
/// assert_eq!(last::<[f32; 2]>(&Strided::from_slice(&[])), None);
/// ```
pub trait Element: Copy + sealed::Sealed {}
impl sealed::Sealed for [f32; 2] {}
impl sealed::Sealed for [f32; 3] {}
impl sealed::Sealed for [f32; 4] {}
impl sealed::Sealed for u16 {}
impl sealed::Sealed for u32 {}
impl Element for [f32; 2] {}
impl Element for [f32; 3] {}
impl Element for [f32; 4] {}
impl Element for u16 {}
impl Element for u32 {}

/// The bytes a strided run of `count` elements of `size` bytes spans: `(count - 1) * stride + size`.
///
/// Fails with [`Error::InvalidStride`] when `stride < size` and [`Error::SizeOverflow`] when the
/// span does not fit in `isize` (the most any allocation can hold).
///
/// ```
/// use tbasis::{span_bytes, Error};
///
/// // Three 12-byte positions in 48-byte vertices: the last ends 108 bytes in.
/// assert_eq!(span_bytes(3, 48, 12), Ok(108));
/// assert_eq!(span_bytes(3, 8, 12), Err(Error::InvalidStride { stride: 8, element_size: 12 }));
/// ```
pub fn span_bytes(count: usize, stride: usize, size: usize) -> Result<usize, Error> {
    if stride < size {
        return Err(Error::InvalidStride {
            stride,
            element_size: size,
        });
    }
    if count == 0 {
        return Ok(0);
    }
    let span = (count - 1)
        .checked_mul(stride)
        .and_then(|bytes| bytes.checked_add(size))
        .ok_or(Error::SizeOverflow)?;
    if span > isize::MAX as usize {
        return Err(Error::SizeOverflow);
    }
    Ok(span)
}

/// The address range `[start, end)` a view covers, used to test buffers for overlap.
///
/// ```
/// use tbasis::Strided;
///
/// // Positions (12 bytes) in 28-byte vertices.
/// let bytes = [0u8; 28 * 3];
/// let positions = Strided::<[f32; 3]>::from_bytes(&bytes, 28, 3)?.footprint();
/// assert_eq!(positions.start, bytes.as_ptr() as usize);
/// assert_eq!((positions.stride, positions.size, positions.count), (28, 12, 3));
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Footprint {
    /// Address of element 0.
    pub start: usize,
    /// Distance between elements, in bytes.
    pub stride: usize,
    /// Bytes of each element that belong to the view.
    pub size: usize,
    /// Number of elements.
    pub count: usize,
}

impl Footprint {
    /// The footprint of `len` contiguous bytes from address `start` (a scratch buffer).
    ///
    /// ```
    /// let scratch = [0u8; 8];
    /// let footprint = tbasis::Footprint::contiguous(scratch.as_ptr() as usize, scratch.len());
    /// assert!(footprint.overlaps(&tbasis::Footprint::contiguous(scratch.as_ptr() as usize + 7, 1)));
    /// ```
    pub fn contiguous(start: usize, len: usize) -> Footprint {
        Footprint {
            start,
            stride: 1,
            size: 1,
            count: len,
        }
    }

    /// One past the last byte of the last element.
    fn end(&self) -> usize {
        self.start + (self.count - 1) * self.stride + self.size
    }

    /// True when some byte belongs to both footprints (not merely to both address ranges:
    /// a tangent interleaved between positions shares the range but no byte).
    ///
    /// ```
    /// use tbasis::Footprint;
    ///
    /// // 48-byte vertices: the position at bytes 0..12, the tangent at 12..28 or, wrongly, 8..24.
    /// let positions = Footprint { start: 1000, stride: 48, size: 12, count: 10 };
    /// let tangents = Footprint { start: 1012, stride: 48, size: 16, count: 10 };
    /// let misplaced = Footprint { start: 1008, ..tangents };
    /// assert!(!positions.overlaps(&tangents));
    /// assert!(positions.overlaps(&misplaced));
    /// ```
    pub fn overlaps(&self, other: &Footprint) -> bool {
        if self.count == 0 || other.count == 0 || self.size == 0 || other.size == 0 {
            return false;
        }
        if self.end() <= other.start || other.end() <= self.start {
            return false;
        }
        if self.stride == other.stride {
            return self.overlaps_same_stride(other);
        }
        self.overlaps_by_walk(other)
    }

    /// Equal strides: element `i` of `self` meets element `j` of `other` iff
    /// `-other.size < d + k * stride < self.size` with `d = other.start - self.start`, `k = j - i`.
    /// Only the `k` nearest `-d / stride` can satisfy that, since both sizes are at most `stride`.
    fn overlaps_same_stride(&self, other: &Footprint) -> bool {
        let stride = self.stride as i128;
        let d = other.start as i128 - self.start as i128;
        let k_lo = -(self.count as i128 - 1);
        let k_hi = other.count as i128 - 1;
        let k_near = (-d).div_euclid(stride);
        (k_near - 1..=k_near + 1)
            .filter(|k| (k_lo..=k_hi).contains(k))
            .any(|k| {
                let offset = d + k * stride;
                -(other.size as i128) < offset && offset < self.size as i128
            })
    }

    /// Different strides: walk both element sequences in address order (a merge), which is exact
    /// and linear in the elements inside the shared address range.
    fn overlaps_by_walk(&self, other: &Footprint) -> bool {
        let (mut i, mut j) = (0usize, 0usize);
        while i < self.count && j < other.count {
            let a = self.start + i * self.stride;
            let b = other.start + j * other.stride;
            if a < b + other.size && b < a + self.size {
                return true;
            }
            if a + self.size <= b {
                i += 1;
            } else {
                j += 1;
            }
        }
        false
    }
}

/// A read-only strided view of `len` elements of type `T`.
///
/// ```
/// use tbasis::Strided;
///
/// // The uv pair at the start of each 16-byte vertex.
/// let floats = [0.0f32, 1.0, 9.0, 9.0, 2.0, 3.0, 9.0, 9.0];
/// let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_ne_bytes()).collect();
/// let uvs = Strided::<[f32; 2]>::from_bytes(&bytes, 16, 2)?;
/// assert_eq!(uvs.get(1), [2.0, 3.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct Strided<'a, T: Element> {
    base: *const u8,
    stride: usize,
    len: usize,
    _borrow: PhantomData<&'a [T]>,
}

impl<'a, T: Element> Strided<'a, T> {
    /// A view of `len` elements, `stride` bytes apart, the first at `bytes[0]`; `T` sits in the
    /// first `size_of::<T>()` bytes of each element.
    ///
    /// ```
    /// use tbasis::{Error, Strided};
    ///
    /// let mut bytes = vec![0u8]; // the indices start at byte 1: any alignment works
    /// bytes.extend([1u16, 2, 3].iter().flat_map(|i| i.to_ne_bytes()));
    /// let indices = Strided::<u16>::from_bytes(&bytes[1..], 2, 3)?;
    /// assert_eq!(indices.get(2), 3);
    /// let too_many = Strided::<u16>::from_bytes(&bytes[1..], 2, 4);
    /// assert_eq!(too_many.err(), Some(Error::BufferTooShort { len: 6, needed: 8 }));
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn from_bytes(bytes: &'a [u8], stride: usize, len: usize) -> Result<Self, Error> {
        let span = span_bytes(len, stride, size_of::<T>())?;
        if bytes.len() < span {
            return Err(Error::BufferTooShort {
                len: bytes.len(),
                needed: span,
            });
        }
        Ok(Strided {
            base: bytes.as_ptr(),
            stride,
            len,
            _borrow: PhantomData,
        })
    }

    /// A view of a packed slice.
    ///
    /// ```
    /// let normals = [[0.0, 0.0, 1.0f32]; 4];
    /// let view = tbasis::Strided::from_slice(&normals);
    /// assert_eq!(view.len(), 4);
    /// assert_eq!(view.get(3), [0.0, 0.0, 1.0]);
    /// ```
    pub fn from_slice(items: &'a [T]) -> Self {
        Strided {
            base: items.as_ptr().cast(),
            stride: size_of::<T>(),
            len: items.len(),
            _borrow: PhantomData,
        }
    }

    /// A view of caller memory.
    ///
    /// # Safety
    /// When `len > 0`, `base` must be valid for reads of `span_bytes(len, stride, size_of::<T>())`
    /// bytes, all in one allocation, for `'a`, `stride >= size_of::<T>()`, and no element may be
    /// written through another pointer while the view is read. Alignment is not required.
    ///
    /// ```
    /// use tbasis::Strided;
    ///
    /// // Position and uv, 20 bytes per vertex.
    /// let vertices = [[0.0f32, 0.0, 0.0, 0.5, 0.5], [1.0, 0.0, 0.0, 0.75, 0.25]];
    /// let base = vertices.as_ptr().cast::<u8>();
    /// // SAFETY: `vertices` is readable for 2 vertices of 20 bytes (the last uv ends at byte 40),
    /// // and nothing writes it while `uvs` lives.
    /// let uvs = unsafe { Strided::<[f32; 2]>::from_raw(base.add(12), 20, 2) };
    /// assert_eq!(uvs.get(1), [0.75, 0.25]);
    /// ```
    pub unsafe fn from_raw(base: *const u8, stride: usize, len: usize) -> Self {
        Strided {
            base,
            stride,
            len,
            _borrow: PhantomData,
        }
    }

    /// Number of elements.
    ///
    /// ```
    /// let indices = [0u32, 1, 2, 0, 2, 3];
    /// assert_eq!(tbasis::Strided::from_slice(&indices).len(), 6);
    /// ```
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the view has no elements.
    ///
    /// ```
    /// use tbasis::Strided;
    ///
    /// assert!(Strided::<u32>::from_slice(&[]).is_empty());
    /// assert!(!Strided::from_slice(&[7u32]).is_empty());
    /// ```
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Element `i`. Panics when `i >= len` (callers check indices first).
    ///
    /// ```
    /// let texcoords = [[0.0, 1.0f32], [2.0, 3.0]];
    /// let view = tbasis::Strided::from_slice(&texcoords);
    /// assert_eq!(view.get(1), [2.0, 3.0]);
    /// ```
    #[inline(always)]
    pub fn get(&self, i: usize) -> T {
        assert!(i < self.len, "strided read out of bounds");
        // SAFETY: i < len.
        unsafe { self.read_unchecked(i) }
    }

    /// Elements `a`, `b` and `c` (a triangle's), with one bounds check, on the largest: a loop
    /// reading triangles then compares once per view and triangle, not once per element. Panics
    /// when an index is `>= len`.
    #[inline(always)]
    pub(crate) fn get_three(&self, [a, b, c]: [usize; 3]) -> [T; 3] {
        assert!(a.max(b).max(c) < self.len, "strided read out of bounds");
        // SAFETY: each index is at most the largest, which is below len.
        unsafe { [self.read_unchecked(a), self.read_unchecked(b), self.read_unchecked(c)] }
    }

    /// Element `i`, unchecked.
    ///
    /// # Safety
    /// `i < len`. The constructor's contract covers every element below len: their bytes lie in
    /// one allocation of at least `span_bytes(len, stride, size)` bytes, so `i * stride` neither
    /// overflows nor leaves it.
    #[inline(always)]
    unsafe fn read_unchecked(&self, i: usize) -> T {
        // SAFETY: the caller's `i < len` and the constructor's contract (above).
        unsafe { self.base.add(i * self.stride).cast::<T>().read_unaligned() }
    }

    /// Asks the CPU to bring element `i` into its cache ahead of a read (nothing when `i` is past
    /// the end): a loop that streams through a view can then wait less for memory.
    #[inline(always)]
    pub(crate) fn prefetch(&self, i: usize) {
        if i < self.len {
            crate::kernel::simd::prefetch_address(self.base.wrapping_add(i * self.stride));
        }
    }

    /// The elements as a slice, when they sit packed (`stride` is the element's size) at an address
    /// aligned for `T`: a kernel reads them as a plain array, in loops the compiler can vectorize.
    #[inline(always)]
    pub(crate) fn packed(&self) -> Option<&[T]> {
        if !sits_packed::<T>(self.base, self.stride) {
            return None;
        }
        if self.len == 0 {
            return Some(&[]);
        }
        // SAFETY: the constructor's contract makes the `len * size_of::<T>()` bytes from `base`
        // readable and unwritten while the view is read (for as long as this borrow of it), `T`
        // is valid for any bytes (`Element`), and `base` is aligned for it.
        Some(unsafe { core::slice::from_raw_parts(self.base.cast::<T>(), self.len) })
    }

    /// Where the view's bytes are, for overlap tests.
    ///
    /// ```
    /// let positions = [[0.0f32; 3]; 4];
    /// let footprint = tbasis::Strided::from_slice(&positions).footprint();
    /// assert_eq!(footprint.start, positions.as_ptr() as usize);
    /// assert_eq!((footprint.stride, footprint.size, footprint.count), (12, 12, 4));
    /// ```
    pub fn footprint(&self) -> Footprint {
        Footprint {
            start: self.base as usize,
            stride: self.stride,
            size: size_of::<T>(),
            count: self.len,
        }
    }
}

// SAFETY: a `Strided` only reads, and its constructors require that nothing writes the elements
// while it lives, so reading them from several threads at once is sound.
unsafe impl<T: Element> Sync for Strided<'_, T> {}
// SAFETY: as above; moving a read-only view to another thread changes nothing.
unsafe impl<T: Element> Send for Strided<'_, T> {}

/// A write-only strided view of `len` elements of type `T`.
///
/// ```
/// use tbasis::{generate, Mesh, Options, Output, StridedMut};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 3];
/// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
/// // The tangents go to bytes 16..32 of each 32-byte vertex record.
/// let mut records = vec![0u8; 32 * 3];
/// let tangents = StridedMut::<[f32; 4]>::from_bytes(&mut records[16..], 32, 3)?;
/// generate(&mesh, &Options::default(), &mut Output::new(tangents))?;
/// assert_eq!(records[80..84], 1.0f32.to_ne_bytes());
/// assert_eq!(records[64..80], [0; 16]);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub struct StridedMut<'a, T: Element> {
    base: *mut u8,
    stride: usize,
    len: usize,
    _borrow: PhantomData<&'a mut [T]>,
}

impl<'a, T: Element> StridedMut<'a, T> {
    /// A view of `len` elements, `stride` bytes apart, the first at `bytes[0]`.
    ///
    /// ```
    /// use tbasis::{Error, StridedMut};
    ///
    /// let mut bytes = [0u8; 32];
    /// let mut tangents = StridedMut::<[f32; 4]>::from_bytes(&mut bytes, 16, 2)?;
    /// tangents.set(1, [1.0, 0.0, 0.0, 1.0]);
    /// assert_eq!(bytes[16..20], 1.0f32.to_ne_bytes());
    /// let narrow = StridedMut::<[f32; 4]>::from_bytes(&mut bytes, 12, 2);
    /// assert!(matches!(narrow, Err(Error::InvalidStride { stride: 12, element_size: 16 })));
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn from_bytes(bytes: &'a mut [u8], stride: usize, len: usize) -> Result<Self, Error> {
        let span = span_bytes(len, stride, size_of::<T>())?;
        if bytes.len() < span {
            return Err(Error::BufferTooShort {
                len: bytes.len(),
                needed: span,
            });
        }
        Ok(StridedMut {
            base: bytes.as_mut_ptr(),
            stride,
            len,
            _borrow: PhantomData,
        })
    }

    /// A view of a packed slice.
    ///
    /// ```
    /// let mut tangents = [[0.0f32; 4]; 2];
    /// let mut view = tbasis::StridedMut::from_slice(&mut tangents);
    /// view.set(1, [0.0, 1.0, 0.0, -1.0]);
    /// assert_eq!(tangents[1], [0.0, 1.0, 0.0, -1.0]);
    /// ```
    pub fn from_slice(items: &'a mut [T]) -> Self {
        StridedMut {
            base: items.as_mut_ptr().cast(),
            stride: size_of::<T>(),
            len: items.len(),
            _borrow: PhantomData,
        }
    }

    /// A view of caller memory.
    ///
    /// # Safety
    /// When `len > 0`, `base` must be valid for writes of `span_bytes(len, stride, size_of::<T>())`
    /// bytes, all in one allocation, for `'a`, `stride >= size_of::<T>()`, and the element bytes
    /// must not be read or written through another pointer while the view lives. Alignment is not
    /// required.
    ///
    /// ```
    /// use tbasis::StridedMut;
    ///
    /// // Position and tangent, 28 bytes per vertex.
    /// let mut vertices = [[0.0f32; 7]; 2];
    /// let base = vertices.as_mut_ptr().cast::<u8>();
    /// // SAFETY: `vertices` is writable for 2 vertices of 28 bytes (the last tangent ends at byte
    /// // 56), and nothing else reads or writes it while `tangents` lives.
    /// let mut tangents = unsafe { StridedMut::<[f32; 4]>::from_raw(base.add(12), 28, 2) };
    /// tangents.set(1, [1.0, 0.0, 0.0, 1.0]);
    /// assert_eq!(vertices[1], [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    /// ```
    pub unsafe fn from_raw(base: *mut u8, stride: usize, len: usize) -> Self {
        StridedMut {
            base,
            stride,
            len,
            _borrow: PhantomData,
        }
    }

    /// Number of elements.
    ///
    /// ```
    /// let mut corners = vec![[0.0f32; 4]; 6];
    /// assert_eq!(tbasis::StridedMut::from_slice(&mut corners).len(), 6);
    /// ```
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the view has no elements.
    ///
    /// ```
    /// use tbasis::StridedMut;
    ///
    /// assert!(StridedMut::<[f32; 4]>::from_slice(&mut []).is_empty());
    /// assert!(!StridedMut::from_slice(&mut [[0.0f32; 4]]).is_empty());
    /// ```
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Writes element `i`. Panics when `i >= len`.
    ///
    /// ```
    /// use tbasis::StridedMut;
    ///
    /// // Tangents at bytes 12..28 of each 28-byte vertex; the positions are left alone.
    /// let mut bytes = vec![0xAAu8; 28 * 2];
    /// let mut tangents = StridedMut::<[f32; 4]>::from_bytes(&mut bytes[12..], 28, 2)?;
    /// tangents.set(1, [1.0, 0.0, 0.0, 1.0]);
    /// assert_eq!(bytes[40..44], 1.0f32.to_ne_bytes());
    /// assert_eq!(bytes[28..40], [0xAA; 12]);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    #[inline(always)]
    pub fn set(&mut self, i: usize, value: T) {
        assert!(i < self.len, "strided write out of bounds");
        // SAFETY: i < len and the constructor's contract covers every element below len.
        unsafe { self.base.add(i * self.stride).cast::<T>().write_unaligned(value) }
    }

    /// Reads element `i` back. Panics when `i >= len`.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize) -> T {
        assert!(i < self.len, "strided read out of bounds");
        // SAFETY: i < len and the constructor's contract covers every element below len; `T` is
        // valid for any bytes (`Element`).
        unsafe { self.base.add(i * self.stride).cast::<T>().read_unaligned() }
    }

    /// The elements as a mutable slice, when they sit packed at an address aligned for `T` (see
    /// [`Strided::packed`]).
    #[inline(always)]
    pub(crate) fn packed_mut(&mut self) -> Option<&mut [T]> {
        if !sits_packed::<T>(self.base, self.stride) {
            return None;
        }
        if self.len == 0 {
            return Some(&mut []);
        }
        // SAFETY: the constructor's contract makes the `len * size_of::<T>()` bytes from `base`
        // writable and untouched through other pointers while the view lives (this borrow of it
        // is exclusive), `T` is valid for any bytes (`Element`), and `base` is aligned for it.
        Some(unsafe { core::slice::from_raw_parts_mut(self.base.cast::<T>(), self.len) })
    }

    /// Where the view's bytes are, for overlap tests.
    ///
    /// ```
    /// use tbasis::{Strided, StridedMut};
    ///
    /// let mut buffer = [[0.0f32; 4]; 3];
    /// let written = StridedMut::from_slice(&mut buffer).footprint();
    /// let positions = [[0.0f32; 3]; 3];
    /// assert!(!written.overlaps(&Strided::from_slice(&positions).footprint()));
    /// assert_eq!((written.stride, written.size, written.count), (16, 16, 3));
    /// ```
    pub fn footprint(&self) -> Footprint {
        Footprint {
            start: self.base as usize,
            stride: self.stride,
            size: size_of::<T>(),
            count: self.len,
        }
    }

    /// The same view, borrowed for a shorter time.
    pub(crate) fn reborrow(&mut self) -> StridedMut<'_, T> {
        // SAFETY: the same elements, exclusively borrowed through `self` for the new lifetime.
        unsafe { StridedMut::from_raw(self.base, self.stride, self.len) }
    }

    /// Disjoint views of consecutive element ranges covering the view, for writing from several
    /// threads; `ends` are the exclusive ends of the ranges in units of `per` elements,
    /// increasing, the last at most `len / per`. Made one at a time as the result is iterated,
    /// without allocating.
    pub(crate) fn split<'p>(&'p mut self, ends: &'p [usize], per: usize) -> Split<'p, T> {
        Split {
            parts: SplitParts {
                base: self.base,
                stride: self.stride,
                len: self.len,
                per,
                start: 0,
                ends: ends.iter(),
                _borrow: PhantomData,
            },
        }
    }
}

/// The parts [`StridedMut::split`] cuts a view into, made as they are iterated.
pub(crate) struct Split<'p, T> {
    parts: SplitParts<'p, T>,
}

impl<'p, T: Element> IntoIterator for Split<'p, T> {
    type Item = StridedMut<'p, T>;
    type IntoIter = SplitParts<'p, T>;

    fn into_iter(self) -> SplitParts<'p, T> {
        self.parts
    }
}

/// The iterator over the parts of a [`Split`].
pub(crate) struct SplitParts<'p, T> {
    base: *mut u8,
    stride: usize,
    len: usize,
    /// Elements per unit of `ends`.
    per: usize,
    /// Where the next part starts.
    start: usize,
    ends: core::slice::Iter<'p, usize>,
    /// The view the parts come from, borrowed mutably for as long as they live.
    _borrow: PhantomData<&'p mut T>,
}

impl<'p, T: Element> Iterator for SplitParts<'p, T> {
    type Item = StridedMut<'p, T>;

    fn next(&mut self) -> Option<StridedMut<'p, T>> {
        let (start, end) = (self.start, self.per * *self.ends.next()?);
        assert!(start <= end && end <= self.len, "split ranges out of order");
        self.start = end;
        // SAFETY: elements start..end lie inside the view `split` borrowed mutably for 'p, the
        // ranges are disjoint (each starts where the previous ended), so nothing else writes them
        // meanwhile.
        Some(unsafe { StridedMut::from_raw(self.base.add(start * self.stride), self.stride, end - start) })
    }
}

// SAFETY: a `StridedMut` is the only writer of its elements (its constructors require it), so it
// may move to another thread.
unsafe impl<T: Element> Send for StridedMut<'_, T> {}

// SAFETY: through a shared reference a `StridedMut` only reads its elements (`get`, `len`), as a
// shared `&mut [T]` does.
unsafe impl<T: Element> Sync for StridedMut<'_, T> {}

impl<'a, T: Element> From<&'a [T]> for Strided<'a, T> {
    fn from(items: &'a [T]) -> Self {
        Strided::from_slice(items)
    }
}

impl<'a, T: Element, const N: usize> From<&'a [T; N]> for Strided<'a, T> {
    fn from(items: &'a [T; N]) -> Self {
        Strided::from_slice(items)
    }
}

impl<'a, T: Element> From<&'a mut [T]> for StridedMut<'a, T> {
    fn from(items: &'a mut [T]) -> Self {
        StridedMut::from_slice(items)
    }
}

impl<'a, T: Element, const N: usize> From<&'a mut [T; N]> for StridedMut<'a, T> {
    fn from(items: &'a mut [T; N]) -> Self {
        StridedMut::from_slice(items)
    }
}

/// Views of glam vectors as the float arrays they start with: each glam type below is laid out as
/// its components in order (`x, y, z[, w]`), `size_of` bytes apart, padding after them (`Vec3A`).
macro_rules! glam_views {
    ($($glam:ty => $array:ty),*) => {$(
        impl<'a> From<&'a [$glam]> for Strided<'a, $array> {
            fn from(items: &'a [$glam]) -> Self {
                const { assert!(size_of::<$glam>() >= size_of::<$array>()) };
                // SAFETY: the slice is readable for `len` elements `size_of::<$glam>()` bytes
                // apart, each starting with the components of `$array`, and stays borrowed for 'a.
                unsafe { Strided::from_raw(items.as_ptr().cast(), size_of::<$glam>(), items.len()) }
            }
        }

        impl<'a> From<&'a mut [$glam]> for StridedMut<'a, $array> {
            fn from(items: &'a mut [$glam]) -> Self {
                const { assert!(size_of::<$glam>() >= size_of::<$array>()) };
                // SAFETY: as above, writable, and exclusively borrowed for 'a; every bit pattern
                // is a valid float.
                unsafe { StridedMut::from_raw(items.as_mut_ptr().cast(), size_of::<$glam>(), items.len()) }
            }
        }
    )*};
}

glam_views!(glam::Vec2 => [f32; 2], glam::Vec3 => [f32; 3], glam::Vec3A => [f32; 3], glam::Vec4 => [f32; 4]);

/// Whether elements `stride` bytes apart from `base` sit packed (`stride` is `T`'s size) at an
/// address aligned for `T`: then a view's elements are a slice.
#[inline(always)]
fn sits_packed<T>(base: *const u8, stride: usize) -> bool {
    stride == size_of::<T>() && base.cast::<T>().is_aligned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fp(start: usize, stride: usize, size: usize, count: usize) -> Footprint {
        Footprint {
            start,
            stride,
            size,
            count,
        }
    }

    /// Brute force: the byte sets of both footprints.
    fn overlaps_brute(a: &Footprint, b: &Footprint) -> bool {
        let bytes = |f: &Footprint| {
            (0..f.count)
                .flat_map(|i| (0..f.size).map(move |k| f.start + i * f.stride + k))
                .collect::<std::collections::HashSet<_>>()
        };
        !bytes(a).is_disjoint(&bytes(b))
    }

    #[test]
    fn interleaved_fields_do_not_overlap_but_shared_bytes_do() {
        let positions = fp(1000, 48, 12, 10);
        let tangent_after = fp(1012, 48, 16, 10);
        let tangent_on_top = fp(1008, 48, 16, 10);
        assert!(!positions.overlaps(&tangent_after));
        assert!(positions.overlaps(&tangent_on_top));
    }

    #[test]
    fn overlap_test_matches_brute_force() {
        for a_start in 0..12 {
            for (a_stride, a_size) in [(4, 4), (8, 4), (12, 8), (7, 3)] {
                for b_start in 0..24 {
                    for (b_stride, b_size) in [(4, 4), (8, 4), (12, 8), (5, 2), (7, 3)] {
                        for (a_count, b_count) in [(1, 1), (3, 2), (4, 6)] {
                            let a = fp(a_start, a_stride, a_size, a_count);
                            let b = fp(b_start, b_stride, b_size, b_count);
                            assert_eq!(a.overlaps(&b), overlaps_brute(&a, &b), "{a:?} {b:?}");
                            assert_eq!(b.overlaps(&a), overlaps_brute(&a, &b), "{b:?} {a:?}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn span_rejects_short_strides_and_overflow() {
        assert_eq!(
            span_bytes(3, 8, 12),
            Err(Error::InvalidStride {
                stride: 8,
                element_size: 12
            })
        );
        assert_eq!(span_bytes(usize::MAX, 16, 12), Err(Error::SizeOverflow));
        assert_eq!(span_bytes(0, 16, 12), Ok(0));
        assert_eq!(span_bytes(3, 16, 12), Ok(44));
    }

    #[test]
    fn unaligned_reads_and_writes_round_trip() {
        let mut bytes = [0u8; 64];
        {
            let mut out = StridedMut::<[f32; 3]>::from_bytes(&mut bytes[1..], 17, 3).unwrap();
            for i in 0..3 {
                out.set(i, [i as f32, 1.5, -2.0]);
            }
        }
        let view = Strided::<[f32; 3]>::from_bytes(&bytes[1..], 17, 3).unwrap();
        assert_eq!(view.get(2), [2.0, 1.5, -2.0]);
    }

    /// Reading several elements at once checks every index: one past the end panics wherever it
    /// sits in the list, and the others read what `get` reads.
    #[test]
    fn reading_several_elements_checks_each_index() {
        let mut bytes = [0u8; 40];
        for (i, chunk) in bytes.chunks_exact_mut(4).enumerate() {
            chunk.copy_from_slice(&(i as u32 * 7).to_ne_bytes());
        }
        let view = Strided::<u32>::from_bytes(&bytes[4..], 8, 4).unwrap();
        assert_eq!(view.get_three([3, 0, 2]), [3, 0, 2].map(|i| view.get(i)));
        for bad in [[4, 0, 1], [0, 4, 1], [0, 1, 4], [usize::MAX, 0, 0]] {
            let read = std::panic::catch_unwind(|| view.get_three(bad));
            assert!(read.is_err(), "{bad:?} read past the end");
        }
    }

    /// A view is read as a slice only when its elements sit packed at an address aligned for
    /// them; the slice holds the view's elements.
    #[test]
    fn only_packed_aligned_views_are_slices() {
        let packed = Strided::<[f32; 3]>::from_slice(&[[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]][..])
            .packed()
            .map(<[_]>::to_vec);
        assert_eq!(packed, Some(vec![[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]]));
        let floats: Vec<f32> = (0..13).map(|i| i as f32).collect();
        let base = floats.as_ptr().cast::<u8>();
        // SAFETY: each view spans at most the 52 bytes of `floats`, which nothing writes.
        let view = |offset: usize, stride: usize, len: usize| unsafe {
            Strided::<[f32; 3]>::from_raw(base.add(offset), stride, len)
        };
        assert!(view(0, 16, 3).packed().is_none(), "a stride other than 12 bytes");
        assert!(view(1, 12, 4).packed().is_none(), "a base off 4-byte alignment");
        assert_eq!(view(4, 12, 4).packed().unwrap()[3], [10.0, 11.0, 12.0]);
        // SAFETY: an empty view reads nothing, whatever its base.
        let empty = unsafe { Strided::<[f32; 3]>::from_raw(core::ptr::null(), 12, 0) };
        assert_eq!(empty.packed(), Some(&[][..]));

        let mut out = vec![0u8; 40];
        assert!(StridedMut::<[f32; 4]>::from_bytes(&mut out, 20, 2)
            .unwrap()
            .packed_mut()
            .is_none());
        assert!(StridedMut::<[f32; 4]>::from_bytes(&mut out[2..], 16, 2)
            .unwrap()
            .packed_mut()
            .is_none());
        let mut frames = [[0.0f32; 4]; 2];
        StridedMut::from_slice(&mut frames[..]).packed_mut().unwrap()[1] = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(frames[1], [1.0, 2.0, 3.0, 4.0]);
    }
}
