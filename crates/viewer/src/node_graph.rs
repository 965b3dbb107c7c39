//! The node hierarchy of a glTF file, checked before it is walked.
//!
//! glTF 2.0 requires the nodes to form disjoint trees. A file from the wild may not:
//! children that form a cycle would make a recursive walk overflow the stack, and a
//! child shared by two parents (or a root listed twice) would be drawn twice, or
//! exponentially often in a chain of shared diamonds. So the loader finds cycles here
//! (an error naming them), and walks the nodes with an explicit stack that draws each
//! node once ([`walk_order`]); nothing recurses on user data.

/// A cycle among the nodes, as the node indices along it (the first repeats at the
/// end), or `None`. `children[i]` lists node `i`'s children; indices past the list
/// are ignored (the glTF validation reports them).
#[must_use]
pub fn find_cycle(children: &[Vec<usize>]) -> Option<Vec<usize>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        OnPath,
        Done,
    }
    let n = children.len();
    let mut mark = vec![Mark::New; n];
    // Each frame: a node and how many of its children have been looked at.
    let mut path: Vec<(usize, usize)> = Vec::new();
    for start in 0..n {
        if mark[start] != Mark::New {
            continue;
        }
        mark[start] = Mark::OnPath;
        path.push((start, 0));
        while let Some(&mut (node, ref mut next)) = path.last_mut() {
            let Some(&child) = children[node].get(*next) else {
                mark[node] = Mark::Done;
                path.pop();
                continue;
            };
            *next += 1;
            match mark.get(child) {
                Some(Mark::New) => {
                    mark[child] = Mark::OnPath;
                    path.push((child, 0));
                }
                Some(Mark::OnPath) => {
                    let from = path.iter().position(|&(p, _)| p == child).unwrap_or(0);
                    let mut cycle: Vec<usize> = path[from..].iter().map(|&(p, _)| p).collect();
                    cycle.push(child);
                    return Some(cycle);
                }
                Some(Mark::Done) | None => {}
            }
        }
    }
    None
}

/// One node to visit: its index and its parent's position in the order (`None` for a
/// root), so a parent's transform and snow value are known when its children come.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Visit {
    /// The node.
    pub node: usize,
    /// Index into the order of its parent's visit.
    pub parent: Option<usize>,
}

/// The nodes under `roots` in depth-first order, each at most once, for an acyclic
/// graph (check with [`find_cycle`] first), with the nodes reached a second time (a
/// shared child, a root listed twice) in the second list.
#[must_use]
pub fn walk_order(children: &[Vec<usize>], roots: &[usize]) -> (Vec<Visit>, Vec<usize>) {
    let mut seen = vec![false; children.len()];
    let mut order = Vec::new();
    let mut again = Vec::new();
    let mut stack: Vec<Visit> = roots
        .iter()
        .rev()
        .map(|&node| Visit { node, parent: None })
        .collect();
    while let Some(visit) = stack.pop() {
        match seen.get_mut(visit.node) {
            Some(true) => again.push(visit.node),
            Some(s) => {
                *s = true;
                let at = order.len();
                order.push(visit);
                stack.extend(children[visit.node].iter().rev().map(|&node| Visit {
                    node,
                    parent: Some(at),
                }));
            }
            None => {}
        }
    }
    (order, again)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn a_two_node_cycle_and_a_self_loop_are_found() {
        assert_eq!(find_cycle(&[vec![1], vec![0]]), Some(vec![0, 1, 0]));
        assert_eq!(find_cycle(&[vec![], vec![1]]), Some(vec![1, 1]));
        assert_eq!(find_cycle(&[vec![1, 2], vec![2], vec![]]), None);
    }

    #[test]
    fn a_deep_chain_is_walked_without_recursion() {
        let n = 200_000;
        let children: Vec<Vec<usize>> = (0..n)
            .map(|i| if i + 1 < n { vec![i + 1] } else { vec![] })
            .collect();
        assert_eq!(find_cycle(&children), None);
        let (order, again) = walk_order(&children, &[0]);
        assert_eq!(order.len(), n);
        assert!(again.is_empty());
    }

    #[test]
    fn shared_children_are_visited_once() {
        // 0 → {1, 2}, 1 → 3, 2 → 3 (a diamond), and root 0 listed twice.
        let children = vec![vec![1, 2], vec![3], vec![3], vec![]];
        let (order, again) = walk_order(&children, &[0, 0]);
        let nodes: Vec<usize> = order.iter().map(|v| v.node).collect();
        assert_eq!(nodes, vec![0, 1, 3, 2]);
        assert_eq!(again, vec![3, 0]);
        assert_eq!(order[2].parent, Some(1));
    }

    proptest! {
        #[test]
        fn random_graphs_never_loop_and_cycles_are_real(
            edges in proptest::collection::vec((0usize..12, 0usize..14), 0..40),
            roots in proptest::collection::vec(0usize..14, 0..6),
        ) {
            let mut children = vec![Vec::new(); 12];
            for (from, to) in edges {
                children[from].push(to);
            }
            match find_cycle(&children) {
                Some(cycle) => {
                    prop_assert_eq!(cycle.first(), cycle.last());
                    for pair in cycle.windows(2) {
                        prop_assert!(children[pair[0]].contains(&pair[1]));
                    }
                }
                None => {
                    let (order, _) = walk_order(&children, &roots);
                    let mut nodes: Vec<usize> = order.iter().map(|v| v.node).collect();
                    let total = nodes.len();
                    nodes.sort_unstable();
                    nodes.dedup();
                    prop_assert_eq!(nodes.len(), total, "a node was visited twice");
                    for (i, v) in order.iter().enumerate() {
                        if let Some(p) = v.parent {
                            prop_assert!(p < i);
                            prop_assert!(children[order[p].node].contains(&v.node));
                        }
                    }
                }
            }
        }
    }
}
