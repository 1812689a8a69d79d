//! Fuzz bytes read as values: a cursor that never fails, reading zeros once the bytes run out,
//! so every input, however short, is a complete case.

/// Scales a drawn number may take: the physical range and both ends of f64, where overflow,
/// underflow and lost precision live.
const SCALES: [f64; 12] = [
    0.0, 1e-300, 1e-9, 1e-4, 0.01, 0.5, 1.0, 2.0, 10.0, 1e5, 1e9, 1e300,
];

/// A cursor over fuzz bytes.
#[derive(Debug, Clone)]
pub struct Bytes<'a> {
    data: &'a [u8],
}

impl<'a> Bytes<'a> {
    /// Reads `data` from its start.
    pub fn new(data: &'a [u8]) -> Self {
        Self { data }
    }

    /// The next byte, or 0 past the end.
    pub fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    /// A number in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        usize::from(self.byte()) % n
    }

    /// A flag.
    pub fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// A number: mostly a signed fraction of one of `SCALES`, sometimes the raw bits of an
    /// f64 (NaN, ±∞, subnormals included).
    pub fn number(&mut self) -> f64 {
        let head = self.byte();
        if head >= 240 {
            let mut bits = [0u8; 8];
            bits.iter_mut().for_each(|b| *b = self.byte());
            return f64::from_le_bytes(bits);
        }
        let scale = SCALES[usize::from(head) % SCALES.len()];
        let fraction = f64::from(u16::from_le_bytes([self.byte(), self.byte()])) / 65535.0;
        let sign = if head & 0x10 != 0 { -1.0 } else { 1.0 };
        sign * scale * fraction
    }

    /// A number in the physical range `[lo, hi]`, for the parts of a case that must be sane for
    /// the rest of it to be reached.
    pub fn within(&mut self, lo: f64, hi: f64) -> f64 {
        let fraction = f64::from(u16::from_le_bytes([self.byte(), self.byte()])) / 65535.0;
        lo + (hi - lo) * fraction
    }
}
