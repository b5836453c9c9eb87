//! Clipping polylines to a rectangle before they reach plotters, which would otherwise draw
//! points outside the axis range clamped onto the edge.

/// An axis-aligned rectangle in data coordinates, `x0 < x1`, `y0 < y1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rect {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
}

impl Rect {
    pub fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }
}

/// Liang–Barsky: the part of segment a→b inside `r`, if any.
fn clip_segment(a: (f64, f64), b: (f64, f64), r: &Rect) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let mut t0 = 0.0f64;
    let mut t1 = 1.0f64;
    for (p, q) in [
        (-dx, a.0 - r.x0),
        (dx, r.x1 - a.0),
        (-dy, a.1 - r.y0),
        (dy, r.y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                if t > t1 {
                    return None;
                }
                t0 = t0.max(t);
            } else {
                if t < t0 {
                    return None;
                }
                t1 = t1.min(t);
            }
        }
    }
    Some((
        (a.0 + t0 * dx, a.1 + t0 * dy),
        (a.0 + t1 * dx, a.1 + t1 * dy),
    ))
}

/// The pieces of a polyline inside `r`. Non-finite points break the line.
pub(crate) fn clip_polyline(points: &[(f64, f64)], r: &Rect) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    if points.len() == 1 && finite(&points[0]) && r.contains(points[0]) {
        return vec![vec![points[0]]];
    }
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        if !(finite(&a) && finite(&b)) {
            if current.len() > 1 {
                runs.push(std::mem::take(&mut current));
            }
            current.clear();
            continue;
        }
        match clip_segment(a, b, r) {
            Some((p, q)) => {
                if current.last() != Some(&p) {
                    if current.len() > 1 {
                        runs.push(std::mem::take(&mut current));
                    }
                    current.clear();
                    current.push(p);
                }
                current.push(q);
                if q != b {
                    runs.push(std::mem::take(&mut current));
                }
            }
            None => {
                if current.len() > 1 {
                    runs.push(std::mem::take(&mut current));
                }
                current.clear();
            }
        }
    }
    if current.len() > 1 {
        runs.push(current);
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: Rect = Rect {
        x0: 0.0,
        x1: 10.0,
        y0: -1.0,
        y1: 1.0,
    };

    #[test]
    fn inside_line_is_kept_whole() {
        let p = vec![(0.0, 0.0), (1.0, 0.5), (2.0, -0.5)];
        assert_eq!(clip_polyline(&p, &R), vec![p]);
    }

    #[test]
    fn leaving_and_reentering_splits_at_the_edge() {
        let p = vec![(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)];
        let runs = clip_polyline(&p, &R);
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0], vec![(0.0, 0.0), (0.5, 1.0)]);
        assert_eq!(runs[1], vec![(1.5, 1.0), (2.0, 0.0)]);
        for run in runs {
            assert!(run.iter().all(|&q| R.contains(q)));
        }
    }

    #[test]
    fn outside_and_nan_are_dropped() {
        let p = vec![
            (0.0, 5.0),
            (1.0, 6.0),
            (f64::NAN, 0.0),
            (3.0, 0.0),
            (4.0, 0.0),
        ];
        assert_eq!(clip_polyline(&p, &R), vec![vec![(3.0, 0.0), (4.0, 0.0)]]);
        assert!(clip_polyline(&[], &R).is_empty());
    }
}
