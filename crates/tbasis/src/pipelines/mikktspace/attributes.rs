//! The caller's vertex attributes as mikktspace.c's callbacks would hand them over.
#![forbid(unsafe_code)]

use crate::kernel::mesh::Mesh;
use crate::kernel::vector::Vec3;

/// Reads vertex attributes, with `v' = 1 - v` applied first when the texture's V points down.
#[derive(Clone, Copy)]
pub(crate) struct Attributes<'a> {
    pub mesh: &'a Mesh<'a>,
    pub flip_v: bool,
    /// Per corner, mikktspace.c's index for it where faces are not all triangles
    /// ([`super::faces_interface`]); `None`: corner `3 t + k` is `4 t + k`.
    pub corner_values: Option<&'a [u32]>,
    /// The position of face 0's vertex 0 when face 0 gives no triangle: mikktspace.c reads index
    /// 0's position to start its bounding box all the same (`GenerateSharedVerticesIndexList`).
    pub index_zero: Option<Vec3>,
}

impl Attributes<'_> {
    /// mikktspace.c's index for corner `c`: `4 * face + vert` (`MakeIndex`).
    #[inline(always)]
    pub fn value_of(&self, c: usize) -> u32 {
        match self.corner_values {
            None => (4 * (c / 3) + c % 3) as u32,
            Some(values) => values[c],
        }
    }

    #[inline(always)]
    pub fn position(&self, v: u32) -> Vec3 {
        self.mesh.positions.get(v as usize)
    }

    #[inline(always)]
    pub fn normal(&self, v: u32) -> Vec3 {
        self.mesh.normals.get(v as usize)
    }

    /// The texture coordinate; the caller has checked that the mesh has them.
    #[inline(always)]
    pub fn texcoord(&self, v: u32) -> [f32; 2] {
        let uv = self.mesh.texcoords.map_or([0.0; 2], |uvs| uvs.get(v as usize));
        if self.flip_v {
            [uv[0], 1.0 - uv[1]]
        } else {
            uv
        }
    }

    /// Position, normal and texture coordinate: the eight floats corners are welded by.
    #[inline(always)]
    pub fn key(&self, v: u32) -> [f32; 8] {
        let ([px, py, pz], [nx, ny, nz], [u, w]) = (self.position(v), self.normal(v), self.texcoord(v));
        [px, py, pz, nx, ny, nz, u, w]
    }
}
