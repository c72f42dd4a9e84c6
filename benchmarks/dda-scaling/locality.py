#!/usr/bin/env python3
"""How local are the open-close iteration's state changes? (section 21)

Reads the trace written by an engine with trace-changes.patch applied
(ROCKDDA_TRACE_CHANGES=FILE):
  A <attempt> <step>            a step attempt begins
  P <block_i> <block_j>         a contact at the attempt's start
  C <it> <block_i> <block_j> <old> <new> <index>
                                a state change at the check of solve <it>

For every solve k >= 2 of an attempt it measures where the changes of
solve k lie relative to the blocks touched by the changes of solve k - 1
(ring distance in the attempt's contact graph: 0 = a block of a changed
contact, 1 = a neighbour of one, ...), how many of them are the same
contact again, and the size of the patch (blocks within r rings of the
previous changes) that a local solve would need.

usage: locality.py TRACE [--rings 3]
"""
import argparse
import collections


def attempts(path):
    """Yields (pairs, changes) per attempt: the start contacts' block pairs
    and {iteration: [(block_i, block_j, index), ...]}."""
    pairs, changes = None, None
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "A":
                if pairs is not None:
                    yield pairs, changes
                pairs, changes = [], collections.defaultdict(list)
            elif w[0] == "P":
                pairs.append((int(w[1]), int(w[2])))
            elif w[0] == "C":
                changes[int(w[1])].append((int(w[2]), int(w[3]), int(w[6])))
    if pairs is not None:
        yield pairs, changes


def distances(adjacency, sources, limit):
    """Ring distance (BFS over the contact graph) from the source blocks,
    up to limit rings."""
    d = {b: 0 for b in sources}
    frontier = list(sources)
    for r in range(1, limit + 1):
        nxt = []
        for b in frontier:
            for n in adjacency.get(b, ()):
                if n not in d:
                    d[n] = r
                    nxt.append(n)
        frontier = nxt
    return d


def main():
    p = argparse.ArgumentParser()
    p.add_argument("trace")
    p.add_argument("--rings", type=int, default=3)
    a = p.parse_args()
    R = a.rings
    hist = collections.Counter()      # ring distance of a change (R+1: beyond)
    hist_union = collections.Counter()  # distance from all earlier changes
    repeats = total = 0
    patch = collections.defaultdict(list)  # r -> patch sizes (blocks)
    n_blocks = collections.Counter()
    per_it = collections.defaultdict(lambda: [0, 0, 0])  # it -> n, d<=1, same
    n_attempts = 0
    for pairs, changes in attempts(a.trace):
        n_attempts += 1
        adjacency = collections.defaultdict(set)
        for i, j in pairs:
            adjacency[i].add(j)
            adjacency[j].add(i)
        n_blocks[len(adjacency)] += 1
        seen = set()
        its = sorted(changes)
        for k in its:
            prev = changes.get(k - 1)
            if k >= 2 and prev:
                src = {b for i, j, _ in prev for b in (i, j)}
                d = distances(adjacency, src, R)
                du = distances(adjacency, seen, R)
                same = {c for _, _, c in prev}
                for r in range(R + 1):
                    patch[r].append(sum(1 for v in d.values() if v <= r))
                for i, j, c in changes[k]:
                    ring = min(d.get(i, R + 1), d.get(j, R + 1))
                    hist[ring] += 1
                    hist_union[min(du.get(i, R + 1), du.get(j, R + 1))] += 1
                    total += 1
                    repeats += c in same
                    s = per_it[min(k, 8)]
                    s[0] += 1
                    s[1] += ring <= 1
                    s[2] += c in same
            seen |= {b for i, j, _ in changes[k] for b in (i, j)}
    blocks = max(n_blocks, key=n_blocks.get) if n_blocks else 0
    print("attempts %d, blocks in contact %d, changes at solves >= 2: %d"
          % (n_attempts, blocks, total))
    if not total:
        return
    print("\nring distance of a change from the blocks of the previous "
          "solve's changes (and from all earlier changes of the attempt):")
    print("| rings | share | cumulative | from all earlier | cumulative |")
    print("|---:|---:|---:|---:|---:|")
    cum = cum_u = 0
    for r in range(R + 2):
        cum += hist[r]
        cum_u += hist_union[r]
        label = str(r) if r <= R else "> %d" % R
        print("| %s | %.1f %% | %.1f %% | %.1f %% | %.1f %% |"
              % (label, 100. * hist[r] / total, 100. * cum / total,
                 100. * hist_union[r] / total, 100. * cum_u / total))
    print("\nsame contact as in the previous solve: %.1f %%"
          % (100. * repeats / total))
    print("\npatch of blocks within r rings of the previous changes "
          "(median, mean, largest; share of the blocks):")
    for r in range(R + 1):
        v = sorted(patch[r])
        print("  r = %d: %d, %.0f, %d (%.1f %% on average)"
              % (r, v[len(v) // 2], sum(v) / len(v), v[-1],
                 100. * sum(v) / len(v) / max(blocks, 1)))
    print("\nper solve: changes, within 1 ring, same contact")
    for k in sorted(per_it):
        n, near, same = per_it[k]
        print("  solve %s: %d, %.1f %%, %.1f %%"
              % ("%d" % k if k < 8 else ">= 8", n, 100. * near / n,
                 100. * same / n))


if __name__ == "__main__":
    main()
