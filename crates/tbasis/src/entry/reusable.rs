//! Scratch memory kept between calls, for callers that compute many meshes in a row.
#![forbid(unsafe_code)]

use crate::entry::generate::{generate_corners_with_scratch, generate_with_scratch, scratch_size_for};
use crate::kernel::error::Error;
use crate::kernel::mesh::{Mesh, Output};
use crate::kernel::options::Options;
use crate::kernel::report::Report;
use crate::kernel::views::strided::StridedMut;

/// Scratch memory reused across calls: it grows to the largest call's need
/// ([`scratch_size_for`]), and calls that fit allocate nothing (with `threads` 0 or 1).
///
/// ```
/// use tbasis::{Mesh, Options, Output, ScratchBuffer};
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 3];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
///
/// let mut scratch = ScratchBuffer::new();
/// for _ in 0..3 {
///     let mut tangents = [[0.0f32; 4]; 3];
///     scratch.generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
///     assert_eq!(tangents[0], [1.0, 0.0, 0.0, 1.0]);
/// }
/// assert!(scratch.len() > 0);
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct ScratchBuffer {
    bytes: Vec<u8>,
}

impl ScratchBuffer {
    /// An empty buffer; the first call allocates.
    ///
    /// ```
    /// let scratch = tbasis::ScratchBuffer::new();
    /// assert_eq!(scratch.len(), 0);
    /// ```
    pub fn new() -> Self {
        ScratchBuffer::default()
    }

    /// Bytes held now.
    ///
    /// ```
    /// use tbasis::{scratch_size_for, Mesh, Options, Output, ScratchBuffer};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let mut scratch = ScratchBuffer::new();
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// scratch.generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
    /// assert_eq!(Some(scratch.len()), scratch_size_for(&mesh, &Options::default()));
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn len(&self) -> usize {
        self.bytes.len()
    }

    /// Whether no bytes are held yet.
    ///
    /// ```
    /// use tbasis::{Mesh, Options, Output, ScratchBuffer};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let mut scratch = ScratchBuffer::new();
    /// assert!(scratch.is_empty());
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// scratch.generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
    /// assert!(!scratch.is_empty());
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// [`generate`](crate::generate) in this buffer, grown first when the call needs more.
    ///
    /// ```
    /// use tbasis::{Mesh, Options, Output, ScratchBuffer};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let mut scratch = ScratchBuffer::new();
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// let report = scratch.generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
    /// assert_eq!(tangents[1], [1.0, 0.0, 0.0, 1.0]);
    /// assert_eq!(report.fallback_vertices, 0);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn generate(&mut self, mesh: &Mesh, options: &Options, output: &mut Output) -> Result<Report, Error> {
        let scratch = self.at_least(scratch_size_for(mesh, options))?;
        generate_with_scratch(mesh, options, output, scratch)
    }

    /// [`generate_corners`](crate::generate_corners) in this buffer, grown first when the call
    /// needs more.
    ///
    /// ```
    /// use tbasis::{Mesh, Options, ScratchBuffer, StridedMut};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let mut scratch = ScratchBuffer::new();
    /// let mut corners = [[0.0f32; 4]; 3];
    /// scratch.generate_corners(&mesh, &Options::mikktspace(), &mut StridedMut::from_slice(&mut corners))?;
    /// assert_eq!(corners, [[1.0, 0.0, 0.0, 1.0]; 3]);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn generate_corners(
        &mut self,
        mesh: &Mesh,
        options: &Options,
        tangents: &mut StridedMut<[f32; 4]>,
    ) -> Result<Report, Error> {
        let scratch = self.at_least(scratch_size_for(mesh, options))?;
        generate_corners_with_scratch(mesh, options, tangents, scratch)
    }

    /// The buffer, grown to `needed` bytes if it is smaller.
    fn at_least(&mut self, needed: Option<usize>) -> Result<&mut [u8], Error> {
        let needed = needed.ok_or(Error::SizeOverflow)?;
        if self.bytes.len() < needed {
            // The old contents mean nothing: a fresh zeroed block costs only the pages used.
            self.bytes = crate::kernel::memory::zeroed_bytes(needed)?;
        }
        Ok(&mut self.bytes)
    }
}
