//! The fuzzer's bytes, read front to back, and the floats, indices and choices drawn from them.

/// The fuzzer's bytes, read front to back; zeros once they run out.
pub struct Input<'a> {
    pub data: &'a [u8],
    pub pos: usize,
}

impl Input<'_> {
    pub fn u8(&mut self) -> u8 {
        let byte = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos = self.pos.saturating_add(1);
        byte
    }
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    pub fn u64(&mut self) -> u64 {
        u64::from(self.u32()) | (u64::from(self.u32()) << 32)
    }
    /// A value below `n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            self.u32() as usize % n
        }
    }
    /// True about once in `n`; false on exhausted input, so short inputs stay ordinary.
    pub fn rare(&mut self, n: u8) -> bool {
        self.u8() % n == n - 1
    }
}

pub fn shuffle(input: &mut Input, items: &mut [usize]) {
    for i in (1..items.len()).rev() {
        let j = input.below(i + 1);
        items.swap(i, j);
    }
}

/// How float values are drawn from the input.
#[derive(Clone, Copy, Debug)]
pub enum Encoding {
    /// Small multiples of 1/8: ordinary meshes.
    Small,
    /// Small integers times a large or tiny scale.
    Scaled(f32),
    /// Small integers, each vector normalized (unit normals).
    Unit,
    /// Any bit pattern: NaN, inf, subnormals, huge values.
    Raw,
    /// Values from a table of edge cases.
    Special,
    /// A per-value mix of the above.
    Mixed,
}

const SCALES: [f32; 6] = [1e-30, 1e-20, 1e-6, 1e6, 1e20, 1e30];

const SPECIALS: [f32; 20] = [
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

pub fn pick_encoding(input: &mut Input) -> Encoding {
    match input.u8() % 12 {
        0..=4 => Encoding::Small,
        5 | 6 => Encoding::Unit,
        7 => Encoding::Raw,
        8 => Encoding::Special,
        9 | 10 => Encoding::Mixed,
        _ => Encoding::Scaled(SCALES[input.u8() as usize % SCALES.len()]),
    }
}

fn small(input: &mut Input) -> f32 {
    f32::from(input.u8() as i8) / 8.0
}

fn scalar(input: &mut Input, encoding: Encoding) -> f32 {
    match encoding {
        Encoding::Small | Encoding::Unit => small(input),
        Encoding::Scaled(scale) => f32::from(input.u8() as i8) * scale,
        Encoding::Raw => f32::from_bits(input.u32()),
        Encoding::Special => SPECIALS[input.u8() as usize % SPECIALS.len()],
        Encoding::Mixed => match input.u8() {
            0..=159 => small(input),
            160..=223 => SPECIALS[input.u8() as usize % SPECIALS.len()],
            _ => f32::from_bits(input.u32()),
        },
    }
}

pub fn vector<const N: usize>(input: &mut Input, encoding: Encoding) -> [f32; N] {
    let mut v = [0.0f32; N];
    for x in &mut v {
        *x = scalar(input, encoding);
    }
    if let Encoding::Unit = encoding {
        let length = v.iter().map(|x| x * x).sum::<f32>().sqrt();
        if length > 0.0 {
            v.iter_mut().for_each(|x| *x /= length);
        }
    }
    v
}

/// An index value: usually in range, sometimes just past it, sometimes anything.
pub fn index_value(input: &mut Input, vertex_count: usize) -> u32 {
    let b = input.u8();
    if b < 250 && vertex_count > 0 {
        return (b as usize % vertex_count.min(256)) as u32;
    }
    match input.u8() % 4 {
        0 => vertex_count as u32,
        1 => (vertex_count as u32).wrapping_add(1 + input.u8() as u32),
        2 => u16::MAX as u32,
        _ => input.u32(),
    }
}
