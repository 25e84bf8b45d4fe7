//! What a call found in the mesh and what it did about it.
#![forbid(unsafe_code)]

/// What a call found in the mesh and what it did about it: returned on success, and carried by
/// [`crate::Error::DegenerateUv`].
///
/// ```
/// use tbasis::{generate, Mesh, Options, Output};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 5.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 4];
/// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]];
/// // Four vertices, one triangle: vertex 3 is in no triangle.
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords).with_indices(&[0u16, 1, 2]);
/// let mut tangents = [[0.0f32; 4]; 4];
/// let report = generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
/// assert_eq!(report.unreferenced_vertices, 1);
/// assert_eq!(report.degenerate_triangles, 0);
/// assert_eq!(report.first_degenerate_triangle, None);
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Report {
    /// Triangles whose UV quality is below the threshold, whose positions have zero area, or
    /// whose inputs are not finite. Method LENGYEL with policy LEGACY (the listing) counts
    /// exactly-zero UV determinants only. Method MIKKTSPACE counts the triangles mikktspace.c cannot
    /// use: two corners at one position, or no texture derivatives (a UV area, |dP/ds| or |dP/dt|
    /// that is NaN or not above the smallest normal float in magnitude); with REJECT, whose test
    /// decides instead, a successful call has none.
    pub degenerate_triangles: usize,
    /// Index of the first such triangle; `None` when there is none (the C report says
    /// `TBASIS_NO_TRIANGLE`).
    pub first_degenerate_triangle: Option<usize>,
    /// Vertices given the fallback frame built from their normal alone.
    pub fallback_vertices: usize,
    /// Vertices used by non-degenerate triangles of both handedness.
    pub mirrored_vertices: usize,
    /// Vertices no triangle uses.
    pub unreferenced_vertices: usize,
    /// Vertices that took their tangent from neighbours (policy INHERIT).
    pub inherited_vertices: usize,
    /// Vertices whose normal is zero, not finite, or off unit length by more than 1e-3 (it was
    /// normalized, or, when it has no direction, ignored). Not counted by policy LEGACY.
    pub abnormal_normals: usize,
    /// Corners where method MIKKTSPACE with policy SKIP or INHERIT replaced what mikktspace.c
    /// gives (a non-finite, zero or non-unit tangent, or one not perpendicular to the normal) with
    /// a finite unit tangent perpendicular to the normal.
    pub repaired_corners: usize,
    /// Method MIKKTSPACE: vertices whose corners do not all get the same bits (the vertices a
    /// seam split duplicates). The per-vertex output gives each such vertex its first corner's.
    pub split_vertices: usize,
}

impl Report {
    /// Adds the counts another worker found over its own vertices and triangles.
    pub(crate) fn merge(&mut self, other: &Report) {
        self.degenerate_triangles += other.degenerate_triangles;
        self.first_degenerate_triangle = earliest(self.first_degenerate_triangle, other.first_degenerate_triangle);
        self.fallback_vertices += other.fallback_vertices;
        self.mirrored_vertices += other.mirrored_vertices;
        self.unreferenced_vertices += other.unreferenced_vertices;
        self.inherited_vertices += other.inherited_vertices;
        self.abnormal_normals += other.abnormal_normals;
        self.repaired_corners += other.repaired_corners;
        self.split_vertices += other.split_vertices;
    }

    /// Records triangle `t` as degenerate.
    pub(crate) fn note_degenerate(&mut self, t: usize) {
        self.degenerate_triangles += 1;
        self.first_degenerate_triangle = earliest(self.first_degenerate_triangle, Some(t));
    }
}

/// The lower of two triangle indices, either of which may be absent.
fn earliest(a: Option<usize>, b: Option<usize>) -> Option<usize> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        _ => a.or(b),
    }
}
