//! Diagnostics of time histories: exponential growth fits.

use serde::Serialize;

/// An exponential fit ln y = a + γ t over a window.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct GrowthFit {
    /// Fitted rate γ (1/time).
    pub rate: f64,
    /// First and last time of the window.
    pub window: (f64, f64),
    /// Number of samples used.
    pub samples: usize,
    /// Coefficient of determination of the linear fit of ln y.
    pub r2: f64,
}

/// Least-squares fit of ln y against t over the samples with lo < y < hi, restricted to the
/// first contiguous stretch that enters the window after y first exceeds `lo` (later re-entries,
/// e.g. after saturation, are ignored). None if fewer than 3 samples qualify.
pub fn growth_fit(t: &[f64], y: &[f64], lo: f64, hi: f64) -> Option<GrowthFit> {
    let start = y.iter().position(|&v| v > lo)?;
    let mut idx = Vec::new();
    for (i, &yi) in y.iter().enumerate().skip(start) {
        // stop at the top of the window, or at a non-positive / NaN sample
        if yi >= hi || yi.is_nan() || yi <= 0.0 {
            break;
        }
        if yi > lo {
            idx.push(i);
        }
    }
    if idx.len() < 3 {
        return None;
    }
    let n = idx.len() as f64;
    let (mut st, mut sy, mut stt, mut sty) = (0.0, 0.0, 0.0, 0.0);
    for &i in &idx {
        let ly = y[i].ln();
        st += t[i];
        sy += ly;
        stt += t[i] * t[i];
        sty += t[i] * ly;
    }
    let den = n * stt - st * st;
    if den <= 0.0 {
        return None;
    }
    let rate = (n * sty - st * sy) / den;
    let a = (sy - rate * st) / n;
    let mean = sy / n;
    let (mut ss_res, mut ss_tot) = (0.0, 0.0);
    for &i in &idx {
        let ly = y[i].ln();
        ss_res += (ly - a - rate * t[i]).powi(2);
        ss_tot += (ly - mean).powi(2);
    }
    let r2 = if ss_tot > 0.0 {
        1.0 - ss_res / ss_tot
    } else {
        1.0
    };
    Some(GrowthFit {
        rate,
        window: (t[idx[0]], t[idx[idx.len() - 1]]),
        samples: idx.len(),
        r2,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fits_a_pure_exponential_exactly() {
        let t: Vec<f64> = (0..200).map(|i| i as f64 * 0.1).collect();
        let y: Vec<f64> = t.iter().map(|&s| 1e-10 * (0.9 * s).exp()).collect();
        let f = growth_fit(&t, &y, 1e-8, 1e-4).unwrap();
        assert!((f.rate - 0.9).abs() < 1e-10);
        assert!(f.r2 > 1.0 - 1e-12);
        assert!(f.window.0 > 5.0 && f.window.1 < 16.0);
    }

    #[test]
    fn no_fit_when_nothing_grows() {
        let t: Vec<f64> = (0..50).map(|i| i as f64).collect();
        let y = vec![1e-10; 50];
        assert!(growth_fit(&t, &y, 1e-8, 1e-4).is_none());
    }
}
