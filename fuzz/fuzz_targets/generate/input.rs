//! The fuzzer's bytes, read through `arbitrary`'s `Unstructured`: the weighted choices, floats,
//! vectors and indices drawn from them.
//!
//! Exhausted input reads as zeros (`int_in_range` gives its start, a derived enum its first
//! variant), so a short input stays ordinary: every choice below puts its ordinary case first and
//! its rare cases (NULL pointers, invalid values) last.

use arbitrary::{Arbitrary, Result, Unstructured};

/// True about once in `N`; false on exhausted input. (`Unstructured::ratio` is true on exhausted
/// input, which would make every rare case the default.)
pub fn one_in<const N: u8>(u: &mut Unstructured) -> Result<bool> {
    Ok(u.int_in_range(0..=N - 1)? == N - 1)
}

/// An index below `n` drawn with the given weights: `i` with probability `weights[i] / sum`; the
/// first on exhausted input.
pub fn weighted(u: &mut Unstructured, weights: &[u16]) -> Result<usize> {
    let total: u32 = weights.iter().map(|&w| u32::from(w)).sum();
    let mut x = u.int_in_range(0..=total - 1)?;
    for (i, &w) in weights.iter().enumerate() {
        if x < u32::from(w) {
            return Ok(i);
        }
        x -= u32::from(w);
    }
    unreachable!("weighted: {x} past the total {total}")
}

/// A value below `n` (0 when `n` is 0).
pub fn below(u: &mut Unstructured, n: usize) -> Result<usize> {
    if n == 0 {
        Ok(0)
    } else {
        u.int_in_range(0..=n - 1)
    }
}

pub fn shuffle(u: &mut Unstructured, items: &mut [usize]) -> Result<()> {
    for i in (1..items.len()).rev() {
        let j = below(u, i + 1)?;
        items.swap(i, j);
    }
    Ok(())
}

/// A small signed offset, `-(n - 1)..=n - 1`.
pub fn nudge(u: &mut Unstructured, n: isize) -> Result<isize> {
    u.int_in_range(-(n - 1)..=n - 1)
}

/// How float values are drawn from the input.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum Encoding {
    /// Small multiples of 1/8: ordinary meshes.
    Small,
    /// Small integers, each vector normalized (unit normals).
    Unit,
    /// A per-value mix: mostly small, sometimes an edge case or any bit pattern.
    Mixed,
    /// A few vectors (drawn mixed), each element one of them: equal corners, shared edges,
    /// collapsed triangles are common, and a large mesh costs a byte per element.
    Palette(#[arbitrary(with = palette_size)] u8),
    /// A regular grid, `width` vertices a row, from the element's index (positions: `(column, row,
    /// height)`; texture coordinates: `(column, row) / 8`, mirrored past the middle column when
    /// `mirror` (a mirror seam); normals: `+z` tilted), each perturbed by one byte: large meshes
    /// with real surfaces from a few bytes.
    Grid(Grid),
    /// Small integers times a large or tiny scale.
    Scaled(#[arbitrary(with = scale)] f32),
    /// Any bit pattern: NaN, inf, subnormals, huge values.
    Raw,
    /// Values from a table of edge cases.
    Special,
}

#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct Grid {
    #[arbitrary(with = grid_width)]
    pub width: usize,
    pub mirror: bool,
}

fn palette_size(u: &mut Unstructured) -> Result<u8> {
    u.int_in_range(1..=8)
}

fn grid_width(u: &mut Unstructured) -> Result<usize> {
    u.int_in_range(2..=64)
}

/// Which vector of a mesh a value is: it decides what a `Grid` gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Attribute {
    Position,
    Normal,
    Texcoord,
}

const SCALES: [f32; 6] = [1e-30, 1e-20, 1e-6, 1e6, 1e20, 1e30];

fn scale(u: &mut Unstructured) -> Result<f32> {
    Ok(*u.choose(&SCALES)?)
}

pub const SPECIALS: [f32; 20] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MIN_POSITIVE,
    f32::from_bits(1),
    f32::MAX,
    -f32::MAX,
    1e-20,
    1e20,
    1e-7,
    1e7,
    3.0e38,
    -1e-38,
    0.1,
];

/// The encoding of one attribute: mostly small values, the rest spread over the other encodings.
pub fn pick_encoding(u: &mut Unstructured) -> Result<Encoding> {
    Ok(match weighted(u, &[5, 2, 2, 1])? {
        0 => Encoding::Small,
        1 => Encoding::Unit,
        2 => Encoding::Mixed,
        _ => Encoding::arbitrary(u)?,
    })
}

fn small(u: &mut Unstructured) -> Result<f32> {
    Ok(f32::from(i8::arbitrary(u)?) / 8.0)
}

pub fn special(u: &mut Unstructured) -> Result<f32> {
    Ok(*u.choose(&SPECIALS)?)
}

fn raw(u: &mut Unstructured) -> Result<f32> {
    Ok(f32::from_bits(u32::arbitrary(u)?))
}

/// One float of the mixed encoding: mostly small, sometimes an edge case, sometimes any bits.
pub fn mixed(u: &mut Unstructured) -> Result<f32> {
    match weighted(u, &[10, 4, 2])? {
        0 => small(u),
        1 => special(u),
        _ => raw(u),
    }
}

fn scalar(u: &mut Unstructured, encoding: Encoding) -> Result<f32> {
    match encoding {
        Encoding::Small | Encoding::Unit | Encoding::Palette(_) | Encoding::Grid(_) => small(u),
        Encoding::Scaled(scale) => Ok(f32::from(i8::arbitrary(u)?) * scale),
        Encoding::Raw => raw(u),
        Encoding::Special => special(u),
        Encoding::Mixed => mixed(u),
    }
}

/// A vector of `N` floats drawn with `encoding` (palettes and grids are per buffer:
/// [`Vectors`]).
pub fn vector<const N: usize>(u: &mut Unstructured, encoding: Encoding) -> Result<[f32; N]> {
    let mut v = [0.0f32; N];
    for x in &mut v {
        *x = scalar(u, encoding)?;
    }
    if let Encoding::Unit = encoding {
        let length = v.iter().map(|x| x * x).sum::<f32>().sqrt();
        if length > 0.0 {
            v.iter_mut().for_each(|x| *x /= length);
        }
    }
    Ok(v)
}

/// Draws the vectors of one buffer, element by element.
pub struct Vectors<const N: usize> {
    encoding: Encoding,
    attribute: Attribute,
    palette: Vec<[f32; N]>,
}

impl<const N: usize> Vectors<N> {
    pub fn new(u: &mut Unstructured, encoding: Encoding, attribute: Attribute) -> Result<Self> {
        let palette = match encoding {
            Encoding::Palette(n) => (0..n).map(|_| vector(u, Encoding::Mixed)).collect::<Result<_>>()?,
            _ => Vec::new(),
        };
        Ok(Vectors {
            encoding,
            attribute,
            palette,
        })
    }

    /// Element `i`.
    pub fn next(&mut self, u: &mut Unstructured, i: usize) -> Result<[f32; N]> {
        match self.encoding {
            Encoding::Palette(_) => Ok(*u.choose(&self.palette)?),
            Encoding::Grid(grid) => grid_vector(u, grid, self.attribute, i),
            encoding => vector(u, encoding),
        }
    }
}

fn grid_vector<const N: usize>(u: &mut Unstructured, grid: Grid, attribute: Attribute, i: usize) -> Result<[f32; N]> {
    let w = grid.width;
    let (column, row) = ((i % w) as f32, (i / w) as f32);
    let p = small(u)?;
    let values = match attribute {
        Attribute::Position => [column, row, p],
        Attribute::Normal => [p / 4.0, 0.0, 1.0],
        Attribute::Texcoord => {
            let mirrored = if grid.mirror && i % w > w / 2 {
                (w - i % w) as f32
            } else {
                column
            };
            [mirrored / 8.0, row / 8.0 + p / 64.0, 0.0]
        }
    };
    Ok(core::array::from_fn(|k| values[k]))
}

/// An index value: usually in range, sometimes just past it, sometimes anything.
pub fn index_value(u: &mut Unstructured, vertex_count: usize) -> Result<u32> {
    if weighted(u, &[250, 6])? == 0 && vertex_count > 0 {
        return Ok(below(u, vertex_count)? as u32);
    }
    Ok(match u.int_in_range(0..=3u8)? {
        0 => vertex_count as u32,
        1 => (vertex_count as u32).wrapping_add(1 + u32::from(u8::arbitrary(u)?)),
        2 => u32::from(u16::MAX),
        _ => u32::arbitrary(u)?,
    })
}

/// How the index buffer is drawn.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum IndexPattern {
    /// Each index drawn on its own ([`index_value`]).
    Random,
    /// Each triangle near the previous one: corner `k` of triangle `t` is `t` plus a byte's worth
    /// (modulo the vertex count), so triangles share vertices and edges.
    Local,
    /// The triangles of a grid `width` vertices a row (modulo the vertex count), two a quad, the
    /// diagonal flipped where a byte says so; then a few indices overwritten.
    Grid(#[arbitrary(with = grid_width)] usize),
}

/// The index values of `count` indices over `vertex_count` vertices.
pub fn index_values(
    u: &mut Unstructured,
    pattern: IndexPattern,
    count: usize,
    vertex_count: usize,
) -> Result<Vec<u32>> {
    let modulo = |x: usize| (x % vertex_count.max(1)) as u32;
    let mut values = Vec::with_capacity(count);
    match pattern {
        IndexPattern::Random => {
            for _ in 0..count {
                values.push(index_value(u, vertex_count)?);
            }
        }
        IndexPattern::Local => {
            for k in 0..count {
                values.push(modulo(k / 3 + usize::from(u.int_in_range(0..=15u8)?)));
            }
        }
        IndexPattern::Grid(w) => {
            let mut quad = 0;
            while values.len() < count {
                let (row, column) = (quad / (w - 1), quad % (w - 1));
                let a = row * w + column;
                let [b, c, d] = [a + 1, a + w, a + w + 1];
                let quads = if bool::arbitrary(u)? {
                    [a, b, d, a, d, c]
                } else {
                    [a, b, c, b, d, c]
                };
                values.extend(quads.iter().take(count - values.len()).map(|&v| modulo(v)));
                quad += 1;
            }
            for _ in 0..u.int_in_range(0..=2u8)? {
                let at = below(u, count)?;
                if at < count {
                    values[at] = index_value(u, vertex_count)?;
                }
            }
        }
    }
    Ok(values)
}
