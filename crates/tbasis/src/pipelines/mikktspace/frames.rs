//! Where each corner's tangent and orientation go: the scratch's per-corner arrays, or the
//! caller's per-corner output itself.
//!
//! Written in place, the caller's output saves the arrays (13 bytes a corner, memory a call would
//! otherwise touch for the first time) and the pass that copies them out. It is offered only where
//! nothing can fail once the first corner is written ([`super::fans`]), since an error must leave
//! the caller's output as it was.
#![forbid(unsafe_code)]

use crate::kernel::parallel;
use crate::kernel::vector::Vec3;
use crate::kernel::views::strided::StridedMut;

/// Per corner of every triangle (`3 t + k`): a space and its orientation (1: preserving).
pub(crate) trait Frames<S>: Send + Sync {
    /// The corners of a range of consecutive triangles, for one worker.
    type Part<'p>: Frames<S>
    where
        Self: 'p;
    fn corners(&self) -> usize;
    fn get(&self, c: usize) -> (S, u8);
    fn set(&mut self, c: usize, space: S, preserving: u8);
    /// Disjoint parts for consecutive triangle ranges (exclusive `triangle_ends`).
    fn split<'p>(&'p mut self, triangle_ends: &'p [usize]) -> impl Iterator<Item = Self::Part<'p>> + 'p;
}

/// The scratch's per-corner arrays.
pub(crate) struct Arrays<'a, S> {
    pub spaces: &'a mut [S],
    pub orientation: &'a mut [u8],
}

impl<S: Copy + Send + Sync> Frames<S> for Arrays<'_, S> {
    type Part<'p>
        = Arrays<'p, S>
    where
        Self: 'p;

    fn corners(&self) -> usize {
        self.orientation.len()
    }

    #[inline(always)]
    fn get(&self, c: usize) -> (S, u8) {
        (self.spaces[c], self.orientation[c])
    }

    #[inline(always)]
    fn set(&mut self, c: usize, space: S, preserving: u8) {
        self.spaces[c] = space;
        self.orientation[c] = preserving;
    }

    fn split<'p>(&'p mut self, triangle_ends: &'p [usize]) -> impl Iterator<Item = Arrays<'p, S>> + 'p {
        parallel::split(&mut *self.spaces, triangle_ends, 3)
            .zip(parallel::split(&mut *self.orientation, triangle_ends, 3))
            .map(|(spaces, orientation)| Arrays { spaces, orientation })
    }
}

/// The caller's output: `setTSpaceBasic`'s tangent and sign, `[x, y, z, ±1]`.
impl Frames<Vec3> for StridedMut<'_, [f32; 4]> {
    type Part<'p>
        = StridedMut<'p, [f32; 4]>
    where
        Self: 'p;

    fn corners(&self) -> usize {
        self.len()
    }

    #[inline(always)]
    fn get(&self, c: usize) -> (Vec3, u8) {
        let [x, y, z, w] = StridedMut::get(self, c);
        ([x, y, z], u8::from(w > 0.0))
    }

    #[inline(always)]
    fn set(&mut self, c: usize, [x, y, z]: Vec3, preserving: u8) {
        StridedMut::set(self, c, [x, y, z, if preserving != 0 { 1.0 } else { -1.0 }]);
    }

    fn split<'p>(&'p mut self, triangle_ends: &'p [usize]) -> impl Iterator<Item = StridedMut<'p, [f32; 4]>> + 'p {
        StridedMut::split(self, triangle_ends, 3).into_iter()
    }
}
