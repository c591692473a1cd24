//! A one-level nested dissection of the KKT graph: two halves and the separator between
//! them, for the two-thread factorization ([`crate::settings::Parallelism`]).
//!
//! The graph is that of the whole KKT matrix (coordinates and constraint rows alike). A
//! breadth-first search from a pseudo-peripheral vertex (George and Liu, "An implementation
//! of a pseudoperipheral node finder", 1979) sorts the vertices into levels; every edge joins
//! two vertices of one level or of adjacent levels, so any one level separates the levels
//! before it from those after it. The level that leaves the two sides closest in size is the
//! separator $S$; its vertices with no neighbour on one side then move to the other side
//! (thinning, which keeps the separation). On the DOG sheet the levels are the fronts of a
//! wave across the page, and the separator is one front.
//!
//! The order is then half $A$, half $B$, separator $S$, each part ordered on its own
//! induced subgraph by the requested [`Ordering`] (faer's AMD on the part, for
//! [`Ordering::Amd`]). With no edge between $A$ and $B$, no fill joins them either: the
//! elimination tree of $A$ climbs into $S$ without passing through $B$, and row $k$ of $L$
//! for $k \in A$ has its columns in $A$ (and likewise for $B$). The up-looking factor can
//! therefore compute the rows of $A$ and of $B$ concurrently, and then those of $S$.
//!
//! With [`Ordering::AmdDelayedDuals`] a constraint row must come after its primal
//! neighbours; a row of $A$ or $B$ with a primal neighbour in $S$ moves into $S$ (the
//! separation holds: $S$ only grows), and each part is then delayed on its own.

use alloc::vec;
use alloc::vec::Vec;

use crate::ordering::{Ordering, permutation};
use crate::pattern::{KktPattern, NONE};

/// The parts of a split order (new indices): half $A$ at `0..a`, half $B$ at `a..b`, the
/// separator at `b..n`. Rows of $L$ in one half have all their columns in that half.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Split {
    /// End of half $A$.
    pub a: usize,
    /// End of half $B$ (start of the separator).
    pub b: usize,
}

/// Part labels.
const HALF_A: u8 = 0;
/// Part labels.
const HALF_B: u8 = 1;
/// Part labels.
const SEPARATOR: u8 = 2;

/// Most pseudo-peripheral search sweeps.
const SWEEPS: usize = 8;

/// Separator levels tried, those that balance the two sides' sizes best.
pub const CANDIDATES: usize = 7;

/// Split orders of `pattern`, one per tried separator level (at most [`CANDIDATES`], the
/// best-balanced by size first): `perm[new] = old` (half $A$, half $B$, separator, each
/// ordered by `ordering` on its own subgraph) and the parts' bounds (module docs). The
/// caller keeps the one whose factor work balances best
/// ([`crate::symbolic::Symbolic::analyse_split`]).
#[must_use]
pub fn split_candidates(pattern: &KktPattern, ordering: Ordering) -> Vec<(Vec<u32>, Split)> {
    let n = pattern.order();
    let (ptr, adj) = adjacency(pattern);
    let neighbours = |v: usize| &adj[ptr[v] as usize..ptr[v + 1] as usize];
    let mut level = vec![NONE; n];
    let mut queue = Vec::with_capacity(n);
    // Pseudo-peripheral root: restart from the least-connected vertex of the last level
    // while the depth grows.
    let mut root = (0..n).min_by_key(|&v| neighbours(v).len()).unwrap_or(0);
    let mut depth = 0;
    for _ in 0..SWEEPS {
        let d = bfs(&ptr, &adj, root, &mut level, &mut queue);
        let last = queue.iter().map(|&v| v as usize).filter(|&v| level[v] == d);
        let far = last.min_by_key(|&v| neighbours(v).len()).unwrap_or(root);
        if d <= depth && depth > 0 {
            break;
        }
        depth = d;
        root = far;
    }
    let depth = bfs(&ptr, &adj, root, &mut level, &mut queue) as usize;
    // Level sizes, and the levels that balance the two sides (unreached vertices go to B).
    let mut count = vec![0usize; depth + 1];
    for &v in &queue {
        count[level[v as usize] as usize] += 1;
    }
    let mut before = 0;
    let mut cuts = Vec::with_capacity(depth + 1);
    for (l, &c) in count.iter().enumerate() {
        let after = n - before - c;
        if l > 0 && l < depth {
            cuts.push((before.abs_diff(after), l as u32));
        }
        before += c;
    }
    if cuts.is_empty() {
        cuts.push((0, 0));
    }
    cuts.sort_unstable();
    cuts.iter()
        .take(CANDIDATES)
        .map(|&(_, cut)| split_at_level(pattern, ordering, (&ptr, &adj), &level, cut))
        .collect()
}

/// The split order with the separator at BFS level `cut` of `level` (depth at least 2;
/// otherwise everything in $B$), on the graph `(ptr, adj)`.
fn split_at_level(
    pattern: &KktPattern,
    ordering: Ordering,
    (ptr, adj): (&[u32], &[u32]),
    level: &[u32],
    cut: u32,
) -> (Vec<u32>, Split) {
    let n = pattern.order();
    let neighbours = |v: usize| &adj[ptr[v] as usize..ptr[v + 1] as usize];
    let mut part: Vec<u8> = level
        .iter()
        .map(|&l| match l {
            NONE => HALF_B,
            l if l < cut => HALF_A,
            l if l == cut && cut > 0 => SEPARATOR,
            _ => HALF_B,
        })
        .collect();
    // Thinning: a separator vertex with no neighbour on one side joins the other.
    for (from, to) in [(HALF_B, HALF_A), (HALF_A, HALF_B)] {
        for v in 0..n {
            if part[v] == SEPARATOR && !neighbours(v).iter().any(|&w| part[w as usize] == from) {
                part[v] = to;
            }
        }
    }
    if ordering == Ordering::AmdDelayedDuals {
        for v in pattern.dofs..n {
            let primal_in_separator = neighbours(v)
                .iter()
                .any(|&w| (w as usize) < pattern.dofs && part[w as usize] == SEPARATOR);
            if part[v] != SEPARATOR && primal_in_separator {
                part[v] = SEPARATOR;
            }
        }
    }
    let mut perm = Vec::with_capacity(n);
    for p in [HALF_A, HALF_B, SEPARATOR] {
        order_part(&mut perm, pattern, &part, p, ordering);
    }
    let size = |p| part.iter().filter(|&&q| q == p).count();
    let a = size(HALF_A);
    let split = Split {
        a,
        b: a + size(HALF_B),
    };
    (perm, split)
}

/// The symmetric graph of `pattern` without its diagonal, as `(ptr, adj)`: vertex $v$'s
/// neighbours at `adj[ptr[v]..ptr[v + 1]]`.
fn adjacency(pattern: &KktPattern) -> (Vec<u32>, Vec<u32>) {
    let n = pattern.order();
    let column =
        |c: usize| &pattern.row_idx[pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize];
    let mut ptr = vec![0u32; n + 1];
    for c in 0..n {
        for &r in column(c).iter().filter(|&&r| r as usize != c) {
            ptr[r as usize + 1] += 1;
            ptr[c + 1] += 1;
        }
    }
    for k in 1..=n {
        ptr[k] += ptr[k - 1];
    }
    let mut next = ptr.clone();
    let mut adj = vec![0u32; ptr[n] as usize];
    for c in 0..n {
        for &r in column(c).iter().filter(|&&r| r as usize != c) {
            for (from, to) in [(r as usize, c as u32), (c, r)] {
                adj[next[from] as usize] = to;
                next[from] += 1;
            }
        }
    }
    (ptr, adj)
}

/// Breadth-first levels from `root`: `level[v]` (or [`NONE`] when unreached), `queue` the
/// reached vertices by level. Returns the deepest level.
fn bfs(ptr: &[u32], adj: &[u32], root: usize, level: &mut [u32], queue: &mut Vec<u32>) -> u32 {
    level.iter_mut().for_each(|l| *l = NONE);
    queue.clear();
    queue.push(root as u32);
    level[root] = 0;
    let mut head = 0;
    while head < queue.len() {
        let v = queue[head] as usize;
        head += 1;
        for &w in &adj[ptr[v] as usize..ptr[v + 1] as usize] {
            if level[w as usize] == NONE {
                level[w as usize] = level[v] + 1;
                queue.push(w);
            }
        }
    }
    queue.last().map_or(0, |&v| level[v as usize])
}

/// Appends to `perm` the vertices labelled `p` in `part`, ordered by `ordering` on their
/// induced subgraph (a pattern of their own, primal unknowns first as in the whole).
fn order_part(perm: &mut Vec<u32>, pattern: &KktPattern, part: &[u8], p: u8, ordering: Ordering) {
    let n = pattern.order();
    let members: Vec<u32> = (0..n as u32).filter(|&v| part[v as usize] == p).collect();
    let mut local = vec![NONE; n];
    for (i, &v) in members.iter().enumerate() {
        local[v as usize] = i as u32;
    }
    // Members ascend, so the local order keeps every stored entry in the upper triangle
    // and every column's rows ascending.
    let mut col_ptr = Vec::with_capacity(members.len() + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for &c in &members {
        let c = c as usize;
        let rows = &pattern.row_idx[pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize];
        row_idx.extend(
            rows.iter()
                .map(|&r| local[r as usize])
                .filter(|&r| r != NONE),
        );
        col_ptr.push(row_idx.len() as u32);
    }
    let dofs = members
        .iter()
        .filter(|&&v| (v as usize) < pattern.dofs)
        .count();
    let sub = KktPattern {
        dofs,
        rows: members.len() - dofs,
        col_ptr,
        row_idx,
        ..KktPattern::default()
    };
    perm.extend(
        permutation(&sub, ordering)
            .iter()
            .map(|&i| members[i as usize]),
    );
}

#[cfg(test)]
mod tests {
    use super::split_candidates;
    use crate::chain::{Chain, entries};
    use crate::ordering::Ordering;
    use crate::pattern::NONE;
    use crate::symbolic::Symbolic;
    use alloc::vec;

    /// Every candidate is a permutation whose halves share no entry, and the chosen
    /// analysis's elimination tree climbs from each half into itself or the separator
    /// only; in the delayed order every constraint row still follows its primal neighbours.
    #[test]
    fn halves_are_separated() {
        for hessian in [false, true] {
            let pattern = Chain::new(40).pattern(hessian);
            let n = pattern.order();
            for ordering in [Ordering::Amd, Ordering::AmdDelayedDuals] {
                let candidates = split_candidates(&pattern, ordering);
                assert!(!candidates.is_empty());
                for (perm, split) in candidates {
                    assert_eq!(perm.len(), n);
                    let mut inverse = vec![NONE; n];
                    for (new, &old) in perm.iter().enumerate() {
                        assert_eq!(inverse[old as usize], NONE, "{old} twice");
                        inverse[old as usize] = new as u32;
                    }
                    let half = |k: u32| {
                        usize::from(k as usize >= split.a) + usize::from(k as usize >= split.b)
                    };
                    assert!(0 < split.a && split.a < split.b && split.b < n, "{split:?}");
                    for (r, c, _) in entries(&pattern) {
                        let (i, j) = (inverse[r], inverse[c]);
                        // Half A is 0, half B is 1: no entry joins them.
                        assert_ne!(half(i) + half(j), 1, "({r}, {c})");
                        let delayed = ordering == Ordering::AmdDelayedDuals;
                        if delayed && r < pattern.dofs && c >= pattern.dofs {
                            assert!(i < j, "row {c} before dof {r}");
                        }
                    }
                }
                let symbolic = Symbolic::analyse_split(&pattern, ordering);
                let split = symbolic.split().unwrap();
                for (k, &p) in symbolic.etree().iter().enumerate().take(split.b) {
                    let inside = if k < split.a {
                        0..split.a
                    } else {
                        split.a..split.b
                    };
                    assert!(p == NONE || inside.contains(&(p as usize)) || p as usize >= split.b);
                }
                let plain = Symbolic::analyse(&pattern, ordering);
                assert_ne!(plain.fingerprint(), symbolic.fingerprint());
                assert_eq!(plain.split(), None);
            }
        }
    }
}
