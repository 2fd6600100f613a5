#!/usr/bin/python3
"""Draws the report figures of a duskmap run from the CSV files `duskmap report` writes.

Usage: plot_report.py REPORT_DIR [--jobs-dir RESULTS_DIR/jobs ...] [--title TEXT]

Writes into REPORT_DIR/figures/:
  relocalization_single_<F>.png   single-session maps x localization sessions, per feature
  relocalization_multi_<F>.png    multi-session maps x localization sessions, per feature
  relocalization_over_time_<F>.png  per localization session, the mapping session matched
  consecutive.png                 consecutive-session re-localization (map session x later session)
  merged_graph_<F>.png            top view of a merged map's optimised graph over ground truth
  scaling.png                     the scaling curve (scaling.csv, a config's "scaling"): LCD + TE
                                  per frame, memory, map open time and re-localization against
                                  the number of sessions in the map, one line per feature
and REPORT_DIR/report.md, which puts the tables (tables.md) and the figures together.
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def heat_map(matrix, rows, cols, title, path, vmax=100.0, fmt="{:.0f}"):
    fig, ax = plt.subplots(figsize=(max(5.0, 1.5 + 0.7 * len(cols)), 1.4 + 0.45 * len(rows)))
    image = ax.imshow(matrix, cmap="viridis", vmin=0.0, vmax=vmax, aspect="auto")
    ax.set_xticks(range(len(cols)), cols)
    ax.set_yticks(range(len(rows)), rows)
    for r, row in enumerate(matrix):
        for c, value in enumerate(row):
            if value == value:  # not NaN
                ax.text(c, r, fmt.format(value), ha="center", va="center",
                        color="white" if value < 0.6 * vmax else "black", fontsize=8)
    ax.set_title(title, fontsize=8, wrap=True)
    fig.colorbar(image, ax=ax, fraction=0.046)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def relocalization_matrices(cells, out_dir):
    written = []
    for feature in ordered(c["feature"] for c in cells):
        mine = [c for c in cells if c["feature"] == feature]
        sessions = ordered(c["session"] for c in mine)
        for kind, keep in (("single", lambda r: all(ch not in r for ch in "+-|")),
                           ("multi", lambda r: any(ch in r for ch in "+-|"))):
            rows = ordered(c["row"] for c in mine if keep(c["row"]))
            if not rows:
                continue
            value = {(c["row"], c["session"]): float(c["relocalized_pct"]) for c in mine}
            matrix = [[value.get((r, s), float("nan")) for s in sessions] for r in rows]
            path = os.path.join(out_dir, f"relocalization_{kind}_{feature}.png")
            heat_map(matrix, rows, sessions,
                     f"{feature}: re-localized frames (%), {kind}-session maps", path)
            written.append(path)
    return written


def relocalization_over_time(cells, timeline, out_dir):
    written = []
    by_job = {}
    for t in timeline:
        by_job.setdefault(t["job"], []).append(t)
    for feature in ordered(c["feature"] for c in cells):
        rows = [c for c in cells if c["feature"] == feature and c["row"].count("+") >= 1]
        if not rows:
            continue
        row = max(ordered(c["row"] for c in rows), key=lambda r: r.count("+"))
        mine = [c for c in rows if c["row"] == row]
        sessions = sorted(set(t["matched_session"] for c in mine for t in by_job.get(c["job"], [])
                              if t["matched_session"]))
        colors = {s: plt.cm.tab10(i % 10) for i, s in enumerate(sessions)}
        fig, ax = plt.subplots(figsize=(9, 0.9 + 0.4 * len(mine)))
        for y, cell in enumerate(mine):
            for t in by_job.get(cell["job"], []):
                if t["matched_session"]:
                    ax.scatter(int(t["frame"]), y, s=6, color=colors[t["matched_session"]])
        ax.set_yticks(range(len(mine)), [c["session"] for c in mine])
        ax.set_xlabel("frame")
        ax.set_title(f"{feature} on map {row}: mapping session matched at each re-localization",
                     fontsize=9)
        handles = [plt.Line2D([], [], marker="o", linestyle="", color=colors[s], label=s)
                   for s in sessions]
        ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0),
                  title="map session", title_fontsize=7)
        fig.tight_layout()
        path = os.path.join(out_dir, f"relocalization_over_time_{feature}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def consecutive_matrix(rows, out_dir):
    if not rows:
        return []
    written = []
    for feature in ordered(r["feature"] for r in rows):
        mine = [r for r in rows if r["feature"] == feature]
        maps = ordered(r["map_session"] for r in mine)
        # The later sessions in the sessions' own order (the map sessions' first), not in
        # the order the pairs list them (1-2, 1-3, 1-6, 2-4, ... would put 6 before 4).
        sessions = ordered([r["map_session"] for r in mine] + [r["localization_session"] for r in mine])
        later = [s for s in sessions if s in {r["localization_session"] for r in mine}]
        value = {(r["map_session"], r["localization_session"]): float(r["within_55cm_pct"])
                 for r in mine}
        matrix = [[value.get((m, s), float("nan")) for s in later] for m in maps]
        path = os.path.join(out_dir, f"consecutive_{feature}.png")
        heat_map(matrix, maps, later,
                 f"{feature}: frames re-localized within 55 cm (%), map session x later session",
                 path)
        written.append(path)
    return written


def merged_graphs(jobs_dirs, out_dir):
    written = []
    graphs = {}  # feature -> (label, graph.csv path) of its largest merged map
    for jobs_dir in jobs_dirs:
        maps_dir = os.path.join(jobs_dir, "map")
        if not os.path.isdir(maps_dir):
            continue
        for feature in sorted(os.listdir(maps_dir)):
            for label in os.listdir(os.path.join(maps_dir, feature)):
                path = os.path.join(maps_dir, feature, label, "graph.csv")
                if "+" not in label or label.endswith(".partial") or not os.path.exists(path):
                    continue
                if feature not in graphs or label.count("+") > graphs[feature][0].count("+"):
                    graphs[feature] = (label, path)
    for feature in sorted(graphs):
        label, path = graphs[feature]
        nodes = read_csv(path)
        if not nodes:
            continue
        fig, ax = plt.subplots(figsize=(6, 6))
        if "connected" in nodes[0]:
            # Sessions not joined to the map frame's session float in their
            # own odometry frame: drawn separately would mislead.
            nodes = [n for n in nodes if n["connected"] == "1"]
        has_truth = all(n.get("truth_x", "") not in ("", "nan") for n in nodes)
        if has_truth:
            ax.plot([float(n["truth_x"]) for n in nodes], [float(n["truth_y"]) for n in nodes],
                    ".", color="0.7", markersize=3, label="ground truth")
        for i, session in enumerate(ordered(n["session"] for n in nodes)):
            mine = [n for n in nodes if n["session"] == session]
            ax.plot([float(n["x"]) for n in mine], [float(n["y"]) for n in mine], "-",
                    linewidth=0.8, color=plt.cm.tab10(i % 10), label=f"session {session}")
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.legend(fontsize=7)
        ax.set_title(f"{feature}: optimised graph of map {label}", fontsize=9)
        fig.tight_layout()
        path = os.path.join(out_dir, f"merged_graph_{feature}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


SCALING_PANELS = [
    ("lcd_te_ms", "loop closure + transformation estimation\nper frame (ms, median)"),
    ("memory_mb", "memory needed for localization (MB)"),
    ("map_open_s", "map open time (s): load + localizer setup"),
    ("relocalized_pct", "re-localization (% of frames)"),
]


def scaling_curve(rows, out_dir):
    """Four panels against the sessions in the map (log2 axis, ticks at the curve's counts)."""
    if not rows:
        return []
    counts = sorted({int(r["sessions"]) for r in rows})
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    for ax, (key, label) in zip(axes.flat, SCALING_PANELS):
        for i, feature in enumerate(ordered(r["feature"] for r in rows)):
            points = [(int(r["sessions"]), float(r[key])) for r in rows
                      if r["feature"] == feature and r.get(key, "") != ""]
            if points:
                ax.plot([p[0] for p in points], [p[1] for p in points], "o-", markersize=4,
                        linewidth=1.2, color=plt.cm.tab10(i % 10), label=feature)
        ax.set_xscale("log", base=2)
        ax.set_xticks(counts, [str(c) for c in counts])
        ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        ax.set_xlabel("sessions in the map")
        ax.set_title(label, fontsize=9)
        ax.grid(True, alpha=0.3)
    axes.flat[3].set_ylim(0, 100)
    handles, labels = [], []
    for ax in axes.flat:  # every feature once, from whichever panel has it
        for handle, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(handle)
                labels.append(label)
    fig.legend(handles, labels, loc="center right", fontsize=8, title="feature", title_fontsize=8)
    fig.suptitle("Scaling curve: maps of growing size, localization sessions of other days",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 0.9, 1))
    path = os.path.join(out_dir, "scaling.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return [path]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report_dir")
    parser.add_argument("--jobs-dir", action="append", default=[],
                        help="a run's jobs/ folder, for the merged-graph figure (repeatable)")
    parser.add_argument("--title", default="", help="the experiment's name, for report.md")
    args = parser.parse_args()
    cells_path = os.path.join(args.report_dir, "cells.csv")
    if not os.path.exists(cells_path):
        print(f"plot_report.py: error: {cells_path}: missing (run `duskmap report` first)",
              file=sys.stderr)
        return 1
    out_dir = os.path.join(args.report_dir, "figures")
    os.makedirs(out_dir, exist_ok=True)
    cells = read_csv(cells_path)
    written = relocalization_matrices(cells, out_dir)
    written += relocalization_over_time(cells, read_csv(os.path.join(args.report_dir,
                                                                     "timeline.csv")), out_dir)
    written += consecutive_matrix(read_csv(os.path.join(args.report_dir, "consecutive.csv")),
                                  out_dir)
    written += merged_graphs(args.jobs_dir, out_dir)
    written += scaling_curve(read_csv(os.path.join(args.report_dir, "scaling.csv")), out_dir)
    write_report_md(args.report_dir, args.title, written)
    for path in written:
        print(path)
    return 0


FIGURE_CAPTIONS = [
    ("relocalization_single_", "Re-localization (% of frames) on single-session maps"),
    ("relocalization_multi_", "Re-localization (% of frames) on multi-session maps"),
    ("relocalization_over_time_", "Re-localization over time, coloured by the mapping session "
                                  "each frame was re-localized on"),
    ("consecutive", "Consecutive sessions: frames re-localized within 55 cm of the previous one"),
    ("merged_graph_", "Optimised graph of the largest merged map over its ground truth (top view)"),
    ("scaling", "Scaling curve: LCD + TE per frame, memory, map open time and re-localization "
                "against the number of sessions in the map (data in scaling.csv)"),
]


def compares_with_paper(agreement_json):
    """Whether agreement.json holds a deviation over some cells or a decided finding."""
    if not os.path.exists(agreement_json):
        return True  # written before agreement.json: keep agreement.md as it is
    with open(agreement_json) as f:
        agreement = json.load(f)
    return (any(d.get("cells", 0) > 0 for d in agreement.get("deviations", []))
            or agreement.get("findings_decided", 0) > 0)


def write_report_md(report_dir, title, figures):
    tables_path = os.path.join(report_dir, "tables.md")
    tables = open(tables_path).read() if os.path.exists(tables_path) else ""
    agreement_path = os.path.join(report_dir, "agreement.md")
    agreement = open(agreement_path).read() if os.path.exists(agreement_path) else ""
    if agreement and not compares_with_paper(os.path.join(report_dir, "agreement.json")):
        # An experiment of its own (the lifelong scaling curve): nothing to agree with.
        agreement = ("No cell of this experiment has a paper value and no finding is decided: "
                     "agreement.md lists why.\n")
    lines = [f"# duskmap report{': ' + title if title else ''}", "",
             "Each cell: measured (paper). Tables as CSV in tables/, LaTeX in tables.tex.", ""]
    if agreement:
        lines += ["## Agreement with the paper", "",
                  "As data in agreement.json; how each finding is decided: "
                  "docs/experiments.md, \"Agreement with the paper\".", "", agreement]
    lines += ["## Tables", "", tables, "## Figures", ""]
    for prefix, caption in FIGURE_CAPTIONS:
        mine = sorted(p for p in figures if os.path.basename(p).startswith(prefix))
        if not mine:
            continue
        lines += [f"### {caption}", ""]
        for path in mine:
            rel = os.path.relpath(path, report_dir)
            lines += [f"![{os.path.basename(path)}]({rel})", ""]
    with open(os.path.join(report_dir, "report.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
