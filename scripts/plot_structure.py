#!/usr/bin/python3
"""Quick-look plots of a 'cut' run: blocks.png (blocks coloured by area,
edges by tag) and histograms.png (block width and area distributions, as
thesis Fig. 3-5). Usage: plot_structure.py OUTPUT_DIR"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

KIND_COLOURS = {"boundary": "black", "bedding": "tab:blue", "joint": "tab:red",
                "excavation": "tab:green", "split": "tab:orange"}


def read_blocks(path):
    with open(path) as f:
        lines = [l.split("#")[0].split() for l in f]
    lines = [l for l in lines if l]
    assert lines[0] == ["rockdda-blocks", "1"], "not a rockdda block file"
    n = int(lines[1][1])
    vertices = [(float(l[1]), float(l[2])) for l in lines[2:2 + n]]
    pos = 2 + n
    m = int(lines[pos][1])
    pos += 1
    blocks = []
    for _ in range(m):
        k = int(lines[pos][2])
        rows = lines[pos + 1:pos + 1 + k]
        blocks.append([(int(r[0]), r[1], int(r[2])) for r in rows])
        pos += 1 + k
    return vertices, blocks


def save(fig, path):
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=150)
    os.replace(tmp, path)


def main(folder):
    vertices, blocks = read_blocks(os.path.join(folder, "blocks.txt"))
    polys = [[vertices[v] for v, _, _ in b] for b in blocks]
    fig, ax = plt.subplots(figsize=(10, 7))
    import random
    rnd = random.Random(1)
    ax.add_collection(PolyCollection(
        polys, facecolors=[plt.cm.Pastel1(rnd.random()) for _ in polys],
        edgecolors="none"))
    segments = {k: [] for k in KIND_COLOURS}
    for b in blocks:
        for i, (v, kind, _) in enumerate(b):
            w = b[(i + 1) % len(b)][0]
            segments.setdefault(kind, []).append([vertices[v], vertices[w]])
    for kind, seg in segments.items():
        if seg:
            ax.add_collection(LineCollection(
                seg, colors=KIND_COLOURS.get(kind, "grey"), linewidths=0.6,
                label=f"{kind} ({len(seg)} block edges)"))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{len(blocks)} blocks")
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    save(fig, os.path.join(folder, "blocks.png"))
    plt.close(fig)

    import csv
    with open(os.path.join(folder, "statistics.csv")) as f:
        rows = list(csv.DictReader(f))
    width = [float(r["width_m"]) for r in rows]
    area = [float(r["area_mp2"]) for r in rows]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    a1.hist(width, bins=30, color="tab:blue", edgecolor="white")
    a1.set_xlabel("block width along bedding (m)")
    a1.set_ylabel("number of blocks")
    a2.hist(area, bins=30, color="tab:red", edgecolor="white")
    a2.set_xlabel("block area (m$^2$)")
    a2.set_ylabel("number of blocks")
    fig.suptitle(f"{len(rows)} blocks: width and area distributions")
    fig.tight_layout()
    save(fig, os.path.join(folder, "histograms.png"))
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
