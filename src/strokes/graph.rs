//! The skeleton as a graph: branches of skeleton pixels between nodes (end points and
//! junctions), traced from a 1-px skeleton in raster order.

use kurbo::Point;

use crate::raster::bitmap::{Bitmap, NEIGHBOUR_OFFSETS};

/// Branches of a skeleton between nodes (end points and junctions).
#[derive(Debug, Default)]
pub(super) struct SkeletonGraph {
    pub(super) nodes: Vec<Node>,
    pub(super) branches: Vec<Branch>,
    /// The centre lines of the double strands found (for the `--debug` pictures).
    pub(super) bands: Vec<Vec<Point>>,
}

#[derive(Debug)]
pub(super) struct Node {
    pub(super) position: Point,
    /// The branch ends that meet here: (branch, whether it is the branch's start).
    pub(super) ends: Vec<(usize, bool)>,
    /// Set when pruning took away every branch of this node (it was the tip of a spur).
    pub(super) pruned: bool,
}

#[derive(Debug)]
pub(super) struct Branch {
    /// From the start node's position to the end node's position; for loops, around the loop.
    pub(super) points: Vec<Point>,
    /// `None` for a loop with no node on it.
    pub(super) nodes: Option<(usize, usize)>,
    pub(super) removed: bool,
    /// Set on the branches that trace a double strand (two stretches of outline merged into one
    /// band of ink): the original branch's number, shared by its copy. Junctions pair such
    /// branches without crossing ([`super::double`]).
    pub(super) strand_of: Option<usize>,
    /// Which side of the band this copy traces, +1 (left, walking from the start) or −1; a
    /// U-turn goes out on the left and back on the right. 0 for a single stroke.
    pub(super) side: f64,
    /// Set on a lone dash whose ink is a band clearly wider than one stroke that was not split
    /// into sides ([`super::double`]): a narrow protrusion cut off at its base by a pen lift.
    pub(super) wide: bool,
}

/// The label of pixels that lie on a branch (node pixels are labelled with their node).
const PATH_PIXEL: usize = usize::MAX;

/// Labels of the skeleton pixels traced so far: a node number or [`PATH_PIXEL`]. The skeleton's
/// pixels are listed row by row (each row's in order of x), so that a pixel's label is found by
/// a short search in its row: a skeleton is a few pixels per row, and a label per page pixel
/// would cost as much memory as the page.
struct Labels {
    /// Where each row's pixels start in `xs` (one more entry than rows).
    row_start: Vec<usize>,
    /// The x of every skeleton pixel, row after row.
    xs: Vec<u32>,
    /// The label of each pixel of `xs`; `None` until it is traced.
    labels: Vec<Option<usize>>,
}

impl Labels {
    /// No pixel of `skeleton` labelled yet.
    fn new(skeleton: &Bitmap) -> Self {
        let width = skeleton.width();
        let bytes = skeleton.as_bytes();
        let mut row_start = Vec::with_capacity(skeleton.height() + 1);
        let mut xs = Vec::new();
        for row in bytes.chunks_exact(width.max(1)).take(skeleton.height()) {
            row_start.push(xs.len());
            // A skeleton is under a hundredth of the page: its runs are found passing sixteen
            // paper bytes at once (a fiftieth of the page's instructions went to this scan byte
            // by byte; passing eight at once, the strokes stage took 97 M instructions on the
            // 12-megapixel page, 86 M now).
            crate::raster::clean::for_each_run(row, true, |start, end| {
                xs.extend((start..end).map(|x| x as u32));
            });
        }
        row_start.push(xs.len());
        let labels = vec![None; xs.len()];
        Self {
            row_start,
            xs,
            labels,
        }
    }

    /// The position of skeleton pixel `(x, y)` in `xs`.
    fn slot(&self, (x, y): (usize, usize)) -> Option<usize> {
        let (from, to) = (*self.row_start.get(y)?, self.row_start[y + 1]);
        self.xs[from..to]
            .binary_search(&(x as u32))
            .ok()
            .map(|k| from + k)
    }

    fn get(&self, pixel: (usize, usize)) -> Option<usize> {
        self.slot(pixel).and_then(|k| self.labels[k])
    }

    fn contains(&self, pixel: (usize, usize)) -> bool {
        self.get(pixel).is_some()
    }

    /// Labels the skeleton pixel `pixel` (a pixel off the skeleton has no label to set).
    fn insert(&mut self, pixel: (usize, usize), label: usize) {
        if let Some(k) = self.slot(pixel) {
            self.labels[k] = Some(label);
        }
    }

    /// The number of rows.
    fn rows(&self) -> usize {
        self.row_start.len() - 1
    }

    /// The x of every skeleton pixel of row `y`, in order; a copy of the row's few entries, so
    /// that the caller may label pixels while it walks them.
    fn row(&self, y: usize) -> Vec<usize> {
        self.xs[self.row_start[y]..self.row_start[y + 1]]
            .iter()
            .map(|&x| x as usize)
            .collect()
    }
}

fn centre(x: usize, y: usize) -> Point {
    Point::new(x as f64 + 0.5, y as f64 + 0.5)
}

/// The ink pixels among the 8 neighbours of `(x, y)`, in [`NEIGHBOUR_OFFSETS`] order.
fn neighbours_of(
    skeleton: &Bitmap,
    (x, y): (usize, usize),
) -> impl Iterator<Item = (usize, usize)> + '_ {
    NEIGHBOUR_OFFSETS.iter().filter_map(move |&(dx, dy)| {
        let (nx, ny) = (x as isize + dx, y as isize + dy);
        skeleton
            .get_signed(nx, ny)
            .then_some((nx as usize, ny as usize))
    })
}

/// Pixels with a neighbour count other than two (ends and junctions) are node pixels.
fn is_node_pixel(skeleton: &Bitmap, (x, y): (usize, usize)) -> bool {
    skeleton.neighbourhood(x, y).count_ones() != 2
}

/// The `k`-th of a branch's `points` counted from its node at its start (or at its end).
fn nth_from_node(points: &[Point], at_start: bool, k: usize) -> Point {
    if at_start {
        points[k]
    } else {
        points[points.len() - 1 - k]
    }
}

impl SkeletonGraph {
    /// The graph of `skeleton`: its nodes, the branches between them, and the loops with no node.
    pub(super) fn trace(skeleton: &Bitmap) -> Self {
        let mut label = Labels::new(skeleton);
        let mut graph = SkeletonGraph::default();
        let members_of_node = graph.find_nodes(skeleton, &mut label);
        // Walk every branch leaving each node; a branch walked from its other end already has
        // its first pixel labelled.
        for (node, members) in members_of_node.iter().enumerate() {
            for &pixel in members {
                let starts: Vec<(usize, usize)> = neighbours_of(skeleton, pixel).collect();
                for first in starts {
                    if !label.contains(first) {
                        graph.walk_branch(skeleton, &mut label, node, pixel, first);
                    }
                }
            }
        }
        graph.trace_loops_without_nodes(skeleton, &mut label);
        graph
    }

    /// Makes a node of every cluster of adjacent node pixels (an 8-connected skeleton often has
    /// two or three junction pixels side by side), at the cluster's centroid, in raster order of
    /// the clusters' first pixels. Returns each node's pixels.
    fn find_nodes(&mut self, skeleton: &Bitmap, label: &mut Labels) -> Vec<Vec<(usize, usize)>> {
        let mut members_of_node: Vec<Vec<(usize, usize)>> = Vec::new();
        for y in 0..label.rows() {
            for x in label.row(y) {
                if !is_node_pixel(skeleton, (x, y)) || label.contains((x, y)) {
                    continue;
                }
                let node = self.nodes.len();
                let mut stack = vec![(x, y)];
                let mut members = Vec::new();
                label.insert((x, y), node);
                while let Some(pixel) = stack.pop() {
                    members.push(pixel);
                    for next in neighbours_of(skeleton, pixel) {
                        if is_node_pixel(skeleton, next) && !label.contains(next) {
                            label.insert(next, node);
                            stack.push(next);
                        }
                    }
                }
                members.sort_unstable_by_key(|&(mx, my)| (my, mx));
                let count = members.len() as f64;
                let (sum_x, sum_y) = members.iter().fold((0.0, 0.0), |(sx, sy), &(mx, my)| {
                    (sx + mx as f64 + 0.5, sy + my as f64 + 0.5)
                });
                self.nodes.push(Node {
                    position: Point::new(sum_x / count, sum_y / count),
                    ends: Vec::new(),
                    pruned: false,
                });
                members_of_node.push(members);
            }
        }
        members_of_node
    }

    /// What is left unlabelled after the branches are walked are loops with no node on them:
    /// each becomes a branch without nodes.
    fn trace_loops_without_nodes(&mut self, skeleton: &Bitmap, label: &mut Labels) {
        for y in 0..label.rows() {
            for x in label.row(y) {
                if label.contains((x, y)) {
                    continue;
                }
                let mut points = vec![centre(x, y)];
                label.insert((x, y), PATH_PIXEL);
                let mut current = (x, y);
                while let Some(next) =
                    neighbours_of(skeleton, current).find(|&p| !label.contains(p))
                {
                    label.insert(next, PATH_PIXEL);
                    points.push(centre(next.0, next.1));
                    current = next;
                }
                self.branches.push(Branch {
                    points,
                    nodes: None,
                    removed: false,
                    strand_of: None,
                    side: 0.0,
                    wide: false,
                });
            }
        }
    }

    /// Follows the branch that leaves node pixel `from` (of `start_node`) through `first` until
    /// it reaches a node pixel, labelling its pixels [`PATH_PIXEL`].
    fn walk_branch(
        &mut self,
        skeleton: &Bitmap,
        label: &mut Labels,
        start_node: usize,
        from: (usize, usize),
        first: (usize, usize),
    ) {
        let mut points = vec![self.nodes[start_node].position, centre(first.0, first.1)];
        label.insert(first, PATH_PIXEL);
        let (mut previous, mut current) = (from, first);
        let end_node = loop {
            let mut next_path = None;
            let mut next_node = None;
            for &(dx, dy) in &NEIGHBOUR_OFFSETS {
                let (nx, ny) = (current.0 as isize + dx, current.1 as isize + dy);
                if !skeleton.get_signed(nx, ny) || (nx as usize, ny as usize) == previous {
                    continue;
                }
                let p = (nx as usize, ny as usize);
                match label.get(p) {
                    None => next_path = next_path.or(Some(p)),
                    Some(PATH_PIXEL) => {}
                    // Touching the cluster just left, on the first step, is not an arrival.
                    Some(node) if node == start_node && points.len() == 2 => {}
                    Some(node) => next_node = next_node.or(Some(node)),
                }
            }
            match (next_node, next_path) {
                (Some(node), _) => break Some(node),
                (None, Some(p)) => {
                    label.insert(p, PATH_PIXEL);
                    points.push(centre(p.0, p.1));
                    previous = current;
                    current = p;
                }
                (None, None) => break None,
            }
        };
        let end_node = match end_node {
            Some(node) => {
                points.push(self.nodes[node].position);
                node
            }
            None if points.len() == 2 && self.touches(skeleton, label, current, start_node) => {
                // A single pixel hugging its own junction: nothing to keep.
                return;
            }
            None => {
                // Only reachable on a skeleton that is not fully thinned; end the branch here.
                let node = self.nodes.len();
                self.nodes.push(Node {
                    position: *points.last().expect("branch has points"),
                    ends: Vec::new(),
                    pruned: false,
                });
                node
            }
        };
        let branch = self.branches.len();
        self.nodes[start_node].ends.push((branch, true));
        self.nodes[end_node].ends.push((branch, false));
        self.branches.push(Branch {
            points,
            nodes: Some((start_node, end_node)),
            removed: false,
            strand_of: None,
            side: 0.0,
            wide: false,
        });
    }

    /// Whether `pixel` has a neighbour labelled as `node`.
    fn touches(
        &self,
        skeleton: &Bitmap,
        label: &Labels,
        pixel: (usize, usize),
        node: usize,
    ) -> bool {
        NEIGHBOUR_OFFSETS.iter().any(|&(dx, dy)| {
            let (nx, ny) = (pixel.0 as isize + dx, pixel.1 as isize + dy);
            skeleton.get_signed(nx, ny) && label.get((nx as usize, ny as usize)) == Some(node)
        })
    }

    pub(super) fn remove_branch(&mut self, branch: usize) {
        self.branches[branch].removed = true;
        if let Some((a, z)) = self.branches[branch].nodes {
            for node in [a, z] {
                self.nodes[node].ends.retain(|&(b, _)| b != branch);
                self.nodes[node].pruned = self.nodes[node].ends.is_empty();
            }
        }
    }

    /// The number of branch ends at `node`.
    pub(super) fn degree(&self, node: usize) -> usize {
        self.nodes[node].ends.len()
    }

    /// Where `branch` is a little away from its node at its start (or end), past the node's own
    /// pixels (a quarter of `scale`), and its direction there, measured over `scale` further.
    pub(super) fn tangent_away_from_node(
        &self,
        branch: usize,
        at_start: bool,
        scale: f64,
    ) -> (Point, kurbo::Vec2) {
        let points = &self.branches[branch].points;
        let along = |k: usize| nth_from_node(points, at_start, k);
        let origin = along(0);
        let mut from = origin;
        let mut k = 0;
        while k + 1 < points.len() && from.distance(origin) < scale / 4.0 {
            k += 1;
            from = along(k);
        }
        let mut target = from;
        while k + 1 < points.len() && target.distance(from) < scale {
            k += 1;
            target = along(k);
        }
        let direction = target - from;
        let length = direction.hypot();
        if length > 0.0 {
            (from, direction / length)
        } else {
            (origin, self.leaving_direction(branch, at_start, scale))
        }
    }

    /// The direction in which `branch` leaves its node at its start (or end), measured to the
    /// point `scale` along it.
    pub(super) fn leaving_direction(
        &self,
        branch: usize,
        at_start: bool,
        scale: f64,
    ) -> kurbo::Vec2 {
        let points = &self.branches[branch].points;
        let along = |k: usize| nth_from_node(points, at_start, k);
        let origin = along(0);
        let mut target = origin;
        for k in 0..points.len() {
            target = along(k);
            if target.distance(origin) >= scale {
                break;
            }
        }
        let direction = target - origin;
        let length = direction.hypot();
        if length > 0.0 {
            direction / length
        } else {
            kurbo::Vec2::ZERO
        }
    }
}
