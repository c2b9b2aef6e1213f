//! Growing chains from seeds: the best-continuing step at either extremity, within the spacing
//! limits, with a look one step ahead after a sharp turn and dead ends last; closing when the step
//! from one extremity to the other is the best there is; short chains and strays released.

use std::collections::VecDeque;

use super::measure::{continuation_score, Local, NONE};
use super::seeds::{self, Seed};
use super::{
    BESIDE, CANDIDATE_LIMIT, CLOSING_GAP_OF_LENGTH, EVIDENT_CURVE_POINTS, MIN_CURVE_POINTS,
    ONWARD_TURN_COS, SHARP_TURN_COS, SPARSE_RATIO, STEP_LIMIT,
};
use crate::crawl::algorithm::Chain;

/// The owner of a vertex that is on no chain.
const FREE: u32 = u32::MAX;

/// A possible step from an extremity.
#[derive(Clone, Copy, Debug)]
struct Step {
    to: u32,
    score: f64,
    turn_cos: f64,
    /// Whether the chain could only turn back after this step.
    dead_end: bool,
}

impl Step {
    /// The order in which steps are preferred: going on before dead ends, then by score, then
    /// by vertex id (the lexicographically smaller point).
    fn key(&self) -> (bool, f64, u32) {
        (self.dead_end, self.score, self.to)
    }
}

/// Which extremity of a chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum End {
    Front,
    Back,
}

impl End {
    fn index(self) -> usize {
        match self {
            End::Front => 0,
            End::Back => 1,
        }
    }

    fn other(self) -> End {
        match self {
            End::Front => End::Back,
            End::Back => End::Front,
        }
    }
}

/// A chain being grown.
struct Growing {
    vertices: VecDeque<u32>,
    /// Sum of its edge lengths.
    length: f64,
    /// Squared lengths of the last two edges at the front and at the back, the last first.
    recent: [[f64; 2]; 2],
}

impl Growing {
    fn new(local: &Local, seed: &Seed) -> Self {
        let [p, q] = seed.ends;
        let (first, second) = (
            local.squared_length(p, seed.middle),
            local.squared_length(seed.middle, q),
        );
        Self {
            vertices: VecDeque::from([p, seed.middle, q]),
            length: first.sqrt() + second.sqrt(),
            recent: [[first, second], [second, first]],
        }
    }

    /// The extremity and the vertex before it.
    fn extremity(&self, end: End) -> (u32, u32) {
        let v = &self.vertices;
        match end {
            End::Front => (v[0], v[1]),
            End::Back => (v[v.len() - 1], v[v.len() - 2]),
        }
    }

    /// The chain's squared spacing at an extremity: the longer of its last two edges. (The longer,
    /// so that a short edge, two samples close together, does not stop the chain.)
    fn squared_spacing(&self, end: End) -> f64 {
        let [last, before] = self.recent[end.index()];
        last.max(before)
    }

    fn add(&mut self, end: End, vertex: u32, squared_length: f64) {
        match end {
            End::Front => self.vertices.push_front(vertex),
            End::Back => self.vertices.push_back(vertex),
        }
        self.length += squared_length.sqrt();
        let recent = &mut self.recent[end.index()];
        *recent = [squared_length, recent[0]];
    }
}

/// The crawl's state: who owns each vertex, and the curves found so far.
pub struct Crawler<'a> {
    local: &'a Local<'a>,
    owner: Vec<u32>,
    /// One bit per vertex: owned by a chain. The crawl asks this for every point it looks at;
    /// a bit set of a million points (128 KiB) stays in cache where the owners would not.
    taken: Vec<u64>,
    /// Points of chains found to be strays: they never seed again.
    stray: Vec<bool>,
    chains: Vec<Chain>,
    /// The smallest second-nearest distance of all points, squared: no chain with a spacing
    /// under SPARSE_RATIO times it can be sparse beside anything.
    densest: f64,
    scratch: Vec<Step>,
}

impl<'a> Crawler<'a> {
    pub fn new(local: &'a Local<'a>) -> Self {
        Self {
            local,
            owner: vec![FREE; local.vertex_count()],
            taken: vec![0; local.vertex_count().div_ceil(64)],
            stray: vec![false; local.vertex_count()],
            chains: Vec::new(),
            densest: local
                .samples
                .iter()
                .map(|s| s.second_nearest_squared)
                .fold(f64::INFINITY, f64::min),
            scratch: Vec::new(),
        }
    }

    /// The curves, and which vertices are on none.
    pub fn finish(self) -> (Vec<Chain>, Vec<bool>) {
        let free = self.owner.iter().map(|&o| o == FREE).collect();
        (self.chains, free)
    }

    /// Sets who owns `v` (`FREE` for no chain).
    fn set_owner(&mut self, v: u32, id: u32) {
        self.owner[v as usize] = id;
        let bit = 1 << (v % 64);
        if id == FREE {
            self.taken[(v / 64) as usize] &= !bit;
        } else {
            self.taken[(v / 64) as usize] |= bit;
        }
    }

    fn is_free(&self, v: u32) -> bool {
        self.taken[(v / 64) as usize] & (1 << (v % 64)) == 0
    }

    /// Grows a chain from the seed at `middle` if its three points are free and it is no stray;
    /// keeps it if it becomes a curve that is no stray either.
    pub fn try_seed(&mut self, middle: u32) {
        if !self.is_free(middle) || self.stray[middle as usize] {
            return;
        }
        let Some(seed) = seeds::seed_at(self.local, middle) else {
            return;
        };
        let points = [seed.ends[0], seed.middle, seed.ends[1]];
        if points
            .iter()
            .any(|&v| !self.is_free(v) || self.stray[v as usize])
        {
            return;
        }
        let id = self.chains.len() as u32;
        for v in points {
            self.set_owner(v, id);
        }
        let mut chain = Growing::new(self.local, &seed);
        let closed = self.grow(&mut chain, id);
        let vertices: Vec<u32> = chain.vertices.iter().copied().collect();
        let is_curve = vertices.len() >= MIN_CURVE_POINTS;
        let strays = is_curve
            && self.sparse_beside_curves(&vertices, self.median_edge(&vertices, closed), id)
            && !(vertices.len() >= EVIDENT_CURVE_POINTS && self.regular(&vertices, closed));
        if !is_curve || strays {
            for &v in &vertices {
                self.set_owner(v, FREE);
                // Strays stay free for a curve that needs them, but never seed again.
                self.stray[v as usize] |= strays;
            }
            return;
        }
        self.chains.push(Chain {
            vertices: chain.vertices,
            closed,
        });
    }

    /// Whether `points` (a grown chain, owned by `id`, with median edge `spacing`) are much
    /// sparser than a curve found before, right beside them: strays, unless evident as a curve.
    ///
    /// DECISION: "beside" is a Delaunay neighbour of one of the points, on another curve, within
    /// [`BESIDE`] spacings; "much sparser" is a spacing above [`SPARSE_RATIO`] times that
    /// neighbour's second-nearest distance. Seeds go densest first, so the curves strays lie among
    /// are known when the strays' seeds come up; a sparse curve away from denser ones (or denser
    /// by less than the ratio) is kept. The grown chain is judged, not the seed: a seed on the far
    /// side of a cluster of strays sees no curve, the whole chain does; and a seed beside a denser
    /// curve may start a long, regular curve of its own.
    fn sparse_beside_curves(&self, points: &[u32], spacing: f64, id: u32) -> bool {
        let squared_spacing = spacing * spacing;
        if squared_spacing <= SPARSE_RATIO * SPARSE_RATIO * self.densest {
            return false;
        }
        let reach = BESIDE * BESIDE * squared_spacing;
        let graph = self.local.graph;
        points.iter().any(|&u| {
            graph
                .neighbours(u)
                .iter()
                .zip(graph.squared_lengths(u))
                .take_while(|&(_, &squared)| squared <= reach)
                .any(|(&w, _)| {
                    let owner = self.owner[w as usize];
                    owner != FREE
                        && owner != id
                        && squared_spacing
                            > SPARSE_RATIO * SPARSE_RATIO * self.local.second_nearest_squared(w)
                })
        })
    }

    /// Whether a chain looks like a sampled curve: it never turns by more than 60° (as a curve
    /// sampled densely enough for its turns, ε < 1/2, turns by at most 2 asin(ε/2) ≈ 29°), and
    /// no edge is more than [`CANDIDATE_LIMIT`] times as long as the one before or after it.
    /// A chain through scattered strays zig-zags and jumps somewhere.
    fn regular(&self, vertices: &[u32], closed: bool) -> bool {
        let n = vertices.len();
        let at = |i: usize| vertices[i % n];
        let corners = if closed { n } else { n - 2 };
        (0..corners).all(|i| {
            let (a, b, c) = (at(i), at(i + 1), at(i + 2));
            let (first, second) = (
                self.local.squared_length(a, b),
                self.local.squared_length(b, c),
            );
            let limit = CANDIDATE_LIMIT * CANDIDATE_LIMIT;
            self.local.turns_at_most(a, b, c, ONWARD_TURN_COS)
                && first <= limit * second
                && second <= limit * first
        })
    }

    /// The median edge length of a chain.
    fn median_edge(&self, vertices: &[u32], closed: bool) -> f64 {
        let mut lengths: Vec<f64> = vertices
            .windows(2)
            .map(|pair| self.local.squared_length(pair[0], pair[1]))
            .collect();
        if closed {
            lengths.push(
                self.local
                    .squared_length(vertices[0], vertices[vertices.len() - 1]),
            );
        }
        let middle = lengths.len() / 2;
        lengths
            .select_nth_unstable_by(middle, f64::total_cmp)
            .1
            .sqrt()
    }

    /// Grows `chain` (owned by `id`) until no step is left or it closes; returns whether it
    /// closed.
    fn grow(&mut self, chain: &mut Growing, id: u32) -> bool {
        let mut best = [
            self.best_step(chain, End::Front),
            self.best_step(chain, End::Back),
        ];
        loop {
            // DECISION: of the two extremities' best steps the one with the smaller key wins
            // (going on before a dead end, then the lower score, then the smaller vertex id);
            // on a tie the front.
            let chosen = match best {
                [None, None] => None,
                [Some(f), None] => Some((End::Front, f)),
                [None, Some(b)] => Some((End::Back, b)),
                [Some(f), Some(b)] if b.key() < f.key() => Some((End::Back, b)),
                [Some(f), Some(_)] => Some((End::Front, f)),
            };
            if let Some(closing) = self.closing_score(chain) {
                if chosen.is_none_or(|(_, step)| step.dead_end || closing <= step.score) {
                    return true;
                }
            }
            let Some((end, step)) = chosen else {
                return false;
            };
            let (extremity, _) = chain.extremity(end);
            chain.add(end, step.to, self.local.squared_length(extremity, step.to));
            self.set_owner(step.to, id);
            best[end.index()] = self.best_step(chain, end);
            // The other extremity's best step stands unless this step took its point, one of its
            // two nearest points, or a point within its reach (its way on, maybe).
            let other = end.other();
            let reach = STEP_LIMIT * STEP_LIMIT * chain.squared_spacing(other);
            if best[other.index()].is_some_and(|s| {
                s.to == step.to
                    || self.local.samples[s.to as usize].nearest.contains(&step.to)
                    || self.local.squared_length(s.to, step.to) <= reach
            }) {
                best[other.index()] = self.best_step(chain, other);
            }
        }
    }

    /// The best acceptable step from an extremity, if any: candidates within the limits in order
    /// of score; the first that is not inside another strand and, after a sharp turn, goes on
    /// gently; a dead end only if no candidate goes on.
    fn best_step(&mut self, chain: &Growing, end: End) -> Option<Step> {
        let (e, p) = chain.extremity(end);
        let reach = STEP_LIMIT * STEP_LIMIT * chain.squared_spacing(end);
        let graph = self.local.graph;
        let mut candidates = std::mem::take(&mut self.scratch);
        candidates.clear();
        for (&w, &squared) in graph.neighbours(e).iter().zip(graph.squared_lengths(e)) {
            if squared > reach {
                break; // neighbours come nearest first
            }
            let limit = CANDIDATE_LIMIT * CANDIDATE_LIMIT * self.local.second_nearest_squared(w);
            if !self.is_free(w) || squared > limit {
                continue;
            }
            // Touch the candidate's neighbour list now: the chain will most likely step there
            // next, and the load overlaps with this step's work instead of stalling the next.
            std::hint::black_box(graph.squared_lengths(w).first());
            let turn_cos = self.local.turn_cos(p, e, w);
            candidates.push(Step {
                to: w,
                score: continuation_score(squared.sqrt(), turn_cos),
                turn_cos,
                dead_end: false,
            });
        }
        candidates.sort_unstable_by(|a, b| a.score.total_cmp(&b.score).then(a.to.cmp(&b.to)));
        let other = chain.other_extremity(end);
        let mut dead_end = None;
        let mut found = None;
        for step in &candidates {
            let w = step.to;
            if self.local.inside_strand(w, e, |x| self.is_free(x))
                || (step.turn_cos < SHARP_TURN_COS
                    && !self.goes_on(e, w, other, reach, ONWARD_TURN_COS))
            {
                continue;
            }
            if self.goes_on(e, w, other, reach, SHARP_TURN_COS) {
                found = Some(*step);
                break;
            }
            dead_end.get_or_insert(Step {
                dead_end: true,
                ..*step
            });
        }
        self.scratch = candidates;
        found.or(dead_end)
    }

    /// Whether the chain could go on from `at` after stepping there from `from`: to a free point
    /// within the squared `reach` and the candidate limit, turning by no more than `min_cos`
    /// allows, or to the chain's other extremity `other` (closing).
    ///
    /// Used twice. After a sharp turn (over 120°) the next step must turn at most 60°: a zig-zag
    /// across a thin part turns sharply at every point, a corner turns once and goes straight on.
    /// And a step after which the chain could only turn back is a dead end, taken only when no
    /// step goes on: on a spike thinner than the spacing the chain crosses to the other side
    /// and leaves the tip, which [`super::tips`] puts back, instead of ending at the tip.
    fn goes_on(&self, from: u32, at: u32, other: u32, reach: f64, min_cos: f64) -> bool {
        let onward = |x: u32, squared: f64| {
            let reachable = x == other
                || (self.is_free(x)
                    && squared
                        <= CANDIDATE_LIMIT
                            * CANDIDATE_LIMIT
                            * self.local.second_nearest_squared(x));
            x != from
                && squared <= reach
                && reachable
                && self.local.turns_at_most(from, at, x, min_cos)
        };
        // Mostly the way on is one of the point's two nearest: look there before its whole
        // neighbourhood.
        let nearest = self.local.samples[at as usize].nearest;
        if nearest
            .iter()
            .any(|&x| x != NONE && onward(x, self.local.squared_length(at, x)))
        {
            return true;
        }
        let graph = self.local.graph;
        graph
            .neighbours(at)
            .iter()
            .zip(graph.squared_lengths(at))
            .take_while(|&(_, &squared)| squared <= reach)
            .any(|(&x, &squared)| onward(x, squared))
    }

    /// The score of the step joining the two extremities, if the chain may close: it has at least
    /// three edges, the two extremities are Delaunay neighbours, the gap is within the step limit
    /// of both extremities' spacing and short against the chain's length, and the turns at the two
    /// ends are acceptable as a step and the step after it.
    ///
    /// DECISION: the paper closes when one extremity is the other's nearest or second-nearest
    /// point; on evenly spaced samples that leaves a curve open whenever its last gap is over
    /// twice the spacing beside it. Here the closing edge is judged like any step.
    fn closing_score(&self, chain: &Growing) -> Option<f64> {
        let n = chain.vertices.len();
        if n < MIN_CURVE_POINTS {
            return None;
        }
        let (front, back) = (chain.vertices[0], chain.vertices[n - 1]);
        let squared_gap = self.local.squared_length(front, back);
        let spacing = chain
            .squared_spacing(End::Front)
            .min(chain.squared_spacing(End::Back));
        if squared_gap > STEP_LIMIT * STEP_LIMIT * spacing {
            return None;
        }
        let gap = squared_gap.sqrt();
        if gap > CLOSING_GAP_OF_LENGTH * chain.length || !self.local.graph.has_edge(front, back) {
            return None;
        }
        let at_front = self.local.turn_cos(chain.vertices[1], front, back);
        let at_back = self.local.turn_cos(chain.vertices[n - 2], back, front);
        let acceptable = match (at_front < SHARP_TURN_COS, at_back < SHARP_TURN_COS) {
            (false, false) => true,
            (true, false) => at_back >= ONWARD_TURN_COS,
            (false, true) => at_front >= ONWARD_TURN_COS,
            (true, true) => false,
        };
        acceptable.then(|| continuation_score(gap, at_front).max(continuation_score(gap, at_back)))
    }
}

impl Growing {
    fn other_extremity(&self, end: End) -> u32 {
        self.extremity(end.other()).0
    }
}
