//! Logarithmic axes: the map from a value to a pixel and the tick marks.

/// A logarithmic axis: the interval `[lo, hi]` of decimal logarithms drawn
/// from pixel `start` to pixel `end` (`end < start` for an upward y axis).
#[derive(Clone, Copy, Debug)]
pub(super) struct LogAxis {
    lo: f64,
    hi: f64,
    start: f32,
    end: f32,
}

/// A tick mark: its pixel along the axis and, for labelled ticks, the label.
pub(super) struct Tick {
    /// Pixel coordinate along the axis.
    pub(super) pixel: f32,
    /// The value in powers of ten (`1e-3`, `2e-4`), or `None` for an unlabelled tick.
    pub(super) label: Option<String>,
}

/// Slack allowed when deciding whether a power of ten lies inside the axis.
const EPS: f64 = 1e-9;

impl LogAxis {
    /// The axis over the logarithms `[lo, hi]`; a degenerate or reversed
    /// interval is widened to one decade about its middle.
    pub(super) fn new(lo: f64, hi: f64, start: f32, end: f32) -> Self {
        let (lo, hi) = if hi - lo > EPS && lo.is_finite() && hi.is_finite() {
            (lo, hi)
        } else if lo.is_finite() {
            (lo - 0.5, lo + 0.5)
        } else {
            (-0.5, 0.5)
        };
        Self { lo, hi, start, end }
    }

    /// The axis that holds the logarithms in `logs` with `pad` (a fraction of
    /// the span) to spare on each side; with no logarithm, `10^-1 ..= 10^1`.
    pub(super) fn fitting(
        logs: impl IntoIterator<Item = f64>,
        pad: f64,
        start: f32,
        end: f32,
    ) -> Self {
        let (lo, hi) = logs
            .into_iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), l| {
                (lo.min(l), hi.max(l))
            });
        if !(lo.is_finite() && hi.is_finite()) {
            return Self::new(-1.0, 1.0, start, end);
        }
        let span = if hi - lo > EPS { hi - lo } else { 1.0 };
        Self::new(lo - pad * span, hi + pad * span, start, end)
    }

    /// Pixel coordinate of the positive `value`.
    pub(super) fn pixel(&self, value: f64) -> f32 {
        self.pixel_of_log(value.log10())
    }

    /// Pixel coordinate of the decimal logarithm `log`.
    pub(super) fn pixel_of_log(&self, log: f64) -> f32 {
        let t = (log - self.lo) / (self.hi - self.lo);
        self.start + (t as f32) * (self.end - self.start)
    }

    /// Lowest logarithm on the axis.
    pub(super) fn lo(&self) -> f64 {
        self.lo
    }

    /// Highest logarithm on the axis.
    pub(super) fn hi(&self) -> f64 {
        self.hi
    }

    /// Ticks at the powers of ten inside the axis, labelled as often as
    /// labels `label_extent(label)` pixels long allow without overlapping.
    /// An axis spanning less than two powers of ten gets ticks at 1, 2 and 5
    /// times powers of ten, or failing that at its two ends.
    pub(super) fn ticks(&self, label_extent: impl Fn(&str) -> f32) -> Vec<Tick> {
        let first = (self.lo - EPS).ceil() as i64;
        let last = (self.hi + EPS).floor() as i64;
        let decades: Vec<(f64, String)> = (first..=last)
            .map(|k| (k as f64, format!("1e{k}")))
            .collect();
        let candidates = if decades.len() >= 2 {
            decades
        } else {
            let mut multiples = Vec::new();
            for k in (first - 1)..=last {
                for m in [1u8, 2, 5] {
                    let log = k as f64 + f64::from(m).log10();
                    if log >= self.lo - EPS && log <= self.hi + EPS {
                        multiples.push((log, format!("{m}e{k}")));
                    }
                }
            }
            if multiples.len() >= 2 {
                multiples
            } else {
                [self.lo, self.hi]
                    .into_iter()
                    .map(|log| (log, format!("{:.1e}", 10f64.powf(log))))
                    .collect()
            }
        };
        let longest = candidates
            .iter()
            .map(|(_, label)| label_extent(label))
            .fold(0.0f32, f32::max);
        let spacing = if candidates.len() >= 2 {
            (self.pixel_of_log(candidates[1].0) - self.pixel_of_log(candidates[0].0)).abs()
        } else {
            f32::INFINITY
        };
        let stride = [1usize, 2, 3, 5, 10, 20, 50, 100]
            .into_iter()
            .find(|&s| s as f32 * spacing >= longest)
            .unwrap_or(candidates.len().max(1));
        candidates
            .into_iter()
            .enumerate()
            .map(|(i, (log, label))| Tick {
                pixel: self.pixel_of_log(log),
                label: (i % stride == 0).then_some(label),
            })
            .collect()
    }
}
