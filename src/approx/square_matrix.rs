//! A dense symmetric matrix stored compactly, that grows and shrinks by one row and column.

use serde::{Deserialize, Serialize};

/// A symmetric `n x n` matrix in a column-major buffer with a fixed column stride (its
/// capacity), so that adding or removing a row and column costs `O(n)`, not `O(n^2)`.
///
/// Used by [`KernelRidge`](super::KernelRidge) for the dictionary's Gram matrix, its inverse
/// and the posterior covariance. Every update keeps the matrix exactly (bitwise) symmetric.
/// It is saved compactly (`n` and the `n * n` entries), whatever its capacity.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(into = "Compact", try_from = "Compact")]
pub struct SquareMatrix {
    n: usize,
    /// Column stride; `data.len() == stride * stride`.
    stride: usize,
    data: Vec<f64>,
}

/// The saved form of a [`SquareMatrix`].
#[derive(Serialize, Deserialize)]
struct Compact {
    n: usize,
    data: Vec<f64>,
}

impl From<SquareMatrix> for Compact {
    fn from(m: SquareMatrix) -> Self {
        let data = (0..m.n).flat_map(|j| m.column(j).to_vec()).collect();
        Compact { n: m.n, data }
    }
}

impl TryFrom<Compact> for SquareMatrix {
    type Error = String;
    fn try_from(c: Compact) -> Result<Self, String> {
        if c.n.checked_mul(c.n) != Some(c.data.len()) {
            return Err(format!("{} entries for a {0} x {0} matrix", c.n));
        }
        Ok(SquareMatrix {
            n: c.n,
            stride: c.n,
            data: c.data,
        })
    }
}

impl PartialEq for SquareMatrix {
    fn eq(&self, other: &Self) -> bool {
        self.n == other.n && (0..self.n).all(|j| self.column(j) == other.column(j))
    }
}

impl Default for SquareMatrix {
    fn default() -> Self {
        Self::with_capacity(0)
    }
}

impl SquareMatrix {
    /// An empty (0 x 0) matrix with room for `capacity x capacity` entries.
    pub fn with_capacity(capacity: usize) -> Self {
        SquareMatrix {
            n: 0,
            stride: capacity,
            data: vec![0.0; capacity * capacity],
        }
    }

    /// The size `n`.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Entry `(i, j)`.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.data[j * self.stride + i]
    }

    /// Column `j` (equal to row `j`).
    #[inline]
    pub fn column(&self, j: usize) -> &[f64] {
        &self.data[j * self.stride..j * self.stride + self.n]
    }

    fn columns(&self) -> impl Iterator<Item = &[f64]> {
        let n = self.n;
        self.data
            .chunks_exact(self.stride.max(1))
            .take(n)
            .map(move |c| &c[..n])
    }

    fn columns_mut(&mut self) -> impl Iterator<Item = &mut [f64]> {
        let n = self.n;
        self.data
            .chunks_exact_mut(self.stride.max(1))
            .take(n)
            .map(move |c| &mut c[..n])
    }

    /// The entries, column by column, as an `n * n` column-major vector.
    pub fn to_compact(&self) -> Vec<f64> {
        self.columns().flatten().copied().collect()
    }

    /// True if the buffer is consistent, all entries are finite and the matrix is exactly
    /// symmetric.
    pub fn is_valid(&self) -> bool {
        self.n <= self.stride
            && self.stride.checked_mul(self.stride) == Some(self.data.len())
            && self.columns().flatten().all(|v| v.is_finite())
            && (0..self.n).all(|j| (0..j).all(|i| self.get(i, j) == self.get(j, i)))
    }

    /// `out = self * x`.
    pub fn mul_vec(&self, x: &[f64], out: &mut [f64]) {
        debug_assert!(x.len() == self.n && out.len() == self.n);
        out.fill(0.0);
        for (col, &xj) in self.columns().zip(x) {
            for (o, c) in out.iter_mut().zip(col) {
                *o += c * xj;
            }
        }
    }

    /// `self += scale * u u^T`, exactly symmetric.
    pub fn add_outer(&mut self, scale: f64, u: &[f64]) {
        debug_assert!(u.len() == self.n);
        for (col, &uj) in self.columns_mut().zip(u) {
            for (c, &ui) in col.iter_mut().zip(u) {
                *c += ui * uj * scale;
            }
        }
    }

    /// `self = a * self + b * other` (same size).
    pub fn scale_add(&mut self, a: f64, b: f64, other: &SquareMatrix) {
        debug_assert!(other.n == self.n);
        for (s, o) in self.columns_mut().zip(other.columns()) {
            for (s, o) in s.iter_mut().zip(o) {
                *s = a * *s + b * o;
            }
        }
    }

    /// Appends a last row and column: `[self, col; col^T, diag]`.
    pub fn push(&mut self, col: &[f64], diag: f64) {
        let n = self.n;
        debug_assert!(col.len() == n);
        if n == self.stride {
            // Out of room (only after loading a compact model): double the stride.
            let mut bigger = SquareMatrix::with_capacity((2 * n).max(4));
            bigger.n = n;
            for (dst, src) in bigger.columns_mut().zip(self.columns()) {
                dst.copy_from_slice(src);
            }
            *self = bigger;
        }
        let s = self.stride;
        for (j, &c) in col.iter().enumerate() {
            self.data[j * s + n] = c;
        }
        self.data[n * s..n * s + n].copy_from_slice(col);
        self.data[n * s + n] = diag;
        self.n = n + 1;
    }

    /// Removes row and column `r`; the last row and column take their place.
    pub fn swap_remove(&mut self, r: usize) {
        let (n, s) = (self.n, self.stride);
        debug_assert!(r < n);
        let last = n - 1;
        if r != last {
            self.data.copy_within(last * s..last * s + n, r * s);
            for j in 0..n {
                self.data[j * s + r] = self.data[j * s + last];
            }
        }
        self.n = last;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn from_fn(n: usize, f: impl Fn(usize, usize) -> f64) -> SquareMatrix {
        let mut m = SquareMatrix::with_capacity(1);
        for k in 0..n {
            let col: Vec<f64> = (0..k).map(|i| f(i, k)).collect();
            m.push(&col, f(k, k));
        }
        m
    }

    #[test]
    fn push_and_swap_remove_keep_the_right_entries() {
        let sym = |i: usize, j: usize| (i.min(j) * 10 + i.max(j)) as f64;
        let mut m = from_fn(4, sym);
        assert!(m.is_valid());
        for i in 0..4 {
            for j in 0..4 {
                assert_eq!(m.get(i, j), sym(i, j));
            }
        }
        // Remove 1: index 3 moves into slot 1.
        m.swap_remove(1);
        let order = [0, 3, 2];
        for (a, &i) in order.iter().enumerate() {
            for (b, &j) in order.iter().enumerate() {
                assert_eq!(m.get(a, b), sym(i, j));
            }
        }
        m.swap_remove(2);
        assert_eq!(m.n(), 2);
        assert_eq!(
            m.to_compact(),
            vec![sym(0, 0), sym(0, 3), sym(3, 0), sym(3, 3)]
        );
        // A saved matrix is compact and comes back equal, and can grow again.
        let json = serde_json::to_string(&m).unwrap();
        assert_eq!(
            json,
            format!(
                "{{\"n\":2,\"data\":[{:?},{:?},{:?},{:?}]}}",
                sym(0, 0),
                sym(0, 3),
                sym(3, 0),
                sym(3, 3)
            )
        );
        let mut back: SquareMatrix = serde_json::from_str(&json).unwrap();
        assert_eq!(back, m);
        back.push(&[1.0, 2.0], 3.0);
        assert_eq!(back.column(2), &[1.0, 2.0, 3.0]);
        assert_eq!(back.get(2, 1), 2.0);
        assert!(back.is_valid());
        assert!(serde_json::from_str::<SquareMatrix>("{\"n\":2,\"data\":[1.0]}").is_err());
        m.swap_remove(0);
        m.swap_remove(0);
        assert_eq!(m.n(), 0);
        assert!(m.to_compact().is_empty());
    }

    #[test]
    fn mul_vec_and_add_outer() {
        let mut m = from_fn(3, |i, j| if i == j { 2.0 } else { 1.0 });
        let mut out = [0.0; 3];
        m.mul_vec(&[1.0, 2.0, 3.0], &mut out);
        assert_eq!(out, [7.0, 8.0, 9.0]);
        m.add_outer(0.5, &[1.0, 0.0, 2.0]);
        assert_eq!(m.get(0, 2), 2.0);
        assert_eq!(m.get(2, 2), 4.0);
        assert!(m.is_valid());
    }
}
