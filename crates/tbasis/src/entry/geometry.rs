//! mikktspace.c's callback interface in Rust: the `Geometry` trait of the `mikktspace` crate 0.3
//! (and of bevy_mikktspace's older API), method for method, with mikktspace.c's bits.
#![forbid(unsafe_code)]

use crate::kernel::error::Error;
use crate::kernel::memory::vec_with_capacity;
use crate::pipelines::mikktspace::faces_interface::{self, face_slots, FaceMesh};

/// The interface by which the generator reads a mesh and hands back its tangent spaces: the same
/// methods, with the same signatures, as the `mikktspace` crate's trait.
///
/// Faces of 3 or 4 vertices count; a quad is split along its shorter diagonal in texture space
/// (in position when the two are equal), as mikktspace.c splits it; faces of any other vertex
/// count are ignored and get no call.
pub trait Geometry {
    /// Returns the number of faces.
    fn num_faces(&self) -> usize;

    /// Returns the number of vertices of a face.
    fn num_vertices_of_face(&self, face: usize) -> usize;

    /// Returns the position of a vertex.
    fn position(&self, face: usize, vert: usize) -> [f32; 3];

    /// Returns the normal of a vertex.
    fn normal(&self, face: usize, vert: usize) -> [f32; 3];

    /// Returns the texture coordinate of a vertex.
    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2];

    /// Sets the generated tangent space of a vertex: unit tangent and bitangent, the magnitudes of
    /// dP/ds and dP/dt, and whether the texture keeps the triangles' winding. Leave it
    /// unimplemented when implementing [`Geometry::set_tangent_encoded`].
    #[allow(clippy::too_many_arguments)]
    fn set_tangent(
        &mut self,
        tangent: [f32; 3],
        _bi_tangent: [f32; 3],
        _f_mag_s: f32,
        _f_mag_t: f32,
        bi_tangent_preserves_orientation: bool,
        face: usize,
        vert: usize,
    ) {
        let sign = if bi_tangent_preserves_orientation { 1.0 } else { -1.0 };
        self.set_tangent_encoded([tangent[0], tangent[1], tangent[2], sign], face, vert);
    }

    /// Sets the generated tangent of a vertex with the bitangent's sign as its fourth component
    /// (`bitangent = w * cross(normal, tangent)`). Called by the default
    /// [`Geometry::set_tangent`] only.
    fn set_tangent_encoded(&mut self, _tangent: [f32; 4], _face: usize, _vert: usize) {}
}

/// How [`generate_tangents_with`] runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// mikktspace.c's `fAngularThreshold` in degrees: triangles of one smooth group whose
    /// tangents (or bitangents) lie further apart than this get separate tangent spaces.
    /// [`generate_tangents`] uses 180, as `genTangSpaceDefault` does.
    pub angular_threshold: f32,
    /// Worker threads for the computation (0 or 1: the calling thread alone). The geometry's
    /// methods are always called from the calling thread, and the result is the same on any count.
    pub threads: u32,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            angular_threshold: 180.0,
            threads: 1,
        }
    }
}

/// Generates a tangent space for every vertex of every face of 3 or 4 vertices, bit for bit what
/// mikktspace.c's `genTangSpaceDefault` gives, and hands each to [`Geometry::set_tangent`], face
/// by face, vertex by vertex. Returns false, with no call to `set_tangent`, when there is no such
/// face or memory runs out.
///
/// Each attribute is read once per face vertex, all before the first `set_tangent`; and, as
/// mikktspace.c does, the position of vertex 0 of face 0 when face 0 has neither 3 nor 4
/// vertices (first, before the other attributes).
///
/// ```
/// use tbasis::mikktspace::{generate_tangents, Geometry};
///
/// struct Quad([[f32; 4]; 4]);
/// impl Geometry for Quad {
///     fn num_faces(&self) -> usize { 1 }
///     fn num_vertices_of_face(&self, _face: usize) -> usize { 4 }
///     fn position(&self, _face: usize, vert: usize) -> [f32; 3] {
///         let [u, v] = self.tex_coord(0, vert);
///         [u, v, 0.0]
///     }
///     fn normal(&self, _face: usize, _vert: usize) -> [f32; 3] { [0.0, 0.0, 1.0] }
///     fn tex_coord(&self, _face: usize, vert: usize) -> [f32; 2] {
///         [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]][vert]
///     }
///     fn set_tangent_encoded(&mut self, tangent: [f32; 4], _face: usize, vert: usize) {
///         self.0[vert] = tangent;
///     }
/// }
///
/// let mut quad = Quad([[0.0; 4]; 4]);
/// assert!(generate_tangents(&mut quad));
/// assert_eq!(quad.0, [[1.0, 0.0, 0.0, 1.0]; 4]);
/// ```
pub fn generate_tangents<I: Geometry>(geometry: &mut I) -> bool {
    generate_tangents_with(geometry, &Settings::default())
}

/// [`generate_tangents`] with mikktspace.c's `genTangSpace` threshold and worker threads.
pub fn generate_tangents_with<I: Geometry>(geometry: &mut I, settings: &Settings) -> bool {
    let Ok(read) = read(geometry) else {
        return false;
    };
    let mesh = FaceMesh {
        positions: &read.positions,
        normals: &read.normals,
        texcoords: &read.texcoords,
        faces: &read.faces,
        index_zero: read.index_zero,
    };
    let threads = settings.threads.max(1);
    let Ok(out) = faces_interface::solve(&mesh, settings.angular_threshold, threads) else {
        return false;
    };
    for (face, slots) in face_slots(&read.faces, out.spaces.len()) {
        for (vert, slot) in slots.enumerate() {
            let (space, preserving) = (&out.spaces[slot], out.preserving[slot] != 0);
            geometry.set_tangent(
                space.s,
                space.t,
                space.mag_s,
                space.mag_t,
                preserving,
                face as usize,
                vert,
            );
        }
    }
    true
}

/// The faces of 3 or 4 vertices and their attributes, one slot per face vertex.
struct Read {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    faces: Vec<(u32, u32)>,
    /// Face 0's vertex 0's position when face 0 is neither a triangle nor a quad: mikktspace.c
    /// reads it all the same, to start its bounding box.
    index_zero: Option<[f32; 3]>,
}

/// Reads every attribute once, face by face; fails when there is no face of 3 or 4 vertices, when
/// the faces are too many to number as mikktspace.c does (`4 * face + vert` in 31 bits), or when
/// memory runs out.
fn read<I: Geometry>(geometry: &I) -> Result<Read, Error> {
    let face_count = geometry.num_faces();
    let mut faces: Vec<(u32, u32)> = Vec::new();
    let mut slots = 0usize;
    for face in 0..face_count {
        let verts = geometry.num_vertices_of_face(face);
        if verts == 3 || verts == 4 {
            // Face INT_MAX / 4 is the last whose `4 * face + 3` is still an int.
            if face > (i32::MAX / 4) as usize {
                return Err(Error::SizeOverflow);
            }
            faces.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
            faces.push((face as u32, slots as u32));
            slots += verts;
        }
    }
    if faces.is_empty() {
        return Err(Error::SizeOverflow);
    }
    let mut read = Read {
        positions: vec_with_capacity(slots)?,
        normals: vec_with_capacity(slots)?,
        texcoords: vec_with_capacity(slots)?,
        index_zero: (faces[0].0 != 0).then(|| geometry.position(0, 0)),
        faces,
    };
    for (face, range) in face_slots(&read.faces, slots) {
        for vert in 0..range.len() {
            read.positions.push(geometry.position(face as usize, vert));
            read.normals.push(geometry.normal(face as usize, vert));
            read.texcoords.push(geometry.tex_coord(face as usize, vert));
        }
    }
    Ok(read)
}
