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

/// Sine-transform power of an n × n field f\[i\]\[j\] (row-major, i along x), the free particles of a
/// box with fixed walls: coefficient (m, l) of sin(mπ(i+1)/(n+1)) sin(lπ(j+1)/(n+1)), computed
/// with rustfft on the odd extension of length 2(n+1) along each axis. Returns the power
/// P\[m−1\]\[l−1\], m, l = 1..n.
pub fn sine_power(f: &[f64], n: usize) -> Vec<Vec<f64>> {
    use rustfft::{FftPlanner, num_complex::Complex};
    let len = 2 * (n + 1);
    let mut planner = FftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(len);
    // transform along j for every row i: coefficients S1[i][l]
    let transform = |row: &[f64]| -> Vec<f64> {
        let mut buf = vec![Complex::new(0.0, 0.0); len];
        for (k, &v) in row.iter().enumerate() {
            buf[k + 1] = Complex::new(v, 0.0);
            buf[len - 1 - k] = Complex::new(-v, 0.0);
        }
        fft.process(&mut buf);
        // FFT of the odd extension: X_l = −2i Σ f_k sin(π l k/(n+1))
        (1..=n).map(|l| -buf[l].im / 2.0).collect()
    };
    let rows: Vec<Vec<f64>> = (0..n).map(|i| transform(&f[i * n..(i + 1) * n])).collect();
    let mut p = vec![vec![0.0; n]; n];
    for l in 0..n {
        let col: Vec<f64> = rows.iter().map(|r| r[l]).collect();
        let s = transform(&col);
        for m in 0..n {
            p[m][l] = s[m] * s[m];
        }
    }
    p
}

/// The dominant standing mode (m, l) of [`sine_power`] summed over several fields (e.g. v_x and
/// v_y), and its share of the total power.
pub fn dominant_mode(fields: &[Vec<f64>], n: usize) -> ((usize, usize), f64) {
    let mut total = vec![vec![0.0; n]; n];
    for f in fields {
        let p = sine_power(f, n);
        for (t, r) in total.iter_mut().zip(&p) {
            for (a, b) in t.iter_mut().zip(r) {
                *a += b;
            }
        }
    }
    let mut best = ((1, 1), 0.0);
    let mut sum = 0.0;
    for (m, r) in total.iter().enumerate() {
        for (l, &v) in r.iter().enumerate() {
            sum += v;
            if v > best.1 {
                best = ((m + 1, l + 1), v);
            }
        }
    }
    (best.0, if sum > 0.0 { best.1 / sum } else { 0.0 })
}

#[cfg(test)]
mod spectrum_tests {
    use super::*;

    /// A pure standing mode is found exactly, with (nearly) all the power.
    #[test]
    fn sine_transform_finds_a_standing_mode() {
        let n = 15;
        let (m, l) = (4usize, 13usize);
        let pi = std::f64::consts::PI;
        let f: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                (m as f64 * pi * (i + 1) as f64 / (n + 1) as f64).sin()
                    * (l as f64 * pi * (j + 1) as f64 / (n + 1) as f64).sin()
            })
            .collect();
        let (ml, share) = dominant_mode(&[f], n);
        assert_eq!(ml, (m, l));
        assert!(share > 1.0 - 1e-12);
    }
}
