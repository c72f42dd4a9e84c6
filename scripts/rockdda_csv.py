"""Reading rockdda's CSV tables in the plot scripts (one copy).

read(path) -> (header, rows of floats), skipping blank lines and lines that
start with '#'; table(path) -> the rows as dicts keyed by the header;
column(header, rows, prefix) -> the values of the first
column named prefix or prefix_<unit> (rockdda's headers are name_unit), or
exits with the list of columns.
"""
import csv


def read(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    if not rows:
        raise SystemExit(f"{path} is empty")
    return rows[0], [[float(v) for v in r] for r in rows[1:]]


def column(header, data, prefix):
    for i, name in enumerate(header):
        if name == prefix or name.startswith(prefix + "_"):
            return [r[i] for r in data]
    raise SystemExit(f"no column {prefix!r} in {header}")


def table(path):
    """Rows of a rockdda CSV as dicts keyed by the header (name_unit)."""
    header, data = read(path)
    return [dict(zip(header, r)) for r in data]
