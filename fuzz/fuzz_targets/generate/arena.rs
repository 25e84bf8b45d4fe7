//! Buffers inside a byte arena the harness owns: where they are, what the header says about them,
//! and reading and writing their elements.

use crate::status::{
    tbasis_status, TBASIS_ERROR_INVALID_STRIDE, TBASIS_ERROR_NULL_POINTER, TBASIS_ERROR_SIZE_OVERFLOW,
};

use arbitrary::{Result, Unstructured};

use crate::input::{Attribute, Encoding, Vectors};

/// One strided buffer in an arena: `count` elements of `size` bytes, `stride` apart from `base`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Buf {
    pub null: bool,
    pub base: usize,
    pub stride: usize,
    pub size: usize,
    pub count: usize,
}

impl Buf {
    /// Bytes from the first element's start to the last one's end, if that is a number.
    pub fn extent(&self) -> Option<usize> {
        if self.count == 0 {
            return Some(0);
        }
        (self.count - 1).checked_mul(self.stride)?.checked_add(self.size)
    }

    /// The harness wrote (and the library may access) this buffer inside an arena of `len` bytes.
    /// A short stride can squeeze a huge count into a few bytes: such a buffer is not placed.
    pub fn placed(&self, len: usize) -> bool {
        !self.null && self.count <= len && self.extent().is_some_and(|e| e <= len.saturating_sub(self.base))
    }

    /// Status bits for what the header says is wrong with this buffer on its own:
    /// a stride below the element size, a span that does not fit, NULL with elements.
    pub fn violations(&self) -> u32 {
        let mut bits = 0;
        if self.stride < self.size {
            bits |= bit(TBASIS_ERROR_INVALID_STRIDE);
        } else if self.count > 0 && self.extent().is_none_or(|e| e > isize::MAX as usize) {
            bits |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
        }
        if self.null && self.count > 0 {
            bits |= bit(TBASIS_ERROR_NULL_POINTER);
        }
        bits
    }

    /// Whether the library may see the bytes of this buffer as a valid footprint.
    pub fn valid_footprint(&self) -> bool {
        !self.null && self.count > 0 && self.violations() == 0
    }

    pub fn element(&self, i: usize) -> usize {
        self.base + i * self.stride
    }

    /// Whether some element shares a byte with `lo..hi`: only the first element ending after
    /// `lo` can (element starts grow with the index, and the stride covers the size).
    pub fn hits(&self, lo: usize, hi: usize) -> bool {
        if lo >= hi || self.count == 0 || self.size == 0 {
            return false;
        }
        let first = if self.base + self.size > lo {
            0
        } else {
            (lo - self.base - self.size) / self.stride + 1
        };
        first < self.count && self.base + first * self.stride < hi
    }

    /// Whether the two buffers share a byte (both valid footprints).
    pub fn shares_bytes(&self, other: &Buf) -> bool {
        (0..self.count).any(|i| other.hits(self.element(i), self.element(i) + self.size))
    }

    /// The element byte ranges.
    pub fn ranges(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.count).map(|i| (self.element(i), self.element(i) + self.size))
    }

    /// Moves the base back so the buffer fits, when it can fit at all.
    pub fn clamp_into(&mut self, len: usize) {
        match self.extent() {
            Some(e) if e <= len => self.base = self.base.min(len - e),
            _ => self.base %= len,
        }
    }
}

pub fn bit(status: tbasis_status) -> u32 {
    1u32 << status.min(31)
}

pub fn put_f32(bytes: &mut [u8], at: usize, value: f32) {
    bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
}

pub fn f32_at(bytes: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

pub fn vec_at<const N: usize>(bytes: &[u8], at: usize) -> [f32; N] {
    core::array::from_fn(|k| f32_at(bytes, at + 4 * k))
}

/// Writes `count` vectors of `N` floats into `buf` (elements may overlap when the stride is short).
pub fn fill_vectors<const N: usize>(
    u: &mut Unstructured,
    encoding: Encoding,
    attribute: Attribute,
    buf: &Buf,
    arena: &mut [u8],
) -> Result<()> {
    if !buf.placed(arena.len()) {
        return Ok(());
    }
    let mut vectors = Vectors::<N>::new(u, encoding, attribute)?;
    for i in 0..buf.count {
        let v: [f32; N] = vectors.next(u, i)?;
        for (k, x) in v.into_iter().enumerate() {
            put_f32(arena, buf.element(i) + 4 * k, x);
        }
    }
    Ok(())
}

/// The first byte outside the `writable` ranges that differs, if any.
pub fn first_change_outside(before: &[u8], after: &[u8], mut writable: Vec<(usize, usize)>) -> Option<usize> {
    writable.sort_unstable();
    let end = before.len();
    let mut at = 0;
    for (lo, hi) in writable.into_iter().chain([(end, end)]) {
        if lo > at && before[at..lo] != after[at..lo] {
            return (at..lo).find(|&i| before[i] != after[i]);
        }
        at = at.max(hi);
    }
    None
}
