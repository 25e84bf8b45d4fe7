//! Which measured points are worth having: the Pareto front of time against error, and which
//! points dominate a given one. Lower is better on both axes.

/// One generator measured on one scene: its time and its error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub ns_per_vertex: f64,
    pub mean_error_deg: f64,
}

impl Point {
    /// `self` dominates `other` when it is no slower and no less accurate, and strictly better on
    /// one of the two: faster and at least as accurate, or exactly as fast and more accurate.
    /// A point with a NaN coordinate neither dominates nor is dominated.
    pub fn dominates(&self, other: &Point) -> bool {
        let (t, e) = (self.ns_per_vertex, self.mean_error_deg);
        let (other_t, other_e) = (other.ns_per_vertex, other.mean_error_deg);
        (t < other_t && e <= other_e) || (t == other_t && e < other_e)
    }
}

/// Whether each point is on the Pareto front: no other point dominates it.
pub fn front(points: &[Point]) -> Vec<bool> {
    points.iter().map(|p| !points.iter().any(|q| q.dominates(p))).collect()
}

/// The indices of the points that dominate `points[of]`, in their order.
pub fn dominators(points: &[Point], of: usize) -> Vec<usize> {
    (0..points.len())
        .filter(|&k| points[k].dominates(&points[of]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(ns_per_vertex: f64, mean_error_deg: f64) -> Point {
        Point {
            ns_per_vertex,
            mean_error_deg,
        }
    }

    #[test]
    fn dominance_needs_one_strict_improvement() {
        let p = point(10.0, 1.0);
        assert!(point(9.0, 1.0).dominates(&p), "faster, as accurate");
        assert!(point(9.0, 0.5).dominates(&p), "faster, more accurate");
        assert!(point(10.0, 0.5).dominates(&p), "as fast, more accurate");
        assert!(
            !point(10.0, 1.0).dominates(&p),
            "equal points do not dominate each other"
        );
        assert!(!point(9.0, 1.5).dominates(&p), "faster but less accurate");
        assert!(!point(11.0, 0.5).dominates(&p), "more accurate but slower");
        assert!(!point(f64::NAN, 0.5).dominates(&p));
        assert!(!point(9.0, 0.5).dominates(&point(10.0, f64::NAN)));
    }

    #[test]
    fn front_and_dominators_of_hand_made_points() {
        let points = [
            point(1.0, 8.0),  // 0: fastest: on the front
            point(2.0, 4.0),  // 1: on the front
            point(3.0, 4.0),  // 2: as accurate as 1, slower: dominated by 1
            point(4.0, 1.0),  // 3: most accurate: on the front
            point(5.0, 9.0),  // 4: dominated by all but 7
            point(4.0, 1.0),  // 5: equal to 3: neither dominates the other, both on the front
            point(2.0, 5.0),  // 6: as fast as 1, less accurate: dominated by 1
            point(0.5, 20.0), // 7: fastest of all, least accurate: on the front
        ];
        assert_eq!(front(&points), [true, true, false, true, false, true, false, true]);
        assert_eq!(dominators(&points, 4), [0, 1, 2, 3, 5, 6]);
        assert_eq!(dominators(&points, 2), [1]);
        assert_eq!(dominators(&points, 6), [1]);
        assert!(dominators(&points, 3).is_empty());
        assert!(dominators(&points, 7).is_empty());
    }
}
