//! The per-vertex running sums' layout ([`crate::kernel::sums`] keeps them with their flags),
//! apart so that the SIMD module, which adds to them ([`crate::kernel::simd::add_and_mark`]), can
//! name the type without importing what lies above it.
#![forbid(unsafe_code)]

use glam::Vec3;

/// Per-vertex running sums.
///
/// Policy LEGACY: `primary` is the listing's `tan1` (sum of dP/du) and `secondary` its `tan2`
/// (sum of dP/dv); from the first loop on `weight` holds the vertex's flags in its bits
/// ([`crate::kernel::simd::add_and_mark`]), until the vertex keeps its frame. Other policies: `primary` sums the tangents of
/// right-handed corners and `secondary` those of left-handed corners, `weight` the total weight of
/// both; once a vertex is resolved, `primary` holds its unit tangent and `weight` its handedness
/// ([`Self::keep_frame`]). For the per-corner output every vertex keeps its frame that way, and a
/// mirror-fold vertex flagged [`SIDE_FRAME`](crate::kernel::sums::flag::SIDE_FRAME) keeps in
/// `secondary` the unit tangent of its other side.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VertexSums {
    /// See the type's description.
    pub primary: [f32; 3],
    /// See the type's description.
    pub weight: f32,
    /// See the type's description.
    pub secondary: [f32; 3],
}

impl VertexSums {
    /// Keeps a resolved frame in place of the sums: `primary` = tangent, `weight` = `w`.
    #[inline(always)]
    pub fn keep_frame(&mut self, tangent: Vec3, w: f32) {
        self.primary = tangent.to_array();
        self.weight = w;
    }

    /// The frame [`Self::keep_frame`] kept, as written out: `x, y, z, w`.
    #[inline(always)]
    pub fn kept_frame(&self) -> [f32; 4] {
        let [x, y, z] = self.primary;
        [x, y, z, self.weight]
    }

    /// The other side's frame a [`flag::SIDE_FRAME`](crate::kernel::sums::flag::SIDE_FRAME) vertex keeps, as written out.
    #[inline(always)]
    pub fn kept_side_frame(&self) -> [f32; 4] {
        let [x, y, z] = self.secondary;
        [x, y, z, -self.weight]
    }
}
