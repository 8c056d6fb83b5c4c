//! The activation scan: a structure-of-arrays copy of every receptive field's centre and
//! metric, so that the squared distances of all fields to a query are computed in tight loops
//! over contiguous columns (which the compiler vectorises across fields) with no branch per
//! input dimension.
//!
//! Every distance is computed with the same floating-point operations in the same order as
//! [`ReceptiveField::squared_distance`], so results are bit-identical to the per-field scan.

use super::receptive_field::ReceptiveField;

/// Centres and metrics of one output's receptive fields, column by column.
///
/// Column `i < n` holds centre coordinate `i` of every field; the next columns hold the
/// diagonal of `D` (`diag_only`, `n` columns) or every element of the factor `M` (`n * n`
/// columns, element `k + i * n` in column `n + k + i * n`). Derived state: never saved,
/// rebuilt from the fields after loading.
#[derive(Debug, Clone, Default)]
pub(crate) struct ScanIndex {
    n: usize,
    diag_only: bool,
    len: usize,
    cols: Vec<Vec<f64>>,
}

impl ScanIndex {
    /// The index of `rfs` for `n` inputs.
    pub fn build(n: usize, diag_only: bool, rfs: &[ReceptiveField]) -> Self {
        let metric_cols = if diag_only { n } else { n * n };
        let mut index = ScanIndex {
            n,
            diag_only,
            len: 0,
            cols: vec![Vec::with_capacity(rfs.len()); n + metric_cols],
        };
        for rf in rfs {
            index.push(rf);
        }
        index
    }

    /// Number of receptive fields indexed.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the index was built for `n` inputs, this metric mode and `len` fields.
    pub fn matches(&self, n: usize, diag_only: bool, len: usize) -> bool {
        self.n == n && self.diag_only == diag_only && self.len == len
    }

    /// Appends `rf`.
    pub fn push(&mut self, rf: &ReceptiveField) {
        for col in &mut self.cols {
            col.push(0.0);
        }
        self.len += 1;
        self.write(self.len - 1, rf);
    }

    /// Copies `rf`'s centre and metric into entry `idx`.
    pub fn write(&mut self, idx: usize, rf: &ReceptiveField) {
        for (col, c) in self.cols.iter_mut().zip(&rf.c) {
            col[idx] = *c;
        }
        self.write_metric(idx, rf);
    }

    /// Copies `rf`'s metric into entry `idx` (after training, which never moves a centre).
    pub fn write_metric(&mut self, idx: usize, rf: &ReceptiveField) {
        let n = self.n;
        let metric = &mut self.cols[n..];
        if self.diag_only {
            for (i, col) in metric.iter_mut().enumerate() {
                col[idx] = rf.d[i + i * n];
            }
        } else {
            for (col, m) in metric.iter_mut().zip(&rf.m) {
                col[idx] = *m;
            }
        }
    }

    /// Removes entry `idx`, moving the last entry into its place (as `Vec::swap_remove`).
    pub fn swap_remove(&mut self, idx: usize) {
        for col in &mut self.cols {
            col.swap_remove(idx);
        }
        self.len -= 1;
    }

    /// Writes the squared distance `(x - c)^T D (x - c)` of every field to `xn` into `q`
    /// (resized to [`Self::len`]); `row` is scratch.
    pub fn distances(&self, xn: &[f64], q: &mut Vec<f64>, row: &mut Vec<f64>) {
        let (n, len) = (self.n, self.len);
        q.clear();
        q.resize(len, 0.0);
        let (centre, metric) = self.cols.split_at(n);
        if self.diag_only {
            for i in 0..n {
                let x = xn[i];
                for ((q, c), d) in q.iter_mut().zip(&centre[i]).zip(&metric[i]) {
                    let dx = x - c;
                    *q += d * dx * dx;
                }
            }
            return;
        }
        // q = |M dx|^2 with M upper triangular, row k of M dx at a time.
        row.clear();
        row.resize(len, 0.0);
        for k in 0..n {
            row.iter_mut().for_each(|r| *r = 0.0);
            for i in k..n {
                let x = xn[i];
                for ((r, c), m) in row.iter_mut().zip(&centre[i]).zip(&metric[k + i * n]) {
                    *r += m * (x - c);
                }
            }
            for (q, r) in q.iter_mut().zip(row.iter()) {
                *q += r * r;
            }
        }
    }

    /// The squared distance of field `idx` to `xn`, or `None` as soon as a partial sum
    /// proves it exceeds `limit`.
    #[inline]
    pub fn distance(&self, idx: usize, xn: &[f64], limit: f64) -> Option<f64> {
        let n = self.n;
        let (centre, metric) = self.cols.split_at(n);
        let mut q = 0.0;
        if self.diag_only {
            for i in 0..n {
                let dx = xn[i] - centre[i][idx];
                q += metric[i][idx] * dx * dx;
                if q > limit {
                    return None;
                }
            }
        } else {
            for k in 0..n {
                let mut row = 0.0;
                for i in k..n {
                    row += metric[k + i * n][idx] * (xn[i] - centre[i][idx]);
                }
                q += row * row;
                if q > limit {
                    return None;
                }
            }
        }
        Some(q)
    }
}
