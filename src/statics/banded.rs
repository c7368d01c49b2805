//! Symmetric banded matrices and their Cholesky factorization: the linear algebra of one
//! Newton step. A cable node interacts with nodes at most two places away (a bending joint
//! couples three consecutive nodes), so with three coordinates per node the Hessian has a
//! half-bandwidth of 8 and a factorization costs `O(n · 8²)` instead of `O(n³)`.

use nalgebra::Matrix3;

/// Half-bandwidth in scalars: node blocks `(p, q)` with `|p − q| ≤ 2`, three coordinates each.
pub(crate) const HALF_BANDWIDTH: usize = 8;

/// Nodes coupled by one Hessian block at most this many places apart.
pub(crate) const NODE_REACH: usize = 2;

/// Lower band of a symmetric `n × n` matrix: `rows[i][k] = A(i, i − k)`.
#[derive(Debug, Clone)]
pub(crate) struct SymmetricBand {
    rows: Vec<[f64; HALF_BANDWIDTH + 1]>,
}

/// The factorization met a pivot that is not positive: the matrix is not positive definite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotPositiveDefinite;

impl SymmetricBand {
    /// The zero matrix of order `n`.
    pub(crate) fn zeros(n: usize) -> Self {
        Self {
            rows: vec![[0.0; HALF_BANDWIDTH + 1]; n],
        }
    }

    /// Order of the matrix.
    pub(crate) fn order(&self) -> usize {
        self.rows.len()
    }

    /// Sets every entry to zero, keeping the order.
    pub(crate) fn clear(&mut self) {
        self.rows.fill([0.0; HALF_BANDWIDTH + 1]);
    }

    /// Adds one node block of a Hessian given as the sum of blocks for ordered node pairs:
    /// an off-diagonal block contributes half to `A(p, q)` and half, transposed, to
    /// `A(q, p)`, so it must be added for `(p, q)` and for `(q, p)`; a diagonal block
    /// contributes its symmetric part. Nodes must be at most [`NODE_REACH`] apart.
    pub(crate) fn add_node_block(&mut self, p: usize, q: usize, block: &Matrix3<f64>) {
        debug_assert!(p.abs_diff(q) <= NODE_REACH);
        if p == q {
            for a in 0..3 {
                for b in 0..=a {
                    let i = 3 * p + a;
                    self.rows[i][a - b] += 0.5 * (block[(a, b)] + block[(b, a)]);
                }
            }
            return;
        }
        let (row_node, column_node, lower) = if p > q {
            (p, q, *block)
        } else {
            (q, p, block.transpose())
        };
        for a in 0..3 {
            for b in 0..3 {
                let (i, j) = (3 * row_node + a, 3 * column_node + b);
                self.rows[i][i - j] += 0.5 * lower[(a, b)];
            }
        }
    }

    /// Adds `shift` to every diagonal entry.
    pub(crate) fn add_to_diagonal(&mut self, shift: f64) {
        for row in &mut self.rows {
            row[0] += shift;
        }
    }

    /// Largest absolute diagonal entry (0 for an empty matrix).
    pub(crate) fn max_diagonal(&self) -> f64 {
        self.rows.iter().map(|r| r[0].abs()).fold(0.0, f64::max)
    }

    /// `y = A x`.
    pub(crate) fn multiply(&self, x: &[f64]) -> Vec<f64> {
        let n = self.order();
        let mut y = vec![0.0; n];
        for i in 0..n {
            for k in 0..=HALF_BANDWIDTH.min(i) {
                let j = i - k;
                y[i] += self.rows[i][k] * x[j];
                if k > 0 {
                    y[j] += self.rows[i][k] * x[i];
                }
            }
        }
        y
    }

    /// Cholesky factor `L` (`A = L Lᵀ`), stored in the same band layout.
    pub(crate) fn cholesky(&self) -> Result<BandCholesky, NotPositiveDefinite> {
        let n = self.order();
        let mut factor = self.rows.clone();
        for i in 0..n {
            let first = i.saturating_sub(HALF_BANDWIDTH);
            for j in first..=i {
                let mut sum = factor[i][i - j];
                for k in first.max(j.saturating_sub(HALF_BANDWIDTH))..j {
                    sum -= factor[i][i - k] * factor[j][j - k];
                }
                if j == i {
                    if sum.is_nan() || sum <= 0.0 {
                        return Err(NotPositiveDefinite);
                    }
                    factor[i][0] = sum.sqrt();
                } else {
                    factor[i][i - j] = sum / factor[j][0];
                }
            }
        }
        Ok(BandCholesky { factor })
    }
}

/// The Cholesky factor of a [`SymmetricBand`].
#[derive(Debug, Clone)]
pub(crate) struct BandCholesky {
    factor: Vec<[f64; HALF_BANDWIDTH + 1]>,
}

impl BandCholesky {
    /// Solves `A x = b` in place (`b` becomes `x`).
    pub(crate) fn solve_in_place(&self, b: &mut [f64]) {
        let n = self.factor.len();
        for i in 0..n {
            let mut sum = b[i];
            for k in 1..=HALF_BANDWIDTH.min(i) {
                sum -= self.factor[i][k] * b[i - k];
            }
            b[i] = sum / self.factor[i][0];
        }
        for i in (0..n).rev() {
            let mut sum = b[i];
            for k in 1..=HALF_BANDWIDTH.min(n - 1 - i) {
                sum -= self.factor[i + k][k] * b[i + k];
            }
            b[i] = sum / self.factor[i][0];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// A symmetric positive definite banded matrix built from random-looking node blocks.
    fn example(nodes: usize) -> (SymmetricBand, DMatrix<f64>) {
        let n = 3 * nodes;
        let mut band = SymmetricBand::zeros(n);
        let mut dense = DMatrix::zeros(n, n);
        let value = |p: usize, q: usize, a: usize, b: usize| {
            (((7 * p + 3 * q + 5 * a + 11 * b) % 17) as f64 - 8.0) / 10.0
        };
        for p in 0..nodes {
            for q in p.saturating_sub(NODE_REACH)..=(p + NODE_REACH).min(nodes - 1) {
                let block = Matrix3::from_fn(|a, b| {
                    // A symmetric pair of blocks: (p, q) and (q, p) transposed.
                    let (lo, hi, x, y) = if p <= q { (p, q, a, b) } else { (q, p, b, a) };
                    value(lo, hi, x, y) + if p == q && a == b { 12.0 } else { 0.0 }
                });
                let block = if p == q {
                    0.5 * (block + block.transpose())
                } else {
                    block
                };
                band.add_node_block(p, q, &block);
                for a in 0..3 {
                    for b in 0..3 {
                        dense[(3 * p + a, 3 * q + b)] += 0.5 * block[(a, b)];
                        dense[(3 * q + b, 3 * p + a)] += 0.5 * block[(a, b)];
                    }
                }
            }
        }
        (band, dense)
    }

    #[test]
    fn band_product_matches_the_dense_matrix() {
        let (band, dense) = example(7);
        let x: Vec<f64> = (0..21).map(|i| (i as f64 * 0.37).sin()).collect();
        let expected = &dense * DVector::from_column_slice(&x);
        for (y, e) in band.multiply(&x).iter().zip(expected.iter()) {
            assert!((y - e).abs() < 1e-12);
        }
    }

    #[test]
    fn cholesky_solves_against_nalgebra_lu() {
        let (band, dense) = example(9);
        let b: Vec<f64> = (0..27).map(|i| (i as f64 * 1.3).cos()).collect();
        let mut x = b.clone();
        band.cholesky().unwrap().solve_in_place(&mut x);
        let reference = dense.lu().solve(&DVector::from_column_slice(&b)).unwrap();
        for (x, r) in x.iter().zip(reference.iter()) {
            assert!((x - r).abs() < 1e-12, "{x} vs {r}");
        }
    }

    #[test]
    fn indefinite_matrices_are_refused() {
        let mut band = SymmetricBand::zeros(6);
        band.add_to_diagonal(1.0);
        band.add_node_block(1, 1, &Matrix3::from_diagonal_element(-3.0));
        assert_eq!(band.cholesky().err(), Some(NotPositiveDefinite));
    }
}
