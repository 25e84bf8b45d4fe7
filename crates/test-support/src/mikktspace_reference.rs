//! mikktspace.c itself (the `mikktspace-sys` crate, which builds the original C file with `cc`), as
//! the reference that method MIKKTSPACE must reproduce bit for bit.
//!
//! Its callbacks read each corner's position, normal and texture coordinate through the index
//! buffer (or, unindexed, triangle `t` is vertices `3t..3t+3`), every face a triangle, and
//! `setTSpaceBasic(face t, vert k)` lands in corner `3t + k` as `[x, y, z, sign]`.
//!
//! Used by `crates/tbasis/tests/mikktspace.rs`, `mikktspace_repair.rs` and `accuracy.rs`, by
//! `crates/compare`'s examples, and by `tools/gltf`'s tests and the fuzz target, which include it
//! by path: so it depends on nothing but the standard library and `mikktspace-sys`.

/// A triangle mesh as mikktspace.c's callbacks read it.
#[derive(Clone, Copy)]
pub struct Geometry<'a> {
    pub positions: &'a [[f32; 3]],
    pub normals: &'a [[f32; 3]],
    pub texcoords: &'a [[f32; 2]],
    /// Three per triangle, each below the vertex count; `None`: unindexed.
    pub indices: Option<&'a [u32]>,
}

impl Geometry<'_> {
    /// Triangle corners: the index count, or the vertex count when unindexed.
    pub fn corner_count(&self) -> usize {
        self.indices.map_or(self.positions.len(), <[u32]>::len)
    }

    /// The vertex corner `3 * face + vert` reads.
    fn vertex(&self, face: usize, vert: usize) -> usize {
        let corner = 3 * face + vert;
        self.indices.map_or(corner, |indices| indices[corner] as usize)
    }
}

/// The callbacks: inputs from `geometry`, outputs into `result` (one per corner).
struct MikkC<'a> {
    geometry: Geometry<'a>,
    result: &'a mut [[f32; 4]],
    /// `setTSpaceBasic` calls so far.
    written: usize,
}

impl mikktspace_sys::MikkTSpaceInterface for MikkC<'_> {
    fn get_num_faces(&self) -> usize {
        self.geometry.corner_count() / 3
    }
    fn get_num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }
    fn get_position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.geometry.positions[self.geometry.vertex(face, vert)]
    }
    fn get_normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.geometry.normals[self.geometry.vertex(face, vert)]
    }
    fn get_tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.geometry.texcoords[self.geometry.vertex(face, vert)]
    }
    fn set_tspace_basic(&mut self, tangent: [f32; 3], sign: f32, face: usize, vert: usize) {
        self.result[3 * face + vert] = [tangent[0], tangent[1], tangent[2], sign];
        self.written += 1;
    }
}

/// Runs `genTangSpaceDefault` on `geometry`, writing every corner of `result` (`corner_count`
/// elements), and returns what it returns. When it returns false (no triangles, or an allocation
/// failed) it has written nothing.
pub fn generate(geometry: Geometry, result: &mut [[f32; 4]]) -> bool {
    assert_eq!(result.len(), geometry.corner_count(), "one result per corner");
    assert_eq!(geometry.corner_count() % 3, 0, "whole triangles");
    let corners = geometry.corner_count();
    // An index out of range would panic inside a C callback, which aborts: refuse it here.
    if let Some(bad) = geometry
        .indices
        .and_then(|indices| indices.iter().find(|&&i| i as usize >= geometry.positions.len()))
    {
        panic!("index {bad} out of range for {} vertices", geometry.positions.len());
    }
    let mut callbacks = MikkC {
        geometry,
        result,
        written: 0,
    };
    let ok = mikktspace_sys::gen_tang_space_default(&mut callbacks);
    let expected = if ok { corners } else { 0 };
    assert_eq!(callbacks.written, expected, "setTSpaceBasic calls (returned {ok})");
    ok
}

/// mikktspace.c's frame per corner for this mesh, with texture coordinates `(u, 1 - v)` (computed
/// per vertex in f32 before anything else) when `flip_v`; `None` when mikktspace.c returns false.
pub fn reference_corners(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    texcoords: &[[f32; 2]],
    indices: Option<&[u32]>,
    flip_v: bool,
) -> Option<Vec<[f32; 4]>> {
    let flipped: Vec<[f32; 2]>;
    let texcoords = if flip_v {
        flipped = texcoords.iter().map(|&[u, v]| [u, 1.0 - v]).collect();
        &flipped
    } else {
        texcoords
    };
    let geometry = Geometry {
        positions,
        normals,
        texcoords,
        indices,
    };
    let mut result = vec![[0.0f32; 4]; geometry.corner_count()];
    generate(geometry, &mut result).then_some(result)
}

/// mikktspace.c's frames with each vertex taking its first corner's (in index order), and
/// `(1, 0, 0, 1)` for a vertex no triangle uses: the per-vertex result a renderer that drops
/// duplicated seam vertices gets, to compare per-vertex methods with.
pub fn first_corner_frames(geometry: Geometry) -> Vec<[f32; 4]> {
    let mut corners = vec![[0.0f32; 4]; geometry.corner_count()];
    assert!(generate(geometry, &mut corners), "mikktspace.c failed");
    let mut vertices = vec![[1.0, 0.0, 0.0, 1.0]; geometry.positions.len()];
    let mut seen = vec![false; geometry.positions.len()];
    for (c, corner) in corners.iter().enumerate() {
        let v = geometry.indices.map_or(c, |indices| indices[c] as usize);
        if !std::mem::replace(&mut seen[v], true) {
            vertices[v] = *corner;
        }
    }
    vertices
}
