//! Compensated summation for the per-pixel means.

/// Kahan–Babuška–Neumaier compensated sum.
///
/// A plain `f64` running sum over a 1920×1080 image of similar-sized terms
/// drifts by ~1e-11 relative (the error grows with the number of terms); the
/// compensation keeps the result within a couple of ulps independently of the
/// image size, for four extra flops per term.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Sum {
    sum: f64,
    compensation: f64,
}

impl Sum {
    #[inline]
    pub(super) fn add(&mut self, x: f64) {
        let t = self.sum + x;
        // Recover the low-order bits lost by whichever operand is smaller.
        if self.sum.abs() >= x.abs() {
            self.compensation += (self.sum - t) + x;
        } else {
            self.compensation += (x - t) + self.sum;
        }
        self.sum = t;
    }

    #[inline]
    pub(super) fn value(&self) -> f64 {
        self.sum + self.compensation
    }
}

impl FromIterator<f64> for Sum {
    fn from_iter<I: IntoIterator<Item = f64>>(iter: I) -> Self {
        let mut s = Sum::default();
        for x in iter {
            s.add(x);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_what_a_naive_sum_loses() {
        // 1 + 1e-16 + … (1e6 times): the naive sum never leaves 1.0; the exact
        // answer is 1 + 1e-10.
        let terms = std::iter::once(1.0).chain(std::iter::repeat_n(1e-16, 1_000_000));
        let naive: f64 = terms.clone().sum();
        assert_eq!(naive, 1.0);
        let s: Sum = terms.collect();
        assert!((s.value() - (1.0 + 1e-10)).abs() < 1e-15);
        // Catastrophic cancellation case from Neumaier's paper: 1, 1e100, 1, −1e100.
        let s: Sum = [1.0, 1e100, 1.0, -1e100].into_iter().collect();
        assert_eq!(s.value(), 2.0);
    }
}
