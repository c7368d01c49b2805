#!/usr/bin/env python3
"""Convert the real-wire measurements of Chen, Bretl & Pham (arXiv 2310.00911)
from github.com/qj25/adapteddlo_muj (MIT) into plain TOML/CSV files.

Python 3.11+ standard library only (numpy is not installed here, so the
numpy pickles of the repo are decoded by a restricted stub unpickler).

Usage:
    python3 scripts/convert_chen2023.py [--git-dir DIR] [--commit SHA] [--out DIR]

The git directory is a clone (or `cable-dict`'s library snapshot) of the upstream repository;
the default output is tests/data/real_cables/chen2023, where the converted files are kept.

Input is read straight from the fetched git snapshot with `git show`, so the
exact upstream commit is pinned.  See NOTES.md for frames and caveats.
"""
import argparse
import csv
import io
import math
import os
import pickle
import re
import shutil
import struct
import subprocess
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_GIT = "/work/.mirror/qj25+adapteddlo_muj/repo"
DEFAULT_COMMIT = "6ed3708cf202d33f8a85d27f17c2a6925c5ee7fa"
UPSTREAM = "https://github.com/qj25/adapteddlo_muj"

WIRES = ["white", "black", "red"]
N_POSES = 4

# ---------------------------------------------------------------------------
# constants transcribed from upstream scripts (see NOTES.md for file/line refs)
# ---------------------------------------------------------------------------
ARM_LEN = 0.40  # scripts/test_shape_w_arm.py: r_len = 0.40
# weighed mass / weighed length (kg, m) in scripts/test_shape_w_arm.py
MASS = {"white": (0.087, 5.0), "black": (0.079, 2.98), "red": (0.043, 2.0)}
# scripts/real2sim_paramiden.py uses 0.081/2.98 for black (discrepancy, noted)
MASS_ALT = {"black": (0.081, 2.98)}
# robot EEF start pose (world frame of the MuJoCo scene), envs/rnrvalid2.py
INIT_POS = [0.385, 0.0, 0.3]
INIT_QUAT = [0.707, 0.0, 0.707, 0.0]  # MuJoCo (w,x,y,z); normalised below
# scripts/test_shape_w_arm.py
MOVE_POS = [[0.20, -0.1, -0.15], [0.095, 0.0, 0.0], [0.2, 0.1, 0.1], [0.2, 0.1, 0.1]]
MOVE_POS_X_SHIFT = -0.035
MOVE_AA_DEG = [[30.0, -40.0, 0.0], [0.0, 0.0, 0.0], [50.0, 10.0, 0.0], [50.0, 20.0, -10.0]]
Z_ROT_DEG = [360.0, -720.0, 360.0, -720.0]
# fixed clamp (teststand at x=0.793, cable exit one half-segment inwards);
# confirmed by node 0 of every stored simulation = (0.785, 0, 0.3)
FIXED_EXIT = [0.785, 0.0, 0.3]
# Azure Kinect NFOV conversion used by upstream utils/finddepth.py
CAM_IMG = (640, 576)
CAM_FOV_DEG = (75.0, 65.0)
# ring (Michell-type) test, scripts/get_pos/dlomuj_2Dpos.py & real2sim_paramiden.py
RING_LEN = 1.5
RING_CLAMP_DIST = 0.12
RING_CRIT_TWIST_DEG = {
    "white": [970.0, 970.0, 980.0, 975.0, 980.0],
    "black": [470.0, 500.0, 480.0, 470.0, 490.0],
    "red": [430.0, 470.0, 445.0, 445.0, 460.0],
}
RING_B_A_TRIALS = {  # per-trial beta/alpha listed in real2sim_paramiden.py
    "white": [0.8291015625, 0.8291015625, 0.8232421875, 0.8232421875, 0.8232421875],
    "black": [1.5205078125, 1.3857421875, 1.4736328125, 1.3857421875, 1.4267578125],
    "red": [1.7724609375, 1.5263671875, 1.6669921875, 1.6669921875, 1.5791015625],
}
MODELS = {"adapt": "adapted", "native": "native", "adapt2": "j-DER"}

# ---------------------------------------------------------------------------
# restricted numpy-pickle decoder (stdlib only)
# ---------------------------------------------------------------------------
_FMT = {"f8": "d", "f4": "f", "i8": "q", "i4": "i", "i2": "h", "u1": "B", "b1": "?"}


class _DType:
    def __init__(self, name, *a):
        self.name, self.order = name, "<"

    def __setstate__(self, st):
        if st[1] in "<>":
            self.order = st[1]


def _decode(dt, raw):
    f = _FMT[dt.name]
    return list(struct.unpack(dt.order + f * (len(raw) // struct.calcsize(f)), raw))


def _reshape(flat, shape):
    if not shape:
        return flat[0]
    if len(shape) == 1:
        return list(flat)
    step = 1
    for s in shape[1:]:
        step *= s
    return [_reshape(flat[i * step:(i + 1) * step], shape[1:]) for i in range(shape[0])]


class _ND:
    def __init__(self, *a):
        self.value = None

    def __setstate__(self, st):
        _, shape, dt, fortran, raw = st
        if fortran:
            raise ValueError("fortran arrays unsupported")
        flat = raw if isinstance(raw, list) else _decode(dt, raw)
        self.value = _reshape(flat, list(shape))


class _Unpickler(pickle.Unpickler):
    def find_class(self, module, name):
        if module.startswith("numpy"):
            table = {"_reconstruct": lambda *a: _ND(), "ndarray": _ND, "dtype": _DType,
                     "scalar": lambda dt, raw: _decode(dt, raw)[0]}
            if name in table:
                return table[name]
        raise pickle.UnpicklingError(f"refusing global {module}.{name}")


def _unwrap(o):
    if isinstance(o, _ND):
        return _unwrap(o.value)
    if isinstance(o, (list, tuple)):
        return [_unwrap(x) for x in o]
    return o


# ---------------------------------------------------------------------------
# small linear algebra
# ---------------------------------------------------------------------------
def add(a, b): return [x + y for x, y in zip(a, b)]
def sub(a, b): return [x - y for x, y in zip(a, b)]
def mul(a, s): return [x * s for x in a]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm(a): return math.sqrt(dot(a, a))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def matvec(M, v): return [dot(r, v) for r in M]
def matT(M): return [list(c) for c in zip(*M)]
def matmul(A, B): return [[dot(r, c) for c in zip(*B)] for r in A]
def plen(P): return sum(norm(sub(P[i + 1], P[i])) for i in range(len(P) - 1))


def rodrigues(axis, ang):
    ux, uy, uz = mul(axis, 1.0 / norm(axis))
    c, s = math.cos(ang), math.sin(ang)
    return [[c + ux * ux * (1 - c), ux * uy * (1 - c) - uz * s, ux * uz * (1 - c) + uy * s],
            [uy * ux * (1 - c) + uz * s, c + uy * uy * (1 - c), uy * uz * (1 - c) - ux * s],
            [uz * ux * (1 - c) - uy * s, uz * uy * (1 - c) + ux * s, c + uz * uz * (1 - c)]]


def quat2mat(q):
    w, x, y, z = mul(q, 1.0 / norm(q))
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def mat2quat(R):
    tr = R[0][0] + R[1][1] + R[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [0.25 * s, (R[2][1] - R[1][2]) / s, (R[0][2] - R[2][0]) / s, (R[1][0] - R[0][1]) / s]
    elif R[0][0] > R[1][1] and R[0][0] > R[2][2]:
        s = math.sqrt(1.0 + R[0][0] - R[1][1] - R[2][2]) * 2
        q = [(R[2][1] - R[1][2]) / s, 0.25 * s, (R[0][1] + R[1][0]) / s, (R[0][2] + R[2][0]) / s]
    elif R[1][1] > R[2][2]:
        s = math.sqrt(1.0 + R[1][1] - R[0][0] - R[2][2]) * 2
        q = [(R[0][2] - R[2][0]) / s, (R[0][1] + R[1][0]) / s, 0.25 * s, (R[1][2] + R[2][1]) / s]
    else:
        s = math.sqrt(1.0 + R[2][2] - R[0][0] - R[1][1]) * 2
        q = [(R[1][0] - R[0][1]) / s, (R[0][2] + R[2][0]) / s, (R[1][2] + R[2][1]) / s, 0.25 * s]
    if q[0] < 0:
        q = mul(q, -1.0)
    return q


def aa2mat(vec):
    a = norm(vec)
    if a < 1e-12:
        return [[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]]
    return rodrigues(vec, a)


# camera frame C (x right, y = depth, z up) -> world W of the MuJoCo scene:
# upstream compares real points with sim nodes whose x and y are negated.
FLIP = [[-1.0, 0, 0], [0, -1.0, 0], [0, 0, 1.0]]


# ---------------------------------------------------------------------------
# faithful ports of upstream utils/finddepth.py
# ---------------------------------------------------------------------------
def locatepointin3d(p):
    half = [int(CAM_IMG[0] / 2), int(CAM_IMG[1] / 2)]
    hf = [math.radians(f) / 2 for f in CAM_FOV_DEG]
    ang = [(p[i] - half[i]) / half[i] * hf[i] for i in range(2)]
    y = p[2]
    return [y * math.tan(ang[0]), y, -y * math.tan(ang[1])]


def split_lines(P, seg_len, leftover=None):
    out = [list(P[0])]
    if leftover is None:
        leftover = seg_len / 2
    for i in range(len(P) - 1):
        part = norm(sub(P[i + 1], P[i]))
        d = mul(sub(P[i + 1], P[i]), 1.0 / part)
        part += leftover
        n = int(part / seg_len)
        for j in range(n):
            out.append(add(P[i], mul(d, (j + 1) * seg_len - leftover)))
        leftover = part - n * seg_len
    if leftover > 1e-5:
        out.append(list(P[-1]))
    return out


def split_lines2(P, n_pieces):
    return split_lines(P, plen(P) / n_pieces, 0.0)


def adjust_linestandard(P, se_axis):
    """rotate about P[0] (=origin) so chord || se_axis, then scale along it."""
    end = sub(P[-1], P[0])
    goal = mul(se_axis, norm(end) / norm(se_axis))
    mid = mul(add(end, goal), 0.5)
    ax = cross(mid, sub(goal, end))
    if norm(ax) < 1e-15:
        Q = [list(p) for p in P]
    else:
        ang = -math.asin(min(1.0, norm(sub(mid, end)) / norm(end))) * 2.0
        R = rodrigues(ax, ang)
        Q = [matvec(matT(R), p) for p in P]  # upstream: points @ R
    a = mul(se_axis, 1.0 / norm(se_axis))
    s = norm(se_axis) / norm(end)
    return [add(q, mul(a, (s - 1.0) * dot(q, a))) for q in Q]


def scale_perp(P, axis, s):
    a = mul(axis, 1.0 / norm(axis))
    out = []
    for p in P:
        proj = mul(a, dot(p, a))
        out.append(add(mul(sub(p, proj), s), proj))
    return out


def optimize_through_axisscale(P, se_axis, r_len):
    """scale components perpendicular to the chord until polyline length = r_len
    (upstream uses an ad-hoc bisection to |dL|<1e-5; we bisect to 1e-12)."""
    f = lambda s: plen(scale_perp(P, se_axis, s)) - r_len
    lo, hi = 0.0, 1.0
    while f(hi) < 0:
        hi *= 2.0
        if hi > 1e6:
            raise RuntimeError("cannot reach target length")
    if f(lo) > 0:  # chord alone already longer than r_len
        return scale_perp(P, se_axis, 0.0), 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-14:
            break
    s = 0.5 * (lo + hi)
    return scale_perp(P, se_axis, s), s


# ---------------------------------------------------------------------------
# repo access
# ---------------------------------------------------------------------------
class Repo:
    def __init__(self, git_dir, commit):
        self.git_dir, self.commit = git_dir, commit
        self.used = []

    def raw(self, path):
        self.used.append(path)
        return subprocess.run(["git", "--git-dir", self.git_dir, "show", f"{self.commit}:{path}"],
                              check=True, capture_output=True).stdout

    def text(self, path):
        return self.raw(path).decode("utf-8")

    def pickle(self, path):
        return _unwrap(_Unpickler(io.BytesIO(self.raw(path))).load())


# ---------------------------------------------------------------------------
# published figure: bar heights of data/figs/plgn/valid_bars2.pdf
# ---------------------------------------------------------------------------
def figure_errors(repo, path="adapteddlo_muj/data/figs/plgn/valid_bars2.pdf"):
    d = repo.raw(path)
    streams = []
    for m in re.finditer(rb"stream\r?\n(.*?)\r?\nendstream", d, re.S):
        try:
            streams.append(zlib.decompress(m.group(1)))
        except zlib.error:
            pass
    c = max(streams, key=len).decode("latin1").replace("\x00", "")
    ticks = [float(t) for t in re.findall(r"[\d.]+ ([\d.]+) m\n59\.41875 [\d.]+ l", c)]
    labels = re.findall(r"\[ \((\d\.\d\d)\) \] TJ", c)
    vals = [float(l.replace(" ", "")) for l in labels]
    assert len(ticks) == len(vals) >= 2, (ticks, vals)
    y0, y1, v0, v1 = ticks[0], ticks[-1], vals[0], vals[-1]
    rects = re.findall(r"\n([\d.]+) ([\d.]+) m\n([\d.]+) ([\d.]+) l\n([\d.]+) ([\d.]+) l\n"
                       r"([\d.]+) ([\d.]+) l\nh\n", c)
    bars = []
    for r in rects:
        xs = [float(r[i]) for i in (0, 2, 4, 6)]
        ys = [float(r[i]) for i in (1, 3, 5, 7)]
        if abs(min(ys) - y0) < 1e-3 and max(xs) - min(xs) < 30:
            bars.append(v0 + (max(ys) - y0) / (y1 - y0) * (v1 - v0))
    # plotting order (utils/plotter.py plot_bars_more, called from
    # scripts/plugin_test/simvreal_dlomuj_demo.py): wire (white, black, red) x
    # model (j-DER, adapted, native) x pose 1..4, each wire followed by 4 zero-height legend bars.
    out = {}
    k = 0
    for w in WIRES:
        for m in ["adapt2", "adapt", "native"]:
            out[(w, m)] = bars[k:k + 4]
            k += 4
        assert all(abs(b) < 1e-9 for b in bars[k:k + 4])  # zero-height legend bars
        k += 4
    return out


# ---------------------------------------------------------------------------
# TOML / CSV writers
# ---------------------------------------------------------------------------
def tval(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return repr(round(v, 10)) if abs(v) >= 1e-4 or v == 0 else f"{v:.10e}"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        if v and isinstance(v[0], (list, tuple)):
            return "[\n" + "".join("  " + tval(x) + ",\n" for x in v) + "]"
        return "[" + ", ".join(tval(x) for x in v) + "]"
    raise TypeError(type(v))


def write_toml(path, doc, header=""):
    lines = [header] if header else []
    scal = {k: v for k, v in doc.items() if not isinstance(v, dict)}
    for k, v in scal.items():
        lines.append(f"{k} = {tval(v)}")

    def emit(prefix, d):
        sc = {k: v for k, v in d.items() if not isinstance(v, dict)}
        sub_ = {k: v for k, v in d.items() if isinstance(v, dict)}
        if sc:
            lines.append("")
            lines.append(f"[{prefix}]")
            for k, v in sc.items():
                lines.append(f"{k} = {tval(v)}")
        for k, v in sub_.items():
            emit(f"{prefix}.{k}", v)

    for k, v in doc.items():
        if isinstance(v, dict):
            emit(k, v)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([f"{x:.9g}" if isinstance(x, float) else x for x in r])


# ---------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--git-dir", default=DEFAULT_GIT)
    ap.add_argument("--commit", default=DEFAULT_COMMIT)
    ap.add_argument("--out", default=os.path.join(HERE, "..", "tests", "data", "real_cables", "chen2023"))
    a = ap.parse_args()
    repo = Repo(a.git_dir, a.commit)
    out = a.out
    # Only what this script writes is replaced (NOTES.md beside it is kept).
    for generated in ("arm", "ring"):
        if os.path.isdir(os.path.join(out, generated)):
            shutil.rmtree(os.path.join(out, generated))
    for d in ("", "arm", "ring"):
        os.makedirs(os.path.join(out, d), exist_ok=True)

    with open(os.path.join(out, "LICENSE.adapteddlo_muj"), "wb") as f:
        f.write(repo.raw("LICENSE"))

    source = {"repository": UPSTREAM, "commit": a.commit,
              "paper": "Chen, Bretl, Pham: Accurate Simulation and Parameter Identification of "
                       "Deformable Linear Objects using Discrete Elastic Rods in Generalized "
                       "Coordinates, arXiv:2310.00911", "license": "MIT (c) 2024 qjchen"}

    # ---------------- wire parameters ----------------
    wires = {}
    for w in WIRES:
        ad = repo.pickle(f"adapteddlo_muj/data/dlo_muj_real/stiff_vals/{w}_adapt_stiff.pickle")
        na = repo.pickle(f"adapteddlo_muj/data/dlo_muj_real/stiff_vals/{w}_native_stiff.pickle")
        m, L = MASS[w]
        wires[w] = {
            "EI_Nm2": ad[0], "GJ_Nm2": ad[0] * ad[1], "GJ_over_EI": ad[1],
            "EI_Nm2_native_model": na[0], "GJ_Nm2_native_model": na[0] * na[1],
            "GJ_over_EI_native_model": na[1],
            "mass_kg_per_m": m / L, "weighed_mass_kg": m, "weighed_length_m": L,
            "diameter_m": float("nan"),
        }
        if w in MASS_ALT:
            m2, L2 = MASS_ALT[w]
            wires[w]["mass_kg_per_m_alt_real2sim_paramiden"] = m2 / L2
    write_toml(os.path.join(out, "wires.toml"),
               {"source": source, **{w: wires[w] for w in WIRES}},
               "# Identified stiffness (adapted-DER model = the paper's model; GJ = EI * beta/alpha)\n"
               "# and weighed mass. diameter_m = nan: not found in the repository.")

    # ---------------- arm cases ----------------
    fig = figure_errors(repo)
    pts_all = repo.pickle("adapteddlo_muj/data/pts_all.pickle")  # [black, red, white][pose][11][3]
    pa_idx = {"black": 0, "red": 1, "white": 2}
    sims = {}
    for m in MODELS:
        for w in WIRES:
            for k in range(N_POSES):
                s = repo.pickle(f"adapteddlo_muj/data/simdata/plugin/simdata_{w}{k}_{m}.pickle")
                sims[(m, w, k)] = s  # [init_qpos, z_rot, nodes(51x3), joint_pos(6)]
    r_len_auth = plen(sims[("adapt2", "black", 0)][2])  # first file loaded upstream

    qi = mul(INIT_QUAT, 1.0 / norm(INIT_QUAT))
    R_init = quat2mat(qi)
    # fixed clamp material frame at the exit: t=-X, d1=+Y, d2=-Z (columns)
    R_fixed = [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]
    summary = []
    for w in WIRES:
        for k in range(N_POSES):
            cid = f"{w}_pose{k + 1}"
            mp = list(MOVE_POS[k])
            mp[0] += MOVE_POS_X_SHIFT
            p_rob = add(INIT_POS, mp)
            R_eef = matmul(R_init, aa2mat([math.radians(x) for x in MOVE_AA_DEG[k]]))
            ex, ey, ez = [list(c) for c in zip(*R_eef)]
            # material frame of the rod at the robot clamp (t = arc-length tangent)
            R_rob = matT([mul(ez, -1.0), ey, ex])
            # --- measured points
            csvp = f"adapteddlo_muj/data/data3d/{w}{k}.csv"
            picked = [[float(x) for x in l.split(",")] for l in repo.text(csvp).splitlines() if l.strip()]
            xyz = [locatepointin3d(p) for p in picked]
            raw_len_mm = plen(xyz)
            sc = ARM_LEN / raw_len_mm
            picked_cam = [mul(p, sc) for p in xyz]
            P_cam = pts_all[pa_idx[w]][k]  # == split_lines(picked_cam, 0.04, 0.0)
            chk = split_lines(picked_cam, ARM_LEN / 10, 0.0)
            assert len(chk) == len(P_cam) and max(norm(sub(a_, b_)) for a_, b_ in zip(chk, P_cam)) < 1e-9
            rel_cam = [sub(p, P_cam[0]) for p in P_cam]
            unal = [add(FIXED_EXIT, matvec(FLIP, p)) for p in rel_cam]
            picked_w = [add(FIXED_EXIT, matvec(FLIP, sub(p, picked_cam[0]))) for p in picked_cam]
            se_cmd_cam = matvec(FLIP, sub(p_rob, FIXED_EXIT))
            al_cam, s_perp = optimize_through_axisscale(adjust_linestandard(rel_cam, se_cmd_cam),
                                                        se_cmd_cam, ARM_LEN)
            al = [add(FIXED_EXIT, matvec(FLIP, p)) for p in al_cam]
            chord_real = matvec(FLIP, rel_cam[-1])
            chord_cmd = sub(p_rob, FIXED_EXIT)
            ang_mis = math.degrees(math.acos(max(-1.0, min(1.0, dot(chord_real, chord_cmd) /
                                                             (norm(chord_real) * norm(chord_cmd))))))
            # --- authors' error metric recomputed per model
            errs = {}
            sim_rows = []
            for m, mname in MODELS.items():
                nodes = sims[(m, w, k)][2]
                for i, p in enumerate(nodes):
                    sim_rows.append([mname, i] + p)
                n11 = split_lines2(nodes, 10)
                n11c = [matvec(FLIP, sub(p, n11[0])) for p in n11]  # upstream negates x,y
                se = sub(n11c[-1], n11c[0])
                real_al, _ = optimize_through_axisscale(adjust_linestandard(rel_cam, se), se, r_len_auth)
                dd = [norm(sub(a_, b_)) for a_, b_ in zip(n11c, real_al)]
                errs[mname] = {
                    "normalized_mean_error_recomputed": sum(dd) / len(dd) / r_len_auth,
                    "normalized_mean_error_published_figure": fig[(w, m)][k],
                    "mean_dist_m_recomputed": sum(dd) / len(dd),
                    "max_dist_m_recomputed": max(dd),
                    "rms_dist_m_recomputed": math.sqrt(sum(x * x for x in dd) / len(dd)),
                    "sim_end_node_m": nodes[-1],
                    "sim_z_rot_deg": math.degrees(sims[(m, w, k)][1]),
                }
            # --- write case
            doc = {
                "case_id": cid, "wire": w, "pose": k + 1,
                "wire_params": {"length_m": ARM_LEN, **{kk: wires[w][kk] for kk in
                                ("EI_Nm2", "GJ_Nm2", "mass_kg_per_m", "diameter_m")}},
                "frame": {
                    "name": "W (MuJoCo world of upstream envs/rnrvalid2.py)",
                    "units": "m", "gravity_m_s2": [0.0, 0.0, -9.81],
                    "rotation_convention": "matrix columns = (t, d1, d2) of the rod material frame in W; "
                                           "t = unit tangent in the direction of increasing arc length "
                                           "(fixed clamp -> robot clamp); quaternions (w,x,y,z)",
                },
                "start_clamp": {
                    "role": "fixed clamp on stand (arc length s=0)",
                    "position_m": FIXED_EXIT, "rotation_matrix": R_fixed, "quat_wxyz": mat2quat(R_fixed),
                    "cable_leaves_along": "+t = -X_world",
                },
                "end_clamp": {
                    "role": "robot (Denso VS-060) gripper (s=L)",
                    "position_m": p_rob, "rotation_matrix": R_rob, "quat_wxyz": mat2quat(R_rob),
                    "eef_site_rotation_matrix": R_eef, "eef_site_quat_wxyz": mat2quat(R_eef),
                    "cable_leaves_along": "-t = +z of eef site (back towards the fixed clamp)",
                    "commanded_offset_from_eef_start_m": mp,
                    "commanded_rotation_vector_deg_eef_local": MOVE_AA_DEG[k],
                    "joint_positions_rad_used_on_robot": [float(x) for x in
                        repo.text(f"adapteddlo_muj/data/excel/jointpos{k}.csv").split()],
                },
                "twist": {
                    "added_twist_deg_authors_sign": Z_ROT_DEG[k],
                    "authors_sign_meaning": "right-handed rotation of the fixed clamp about world +X "
                                            "(= about -t); applied after the robot reached the pose",
                    "added_twist_deg_about_t": -Z_ROT_DEG[k],
                    "sign_certainty": "simulation convention certain; mapping to the physical "
                                      "turning direction not verifiable from the repo",
                },
                "measurement": {
                    "sensor": "Azure Kinect depth (640x576 NFOV, 75x65 deg FOV), points hand-picked",
                    "source_csv": csvp, "n_picked": len(picked),
                    "picked_polyline_length_before_rescale_m": raw_len_mm / 1000.0,
                    "note": "points were rescaled by upstream so the picked polyline is 0.4 m, "
                            "then resampled at 0.04 m chords (11 pts); first point = fixed clamp",
                    "chord_unaligned_m": chord_real, "chord_commanded_m": chord_cmd,
                    "chord_angle_mismatch_deg": ang_mis,
                    "perp_scale_factor_aligned": s_perp,
                    "points_aligned_m": al,
                    "points_unaligned_m": unal,
                    "points_camera_frame_m": P_cam,
                },
                "authors_error": {
                    "metric": "mean over 11 equal-arc-length points of |sim - aligned real| / L "
                              "(scripts/plugin_test/simvreal_dlomuj_demo.py); 'published_figure' = bar "
                              "heights read from data/figs/plgn/valid_bars2.pdf",
                    "L_used_m": r_len_auth,
                    **errs,
                },
            }
            write_toml(os.path.join(out, "arm", cid + ".toml"), {"source": source, **doc},
                       f"# {cid}: real wire, one end clamped, other held by robot. See NOTES.md.")
            s_al = [0.0]
            for i in range(1, len(al)):
                s_al.append(s_al[-1] + norm(sub(al[i], al[i - 1])))
            write_csv(os.path.join(out, "arm", cid + "_points.csv"),
                      ["i", "s_aligned_m", "x_m", "y_m", "z_m", "x_unaligned_m", "y_unaligned_m",
                       "z_unaligned_m", "x_cam_m", "y_cam_m", "z_cam_m"],
                      [[i, s_al[i]] + al[i] + unal[i] + P_cam[i] for i in range(len(al))])
            write_csv(os.path.join(out, "arm", cid + "_picked.csv"),
                      ["i", "u_px", "v_px", "depth_mm", "x_unaligned_m", "y_unaligned_m", "z_unaligned_m"],
                      [[i] + picked[i] + picked_w[i] for i in range(len(picked))])
            write_csv(os.path.join(out, "arm", cid + "_authors_sim.csv"),
                      ["model", "node", "x_m", "y_m", "z_m"], sim_rows)
            summary.append([cid, w, k + 1, ARM_LEN, wires[w]["EI_Nm2"], wires[w]["GJ_Nm2"],
                            wires[w]["mass_kg_per_m"], Z_ROT_DEG[k]] + p_rob + mat2quat(R_rob) +
                           [len(al), ang_mis] +
                           [errs[MODELS[m]]["normalized_mean_error_published_figure"] for m in MODELS] +
                           [errs[MODELS[m]]["normalized_mean_error_recomputed"] for m in MODELS] +
                           [errs["adapted"]["mean_dist_m_recomputed"], errs["adapted"]["max_dist_m_recomputed"]])
    write_csv(os.path.join(out, "arm_summary.csv"),
              ["case_id", "wire", "pose", "length_m", "EI_Nm2", "GJ_Nm2", "mass_kg_per_m",
               "twist_deg_authors_sign", "end_x_m", "end_y_m", "end_z_m", "end_qw", "end_qx", "end_qy",
               "end_qz", "n_points", "chord_mismatch_deg",
               "fig_err_adapted", "fig_err_native", "fig_err_jDER",
               "recomp_err_adapted", "recomp_err_native", "recomp_err_jDER",
               "adapted_mean_dist_m", "adapted_max_dist_m"], summary)

    # ---------------- ring (bending identification) ----------------
    ring_rows = []
    for w in WIRES:
        for i in range(5):
            src = f"adapteddlo_muj/data/dlo_muj_real/{w}{i}_data.pickle"
            pts, (px, start_px) = repo.pickle(src)
            ei_a = repo.pickle(f"adapteddlo_muj/data/dlo_muj_real/stiff_vals/{w}_adapt_{i}_bendstiff.pickle")
            ei_n = repo.pickle(f"adapteddlo_muj/data/dlo_muj_real/stiff_vals/{w}_native_{i}_bendstiff.pickle")
            name = f"{w}_photo{i}"
            write_csv(os.path.join(out, "ring", name + ".csv"), ["i", "u_m", "v_m", "u_px_rel", "v_px_rel"],
                      [[j] + pts[j] + px[j] for j in range(len(pts))])
            ring_rows.append([name, w, i, RING_LEN, RING_CLAMP_DIST, len(pts), plen(pts)] + pts[-1] +
                             list(start_px) + [ei_a, ei_n, RING_CRIT_TWIST_DEG[w][i], RING_B_A_TRIALS[w][i],
                                               wires[w]["mass_kg_per_m"]])
    write_csv(os.path.join(out, "ring_summary.csv"),
              ["photo_id", "wire", "photo", "length_m", "clamp_distance_nominal_m", "n_points",
               "polyline_length_m", "end_u_m", "end_v_m", "start_px_x", "start_px_y", "EI_fit_adapted_Nm2",
               "EI_fit_native_Nm2", "critical_twist_deg_trial_i", "beta_over_alpha_trial_i_listed",
               "mass_kg_per_m"], ring_rows)
    for tag in ("crit", "lax"):
        pts, (px, start_px) = repo.pickle(f"adapteddlo_muj/data/dlo_muj_real/white{tag}_data.pickle")
        write_csv(os.path.join(out, "ring", f"white_{tag}_supplementary.csv"),
                  ["i", "u_m", "v_m", "u_px_rel", "v_px_rel"], [[j] + pts[j] + px[j] for j in range(len(pts))])
    write_toml(os.path.join(out, "ring.toml"), {
        "source": source,
        "setup": {
            "description": "1.5 m wire hanging as a loop between two clamps 0.12 m apart (photos, "
                           "Samsung S22 Ultra 3x tele); EI fitted per photo with gravity; then one clamp "
                           "twisted until out-of-plane buckling (critical twist) to fit GJ/EI",
            "length_m": RING_LEN, "clamp_distance_m": RING_CLAMP_DIST,
            "frame": "image plane: origin at start-clamp exit, u to the right, v downward (= gravity, "
                     "assumed camera level), metres; scaled so the picked polyline = 1.5 m",
            "start_clamp_position_m": [0.0, 0.0], "start_clamp_tangent": [1.0, 0.0],
            "end_clamp_position_m_nominal": [-RING_CLAMP_DIST, 0.0], "end_clamp_tangent": [1.0, 0.0],
            "tangent_note": "t = direction of increasing arc length; both clamps horizontal and parallel, "
                            "inferred from upstream sim (envs/realgrav_valid_test.py circle_init)",
            "n_points_per_photo": 51,
        },
        **{w: {"EI_Nm2_mean_adapted": wires[w]["EI_Nm2"], "GJ_over_EI_adapted": wires[w]["GJ_over_EI"],
               "EI_Nm2_mean_native": wires[w]["EI_Nm2_native_model"],
               "critical_twist_deg_trials": RING_CRIT_TWIST_DEG[w],
               "critical_twist_deg_mean": sum(RING_CRIT_TWIST_DEG[w]) / 5,
               "mass_kg_per_m": wires[w]["mass_kg_per_m"]} for w in WIRES},
    }, "# Ring (hanging loop) identification data. Per-photo points in ring/*.csv")

    with open(os.path.join(out, "SOURCES.txt"), "w") as f:
        f.write(f"{UPSTREAM} @ {a.commit}\n")
        for p in sorted(set(repo.used)):
            f.write(p + "\n")
    print("wrote", out)


if __name__ == "__main__":
    main()
