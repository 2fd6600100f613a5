#!/usr/bin/python3
"""Classifies every wrong re-localization of a results folder by cause (issue 47, item 4).

A re-localization is wrong exactly as the report counts it (slam/eval/relocalization_metrics.cc,
slam/report/report_builder.cc): the frame was re-localized (`relocalized`) and is not within the
default threshold 0.5 m / 5 degrees (`correct` false). Every localization job of
`jobs/localize/<feature>/<map>/<session>/frames.jsonl` is counted once (the closest-in-time row
reuses the single maps' jobs and has no folder of its own). The report's "No wrong
re-localization" finding sums the paper's feature columns (PAPER_FEATURES that were run); the
tables below give every feature and both totals.

The matched map node is resolved to its map frame through the map job's frames.jsonl: one line per
mapped frame, in the order the frames were fed (the map's sessions in label order, each session's
frames in time order), each naming the node it made and its session index. The resolution is
checked against graph.csv (a node's truth_x, truth_y must equal the resolved frame's
groundtruth.txt position) and the script stops if it is not.

Each wrong re-localization gets ONE primary cause: the first rule that holds, in this order.
  1. odometry_cache     the odometry cache validated the accepted registration
                        (cache_validation == "accepted"; the paper's engine config has the cache off).
  2. stale_hypothesis   matched by the loop-closure hypothesis (matched_by loop_closure), the same
                        node was already the Bayes filter's hypothesis on the previous frame, and
                        since the first frame of that run of hypotheses the query has moved
                        STALE_MOVED_M farther (ground truth) from the node's true position.
  3. wrong place        the matched node's true camera is more than FAR_M from the query's true
                        camera. Split by how the node was found:
       3a. proximity_wrong_prior   a proximity candidate (matched_by proximity): searched around
                                   the pose the engine already had, which was wrong.
       3b. aliasing_elsewhere      the loop-closure hypothesis: the same catalog model, or a
                                   repeated texture, seen at another place.
  Right place (the node's camera is near), inaccurate pose:
  4. map_node_pose      the matched node's own map position (graph.csv, aligned to the truth) is
                        more than WRONG_M from its true position: the map, not the registration,
                        is off (only nodes of the group aligned to the truth).
  5. few_inliers        fewer than FEW_INLIERS_FACTOR x the registration's minimum inliers
                        (registration.min_inliers of run.json's engine config, Vis/MinInliers).
  6. wide_viewpoint     the query and the node look more than WIDE_DEG apart (ground truth; the
                        engine's own proximity max_angle_deg): the shared object is seen from a
                        very different direction.
  7. far_or_grazing     the query's depth image: median valid depth above FAR_DEPTH_M, or less
                        than MIN_VALID_FRACTION of the pixels with depth, or more than
                        GRAZING_FRACTION of the valid pixels seen at more than GRAZING_DEG between
                        the viewing ray and the surface normal.
  8. fast_turn          the query camera or the matched map frame's camera turns faster than
                        FAST_TURN_DEG_S (ground truth, to the previous or the next frame of its
                        session; a smeared map frame places its 3D points as wrongly as a
                        smeared query its 2D points): the renderer smears the image by the image
                        motion during the exposure (about 9 px at 30 deg/s and 1/30 s).
  9. unexplained        none of the above: near node, enough inliers, similar viewing direction,
                        close and frontal depth, slow camera.
The thresholds are physical round numbers fixed before looking at the counts; none is tuned on
the count itself. Besides the cause, every row has pivot_ratio = error_m / (error in radians x
the query's median depth): about 1 when the estimated camera is rotated about the viewed scene
(the rotation-translation ambiguity of a pose from points on one surface), which causes.md counts.

The matrix cells and the registration's minimum inliers are read from RESULTS/run.json.

Usage:
  classify_wrong_relocalizations.py --results RESULTS --dataset DATASET --output OUT [--examples N]
Writes OUT/wrong_relocalizations.csv, OUT/causes.md and OUT/examples/*.png (query left, matched
map frame right). Exit 1 with a one-line error for unreadable or inconsistent input.
"""
import argparse
import csv
import json
import math
import os
import re
import sys
from collections import Counter, defaultdict

import numpy as np
from PIL import Image, ImageDraw

WRONG_M = 0.5            # the report's default threshold (correct = within 0.5 m and 5 deg)
WRONG_DEG = 5.0
COARSE_M = 5.0           # the report's third threshold, 5 m / 10 deg
COARSE_DEG = 10.0
STALE_MOVED_M = 0.5      # moved away from the hypothesis node by more than the wrong threshold
FAR_M = 1.5              # matched node's true camera farther than this from the query's: wrong place
WIDE_DEG = 45.0          # query and node look farther apart than the engine's proximity max_angle_deg
FAST_TURN_DEG_S = 30.0   # camera turn rate that smears the image by several pixels
PIVOT_RANGE = (0.8, 1.25)  # pivot_ratio counted as a rotation about the viewed scene
FEW_INLIERS_FACTOR = 1.5  # fewer than 1.5 x min_inliers
FAR_DEPTH_M = 3.0        # median valid depth beyond 3 m
MIN_VALID_FRACTION = 0.5  # less than half of the image with depth
GRAZING_DEG = 75.0       # ray-to-normal angle counted as grazing
GRAZING_FRACTION = 0.5   # more than half of the valid pixels grazing
DEFAULT_MIN_INLIERS = 20  # transform_estimation.h, when the engine config does not say
PAPER_FEATURES = ["SU", "SI", "BF", "BK", "KA", "DY", "SP", "SG"]

CAUSES = [
    ("odometry_cache", "odometry cache"),
    ("stale_hypothesis", "stale Bayes-filter hypothesis"),
    ("proximity_wrong_prior", "wrong place: proximity search around a wrong prior pose"),
    ("aliasing_elsewhere", "wrong place: same model / repeated texture elsewhere (loop closure)"),
    ("map_node_pose", "right place: the matched node's map pose is off"),
    ("few_inliers", "right place: few inliers"),
    ("wide_viewpoint", "right place: wide viewpoint change"),
    ("far_or_grazing", "right place: far or grazing depth"),
    ("fast_turn", "right place: fast turn (motion blur)"),
    ("unexplained", "right place: no diagnostic explains"),
]

CSV_COLUMNS = [
    "feature", "map", "query_session", "query_frame", "query_timestamp_s", "error_m", "error_deg",
    "band", "matched_by", "inliers", "matched_node", "matched_session", "matched_frame",
    "matched_timestamp_s", "true_distance_m", "true_angle_deg", "node_map_error_m",
    "hypothesis_run", "moved_away_m", "depth_median_m", "depth_valid_fraction",
    "depth_grazing_fraction", "query_turn_deg_s", "map_turn_deg_s", "pivot_ratio", "cause",
]


class InputFailure(Exception):
    pass


def fail(message):
    print("classify_wrong_relocalizations: " + message, file=sys.stderr)
    sys.exit(1)


def read_jsonl(path):
    try:
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip()]
    except (OSError, ValueError) as e:
        raise InputFailure("%s: %s" % (path, e))


# --- dataset -------------------------------------------------------------------------------

def quat_to_matrix(qx, qy, qz, qw):
    n = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
    x, y, z, w = qx / n, qy / n, qz / n, qw / n
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def read_timed_list(path):
    """timestamp -> rest of line (TUM list files)."""
    out = {}
    try:
        with open(path) as f:
            for line in f:
                if not line.strip() or line.startswith("#"):
                    continue
                parts = line.split()
                out[round(float(parts[0]), 6)] = parts[1:]
    except (OSError, ValueError, IndexError) as e:
        raise InputFailure("%s: %s" % (path, e))
    return out


class Session:
    def __init__(self, root, name):
        self.name = name
        self.dir = os.path.join(root, name)
        gt = read_timed_list(os.path.join(self.dir, "groundtruth.txt"))
        self.poses = {}
        for t, v in gt.items():
            p = np.array([float(x) for x in v[0:3]])
            self.poses[t] = (p, quat_to_matrix(*[float(x) for x in v[3:7]]))
        self.rgb = read_timed_list(os.path.join(self.dir, "rgb.txt"))
        self.depth = read_timed_list(os.path.join(self.dir, "depth.txt"))
        self.timestamps = sorted(self.rgb)
        try:
            with open(os.path.join(self.dir, "calibration.json")) as f:
                self.calibration = json.load(f)
        except (OSError, ValueError) as e:
            raise InputFailure("%s: %s" % (os.path.join(self.dir, "calibration.json"), e))

    def pose(self, t):
        t = round(t, 6)
        if t not in self.poses:
            raise InputFailure("session %s: no ground truth at %.6f" % (self.name, t))
        return self.poses[t]

    def rgb_path(self, t):
        return os.path.join(self.dir, self.rgb[round(t, 6)][0])

    def depth_path(self, t):
        return os.path.join(self.dir, self.depth[round(t, 6)][0])


class Dataset:
    def __init__(self, root):
        self.root = root
        self.sessions = {}
        self.depth_cache = {}

    def session(self, name):
        if name not in self.sessions:
            if not os.path.isdir(os.path.join(self.root, name)):
                raise InputFailure("%s: no session folder %s" % (self.root, name))
            self.sessions[name] = Session(self.root, name)
        return self.sessions[name]

    def depth_stats(self, session_name, t):
        """(median valid depth m, valid fraction, grazing fraction of valid pixels)."""
        key = (session_name, round(t, 6))
        if key in self.depth_cache:
            return self.depth_cache[key]
        s = self.session(session_name)
        path = s.depth_path(t)
        try:
            raw = np.array(Image.open(path)).astype(np.float64)
        except OSError as e:
            raise InputFailure("%s: %s" % (path, e))
        c = s.calibration
        depth = raw / float(c.get("depth_scale", 1000.0))
        valid = depth > 0
        valid_fraction = float(valid.mean())
        median = float(np.median(depth[valid])) if valid.any() else float("nan")
        # Surface normals from the back-projected points on a 4-pixel grid.
        step = 4
        d = depth[::step, ::step]
        h, w = d.shape
        us = (np.arange(w) * step - c["cx"]) / c["fx"]
        vs = (np.arange(h) * step - c["cy"]) / c["fy"]
        rays = np.stack([np.broadcast_to(us[None, :], (h, w)), np.broadcast_to(vs[:, None], (h, w)),
                         np.ones((h, w))], axis=-1)
        pts = rays * d[..., None]
        du = pts[1:-1, 2:] - pts[1:-1, :-2]
        dv = pts[2:, 1:-1] - pts[:-2, 1:-1]
        normal = np.cross(du, dv)
        ok = (d[1:-1, 2:] > 0) & (d[1:-1, :-2] > 0) & (d[2:, 1:-1] > 0) & (d[:-2, 1:-1] > 0) \
            & (d[1:-1, 1:-1] > 0)
        ray = rays[1:-1, 1:-1]
        nn = np.linalg.norm(normal, axis=-1) * np.linalg.norm(ray, axis=-1)
        ok &= nn > 0
        cosang = np.abs((normal * ray).sum(-1)[ok]) / nn[ok]
        grazing = float((cosang < math.cos(math.radians(GRAZING_DEG))).mean()) if ok.any() else 0.0
        self.depth_cache[key] = (median, valid_fraction, grazing)
        return self.depth_cache[key]


# --- results -------------------------------------------------------------------------------

def map_sessions(label):
    """The sessions of a map label in feeding order ('1+3+5', '1-2-3-4-5-6', '1')."""
    return [s for s in re.split(r"[+\-]", label) if s]


class MapJob:
    """Node id -> (session name, frame index, timestamp), and the graph's positions."""

    def __init__(self, folder, label, dataset):
        self.label = label
        sessions = map_sessions(label)
        lines = read_jsonl(os.path.join(folder, "frames.jsonl"))
        self.frame_of = {}
        count = Counter()
        for line in lines:
            index = line["session"]
            if index < 0 or index >= len(sessions):
                raise InputFailure("%s: session index %d for map %s" % (folder, index, label))
            name = sessions[index]
            session = dataset.session(name)
            k = count[index]
            count[index] += 1
            if k >= len(session.timestamps):
                raise InputFailure("%s: more frames of session %s than the dataset has" % (folder, name))
            self.frame_of[line["node"]] = (name, k, session.timestamps[k])
        self.graph = {}
        path = os.path.join(folder, "graph.csv")
        try:
            with open(path) as f:
                for row in csv.DictReader(f):
                    self.graph[int(row["node"])] = row
        except (OSError, ValueError, KeyError) as e:
            raise InputFailure("%s: %s" % (path, e))
        # Check the resolution against the graph's ground truth.
        for node, row in self.graph.items():
            if node not in self.frame_of:
                raise InputFailure("%s: node %d of graph.csv is in no frames.jsonl line" % (folder, node))
            if row["truth_x"] == "":
                continue
            name, _, t = self.frame_of[node]
            p, _ = dataset.session(name).pose(t)
            if abs(p[0] - float(row["truth_x"])) > 1e-3 or abs(p[1] - float(row["truth_y"])) > 1e-3:
                raise InputFailure(
                    "%s: node %d resolves to session %s at %.6f (%.4f, %.4f), graph.csv says (%s, %s)"
                    % (folder, node, name, t, p[0], p[1], row["truth_x"], row["truth_y"]))

    def node_map_error(self, node):
        row = self.graph.get(node)
        if row is None or row["connected"] != "1" or row["truth_x"] == "":
            return None
        return math.hypot(float(row["x"]) - float(row["truth_x"]), float(row["y"]) - float(row["truth_y"]))


def read_run(results):
    """The run's configuration (run.json): (min_inliers, matrix maps, localization sessions)."""
    path = os.path.join(results, "run.json")
    try:
        with open(path) as f:
            configuration = json.load(f)["configuration"]
        experiment = configuration["experiment"]
        maps = [m for m in experiment["maps"] if "|" not in m]  # closest-in-time: no job of its own
        sessions = list(experiment["localization_sessions"])
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise InputFailure("%s: %s" % (path, e))
    registration = configuration.get("engine", {}).get("registration", {})
    return int(registration.get("min_inliers", DEFAULT_MIN_INLIERS)), maps, sessions


def rotation_deg(r):
    return math.degrees(math.acos(max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0))))


def relative(dataset, qs, qt, ms, mt):
    """True distance (m) and angle (deg) between the query's and the map frame's cameras."""
    qp, qr = dataset.session(qs).pose(qt)
    mp, mr = dataset.session(ms).pose(mt)
    return float(np.linalg.norm(qp - mp)), rotation_deg(mr.T @ qr)


def classify(row, min_inliers):
    """The primary cause of one wrong re-localization (rules 1-7 of the module doc)."""
    if row["cache_validation"] == "accepted":
        return "odometry_cache"
    if row["matched_by"] == "loop_closure" and row["hypothesis_run"] >= 2 and \
            row["moved_away_m"] > STALE_MOVED_M:
        return "stale_hypothesis"
    if row["true_distance_m"] > FAR_M:
        return "proximity_wrong_prior" if row["matched_by"] == "proximity" else "aliasing_elsewhere"
    if row["node_map_error_m"] is not None and row["node_map_error_m"] > WRONG_M:
        return "map_node_pose"
    if row["inliers"] < FEW_INLIERS_FACTOR * min_inliers:
        return "few_inliers"
    if row["true_angle_deg"] > WIDE_DEG:
        return "wide_viewpoint"
    median, valid, grazing = row["depth"]
    if (not median <= FAR_DEPTH_M) or valid < MIN_VALID_FRACTION or grazing > GRAZING_FRACTION:
        return "far_or_grazing"
    if max(row["query_turn_deg_s"], row["map_turn_deg_s"]) > FAST_TURN_DEG_S:
        return "fast_turn"
    return "unexplained"


def turn_rate(session, k):
    """The camera's fastest turn (deg/s, ground truth) to the previous or the next frame."""
    ts = session.timestamps
    best = 0.0
    for a, b in ((k - 1, k), (k, k + 1)):
        if 0 <= a and b < len(ts) and ts[b] > ts[a]:
            ra, rb = session.pose(ts[a])[1], session.pose(ts[b])[1]
            best = max(best, rotation_deg(ra.T @ rb) / (ts[b] - ts[a]))
    return best


def pivot_ratio(error_m, error_deg, depth_m):
    if not error_deg > 0 or not depth_m > 0:
        return None
    return error_m / (math.radians(error_deg) * depth_m)


def band(error_m, error_deg):
    if error_m <= COARSE_M and error_deg <= COARSE_DEG:
        return "between"
    return "beyond_coarse"


def collect(results, dataset, min_inliers, maps_wanted, sessions_wanted):
    """The wrong re-localizations of the matrix cells (maps x localization sessions), and how many
    more the other localize jobs (the consecutive-sessions experiment) have."""
    rows, other = [], 0
    base = Counter()  # every re-localized frame of the matrix cells: how often each property holds
    localize = os.path.join(results, "jobs", "localize")
    if not os.path.isdir(localize):
        raise InputFailure("%s: no jobs/localize folder" % results)
    maps = {}
    for feature in sorted(os.listdir(localize)):
        for label in sorted(os.listdir(os.path.join(localize, feature))):
            for query in sorted(os.listdir(os.path.join(localize, feature, label))):
                path = os.path.join(localize, feature, label, query, "frames.jsonl")
                if not os.path.exists(path):
                    continue
                frames = read_jsonl(path)
                wrong = [i for i, f in enumerate(frames) if f.get("relocalized") and not f.get("correct")]
                if label not in maps_wanted or query not in sessions_wanted:
                    other += len(wrong)
                    continue
                count_base(base, frames, dataset.session(query), min_inliers)
                if not wrong:
                    continue
                key = (feature, label)
                if key not in maps:
                    folder = os.path.join(results, "jobs", "map", feature, label)
                    if not os.path.isdir(folder):
                        raise InputFailure("%s: missing (needed for %s)" % (folder, path))
                    maps[key] = MapJob(folder, label, dataset)
                job = maps[key]
                for i in wrong:
                    rows.append(describe(frames, i, feature, label, query, job, dataset, min_inliers, path))
    return rows, other, base


def count_base(base, frames, session, min_inliers):
    for k, f in enumerate(frames):
        if not f.get("relocalized"):
            continue
        base["relocalized"] += 1
        base["few_inliers"] += f["inliers"] < FEW_INLIERS_FACTOR * min_inliers
        angle = [a.get("truth_angle_deg") for a in f.get("attempts", [])
                 if a.get("node") == f["matched_node"] and a.get("status") == "accepted"]
        base["wide_viewpoint"] += bool(angle) and angle[-1] is not None and angle[-1] > WIDE_DEG
        base["fast_turn"] += turn_rate(session, session.timestamps.index(round(f["timestamp_s"], 6))) > FAST_TURN_DEG_S


def describe(frames, i, feature, label, query, job, dataset, min_inliers, path):
    f = frames[i]
    node = f["matched_node"]
    if node not in job.frame_of:
        raise InputFailure("%s: frame %d matched node %d, which the map has no frame for" % (path, i, node))
    ms, mk, mt = job.frame_of[node]
    qt = f["timestamp_s"]
    distance, angle = relative(dataset, query, qt, ms, mt)
    # The accepted attempt's own ground-truth distance must agree with the resolved frame.
    for a in f.get("attempts", []):
        if a.get("node") == node and a.get("status") == "accepted" and a.get("truth_distance_m") is not None:
            if abs(a["truth_distance_m"] - distance) > 1e-3:
                raise InputFailure("%s: frame %d: node %d resolves %.4f m from the query, the attempt says %.4f"
                                   % (path, i, node, distance, a["truth_distance_m"]))
    # The run of frames, ending here, whose accepted Bayes hypothesis was this node.
    run = 0
    j = i
    while j >= 0 and frames[j].get("lcd_hypothesis") == node:
        run += 1
        j -= 1
    moved = 0.0
    if run >= 2:
        start, _ = relative(dataset, query, frames[i - run + 1]["timestamp_s"], ms, mt)
        moved = distance - start
    row = {
        "feature": feature, "map": label, "query_session": query, "query_frame": f["frame"],
        "query_timestamp_s": qt, "error_m": f["error_m"], "error_deg": f["error_deg"],
        "band": band(f["error_m"], f["error_deg"]), "matched_by": f["matched_by"],
        "inliers": f["inliers"], "matched_node": node, "matched_session": ms, "matched_frame": mk,
        "matched_timestamp_s": mt, "true_distance_m": distance, "true_angle_deg": angle,
        "node_map_error_m": job.node_map_error(node), "hypothesis_run": run, "moved_away_m": moved,
        "cache_validation": f.get("cache_validation"),
        "depth": dataset.depth_stats(query, qt),
        "query_turn_deg_s": turn_rate(dataset.session(query), dataset.session(query).timestamps.index(round(qt, 6))),
        "map_turn_deg_s": turn_rate(dataset.session(ms), dataset.session(ms).timestamps.index(round(mt, 6))),
    }
    row["pivot_ratio"] = pivot_ratio(row["error_m"], row["error_deg"], row["depth"][0])
    row["cause"] = classify(row, min_inliers)
    return row


# --- report --------------------------------------------------------------------------------

def fmt(v, digits=3):
    if v is None:
        return ""
    if isinstance(v, float):
        return ("%." + str(digits) + "f") % v
    return str(v)


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_COLUMNS)
        for r in rows:
            median, valid, grazing = r["depth"]
            values = dict(r, depth_median_m=median, depth_valid_fraction=valid, depth_grazing_fraction=grazing)
            w.writerow([fmt(values[c], 6 if c == "query_timestamp_s" or c == "matched_timestamp_s" else 3)
                        for c in CSV_COLUMNS])


def report_wrong_count(results):
    """The report's count, when its agreement.md is there: (count, cells) or None."""
    path = os.path.join(results, "report", "agreement.md")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        m = re.search(r"(\d+) wrong re-localizations \(beyond 0\.5 m/5°\), in (\d+) of (\d+) cells", f.read())
    return (int(m.group(1)), m.group(2) + " of " + m.group(3)) if m else None


def cells_csv_wrong(results):
    """feature -> wrong, summed over the jobs of report/cells.csv (each job once)."""
    path = os.path.join(results, "report", "cells.csv")
    if not os.path.exists(path):
        return None
    out, seen = Counter(), set()
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["job"] in seen:
                continue
            seen.add(row["job"])
            out[row["feature"]] += int(row["wrong"])
    return out


def write_markdown(rows, results, min_inliers, path, examples, other, base):
    features = sorted({r["feature"] for r in rows}, key=lambda x: (x not in PAPER_FEATURES, x))
    paper = [x for x in features if x in PAPER_FEATURES]
    counts = Counter((r["cause"], r["feature"]) for r in rows)
    lines = ["# Wrong re-localizations by cause", "",
             "Results: `%s`. Wrong = re-localized but not within 0.5 m / 5° (the report's definition); "
             "every localization job once. Rules (first that holds) are documented in "
             "`scripts/classify_wrong_relocalizations.py`; minimum inliers %d." % (results, min_inliers), ""]
    header = "| cause | " + " | ".join(features) + " | paper features | all |"
    lines += [header, "| --- |" + " ---: |" * (len(features) + 2)]

    def line(label, pred):
        per = [sum(1 for r in rows if r["feature"] == x and pred(r)) for x in features]
        p = sum(n for x, n in zip(features, per) if x in paper)
        return "| %s | %s | %d | %d |" % (label, " | ".join(str(n) for n in per), p, sum(per))

    for cause, text in CAUSES:
        lines.append(line("%s (%s)" % (text, cause), lambda r, c=cause: r["cause"] == c))
    lines.append(line("**total**", lambda r: True))
    lines.append(line("between 0.5 m/5° and 5 m/10°", lambda r: r["band"] == "between"))
    lines.append(line("beyond 5 m/10°", lambda r: r["band"] == "beyond_coarse"))
    lines.append(line("translation within 0.5 m (rotation only)", lambda r: r["error_m"] <= WRONG_M))
    lines.append(line("pivot about the viewed scene (pivot_ratio %.2f-%.2f)" % PIVOT_RANGE,
                      lambda r: r["pivot_ratio"] is not None and PIVOT_RANGE[0] <= r["pivot_ratio"] <= PIVOT_RANGE[1]))
    lines.append(line("matched by loop closure", lambda r: r["matched_by"] == "loop_closure"))
    lines.append(line("matched by proximity", lambda r: r["matched_by"] == "proximity"))
    lines.append("")
    lines.append("Paper features counted by the report's finding: %s. Not counted here (as in the report): "
                 "%d wrong re-localizations of the consecutive-sessions jobs (a map localized with a "
                 "later mapping session)." % (", ".join(paper), other))
    distinct = len({(r["query_session"], r["query_frame"]) for r in rows})
    lines.append("The %d wrong re-localizations (all features) come from %d distinct query frames." % (len(rows), distinct))
    if base["relocalized"]:
        lines += ["", "How often a property holds among the wrong re-localizations and among all %d "
                  "re-localized frames of the same cells (any cause order):" % base["relocalized"], "",
                  "| property | wrong | all re-localized |", "| --- | ---: | ---: |"]
        props = [("few_inliers", "fewer than %.0f inliers" % (FEW_INLIERS_FACTOR * min_inliers),
                  lambda r: r["inliers"] < FEW_INLIERS_FACTOR * min_inliers),
                 ("wide_viewpoint", "query and node more than %.0f° apart" % WIDE_DEG,
                  lambda r: r["true_angle_deg"] > WIDE_DEG),
                 ("fast_turn", "camera turning faster than %.0f°/s" % FAST_TURN_DEG_S,
                  lambda r: r["query_turn_deg_s"] > FAST_TURN_DEG_S)]
        for key, text, pred in props:
            n = sum(1 for r in rows if pred(r))
            lines.append("| %s | %.1f %% | %.1f %% |" % (text, 100.0 * n / max(1, len(rows)),
                                                       100.0 * base[key] / base["relocalized"]))
        either = sum(1 for r in rows if max(r["query_turn_deg_s"], r["map_turn_deg_s"]) > FAST_TURN_DEG_S)
        lines.append("| query or matched map frame turning faster than %.0f°/s | %.1f %% | |"
                     % (FAST_TURN_DEG_S, 100.0 * either / max(1, len(rows))))
        lines.append("")
    reported = report_wrong_count(results)
    ours = sum(1 for r in rows if r["feature"] in paper)
    if reported is not None:
        lines.append("Reproduction: the report (agreement.md) says %d wrong re-localizations in %s cells; "
                     "this script finds %d on the same features (%s)." %
                     (reported[0], reported[1], ours, "equal" if reported[0] == ours else "DIFFERENT"))
    by_cells = cells_csv_wrong(results)
    if by_cells is not None:
        mine = Counter(r["feature"] for r in rows)
        diff = [x for x in sorted(set(by_cells) | set(mine)) if by_cells[x] != mine[x]]
        lines.append("report/cells.csv per feature: %s; %s." % (
            ", ".join("%s %d" % (x, by_cells[x]) for x in sorted(by_cells)),
            "every feature equal to this script's count" if not diff else "DIFFERENT for " + ", ".join(diff)))
    if examples:
        lines += ["", "## Examples", "", "Query left, matched map frame right.", ""]
        for name, r in examples:
            lines.append("- `examples/%s`: %s" % (name, caption(r)))
    lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return reported, ours


def caption_lines(r):
    return ("%s, map %s: query %s frame %d -> map frame %s/%d (%s)" % (
                r["feature"], r["map"], r["query_session"], r["query_frame"], r["matched_session"],
                r["matched_frame"], r["matched_by"]),
            "error %.2f m %.1f deg; truly %.2f m %.0f deg apart; %d inliers; cause %s" % (
                r["error_m"], r["error_deg"], r["true_distance_m"], r["true_angle_deg"], r["inliers"],
                r["cause"]))


def caption(r):
    return "; ".join(caption_lines(r))


def choose_examples(rows, n):
    """Round-robin over the causes (most frequent first), the largest error of each first."""
    by_cause = defaultdict(list)
    for r in rows:
        by_cause[r["cause"]].append(r)
    order = sorted(by_cause, key=lambda c: (-len(by_cause[c]), c))
    for c in order:
        by_cause[c].sort(key=lambda r: (-r["error_m"], r["feature"], r["map"], r["query_session"], r["query_frame"]))
    chosen, k = [], 0
    while len(chosen) < n and any(k < len(by_cause[c]) for c in order):
        for c in order:
            if k < len(by_cause[c]) and len(chosen) < n:
                chosen.append(by_cause[c][k])
        k += 1
    return chosen


def write_example(dataset, r, path):
    width = 320
    q = Image.open(dataset.session(r["query_session"]).rgb_path(r["query_timestamp_s"])).convert("RGB")
    m = Image.open(dataset.session(r["matched_session"]).rgb_path(r["matched_timestamp_s"])).convert("RGB")
    height = round(q.height * width / q.width)
    q = q.resize((width, height), Image.BILINEAR)
    m = m.resize((width, height), Image.BILINEAR)
    strip = 28
    out = Image.new("RGB", (2 * width + 4, height + strip), (255, 255, 255))
    out.paste(q, (0, strip))
    out.paste(m, (width + 4, strip))
    draw = ImageDraw.Draw(out)
    first, second = caption_lines(r)
    draw.text((3, 1), first, fill=(0, 0, 0))
    draw.text((3, 14), second, fill=(0, 0, 0))
    out.quantize(colors=128, method=Image.MEDIANCUT, dither=Image.NONE).save(path, optimize=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--results", required=True)
    parser.add_argument("--dataset", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--examples", type=int, default=6)
    args = parser.parse_args()
    try:
        min_inliers, maps_wanted, sessions_wanted = read_run(args.results)
        dataset = Dataset(args.dataset)
        rows, other, base = collect(args.results, dataset, min_inliers, maps_wanted, sessions_wanted)
        os.makedirs(os.path.join(args.output, "examples"), exist_ok=True)
        write_csv(rows, os.path.join(args.output, "wrong_relocalizations.csv"))
        examples = []
        for k, r in enumerate(choose_examples(rows, args.examples)):
            name = "%02d_%s_%s_%s_%s_%d.png" % (k + 1, r["cause"], r["feature"], r["map"].replace("+", "p"),
                                              r["query_session"], r["query_frame"])
            write_example(dataset, r, os.path.join(args.output, "examples", name))
            examples.append((name, r))
        reported, ours = write_markdown(rows, args.results, min_inliers,
                                        os.path.join(args.output, "causes.md"), examples, other, base)
    except InputFailure as e:
        fail(str(e))
    print("%d wrong re-localizations (%d on the paper's features%s); wrote %s" % (
        len(rows), ours, "" if reported is None else ", report says %d" % reported[0], args.output))
    for cause, _ in CAUSES:
        print("  %-22s %d" % (cause, sum(1 for r in rows if r["cause"] == cause)))


if __name__ == "__main__":
    main()
