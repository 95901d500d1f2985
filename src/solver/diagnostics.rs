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

/// Sine-transform power of an n^dim field (row-major: first index slowest, along x), the free
/// particles of a box with fixed walls: coefficient (m_1, …, m_dim) of
/// Π_a sin(m_a π(i_a+1)/(n+1)), computed with rustfft on the odd extension of length 2(n+1)
/// along each axis, the last axis first. Returns the power, flat and row-major like the field,
/// at index (m_1 − 1, …, m_dim − 1), m_a = 1..n.
pub fn sine_power_nd(f: &[f64], n: usize, dim: usize) -> Vec<f64> {
    use rustfft::{FftPlanner, num_complex::Complex};
    let len = 2 * (n + 1);
    let mut planner = FftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(len);
    let mut buf = vec![Complex::new(0.0, 0.0); len];
    let mut c = f.to_vec();
    for axis in (0..dim).rev() {
        // elements along `axis` are `stride` apart; lines start at every index whose
        // coordinate along `axis` is 0
        let stride = n.pow((dim - 1 - axis) as u32);
        for start in (0..c.len()).filter(|&i| (i / stride).is_multiple_of(n)) {
            buf.fill(Complex::new(0.0, 0.0));
            for k in 0..n {
                let v = c[start + k * stride];
                buf[k + 1] = Complex::new(v, 0.0);
                buf[len - 1 - k] = Complex::new(-v, 0.0);
            }
            fft.process(&mut buf);
            // FFT of the odd extension: X_l = −2i Σ f_k sin(π l k/(n+1))
            for l in 1..=n {
                c[start + (l - 1) * stride] = -buf[l].im / 2.0;
            }
        }
    }
    c.iter_mut().for_each(|v| *v *= *v);
    c
}

/// [`sine_power_nd`] of an n × n field as rows: P\[m−1\]\[l−1\], m, l = 1..n.
pub fn sine_power(f: &[f64], n: usize) -> Vec<Vec<f64>> {
    sine_power_nd(f, n, 2)
        .chunks(n)
        .map(<[f64]>::to_vec)
        .collect()
}

/// The dominant standing mode (m_1, …, m_dim) of [`sine_power_nd`] summed over several fields
/// (e.g. the velocity components), and its share of the total power.
pub fn dominant_mode_nd(fields: &[Vec<f64>], n: usize, dim: usize) -> (Vec<usize>, f64) {
    let mut total = vec![0.0; n.pow(dim as u32)];
    for f in fields {
        for (a, b) in total.iter_mut().zip(sine_power_nd(f, n, dim)) {
            *a += b;
        }
    }
    let mut best = (0, 0.0);
    let mut sum = 0.0;
    for (i, &v) in total.iter().enumerate() {
        sum += v;
        if v > best.1 {
            best = (i, v);
        }
    }
    let mut modes = vec![1; dim];
    let mut rest = best.0;
    for m in modes.iter_mut().rev() {
        *m = rest % n + 1;
        rest /= n;
    }
    (modes, if sum > 0.0 { best.1 / sum } else { 0.0 })
}

/// [`dominant_mode_nd`] of n × n fields: ((m, l), share).
pub fn dominant_mode(fields: &[Vec<f64>], n: usize) -> ((usize, usize), f64) {
    let (m, share) = dominant_mode_nd(fields, n, 2);
    ((m[0], m[1]), share)
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

    /// The same in 3D, with three fields (one holding the mode, two empty).
    #[test]
    fn sine_transform_finds_a_standing_mode_in_3d() {
        let n = 7;
        let m = [2usize, 7, 5];
        let pi = std::f64::consts::PI;
        let s = |mode: usize, i: usize| (mode as f64 * pi * (i + 1) as f64 / (n + 1) as f64).sin();
        let f: Vec<f64> = (0..n * n * n)
            .map(|k| s(m[0], k / (n * n)) * s(m[1], (k / n) % n) * s(m[2], k % n))
            .collect();
        let zero = vec![0.0; f.len()];
        let (ml, share) = dominant_mode_nd(&[zero.clone(), f, zero], n, 3);
        assert_eq!(ml, m.to_vec());
        assert!(share > 1.0 - 1e-12);
    }
}
