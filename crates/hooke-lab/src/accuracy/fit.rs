//! The observed order of convergence: a least-squares line through
//! `(ln h, ln e)`.

/// The slope `p` of the least-squares line `ln e = p ln h + b` through the
/// points `(h, e)`,
///
/// ```text
/// p = Σ (ln hⱼ − m_h)(ln eⱼ − m_e) / Σ (ln hⱼ − m_h)²,
/// ```
///
/// with `m_h`, `m_e` the means of `ln h` and `ln e`; `None` for fewer than
/// three points or when every `h` is the same.
pub(crate) fn slope(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let logs: Vec<(f64, f64)> = points.iter().map(|&(h, e)| (h.ln(), e.ln())).collect();
    let mean_h = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let mean_e = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for &(x, y) in &logs {
        sxy += (x - mean_h) * (y - mean_e);
        sxx += (x - mean_h) * (x - mean_h);
    }
    let p = sxy / sxx;
    p.is_finite().then_some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_the_exponent_of_a_power_law() {
        let points: Vec<(f64, f64)> = [1e-3, 4e-3, 2e-2, 0.1]
            .iter()
            .map(|&h: &f64| (h, 3.0 * h.powf(2.5)))
            .collect();
        let p = slope(&points).unwrap();
        assert!((p - 2.5).abs() < 1e-12, "{p}");
    }

    #[test]
    fn needs_three_distinct_steps() {
        assert_eq!(slope(&[(1.0, 1.0), (2.0, 4.0)]), None);
        assert_eq!(slope(&[(1.0, 1.0), (1.0, 2.0), (1.0, 3.0)]), None);
    }
}
