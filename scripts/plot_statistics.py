#!/usr/bin/python3
"""Plot a rockdda statistics.csv against its first column (usually time).

usage: plot_statistics.py OUTPUT_DIR [COLUMN ...]

Writes OUTPUT_DIR/statistics.png: one panel per unit, with one line per
column of that unit (e.g. all energies in J/m share a panel). The unit of a
column is the suffix of its name as rockdda writes it: '/' is written as
'_' and '^' as 'p', so kinetic_energy_J_m is in J/m, velocity_m_s in m/s,
area_mp2 in m^2. Columns without a unit (counts, coefficients) share a
dimensionless panel. COLUMN restricts the plot to the named columns; an
unknown name is an error listing the columns there are.

The shebang is /usr/bin/python3: the interpreter of Debian's
python3-matplotlib (an 'env python3' may find one without matplotlib).
"""
import csv
import os
import sys

# Unit symbols rockdda writes (SI and the few customary ones it uses).
SYMBOLS = {
    "1", "m", "s", "g", "kg", "J", "N", "Pa", "W", "K", "degC", "deg",
    "rad", "Hz", "day", "year",
}


def _symbol(token):
    """The unit symbol of one encoded token ('mp2' -> 'm^2'), or None."""
    if token in SYMBOLS:
        return token
    base, p, power = token.rpartition("p")
    if p and base in SYMBOLS and power.isdigit():
        return f"{base}^{power}"
    return None


def split_unit(name):
    """Split a column name into (quantity, unit); unit '' if it has none.

    The unit is the longest run of trailing '_'-separated tokens that are
    all unit symbols (at most three: numerator and up to two denominators),
    leaving a non-empty quantity: kinetic_energy_J_m -> ('kinetic energy',
    'J/m'), mp1_ux_m -> ('mp1 ux', 'm'), contacts_open -> ('contacts open',
    '').
    """
    tokens = name.split("_")
    for n in (3, 2, 1):
        if len(tokens) <= n:
            continue
        symbols = [_symbol(t) for t in tokens[-n:]]
        if all(symbols):
            unit = symbols[0]
            if n == 2:
                unit += "/" + symbols[1]
            elif n == 3:
                unit += f"/({symbols[1]} {symbols[2]})"
            return " ".join(tokens[:-n]), unit
    return " ".join(tokens), ""


def label(name):
    """Axis label of a column: 'kinetic energy [J/m]'."""
    quantity, unit = split_unit(name)
    return f"{quantity} [{unit}]" if unit else quantity


def group_by_unit(columns):
    """Group column names by unit, in order of first appearance."""
    groups = {}
    for c in columns:
        groups.setdefault(split_unit(c)[1], []).append(c)
    return groups


def read_statistics(path):
    """Header and rows (floats) of a statistics.csv."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    if not rows:
        raise ValueError(f"{path} is empty")
    header, data = rows[0], []
    for line_no, r in enumerate(rows[1:], start=2):
        if len(r) != len(header):
            raise ValueError(f"{path}:{line_no}: {len(r)} values, "
                             f"{len(header)} columns")
        try:
            data.append([float(v) for v in r])
        except ValueError as e:
            raise ValueError(f"{path}:{line_no}: {e}") from None
    return header, data


def fail(message):
    """Print a one-line error and exit with status 1 (no traceback)."""
    print(f"plot_statistics.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__, file=sys.stderr if len(argv) < 2 else sys.stdout)
        return 2 if len(argv) < 2 else 0
    folder = argv[1]
    path = os.path.join(folder, "statistics.csv")
    if not os.path.isfile(path):
        fail(f"no statistics.csv in '{folder}'")
    try:
        header, data = read_statistics(path)
    except (OSError, ValueError) as e:
        fail(str(e))
    if len(header) < 2:
        fail(f"{path} has no column to plot against '{header[0]}'")
    unknown = [c for c in argv[2:] if c not in header[1:]]
    if unknown:
        fail(f"no column {', '.join(repr(c) for c in unknown)} in {path}; "
             f"columns: {', '.join(header[1:])}")
    wanted = argv[2:] or header[1:]
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail(f"matplotlib is not installed for {sys.executable} "
             "(Debian: apt-get install python3-matplotlib)")

    groups = group_by_unit(wanted)
    x = [r[0] for r in data]
    fig, axes = plt.subplots(len(groups), 1,
                             figsize=(9, 2.2 * len(groups) + 0.8),
                             sharex=True, squeeze=False)
    for ax, (unit, columns) in zip(axes[:, 0], groups.items()):
        for c in columns:
            i = header.index(c)
            ax.plot(x, [r[i] for r in data], lw=0.9,
                    label=split_unit(c)[0])
        ax.set_ylabel(f"[{unit}]" if unit else "[-]", fontsize=8)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axes[-1, 0].set_xlabel(label(header[0]))
    fig.suptitle(folder, fontsize=9)
    fig.tight_layout()
    out = os.path.join(folder, "statistics.png")
    fig.savefig(out, dpi=100)
    print(f"wrote {out} ({len(groups)} panels, {len(wanted)} columns)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
