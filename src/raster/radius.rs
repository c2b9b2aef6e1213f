//! The ink's radius at a point: the distance from a pixel centre to the nearest paper, found by a
//! search of the pixels around it (a local, exact Euclidean distance transform, done only where it
//! is asked for, so it costs nothing for the rest of the page).

use kurbo::Point;

use super::bitmap::Bitmap;

/// The radius of the ink around `point` (sub-pixel): the distance to the nearest paper pixel's
/// centre less half a pixel (the ink's edge lies between the two), at most `limit` (the search
/// stops there). Outside the image counts as paper; a point on a paper pixel has radius 0.
pub fn ink_radius(mask: &Bitmap, point: Point, limit: f64) -> f64 {
    let (cx, cy) = (point.x.floor() as isize, point.y.floor() as isize);
    if !mask.get_signed(cx, cy) {
        return 0.0;
    }
    let reach = limit.max(0.0).ceil() as isize + 2;
    let mut nearest_squared = f64::INFINITY;
    // Square rings of growing size around the point's pixel: a ring `r` away holds no pixel
    // centre nearer than r − 1 to the point, so once that is beyond the nearest paper, stop.
    for ring in 1..=reach {
        if ((ring - 1) as f64).powi(2) > nearest_squared {
            break;
        }
        for (dx, dy) in ring_offsets(ring) {
            let (x, y) = (cx + dx, cy + dy);
            if !mask.get_signed(x, y) {
                let centre = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                nearest_squared = nearest_squared.min(point.distance_squared(centre));
            }
        }
    }
    (nearest_squared.sqrt() - 0.5).clamp(0.0, limit.max(0.0))
}

/// The offsets on the square ring at Chebyshev distance `ring` from the origin.
fn ring_offsets(ring: isize) -> impl Iterator<Item = (isize, isize)> {
    (-ring..=ring).flat_map(move |d| {
        [(d, -ring), (d, ring)].into_iter().chain(
            (d > -ring && d < ring)
                .then_some([(-ring, d), (ring, d)])
                .into_iter()
                .flatten(),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radius_is_the_distance_to_the_paper() {
        let mask = Bitmap::from_grid(
            "
            .........
            .#######.
            .#######.
            .#######.
            .#######.
            .#######.
            .........",
        );
        // The middle of a 5-px-high band: 3 px to the paper row, less half a pixel.
        assert_eq!(ink_radius(&mask, Point::new(4.5, 3.5), 10.0), 2.5);
        assert_eq!(ink_radius(&mask, Point::new(1.5, 1.5), 10.0), 0.5);
        assert_eq!(ink_radius(&mask, Point::new(0.5, 0.5), 10.0), 0.0);
        assert_eq!(ink_radius(&mask, Point::new(4.5, 3.5), 1.0), 1.0);
    }

    #[test]
    fn diagonal_paper_counts_at_its_true_distance() {
        let mask = Bitmap::from_grid(
            "
            #####
            #####
            #####
            #####
            ####.",
        );
        // Everything but the corner is ink, and outside the image is paper: from (1, 1) the
        // nearest paper is the outside, 2 px away; from the centre the corner pixel, √8 away.
        assert_eq!(ink_radius(&mask, Point::new(1.5, 1.5), 10.0), 1.5);
        let r = ink_radius(&mask, Point::new(2.5, 2.5), 10.0);
        assert!((r - (8f64.sqrt() - 0.5)).abs() < 1e-12, "{r}");
        // Between pixel centres the distance is measured from the point itself: 2.5 px up to
        // the row outside.
        let r = ink_radius(&mask, Point::new(2.5, 2.0), 10.0);
        assert!((r - 2.0).abs() < 1e-12, "{r}");
    }

    #[test]
    fn every_ring_offset_is_on_its_ring_once() {
        for ring in 1..5 {
            let offsets: Vec<_> = ring_offsets(ring).collect();
            assert_eq!(offsets.len() as isize, 8 * ring);
            let unique: std::collections::HashSet<_> = offsets.iter().collect();
            assert_eq!(unique.len(), offsets.len());
            assert!(offsets.iter().all(|&(x, y)| x.abs().max(y.abs()) == ring));
        }
    }
}
