"""Φ_q in block-triangular form: linear solves that grow with the chain, not with its cube.

A mechanism built of groups (dyads, triads, any Assur group) has a constraint
Jacobian that a permutation of rows and columns makes block lower-triangular:
each group's rows involve only its own links and links placed before it.  The
permutation is found once per constraint system from its sparsity pattern —
a maximum matching of rows to columns, then the strongly connected components
of the dependency graph (Tarjan), emitted dependencies first — and each solve
is then one small dense solve per block, in order.  A 200-link chain of dyads
is 100 solves of 6 × 6 instead of one LU of 600 × 600.

Only square systems with a perfect matching are put in this form; anything
else (redundant rows, a structurally singular pattern) keeps the dense path.
The condition number of a block-triangular matrix is not the largest of its
blocks' numbers, but a configuration is singular exactly when one block is:
so singularity is judged block by block, and the null vector reported is the
singular block's own (zero elsewhere), which names the links that lose their
guidance.  Pure numpy; nothing here knows what the rows mean.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["BlockForm", "block_form"]


class BlockForm:
    """The block-triangular order of a square Φ_q, blocks grouped to be solved many at once.

    ``blocks`` lists (rows, columns) of each diagonal block, dependencies
    first.  For solving, blocks are grouped by *level* (a block's level is one
    more than the highest level it depends on: blocks of one level are
    independent of each other) and by size, and each group is one stacked
    (k, s, s) solve: a chain of 100 dyads hanging off one crank is a handful
    of numpy calls, not 100.
    """

    __slots__ = ("blocks", "groups", "size")

    def __init__(self, blocks: list[tuple[np.ndarray, np.ndarray]], size: int, pattern: np.ndarray) -> None:
        self.blocks, self.size = blocks, size
        owner = np.empty(size, int)
        for b, (_, cols) in enumerate(blocks):
            owner[cols] = b
        level = [0] * len(blocks)
        for b, (rows, _) in enumerate(blocks):
            needs = set(owner[np.flatnonzero(pattern[rows].any(axis=0))].tolist()) - {b}
            level[b] = 1 + max((level[d] for d in needs), default=-1)
        grouped: dict[tuple[int, int], list[int]] = {}
        for b, (_, cols) in enumerate(blocks):
            grouped.setdefault((level[b], cols.size), []).append(b)
        self.groups = [
            (np.array([blocks[b][0] for b in members]), np.array([blocks[b][1] for b in members]))
            for _, members in sorted(grouped.items())
        ]

    @property
    def largest(self) -> int:
        """Columns in the largest block (the cube of which bounds one solve's cost)."""
        return max((c.size for _, c in self.blocks), default=0)

    def solve(self, jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """x with ``jac @ x = rhs`` (one pass; raises LinAlgError when a block is singular)."""
        x = np.zeros(self.size)
        for rows, cols in self.groups:
            a = jac[rows[:, :, None], cols[:, None, :]]
            r = rhs[rows] - (jac[rows.ravel()] @ x).reshape(rows.shape)
            x[cols] = np.linalg.solve(a, r[..., None])[..., 0]
        return x

    def condition(self, jac: np.ndarray) -> tuple[float, np.ndarray | None]:
        """Largest block condition number (2-norm) and, for that block, its null direction in q.

        The direction is the block's last right singular vector placed in its
        columns (zero elsewhere): how the configuration can move with every
        equation of that block held to first order.
        """
        worst, vec = 1.0, None
        for rows, cols in self.groups:
            _, s, vt = np.linalg.svd(jac[rows[:, :, None], cols[:, None, :]])
            with np.errstate(divide="ignore"):
                conds = np.where(s[:, -1] > 0, s[:, 0] / s[:, -1], math.inf)
            k = int(np.argmax(conds))
            if vec is None or conds[k] > worst:
                worst = max(worst, float(conds[k]))
                vec = np.zeros(self.size)
                vec[cols[k]] = vt[k, -1]
        return worst, vec


def block_form(pattern: np.ndarray) -> BlockForm | None:
    """The block-triangular form of a square sparsity ``pattern`` (bool, m × m), or None.

    None when the pattern is not square or has no perfect matching (some
    equations cannot each be given an unknown of their own).
    """
    m, n = pattern.shape
    if m != n:
        return None
    row_cols = [np.flatnonzero(pattern[r]).tolist() for r in range(m)]
    match_col = _matching(row_cols, n)  # column -> its row
    if match_col is None:
        return None
    # column j (solved by its matched row) depends on every other column of that row
    deps = [[k for k in row_cols[match_col[j]] if k != j] for j in range(n)]
    blocks = []
    for comp in _components(deps):
        cols = np.array(sorted(comp))
        rows = np.array([match_col[j] for j in cols])
        blocks.append((rows, cols))
    return BlockForm(blocks, n, pattern)


def _matching(row_cols: list[list[int]], n: int) -> list[int] | None:
    """A perfect matching column → row (Kuhn's augmenting paths, iterative), or None."""
    col_row = [-1] * n
    row_col = [-1] * len(row_cols)
    for r0 in range(len(row_cols)):  # cheap greedy start
        for c in row_cols[r0]:
            if col_row[c] < 0:
                col_row[c], row_col[r0] = r0, c
                break
    for r0 in range(len(row_cols)):
        if row_col[r0] >= 0:
            continue
        # breadth-first search for an augmenting path from r0
        parent: dict[int, int] = {}  # column -> row that reached it
        frontier, seen, end = [r0], set(), -1
        while frontier and end < 0:
            nxt = []
            for r in frontier:
                for c in row_cols[r]:
                    if c in seen:
                        continue
                    seen.add(c)
                    parent[c] = r
                    if col_row[c] < 0:
                        end = c
                        break
                    nxt.append(col_row[c])
                if end >= 0:
                    break
            frontier = nxt
        if end < 0:
            return None
        c = end
        while True:  # flip the path
            r = parent[c]
            prev = row_col[r]
            col_row[c], row_col[r] = r, c
            if r == r0:
                break
            c = prev
    return col_row


def _components(deps: list[list[int]]) -> list[list[int]]:
    """Strongly connected components (Tarjan, iterative), each after every component it depends on."""
    n = len(deps)
    index = [-1] * n
    low = [0] * n
    on_stack = [False] * n
    stack: list[int] = []
    out: list[list[int]] = []
    counter = 0
    for root in range(n):
        if index[root] >= 0:
            continue
        work = [(root, 0)]
        while work:
            v, i = work[-1]
            if i == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on_stack[v] = True
            if i < len(deps[v]):
                work[-1] = (v, i + 1)
                w = deps[v][i]
                if index[w] < 0:
                    work.append((w, 0))
                elif on_stack[w]:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                u = work[-1][0]
                low[u] = min(low[u], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack[w] = False
                    comp.append(w)
                    if w == v:
                        break
                out.append(comp)
    return out
