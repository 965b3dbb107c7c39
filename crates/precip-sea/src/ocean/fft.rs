//! The fast Fourier transform the sea's synthesis uses: radix-2 Stockham
//! (autosort: no bit reversal, each stage reads one buffer and writes the other),
//! the form a compute kernel runs one stage of per dispatch (docs/model.md
//! (13.7)). `N` a power of two.

/// A complex number.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Complex {
    /// The real part.
    pub re: f32,
    /// The imaginary part.
    pub im: f32,
}

impl Complex {
    /// `re + i·im`.
    #[must_use]
    pub const fn new(re: f32, im: f32) -> Self {
        Self { re, im }
    }

    /// `e^(iθ)`.
    #[must_use]
    pub fn cis(theta: f32) -> Self {
        Self::new(theta.cos(), theta.sin())
    }

    /// The conjugate.
    #[must_use]
    pub fn conj(self) -> Self {
        Self::new(self.re, -self.im)
    }

    /// Times a real.
    #[must_use]
    pub fn scale(self, s: f32) -> Self {
        Self::new(self.re * s, self.im * s)
    }
}

impl std::ops::Mul for Complex {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

impl std::ops::Add for Complex {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.im + o.im)
    }
}

impl std::ops::Sub for Complex {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.im - o.im)
    }
}

/// One Stockham stage `stage` (0-based) of an inverse transform of `input.len()`
/// points: `output[j·2m + k] = a + w·b`, `output[j·2m + k + m] = a − w·b`, with
/// `a = input[j·m + k]`, `b = input[j·m + k + N/2]`, `m = 2^stage`, `w =
/// e^(iπk/m)` (the twiddle of the inverse): the step a GPU kernel takes per stage
/// (its WGSL twin is still to be written, issue 28).
pub fn inverse_stage(input: &[Complex], output: &mut [Complex], stage: u32) {
    let n = input.len();
    let half = n / 2;
    let m = 1usize << stage;
    for p in 0..half {
        let (j, k) = (p / m, p % m);
        let (sum, difference) = butterfly(input[j * m + k], input[j * m + k + half], k, m);
        output[j * 2 * m + k] = sum;
        output[j * 2 * m + k + m] = difference;
    }
}

/// One butterfly of a stage `m = 2^stage`: `(a + w·b, a − w·b)`, `w = e^(iπk/m)`.
/// WGSL twin: `sea_butterfly` (on two complex numbers at once).
#[must_use]
pub fn butterfly(a: Complex, b: Complex, k: usize, m: usize) -> (Complex, Complex) {
    let w = Complex::cis(std::f32::consts::PI * k as f32 / m as f32);
    let wb = b * w;
    (a + wb, a - wb)
}

/// The inverse transform `x[n] = Σ_k X[k]·e^(2πi·kn/N)` (no 1/N) of `data`, in
/// place; `scratch` as long.
///
/// # Panics
///
/// Never for a length that is a power of two; other lengths are refused by the
/// callers (`OceanCascade::new`).
pub fn inverse(data: &mut [Complex], scratch: &mut [Complex]) {
    let n = data.len();
    debug_assert!(n.is_power_of_two() && scratch.len() == n);
    let stages = n.trailing_zeros();
    for stage in 0..stages {
        if stage % 2 == 0 {
            inverse_stage(data, scratch, stage);
        } else {
            inverse_stage(scratch, data, stage);
        }
    }
    if stages % 2 == 1 {
        data.copy_from_slice(scratch);
    }
}

/// The 2D inverse transform of an `n × n` grid (rows, then columns), in place.
pub fn inverse_2d(grid: &mut [Complex], n: usize) {
    let mut line = vec![Complex::default(); n];
    let mut scratch = vec![Complex::default(); n];
    for row in grid.chunks_mut(n) {
        inverse(row, &mut scratch);
    }
    for x in 0..n {
        for (y, v) in line.iter_mut().enumerate() {
            *v = grid[y * n + x];
        }
        inverse(&mut line, &mut scratch);
        for (y, v) in line.iter().enumerate() {
            grid[y * n + x] = *v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stages_make_the_discrete_fourier_sum() {
        for n in [2usize, 8, 64, 256] {
            let data: Vec<Complex> = (0..n)
                .map(|i| Complex::new((i as f32 * 0.7).sin(), (i as f32 * 1.3).cos() - 0.2))
                .collect();
            let mut fast = data.clone();
            let mut scratch = vec![Complex::default(); n];
            inverse(&mut fast, &mut scratch);
            for (out, got) in fast.iter().enumerate() {
                let mut want = Complex::default();
                for (k, x) in data.iter().enumerate() {
                    let theta = std::f64::consts::TAU * (k * out % n) as f64 / n as f64;
                    want = want + *x * Complex::cis(theta as f32);
                }
                let err = *got - want;
                assert!(
                    err.re.abs().max(err.im.abs()) < 2e-4 * n as f32,
                    "{n}: x[{out}] {got:?} against {want:?}"
                );
            }
        }
    }
}
