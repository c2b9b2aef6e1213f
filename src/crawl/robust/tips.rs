//! Putting skipped points back. Where a corner is sharper than the crawl's turns, the chain steps
//! across from one side to the other just before the tip and leaves the tip out: on a corner of
//! angle θ with the tip on a sample, its two neighbours are 2 s sin(θ/2) apart, nearer than the tip
//! for θ < 60°. Where a notch is narrower than a couple of spacings, good continuation bridges its
//! mouth and leaves the one to three points inside it out. Either way the points left out form a
//! *detour* between the two ends a, b of one chain edge: each one's two nearest points are its
//! neighbours along a → t₁ → … → tₖ → b. The detour replaces the edge.

use std::collections::BTreeMap;

use super::measure::Local;
use super::{MIN_CURVE_POINTS, STEP_LIMIT};
use crate::crawl::algorithm::Chain;

/// Puts every skipped detour back into its chain. `free` marks the vertices on no chain.
///
/// DECISION: a detour has fewer points than a curve ([`MIN_CURVE_POINTS`]); its edges are
/// Delaunay edges (each point's two nearest Delaunay neighbours) and each at most [`STEP_LIMIT`]
/// times the curve's spacing beside the skipped edge, so a stray kept off the curve is never
/// taken in. A point whose nearest two are not its detour neighbours stays an outlier.
pub fn put_back_tips(local: &Local, chains: &mut [Chain], free: &[bool]) {
    if !free.contains(&true) {
        return;
    }
    // Where each vertex sits: (chain, position).
    let mut place: Vec<Option<(usize, usize)>> = vec![None; local.vertex_count()];
    for (c, chain) in chains.iter().enumerate() {
        for (i, &v) in chain.vertices.iter().enumerate() {
            place[v as usize] = Some((c, i));
        }
    }
    let mut taken = vec![false; local.vertex_count()];
    // (chain, position of the edge's first vertex) → the detour to insert after it, in order.
    let mut insertions: BTreeMap<(usize, usize), Vec<u32>> = BTreeMap::new();
    for start in 0..local.vertex_count() as u32 {
        if !free[start as usize] || taken[start as usize] {
            continue;
        }
        let Some((a, detour, b)) = detour_from(local, free, &place, start) else {
            continue;
        };
        let ((chain_a, at_a), (chain_b, at_b)) = (
            place[a as usize].expect("on a chain"),
            place[b as usize].expect("on a chain"),
        );
        if chain_a != chain_b || detour.iter().any(|&t| taken[t as usize]) {
            continue;
        }
        let chain = &chains[chain_a];
        let Some(edge) = edge_position(chain, at_a, at_b) else {
            continue;
        };
        let reach = STEP_LIMIT * spacing_beside(local, chain, edge);
        let mut path = vec![a];
        path.extend_from_slice(&detour);
        path.push(b);
        let within = path
            .windows(2)
            .all(|pair| local.length(pair[0], pair[1]) <= reach);
        if !within || insertions.contains_key(&(chain_a, edge)) {
            continue;
        }
        // In chain order: from the vertex at `edge` to the one after it.
        let mut ordered = detour;
        if chain.vertices[edge] != a {
            ordered.reverse();
        }
        for &t in &ordered {
            taken[t as usize] = true;
        }
        insertions.insert((chain_a, edge), ordered);
    }
    // Insert from the back of each chain so earlier positions stay valid.
    for (&(c, edge), detour) in insertions.iter().rev() {
        for (k, &t) in detour.iter().enumerate() {
            chains[c].vertices.insert(edge + 1 + k, t);
        }
    }
}

/// The two nearest Delaunay neighbours of `v`, if it has two.
fn nearest_two(local: &Local, v: u32) -> Option<[u32; 2]> {
    match local.graph.neighbours(v) {
        [a, b, ..] => Some([*a, *b]),
        _ => None,
    }
}

/// The detour through the free point `start`: following each point's two nearest neighbours
/// both ways until a point on a chain, through at most `MIN_CURVE_POINTS - 1` free points that
/// each name both their detour neighbours as their nearest two. Returns (a, free points from a's
/// side, b).
fn detour_from(
    local: &Local,
    free: &[bool],
    place: &[Option<(usize, usize)>],
    start: u32,
) -> Option<(u32, Vec<u32>, u32)> {
    let [left, right] = nearest_two(local, start)?;
    let mut sides = Vec::with_capacity(2);
    let mut count = 1;
    for first in [left, right] {
        let (mut previous, mut current) = (start, first);
        let mut run = Vec::new();
        while free[current as usize] {
            count += 1;
            if count >= MIN_CURVE_POINTS {
                return None;
            }
            let pair = nearest_two(local, current)?;
            if !pair.contains(&previous) {
                return None;
            }
            run.push(current);
            let next = if pair[0] == previous {
                pair[1]
            } else {
                pair[0]
            };
            (previous, current) = (current, next);
        }
        place[current as usize]?;
        sides.push((current, run));
    }
    let (b, right_run) = sides.pop().expect("two sides");
    let (a, left_run) = sides.pop().expect("two sides");
    let mut detour: Vec<u32> = left_run.into_iter().rev().collect();
    detour.push(start);
    detour.extend(right_run);
    Some((a, detour, b))
}

/// If positions `i` and `j` of `chain` are consecutive, the position of the edge's first vertex
/// (the edge from the last vertex back to the first of a closed chain is at the last position).
fn edge_position(chain: &Chain, i: usize, j: usize) -> Option<usize> {
    let n = chain.vertices.len();
    let (low, high) = (i.min(j), i.max(j));
    if high == low + 1 {
        Some(low)
    } else if chain.closed && low == 0 && high == n - 1 {
        Some(n - 1)
    } else {
        None
    }
}

/// The curve's spacing beside the edge at `edge`: the longer of the edges before and after it.
fn spacing_beside(local: &Local, chain: &Chain, edge: usize) -> f64 {
    let n = chain.vertices.len();
    let v = |i: usize| chain.vertices[i % n];
    let mut spacing: f64 = 0.0;
    if edge > 0 || chain.closed {
        let before = (edge + n - 1) % n;
        spacing = spacing.max(local.length(v(before), v(edge)));
    }
    if edge + 2 < n || chain.closed {
        spacing = spacing.max(local.length(v(edge + 1), v(edge + 2)));
    }
    spacing
}
