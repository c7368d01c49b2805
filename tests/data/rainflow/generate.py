#!/usr/bin/env python3
"""Generate reference.json: rainflow-counting reference data (ASTM E1049-85, 5.4.4).

Uses only the Python standard library plus the PyPI package `rainflow`
(pinned, see README.md). Output is deterministic: same package version ->
byte-identical file.

Run from anywhere:  python3 tests/data/rainflow/generate.py
"""
import json
import math
import os
import sys

import rainflow

EXPECTED_VERSION = "3.2.0"

# Linear congruential generator (Numerical Recipes constants).
LCG_A = 1664525
LCG_C = 1013904223
LCG_M = 2 ** 32


def lcg_series(seed, n):
    """n floats in [-10, 10).

    state_{k+1} = (A * state_k + C) mod M, starting from state_0 = seed;
    the k-th output (k = 0..n-1) uses state_{k+1}:
        value = -10.0 + (20.0 * state) / 2**32
    20*state and the division by 2**32 are exact in IEEE double, so the
    only rounding is the final addition (reproducible in any language as
    `-10.0 + 20.0 * (state as f64) / 4294967296.0`).
    """
    state = seed
    out = []
    for _ in range(n):
        state = (LCG_A * state + LCG_C) % LCG_M
        out.append(-10.0 + (20.0 * state) / 4294967296.0)
    return out


def two_sines(n=500):
    """5*sin(2*pi*i/100) + 1.5*sin(2*pi*i/13), i = 0..n-1, rounded to 6 decimals."""
    return [
        round(5.0 * math.sin(2.0 * math.pi * i / 100.0)
              + 1.5 * math.sin(2.0 * math.pi * i / 13.0), 6)
        for i in range(n)
    ]


def make_series():
    lcg_desc = (
        "LCG state=(a*state+c) mod m, a=%d, c=%d, m=2**32, initial state=seed; "
        "k-th value uses the state after k+1 steps: -10.0 + (20.0*state)/2**32"
        % (LCG_A, LCG_C)
    )
    series = [
        {
            "name": "astm_e1049_example",
            "description": "ASTM E1049-85 section 5.4.4 example load sequence",
            "values": [-2, 1, -3, 5, -1, 3, -4, 4, -2],
        },
    ]
    for seed, n in ((1, 40), (2, 300), (3, 2000)):
        series.append({
            "name": "lcg_seed%d_n%d" % (seed, n),
            "description": lcg_desc,
            "generator": {"kind": "lcg", "a": LCG_A, "c": LCG_C, "m": LCG_M,
                          "seed": seed, "n": n, "low": -10.0, "high": 10.0},
            "values": lcg_series(seed, n),
        })
    series.append({
        "name": "plateaus",
        "description": "plateaus / repeated equal consecutive values",
        "values": [0, 2, 2, 2, 1, 1, 3, 3, 0, 0, 4, -1, -1, 4],
    })
    series.append({
        "name": "plateaus_at_ends",
        "description": "equal values at the start and end, and a flat "
                       "step inside a monotonic run (not a reversal)",
        "values": [1, 1, 3, 3, 3, -2, -2, 0, 0, 0, 2, 2, 5, 5],
    })
    series.append({
        "name": "constant",
        "description": "degenerate: all samples equal (the package yields "
                       "reversals at the first and last index and one "
                       "zero-range half cycle)",
        "values": [3, 3, 3],
    })
    series.append({
        "name": "two_sines_500",
        "description": "round(5*sin(2*pi*i/100) + 1.5*sin(2*pi*i/13), 6), i=0..499",
        "values": two_sines(500),
    })
    for s in series:
        s["values"] = [float(v) for v in s["values"]]
    return series


def analyse(values):
    rev = list(rainflow.reversals(values))
    cycles = [
        {"range": rng, "mean": mean, "count": count,
         "i_start": i_start, "i_end": i_end}
        for rng, mean, count, i_start, i_end in rainflow.extract_cycles(values)
    ]
    counted = [[rng, count] for rng, count in rainflow.count_cycles(values)]
    return {
        "reversals": {"indices": [i for i, _ in rev],
                      "values": [v for _, v in rev]},
        "cycles": cycles,
        "counted": counted,
    }


def _c(obj):
    """Compact JSON; floats via repr (json's default), no NaN/inf."""
    return json.dumps(obj, separators=(",", ":"), allow_nan=False)


def to_json(doc):
    """Compact JSON laid out one field / one cycle per line (diffable)."""
    lines = ["{"]
    for key in ("source", "package", "package_version", "notes"):
        lines.append("%s:%s," % (_c(key), _c(doc[key])))
    lines.append('"series":[')
    for n, s in enumerate(doc["series"]):
        lines.append("{")
        fields = []
        for key, val in s.items():
            if key == "cycles":
                body = ",\n".join(_c(c) for c in val)
                fields.append('"cycles":[\n%s\n]' % body if val else '"cycles":[]')
            else:
                fields.append("%s:%s" % (_c(key), _c(val)))
        lines.append(",\n".join(fields))
        lines.append("}" + ("," if n + 1 < len(doc["series"]) else ""))
    lines.append("]")
    lines.append("}")
    return "\n".join(lines) + "\n"


def main():
    version = getattr(rainflow, "__version__", "unknown")
    if version != EXPECTED_VERSION:
        sys.stderr.write("warning: rainflow %s installed, reference was made "
                         "with %s\n" % (version, EXPECTED_VERSION))
    doc = {
        "source": "rainflow counting per ASTM E1049-85 (2017) section 5.4.4, "
                  "computed with the PyPI package 'rainflow'",
        "package": "rainflow",
        "package_version": version,
        "notes": {
            "count": "count is 1.0 for a full cycle and 0.5 for a half cycle",
            "cycles": "rainflow.extract_cycles(values) in the order yielded; "
                      "range=|x1-x2|, mean=(x1+x2)/2, i_start/i_end are indices "
                      "into values of the two reversals bounding the cycle",
            "counted": "rainflow.count_cycles(values): [range, summed count] "
                       "sorted by range, exact float ranges (no rounding/binning)",
            "reversals": "rainflow.reversals(values): first and last samples are "
                         "always included (index 0 and len-1, even when they lie on a "
                         "plateau); equal consecutive values are skipped, so an "
                         "interior reversal on a plateau gets the index of the "
                         "plateau's last sample",
            "floats": "all values are IEEE doubles written with Python repr "
                      "(shortest round-trip)",
        },
        "series": [],
    }
    for s in make_series():
        entry = dict(s)
        entry.update(analyse(s["values"]))
        doc["series"].append(entry)

    # Sanity check against the table of ASTM E1049-85 section 5.4.4.
    astm = doc["series"][0]
    assert astm["name"] == "astm_e1049_example"
    astm_table = [[3.0, 0.5], [4.0, 1.5], [6.0, 0.5], [8.0, 1.0], [9.0, 0.5]]
    if astm["counted"] != astm_table:
        sys.exit("ASTM example mismatch: got %r, standard says %r"
                 % (astm["counted"], astm_table))

    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference.json")
    with open(out, "w", encoding="utf-8", newline="\n") as f:
        f.write(to_json(doc))
    print("wrote %s (%d bytes)" % (out, os.path.getsize(out)))


if __name__ == "__main__":
    main()
