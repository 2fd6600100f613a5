#!/usr/bin/python3
"""Compares duskmap's per-frame localization outcomes with a peer system's, frame by frame.

The peer's outcomes are one CSV per cell, `FEATURE_MAP_SESSION.csv` with the map's '+' written
'p' (`SI_1p6_F.csv`: SIFT, map 1+6, session F), one row per frame: timestamp, relocalized, kind
(loop | prox), map_node, map_session_index, error_m, error_deg (the layout of
`../shared/data/peer/rtabmap-0.23.8/`, see its README). duskmap's are the `frames.jsonl` of the
localize jobs of a results folder (`jobs/localize/<feature>/<map>/<session>/frames.jsonl`).
Frames are matched by timestamp.

For every cell both have, it prints the re-localization rates, the frames only one system
re-localized (by how each did it) and the wrong re-localizations (beyond 0.5 m / 5 degrees), and
writes every disagreeing frame with duskmap's attempts (source, status, inliers, the proximity
candidate's search distance, the estimated and the true distance) to a CSV.

Usage: compare_peer.py PEER_DIR RESULTS_DIR [--csv OUT.csv] [--markdown OUT.md]
Exit 1 with a one-line error naming the file for unreadable input; 2 for bad arguments.
"""
import argparse
import csv
import json
import math
import os
import sys

WRONG_M = 0.5
WRONG_DEG = 5.0


def fail(message):
    print(f"compare_peer: {message}", file=sys.stderr)
    sys.exit(1)


def read_peer(path):
    frames = {}
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            needed = {"timestamp", "relocalized", "kind", "error_m", "error_deg"}
            if not needed <= set(reader.fieldnames or []):
                fail(f"{path}: missing columns {sorted(needed - set(reader.fieldnames or []))}")
            for line, row in enumerate(reader, start=2):
                try:
                    stamp = round(float(row["timestamp"]), 3)
                    relocalized = row["relocalized"] == "1"
                    error_m = float(row["error_m"]) if row["error_m"] else math.nan
                    error_deg = float(row["error_deg"]) if row["error_deg"] else math.nan
                except ValueError as e:
                    fail(f"{path}:{line}: {e}")
                frames[stamp] = {"relocalized": relocalized, "kind": row["kind"] if relocalized else "",
                                 "error_m": error_m, "error_deg": error_deg}
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    return frames


def read_duskmap(path):
    frames = {}
    try:
        with open(path) as f:
            for line, text in enumerate(f, start=1):
                try:
                    record = json.loads(text)
                except json.JSONDecodeError as e:
                    fail(f"{path}:{line}: not JSON ({e.msg})")
                frames[round(float(record["timestamp_s"]), 3)] = record
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    return frames


def is_wrong(error_m, error_deg):
    return error_m > WRONG_M or error_deg > WRONG_DEG


def duskmap_wrong(record):
    return record.get("relocalized") and record.get("correct") is False


def attempt_text(attempt):
    parts = [attempt.get("source", "?"), attempt.get("status", "?"), f"inl={attempt.get('inliers', 0)}"]
    for key, label in (("search_distance_m", "search"), ("estimate_distance_m", "est"),
                       ("truth_distance_m", "true")):
        if attempt.get(key) is not None:
            parts.append(f"{label}={attempt[key]:.2f}m")
    return " ".join(parts)


def cell_name(file_name):
    stem = file_name[:-len(".csv")]
    feature, map_name, session = stem.split("_")
    return feature, map_name.replace("p", "+"), session


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("peer_dir")
    parser.add_argument("results_dir")
    parser.add_argument("--csv", help="write every disagreeing frame here")
    parser.add_argument("--markdown", help="write the per-cell table here")
    args = parser.parse_args()
    if not os.path.isdir(args.peer_dir):
        fail(f"{args.peer_dir}: not a folder")
    if not os.path.isdir(args.results_dir):
        fail(f"{args.results_dir}: not a folder")

    rows, disagreements = [], []
    totals = {"only_duskmap": 0, "only_peer": 0, "wrong_duskmap": 0, "wrong_peer": 0}
    causes = {}
    for name in sorted(os.listdir(args.peer_dir)):
        if not name.endswith(".csv"):
            continue
        feature, map_name, session = cell_name(name)
        frames_path = os.path.join(args.results_dir, "jobs", "localize", feature, map_name, session,
                                   "frames.jsonl")
        if not os.path.exists(frames_path):
            continue
        peer = read_peer(os.path.join(args.peer_dir, name))
        ours = read_duskmap(frames_path)
        stamps = sorted(set(peer) & set(ours))
        if not stamps:
            fail(f"{frames_path}: no timestamp in common with {name}")
        only_ours = only_peer = wrong_ours = wrong_peer = 0
        for stamp in stamps:
            p, d = peer[stamp], ours[stamp]
            if p["relocalized"] and is_wrong(p["error_m"], p["error_deg"]):
                wrong_peer += 1
            if duskmap_wrong(d):
                wrong_ours += 1
            if p["relocalized"] == bool(d["relocalized"]):
                continue
            if d["relocalized"]:
                only_ours += 1
                cause = ("duskmap", d.get("matched_by") or "?")
            else:
                only_peer += 1
                cause = ("peer", p["kind"])
            causes[cause] = causes.get(cause, 0) + 1
            disagreements.append({
                "cell": f"{feature} {map_name} {session}", "timestamp": stamp,
                "relocalized_by": cause[0], "how": cause[1],
                "duskmap_outcome": d.get("outcome"), "duskmap_correct": d.get("correct"),
                "duskmap_error_m": d.get("error_m"), "peer_error_m": p["error_m"],
                "proximity_candidates": d.get("proximity_candidates"),
                "lcd_hypothesis": d.get("lcd_hypothesis"),
                "distance_since_last_m": d.get("distance_since_last_m"),
                "attempts": " | ".join(attempt_text(a) for a in d.get("attempts", [])),
            })
        n = len(stamps)
        rate_peer = 100.0 * sum(peer[s]["relocalized"] for s in stamps) / n
        rate_ours = 100.0 * sum(bool(ours[s]["relocalized"]) for s in stamps) / n
        rows.append((feature, map_name, session, n, rate_peer, rate_ours, only_ours, only_peer,
                     wrong_ours, wrong_peer))
        totals["only_duskmap"] += only_ours
        totals["only_peer"] += only_peer
        totals["wrong_duskmap"] += wrong_ours
        totals["wrong_peer"] += wrong_peer
    if not rows:
        fail(f"{args.results_dir}: no localize job matches a cell of {args.peer_dir}")

    lines = ["| feature | map | session | frames | peer % | duskmap % | difference | only duskmap | "
             "only peer | wrong duskmap | wrong peer |",
             "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for (feature, map_name, session, n, rp, ro, oo, op, wo, wp) in rows:
        lines.append(f"| {feature} | {map_name} | {session} | {n} | {rp:.1f} | {ro:.1f} | "
                     f"{ro - rp:+.1f} | {oo} | {op} | {wo} | {wp} |")
    lines.append("")
    lines.append(f"Frames re-localized by only one system: {totals['only_duskmap'] + totals['only_peer']} "
                 f"({totals['only_duskmap']} duskmap, {totals['only_peer']} peer). Wrong re-localizations: "
                 f"duskmap {totals['wrong_duskmap']}, peer {totals['wrong_peer']}.")
    lines.append("By cause: " + ", ".join(f"{who} by {how}: {count}"
                                         for (who, how), count in sorted(causes.items())))
    text = "\n".join(lines)
    print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text + "\n")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(disagreements[0].keys()) if disagreements else ["cell"])
            writer.writeheader()
            writer.writerows(disagreements)


if __name__ == "__main__":
    main()
