#!/usr/bin/python3
"""scripts/classify_wrong_relocalizations.py on a tiny hand-written results folder and dataset:
one wrong re-localization per cause rule, a correct frame and a consecutive-sessions job that are
not counted, the CSV's columns, the example images, and a node that resolves to the wrong frame."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "classify_wrong_relocalizations.py")
W, H = 64, 48
CALIBRATION = {"fx": 50.0, "fy": 50.0, "cx": 31.5, "cy": 23.5, "width": W, "height": H, "depth_scale": 1000.0}

# Map session 1: five frames 1 m apart along x, looking the same way; nodes 1-5.
MAP_POSITIONS = [(float(k), 0.0, 0.0) for k in range(5)]


def yaw_quat(deg):
    """(qx, qy, qz, qw) of a turn about the camera's y axis."""
    h = math.radians(deg) / 2
    return (0.0, math.sin(h), 0.0, math.cos(h))


# Query session A: (timestamp, position, yaw deg, depth mm, frame record overrides, expected cause).
# Node n is at MAP_POSITIONS[n - 1].
QUERY = [
    (100, (0.0, 0.0, 0.0), 0, 1000, {"correct": True, "matched_node": 1}, None),
    (110, (0.0, 0.1, 0.0), 0, 1000, {"matched_node": 1, "cache_validation": "accepted"}, "odometry_cache"),
    (120, (1.0, 0.0, 0.0), 0, 1000, {"correct": True, "matched_node": 2, "lcd_hypothesis": 2}, None),
    (121, (1.0, 0.8, 0.0), 0, 1000, {"matched_node": 2, "lcd_hypothesis": 2}, "stale_hypothesis"),
    (130, (0.0, 0.0, 0.0), 0, 1000, {"matched_node": 4, "matched_by": "proximity"}, "proximity_wrong_prior"),
    (140, (0.0, 0.0, 0.0), 0, 1000, {"matched_node": 4, "lcd_hypothesis": 4}, "aliasing_elsewhere"),
    (150, (4.0, 0.2, 0.0), 0, 1000, {"matched_node": 5}, "map_node_pose"),
    (160, (2.0, 0.1, 0.0), 0, 1000, {"matched_node": 3, "inliers": 25}, "few_inliers"),
    (170, (2.0, 0.1, 0.0), 60, 1000, {"matched_node": 3}, "wide_viewpoint"),
    (180, (2.0, 0.1, 0.0), 0, 5000, {"matched_node": 3}, "far_or_grazing"),
    (190, (2.0, 0.1, 0.0), 0, 1000, {"matched_node": 3}, "fast_turn"),
    (191, (2.0, 0.1, 0.0), 40, 1000, {"correct": True, "matched_node": 3}, None),
    (300, (1.0, 0.1, 0.0), 0, 1000, {"matched_node": 2}, "unexplained"),
]


def write_session(root, name, frames):
    """frames: (timestamp, position, yaw, depth_mm)."""
    d = os.path.join(root, name)
    os.makedirs(os.path.join(d, "rgb"))
    os.makedirs(os.path.join(d, "depth"))
    with open(os.path.join(d, "calibration.json"), "w") as f:
        json.dump(CALIBRATION, f)
    with open(os.path.join(d, "rgb.txt"), "w") as rgb, open(os.path.join(d, "depth.txt"), "w") as dep, \
            open(os.path.join(d, "groundtruth.txt"), "w") as gt:
        gt.write("# timestamp tx ty tz qx qy qz qw\n")
        for k, (t, p, yaw, depth_mm) in enumerate(frames):
            name_t = "%.6f" % t
            rgb.write("%s rgb/%s.png\n" % (name_t, name_t))
            dep.write("%s depth/%s.png\n" % (name_t, name_t))
            gt.write("%s %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n" % ((name_t,) + tuple(p) + yaw_quat(yaw)))
            Image.fromarray(np.full((H, W, 3), (40 * k) % 256, np.uint8)).save(
                os.path.join(d, "rgb", name_t + ".png"))
            Image.fromarray(np.full((H, W), depth_mm, np.uint16)).save(os.path.join(d, "depth", name_t + ".png"))


def frame_record(k, t, position, fields):
    record = {"frame": k, "timestamp_s": float(t), "relocalized": True, "correct": False,
              "outcome": "relocalized", "error_m": 0.3, "error_deg": 7.0, "matched_by": "loop_closure",
              "matched_session": 0, "inliers": 100, "lcd_hypothesis": 0, "cache_validation": None,
              "attempts": []}
    record.update(fields)
    node = record["matched_node"]
    distance = math.dist(position, MAP_POSITIONS[node - 1])
    record["attempts"] = [{"node": node, "session": 0, "source": "proximity", "status": "accepted",
                           "inliers": record["inliers"], "truth_distance_m": distance,
                           "truth_angle_deg": 0.0}]
    return record


def make_fixture(root, graph_truth_shift=0.0):
    dataset = os.path.join(root, "dataset")
    results = os.path.join(root, "results")
    write_session(dataset, "1", [(10 + k, p, 0, 1000) for k, p in enumerate(MAP_POSITIONS)])
    write_session(dataset, "A", [(t, p, yaw, d) for t, p, yaw, d, _, _ in QUERY])
    os.makedirs(results)
    with open(os.path.join(results, "run.json"), "w") as f:
        json.dump({"configuration": {"engine": {"registration": {"min_inliers": 20}},
                                     "experiment": {"maps": ["1", "1|2"], "localization_sessions": ["A"]}}}, f)
    map_dir = os.path.join(results, "jobs", "map", "XX", "1")
    os.makedirs(map_dir)
    with open(os.path.join(map_dir, "frames.jsonl"), "w") as f:
        for k in range(len(MAP_POSITIONS)):
            f.write(json.dumps({"node": k + 1, "session": 0}) + "\n")
    with open(os.path.join(map_dir, "graph.csv"), "w") as f:
        f.write("node,session,connected,x,y,truth_x,truth_y\n")
        for k, (x, y, _) in enumerate(MAP_POSITIONS):
            map_x = x + (1.0 if k == 4 else 0.0)  # node 5's map pose is 1 m off
            f.write("%d,1,1,%g,%g,%g,%g\n" % (k + 1, map_x, y, x + graph_truth_shift, y))
    loc = os.path.join(results, "jobs", "localize", "XX", "1", "A")
    os.makedirs(loc)
    with open(os.path.join(loc, "frames.jsonl"), "w") as f:
        for k, (t, p, _, _, fields, _) in enumerate(QUERY):
            f.write(json.dumps(frame_record(k, t, p, fields)) + "\n")
    # A consecutive-sessions job (map 1 localized with mapping session 2): not a matrix cell.
    other = os.path.join(results, "jobs", "localize", "XX", "1", "2")
    os.makedirs(other)
    with open(os.path.join(other, "frames.jsonl"), "w") as f:
        f.write(json.dumps(frame_record(0, 10, MAP_POSITIONS[0], {"matched_node": 1})) + "\n")
    return results, dataset


class ClassifyWrongRelocalizationsTest(unittest.TestCase):
    def run_script(self, results, dataset, out):
        return subprocess.run([sys.executable, SCRIPT, "--results", results, "--dataset", dataset,
                               "--output", out, "--examples", "3"], capture_output=True, text=True)

    def test_every_rule(self):
        with tempfile.TemporaryDirectory() as root:
            results, dataset = make_fixture(root)
            out = os.path.join(root, "out")
            done = self.run_script(results, dataset, out)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(os.path.join(out, "wrong_relocalizations.csv")) as f:
                reader = csv.DictReader(f)
                rows = list(reader)
                columns = reader.fieldnames
            for column in ["feature", "map", "query_session", "query_timestamp_s", "error_m", "error_deg",
                           "matched_by", "inliers", "matched_session", "matched_frame",
                           "matched_timestamp_s", "true_distance_m", "depth_median_m",
                           "depth_valid_fraction", "cause"]:
                self.assertIn(column, columns)
            expected = {"%.6f" % t: cause for t, _, _, _, _, cause in QUERY if cause is not None}
            got = {r["query_timestamp_s"]: r["cause"] for r in rows}
            self.assertEqual(got, expected)
            by_time = {r["query_timestamp_s"]: r for r in rows}
            # Node 4 resolves to map frame 3 of session 1 (timestamp 13), 3 m from the query.
            self.assertEqual(by_time["130.000000"]["matched_session"], "1")
            self.assertEqual(by_time["130.000000"]["matched_frame"], "3")
            self.assertEqual(by_time["130.000000"]["matched_timestamp_s"], "13.000000")
            self.assertAlmostEqual(float(by_time["130.000000"]["true_distance_m"]), 3.0, places=3)
            self.assertAlmostEqual(float(by_time["180.000000"]["depth_median_m"]), 5.0, places=3)
            with open(os.path.join(out, "causes.md")) as f:
                md = f.read()
            self.assertIn("| **total** | %d |" % len(expected), md)
            self.assertIn("Not counted here (as in the report): 1 wrong", md)
            images = sorted(os.listdir(os.path.join(out, "examples")))
            self.assertEqual(len(images), 3)
            for name in images:
                self.assertLess(os.path.getsize(os.path.join(out, "examples", name)), 80 * 1024)

    def test_node_resolving_to_another_frame_fails(self):
        with tempfile.TemporaryDirectory() as root:
            results, dataset = make_fixture(root, graph_truth_shift=1.0)
            done = self.run_script(results, dataset, os.path.join(root, "out"))
            self.assertEqual(done.returncode, 1)
            self.assertIn("graph.csv says", done.stderr)


if __name__ == "__main__":
    unittest.main()
