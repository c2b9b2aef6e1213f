//! Closing outlines across the ends left side by side: once the gap bridges are chosen, two free
//! ends that stop beside each other, pointing the same way (the foot of a leg, the end of a
//! finger or a tail whose pen lift falls at its tip), are joined where that closes an outline
//! that holds a body, and left apart where it would only seal two lines drawn side by side.
//! The global closure prior of issue 9 ("an outline of a solid closes"), on top of the stroke
//! crawl of [`super::strokes`] (Parakkat & Muthuganapathy 2016 decide closing by the chain alone).

use std::collections::{HashMap, HashSet};

use kurbo::{Point, Vec2};

use super::bridges::BridgeableEnd;
use super::strokes::{components, StrokeVertices};

/// DECISION: two free ends side by side are at most this far apart (centre to centre, in widths
/// of the page's typical stroke) to be joined across: a leg's or finger's two sides drawn 0.5–3
/// pen widths apart (issue 9's families), measured in the page's stroke width (which a scan's
/// faint edges make narrower than the pen) and with a foot cut at a slant. Measured on the
/// benchmark: the same-way ends left open in failing silhouettes lie 1.8–4.3 stroke widths
/// apart; 3.5 fixed two drawings of seed 1; 4.5, 5 and 6 one more of seed 3; none lost at any.
const SIDE_BY_SIDE_MAX_IN_PEN_WIDTHS: f64 = 4.5;

/// Two ends point the same way where the cosine of the angle between them is at least this
/// (45°).
const SAME_WAY_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// DECISION: a loop closed across ends side by side must hold a body: at least this many times
/// the reach of [`SIDE_BY_SIDE_MAX_IN_PEN_WIDTHS`] of its length must have no other part of the
/// loop (farther along it than twice that reach) within that reach. Two lines side by side
/// sealed at both ends have such a stretch only at each of their two round ends (about one reach
/// on each side of each end: four in all); an animal's body or a palm has hundreds of pixels.
const BODY_MIN_UNBACKED_IN_REACHES: f64 = 8.0;

/// Joins free ends of open chains that stop side by side (see the module documentation), adding
/// the joins to `edges`. `attachment` holds the ends that end on another stroke (they are not
/// free).
pub(super) fn close_across_side_by_side_ends(
    vertices: &StrokeVertices,
    ends: &[BridgeableEnd],
    attachment: &HashMap<u32, Point>,
    edges: &mut Vec<(u32, u32)>,
    stroke_width: f64,
) {
    let reach = SIDE_BY_SIDE_MAX_IN_PEN_WIDTHS * stroke_width;
    let positions = &vertices.positions;
    let free: HashMap<u32, Vec2> = ends
        .iter()
        .filter(|end| !end.attached && !attachment.contains_key(&end.vertex))
        .filter(|end| !vertices.dot_radius.contains_key(&end.vertex))
        .filter_map(|end| Some((end.vertex, end.outward?)))
        .collect();
    // The free ends of open chains, in vertex order (deterministic).
    let mut chain_ends: Vec<u32> = components(positions.len(), edges)
        .into_iter()
        .filter(|chain| !chain.closed && chain.vertices.len() >= 2)
        .flat_map(|chain| [chain.vertices[0], chain.vertices[chain.vertices.len() - 1]])
        .filter(|v| free.contains_key(v))
        .collect();
    if chain_ends.len() < 2 {
        return;
    }
    chain_ends.sort_by(|a, b| {
        positions[*a as usize]
            .x
            .total_cmp(&positions[*b as usize].x)
            .then(a.cmp(b))
    });
    let mut candidates: Vec<(f64, u32, u32)> = Vec::new();
    for (i, &u) in chain_ends.iter().enumerate() {
        let pu = positions[u as usize];
        for &v in &chain_ends[i + 1..] {
            let pv = positions[v as usize];
            if pv.x - pu.x > reach {
                break;
            }
            let distance = pu.distance(pv);
            if distance > reach || distance == 0.0 {
                continue;
            }
            let (ou, ov) = (free[&u], free[&v]);
            if ou.dot(ov) < SAME_WAY_COSINE {
                continue;
            }
            candidates.push((distance, u.min(v), u.max(v)));
        }
    }
    if candidates.is_empty() {
        return;
    }
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut used: HashSet<u32> = HashSet::new();
    let mut joins: Vec<(u32, u32)> = Vec::new();
    for (_, u, v) in candidates {
        if used.contains(&u) || used.contains(&v) {
            continue;
        }
        used.insert(u);
        used.insert(v);
        joins.push((u, v));
    }
    let base = edges.len();
    edges.extend(joins.iter().copied());
    // Keep the joins of the loops they closed round a body; take back every other.
    let join_set: HashSet<(u32, u32)> = joins.iter().flat_map(|&(u, v)| [(u, v), (v, u)]).collect();
    let mut kept: HashSet<(u32, u32)> = HashSet::new();
    for chain in components(positions.len(), edges) {
        if !chain.closed {
            continue;
        }
        let order: Vec<u32> = chain.vertices.iter().copied().collect();
        let n = order.len();
        let closing: Vec<(u32, u32)> = (0..n)
            .map(|k| (order[k], order[(k + 1) % n]))
            .filter(|edge| join_set.contains(edge))
            .collect();
        if closing.is_empty() {
            continue;
        }
        let points: Vec<Point> = order.iter().map(|&v| positions[v as usize]).collect();
        if holds_a_body(&densified(&points, 0.25 * reach), reach) {
            kept.extend(closing.iter().map(|&(u, v)| (u.min(v), u.max(v))));
        }
    }
    let added: Vec<(u32, u32)> = edges.drain(base..).collect();
    edges.extend(added.into_iter().filter(|edge| kept.contains(edge)));
}

/// Whether a closed loop of `points` holds a body, not two lines side by side: see
/// [`BODY_MIN_UNBACKED_IN_REACHES`].
fn holds_a_body(points: &[Point], reach: f64) -> bool {
    let n = points.len();
    let mut along = Vec::with_capacity(n);
    let mut total = 0.0;
    for k in 0..n {
        along.push(total);
        total += points[k].distance(points[(k + 1) % n]);
    }
    let cell = |p: Point| ((p.x / reach).floor() as i64, (p.y / reach).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (k, &p) in points.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(k);
    }
    let far_along = 2.0 * reach;
    let mut unbacked = 0.0;
    for k in 0..n {
        let p = points[k];
        let (cx, cy) = cell(p);
        let backed = (cx - 1..=cx + 1).any(|x| {
            (cy - 1..=cy + 1).any(|y| {
                grid.get(&(x, y)).is_some_and(|near| {
                    near.iter().any(|&j| {
                        let apart = (along[j] - along[k]).abs();
                        apart.min(total - apart) > far_along && points[j].distance(p) <= reach
                    })
                })
            })
        });
        if !backed {
            unbacked += points[(k + 1) % n].distance(p);
        }
    }
    unbacked >= BODY_MIN_UNBACKED_IN_REACHES * reach
}

/// The closed loop of `points` with points added along every edge longer than `step` (a bridge
/// across a gap has no samples of its own), so that no stretch is missed between two samples.
fn densified(points: &[Point], step: f64) -> Vec<Point> {
    let n = points.len();
    let mut dense = Vec::with_capacity(n);
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        let pieces = (a.distance(b) / step).ceil().max(1.0) as usize;
        dense.extend((0..pieces).map(|i| a.lerp(b, i as f64 / pieces as f64)));
    }
    dense
}

#[cfg(test)]
mod tests {
    use kurbo::Point;

    use crate::crawl::strokes::{connect, Method};
    use crate::geometry::Polyline;
    use crate::strokes::{Stroke, StrokeEnd};

    /// One free-ended stroke through `corners`, sampled about every 3 px.
    fn stroke_through(corners: &[(f64, f64)]) -> Stroke {
        let mut points = vec![Point::from(corners[0])];
        for pair in corners.windows(2) {
            let (a, b) = (Point::from(pair[0]), Point::from(pair[1]));
            let steps = (a.distance(b) / 3.0).ceil() as usize;
            points.extend((1..=steps).map(|k| a.lerp(b, k as f64 / steps as f64)));
        }
        Stroke {
            line: Polyline::new(points, false),
            ends: [StrokeEnd::Free, StrokeEnd::Free],
            wide: false,
        }
    }

    #[test]
    fn a_leg_whose_foot_falls_in_a_pen_lift_closes_the_body() {
        // A square body with one leg 8 px wide (a 3 px pen) below it, drawn in one stroke that
        // starts down the leg's right side and ends down its left side: the foot is a pen lift,
        // the two ends stop side by side. The outline of the body closes across it.
        let strokes = [stroke_through(&[
            (108.0, 160.0),
            (108.0, 100.0),
            (160.0, 100.0),
            (160.0, 0.0),
            (40.0, 0.0),
            (40.0, 100.0),
            (100.0, 100.0),
            (100.0, 160.0),
        ])];
        let curves = connect(&strokes, Method::Strokes, 3.0, 3.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        assert!(curves[0].closed, "{curves:?}");
    }

    #[test]
    fn two_lines_side_by_side_stay_open_at_their_ends() {
        // The same ends, but the stroke only runs up 160 px and back down 8 px beside itself:
        // sealed at the foot it would hold no body, only two lines side by side.
        let strokes = [stroke_through(&[
            (108.0, 160.0),
            (108.0, 0.0),
            (100.0, 0.0),
            (100.0, 160.0),
        ])];
        let curves = connect(&strokes, Method::Strokes, 3.0, 3.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        assert!(!curves[0].closed, "{curves:?}");
    }

    #[test]
    fn two_parallel_lines_are_not_sealed_into_a_loop() {
        // Two straight lines 6 px apart: their two pairs of ends side by side would make a loop
        // of two joins round nothing but the paper between the lines.
        let strokes = [
            stroke_through(&[(0.0, 0.0), (150.0, 0.0)]),
            stroke_through(&[(0.0, 6.0), (150.0, 6.0)]),
        ];
        let curves = connect(&strokes, Method::Strokes, 3.0, 3.0);
        assert_eq!(curves.len(), 2, "{curves:?}");
        assert!(curves.iter().all(|curve| !curve.closed), "{curves:?}");
    }
}
