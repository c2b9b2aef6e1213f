//! Joining chains end to end. Seeds go densest first, so a short dense run of samples (a sample
//! repeated a few times close together) becomes a chain of its own before the curve around it is
//! crawled, and that curve then stops at both of its ends. Any two chain ends that are Delaunay
//! neighbours are joined when the step between them is acceptable from both sides: within the
//! step limit of the sparser of the two chains' spacings, and turning at the two ends as a step
//! and the step after it would. Best joins first; a join between the two ends of what has become
//! one chain closes it, under the closing rule's length condition.

use super::measure::{continuation_score, Local};
use super::{CLOSING_GAP_OF_LENGTH, ONWARD_TURN_COS, SHARP_TURN_COS, STEP_LIMIT};
use crate::crawl::algorithm::Chain;

/// One end of an open chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct EndRef {
    chain: usize,
    front: bool,
}

impl EndRef {
    fn slot(self) -> usize {
        2 * self.chain + usize::from(!self.front)
    }
}

/// An end's vertex, the vertex before it, and the chain's squared spacing there (the longer of
/// its last two edges).
fn end_of(local: &Local, chain: &Chain, front: bool) -> (u32, u32, f64) {
    let v = &chain.vertices;
    let n = v.len();
    let (e, p, b) = if front {
        (v[0], v[1], v[2])
    } else {
        (v[n - 1], v[n - 2], v[n - 3])
    };
    let spacing = local.squared_length(e, p).max(local.squared_length(p, b));
    (e, p, spacing)
}

/// Joins open chains end to end where acceptable; returns the chains, merged ones in the place of
/// their first part.
pub fn join_chains(local: &Local, chains: Vec<Chain>) -> Vec<Chain> {
    let mut end_at = std::collections::HashMap::new();
    for (c, chain) in chains.iter().enumerate() {
        if !chain.closed {
            for front in [true, false] {
                let (e, _, _) = end_of(local, chain, front);
                end_at.insert(e, EndRef { chain: c, front });
            }
        }
    }
    if end_at.len() < 2 {
        return chains;
    }
    let mut ends: Vec<(u32, EndRef)> = end_at.iter().map(|(&e, &a)| (e, a)).collect();
    ends.sort_unstable();
    let mut candidates = Vec::new();
    for (e, a) in ends {
        for &w in local.graph.neighbours(e) {
            if let Some(&b) = end_at.get(&w) {
                if a < b {
                    if let Some((score, gap)) = join_score(local, &chains, a, b) {
                        candidates.push((score, e.min(w), e.max(w), gap, a, b));
                    }
                }
            }
        }
    }
    // DECISION: best joins first (lowest score), ties by the two end vertices' ids.
    candidates.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let mut joins = Joins::new(local, &chains);
    for (_, _, _, gap, a, b) in candidates {
        joins.try_join(a, b, gap);
    }
    joins.into_chains(chains)
}

/// The score and length of the edge joining ends `a` and `b`, if acceptable.
fn join_score(local: &Local, chains: &[Chain], a: EndRef, b: EndRef) -> Option<(f64, f64)> {
    let (ea, pa, spacing_a) = end_of(local, &chains[a.chain], a.front);
    let (eb, pb, spacing_b) = end_of(local, &chains[b.chain], b.front);
    let squared_gap = local.squared_length(ea, eb);
    if squared_gap > STEP_LIMIT * STEP_LIMIT * spacing_a.max(spacing_b) {
        return None;
    }
    let (at_a, at_b) = (local.turn_cos(pa, ea, eb), local.turn_cos(pb, eb, ea));
    let acceptable = match (at_a < SHARP_TURN_COS, at_b < SHARP_TURN_COS) {
        (false, false) => true,
        (true, false) => at_b >= ONWARD_TURN_COS,
        (false, true) => at_a >= ONWARD_TURN_COS,
        (true, true) => false,
    };
    let gap = squared_gap.sqrt();
    acceptable.then(|| {
        let score = continuation_score(gap, at_a).max(continuation_score(gap, at_b));
        (score, gap)
    })
}

/// The joins made so far: which end is joined to which, and the chains grouped by joins.
struct Joins {
    joined: Vec<Option<EndRef>>,
    parent: Vec<usize>,
    /// Per group root: the total length of its chains and joins.
    length: Vec<f64>,
    /// Per group root: whether a join closed it.
    closed: Vec<bool>,
}

impl Joins {
    fn new(local: &Local, chains: &[Chain]) -> Self {
        let length = chains
            .iter()
            .map(|chain| {
                let v = &chain.vertices;
                (1..v.len()).map(|i| local.length(v[i - 1], v[i])).sum()
            })
            .collect();
        Self {
            joined: vec![None; 2 * chains.len()],
            parent: (0..chains.len()).collect(),
            length,
            closed: vec![false; chains.len()],
        }
    }

    fn root(&self, mut c: usize) -> usize {
        while self.parent[c] != c {
            c = self.parent[c];
        }
        c
    }

    /// Joins ends `a` and `b` (`gap` apart) if both are still free; if they are the two ends of
    /// one group already, that closes it, when the gap is short against the group's length.
    fn try_join(&mut self, a: EndRef, b: EndRef, gap: f64) {
        if self.joined[a.slot()].is_some() || self.joined[b.slot()].is_some() {
            return;
        }
        let (ra, rb) = (self.root(a.chain), self.root(b.chain));
        if ra == rb {
            if gap > CLOSING_GAP_OF_LENGTH * self.length[ra] {
                return;
            }
            self.closed[ra] = true;
        } else {
            // The smaller chain index stays the root: merged chains take the first one's place.
            let (keep, into) = (ra.min(rb), ra.max(rb));
            self.parent[into] = keep;
            self.length[keep] += self.length[into] + gap;
        }
        self.joined[a.slot()] = Some(b);
        self.joined[b.slot()] = Some(a);
    }

    /// The merged chains, each in the place of its first part.
    fn into_chains(self, chains: Vec<Chain>) -> Vec<Chain> {
        let mut merged = Vec::new();
        for c in 0..chains.len() {
            if self.root(c) != c {
                continue;
            }
            let untouched = self.joined[2 * c].is_none() && self.joined[2 * c + 1].is_none();
            if untouched {
                merged.push(chains[c].clone());
                continue;
            }
            merged.push(self.walk(&chains, c));
        }
        merged
    }

    /// The vertices of group `root`, from a free end (or the root's front when it closed).
    fn walk(&self, chains: &[Chain], root: usize) -> Chain {
        let start = (root..chains.len())
            .filter(|&c| self.root(c) == root)
            .flat_map(|c| [true, false].map(|front| EndRef { chain: c, front }))
            .find(|end| self.joined[end.slot()].is_none())
            .unwrap_or(EndRef {
                chain: root,
                front: true,
            });
        let mut vertices = std::collections::VecDeque::new();
        let mut at = start;
        loop {
            let chain = &chains[at.chain].vertices;
            if at.front {
                vertices.extend(chain.iter().copied());
            } else {
                vertices.extend(chain.iter().rev().copied());
            }
            let far = EndRef {
                chain: at.chain,
                front: !at.front,
            };
            match self.joined[far.slot()] {
                Some(next) if next != start => at = next,
                _ => break,
            }
        }
        Chain {
            vertices,
            closed: self.closed[root],
        }
    }
}
