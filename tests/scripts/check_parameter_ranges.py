#!/usr/bin/python3
"""ctest parameters.ranges: every numeric key's declared range matches its
help text (issue 11, item 8).

Runs 'rockdda --print-parameters', reads each key's valid values (deal.II
"[Double A...B (inclusive)]", "[Integer range A...B (inclusive)]" or
rockdda's "[Double x > 0]", "[Double 0 <= x < 90]") and the ranges its help
states ("> 0", ">= 0", "0 <= dip < 90", "in [0, 1]", "0 to 360"). Each
stated end must be the declared end: a key documented as "> 0" must reject
0 while the parameter file is read, one documented as "0 <= phi < 90" must
reject -1 and 90. Exits 1 listing every mismatch.
usage: check_parameter_ranges.py ROCKDDA
"""
import math
import re
import subprocess
import sys

NUMBER = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"


def value(text):
    if text == "MAX_DOUBLE":
        return math.inf
    if text == "-MAX_DOUBLE":
        return -math.inf
    return float(text)


def declared_range(valid):
    """(lower, lower_open, upper, upper_open, integer) or None."""
    m = re.fullmatch(r"\[(Double|Integer range) (-?[\w.+-]+?)\.\.\.(-?[\w.+-]+) "
                     r"\(inclusive\)\]", valid)
    if m:
        return (value(m[2]), False, value(m[3]), False, m[1] != "Double")
    m = re.fullmatch(rf"\[Double ({NUMBER}) (<=?) x (<=?) ({NUMBER})\]", valid)
    if m:
        return (float(m[1]), m[2] == "<", float(m[4]), m[3] == "<", False)
    m = re.fullmatch(rf"\[Double x (>=?|<=?) ({NUMBER})\]", valid)
    if m:
        if m[1].startswith(">"):
            return (float(m[2]), m[1] == ">", math.inf, False, False)
        return (-math.inf, False, float(m[2]), m[1] == "<", False)
    return None


def stated_ends(help_text):
    """Ends the help states: list of (side, bound, open, quote)."""
    ends = []
    for m in re.finditer(rf"({NUMBER}) (<=?) [A-Za-z_]+ (<=?) ({NUMBER})",
                         help_text):
        ends += [("lower", float(m[1]), m[2] == "<", m[0]),
                 ("upper", float(m[4]), m[3] == "<", m[0])]
    for m in re.finditer(rf"\b[Ii]n \[({NUMBER}), ({NUMBER})([\])])(?! *x\b)",
                         help_text):
        ends += [("lower", float(m[1]), False, m[0]),
                 ("upper", float(m[2]), m[3] == ")", m[0])]
    # "> 0", "(> 0)", "; >= 1", "Must be > 0" (not "If > 0, ...").
    for m in re.finditer(rf"(?:^|\(|[;,.] |\bbe )(>=?) ({NUMBER})\b"
                         rf"(?! *[x*/])", help_text):
        ends.append(("lower", float(m[2]), m[1] == ">", m[0].lstrip("(;,. ")))
    for m in re.finditer(rf"(?:\(|, |^)({NUMBER}) to ({NUMBER})\b", help_text):
        ends += [("lower", float(m[1]), False, m[0]),
                 ("upper", float(m[2]), False, m[0])]
    return ends


def consistent(end, declared):
    side, bound, is_open, _ = end
    lo, lo_open, hi, hi_open, integer = declared
    if integer:
        # Integers: x > n is x >= n + 1, x < n is x <= n - 1.
        if side == "lower":
            return (bound + 1 if is_open else bound) == lo
        return (bound - 1 if is_open else bound) == hi
    if side == "lower":
        return bound == lo and is_open == lo_open
    return bound == hi and is_open == hi_open


def main(argv):
    run = subprocess.run([argv[1], "--print-parameters"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print("rockdda --print-parameters failed:", run.stderr)
        return 1
    section, checked, problems = None, 0, []
    for line in run.stdout.splitlines():
        if line.startswith("## "):
            section = line[3:]
            continue
        if not line.startswith("| `"):
            continue
        cells = [c.strip().replace("\\|", "|")
                 for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        key, valid, help_text = cells[0].strip("`"), cells[2], cells[4]
        if not valid.startswith(("[Double", "[Integer")):
            continue
        declared = declared_range(valid)
        name = f"{section} / {key}"
        if declared is None:
            problems.append(f"{name}: cannot read the valid values {valid}")
            continue
        for end in stated_ends(help_text):
            checked += 1
            if not consistent(end, declared):
                problems.append(f"{name}: the help says '{end[3]}' but the "
                                f"declared valid values are {valid}")
    for p in problems:
        print("MISMATCH", p)
    print(f"{checked} stated range ends checked, {len(problems)} mismatches")
    if checked < 50:
        print("too few stated ranges found: is the parser broken?")
        return 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
