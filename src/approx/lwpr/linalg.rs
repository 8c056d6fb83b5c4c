//! Small dense helpers on column-major `n x n` matrices stored in slices.

/// Dot product of two equally long slices.
#[inline]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `y += a * x`.
#[inline]
pub(crate) fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// Upper-triangular Cholesky factor `M` of a symmetric positive definite `a` (`a = M^T M`),
/// or `None` if `a` is not positive definite.
pub(crate) fn cholesky_upper(n: usize, a: &[f64]) -> Option<Vec<f64>> {
    let mut m = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..=j {
            // a[i, j] = sum_{k <= i} m[k, i] m[k, j]
            let mut s = a[i + j * n];
            for k in 0..i {
                s -= m[k + i * n] * m[k + j * n];
            }
            if i == j {
                if s <= 0.0 || !s.is_finite() {
                    return None;
                }
                m[j + j * n] = s.sqrt();
            } else {
                m[i + j * n] = s / m[i + i * n];
            }
        }
    }
    Some(m)
}

/// Writes `d = M^T M` for an upper-triangular `m` (both column-major `n x n`).
pub(crate) fn metric_from_factor(n: usize, m: &[f64], d: &mut [f64]) {
    for j in 0..n {
        for i in j..n {
            // (M^T M)[i, j] = sum_{k <= min(i, j)} m[k, i] m[k, j]
            let v = dot(&m[i * n..i * n + j + 1], &m[j * n..j * n + j + 1]);
            d[i + j * n] = v;
            d[j + i * n] = v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_reconstructs_and_rejects_indefinite() {
        let a = [4.0, 2.0, 0.4, 2.0, 5.0, 1.0, 0.4, 1.0, 3.0];
        let m = cholesky_upper(3, &a).unwrap();
        // upper triangular
        assert_eq!((m[1], m[2], m[5]), (0.0, 0.0, 0.0));
        let mut d = [0.0; 9];
        metric_from_factor(3, &m, &mut d);
        for (x, y) in a.iter().zip(&d) {
            assert!((x - y).abs() < 1e-12);
        }
        assert!(cholesky_upper(2, &[1.0, 2.0, 2.0, 1.0]).is_none());
        assert_eq!(cholesky_upper(1, &[9.0]).unwrap(), vec![3.0]);
    }
}
