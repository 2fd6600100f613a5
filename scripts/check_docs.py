#!/usr/bin/python3
"""Checks that the docs say what the tree is (run by scripts/test.sh).

1. Every path into the repository that a doc names in backticks
   (`slam/features/superpoint.h`, `features/h5_extractor.h` for a module's
   file, `scripts/setup.sh`, `configs/paper_matrix.json`, ...) exists. Bare
   file names are not checked: docs also name output files and other
   projects' sources that way.
2. A test count the README quotes ("N tests") is the number ctest lists,
   when a build folder is given.
3. docs/architecture.md's module table has a row (`| `m/` | ...`) for every
   module folder of slam/ and for every sub-module folder holding sources
   (`| `synthetic/scene/` | ...`), and the page says where the spec that
   comments cite as "spec §" lives.
4. The committed reference report is the main job's: results/paper_matrix/report.md
   is titled after configs/paper_matrix.json, and no committed result under
   results/ holds an absolute path of a machine (a JSON string, or a CSV or
   markdown field, starting with "/").
5. The includes of slam/ follow docs/architecture.md's module table and
   synthetic/'s sub-module order, with no cycle between units
   (scripts/check_includes.py).

Usage: check_docs.py [BUILD_DIR]     exit 1 with one line per problem
"""
import json
import os
import re
import subprocess
import sys

import check_includes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = ["README.md"] + sorted(os.path.join("docs", f) for f in os.listdir(os.path.join(ROOT, "docs"))
                              if f.endswith(".md"))
FILE_TOKEN = re.compile(r"`([A-Za-z0-9_./-]+\.(?:h|cc|py|sh|json|md|txt|csv))`")
SKIPPED_DIRS = {".git", "build", "build-sanitize", "out", "data"}


def repository_files():
    paths = set()
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d not in SKIPPED_DIRS and not d.startswith(".")]
        for f in files:
            rel = os.path.relpath(os.path.join(folder, f), ROOT)
            paths.add(rel)
    return paths


MODULE_ROW = re.compile(r"^\| `([A-Za-z0-9_/]+/)` \|", re.M)


def module_folders():
    """slam/'s module folders and their sub-module folders that hold sources, as `m/`, `m/sub/`."""
    slam = os.path.join(ROOT, "slam")
    folders = []
    for module in sorted(os.listdir(slam)):
        path = os.path.join(slam, module)
        if not os.path.isdir(path):
            continue
        folders.append(module + "/")
        for folder, dirs, files in os.walk(path):
            dirs.sort()
            if folder != path and any(f.endswith((".h", ".cc")) for f in files):
                folders.append(os.path.relpath(folder, slam).replace(os.sep, "/") + "/")
    return folders


ABSOLUTE_PATH = re.compile(r"(?:^|[\s(,|\"'`])(/(?:work|home|tmp|root|mnt|var|srv|opt|data)/[^\s,|\"'`)]*)")


def results_problems():
    problems = []
    report = os.path.join(ROOT, "results", "paper_matrix", "report.md")
    if os.path.exists(report):
        with open(report, encoding="utf-8") as text:
            title = text.readline().strip()
        if title != "# duskmap report: paper_matrix.json":
            problems.append(f"results/paper_matrix/report.md: titled '{title}', not the main job's "
                            "configs/paper_matrix.json")
    for folder, dirs, files in os.walk(os.path.join(ROOT, "results")):
        for name in files:
            if not name.endswith((".json", ".md", ".csv", ".tex")):
                continue
            path = os.path.join(folder, name)
            with open(path, encoding="utf-8") as text:
                for number, line in enumerate(text, 1):
                    found = ABSOLUTE_PATH.search(line)
                    if found:
                        problems.append(f"{os.path.relpath(path, ROOT)}:{number}: names the machine path "
                                        f"{found.group(1)}")
                        break
    return problems


def main():
    problems = []
    paths = repository_files()
    modules = sorted(d for d in os.listdir(os.path.join(ROOT, "slam"))
                     if os.path.isdir(os.path.join(ROOT, "slam", d)))
    top = ("slam/", "tests/", "bench/", "scripts/", "configs/", "experiments/", "docs/", "results/")
    for doc in DOCS:
        with open(os.path.join(ROOT, doc), encoding="utf-8") as text:
            for number, line in enumerate(text, 1):
                for token in FILE_TOKEN.findall(line):
                    # Paths into the repository only: from its root, or from slam/ for a module's file.
                    from_root = token.startswith(top)
                    from_slam = token.split("/")[0] in modules and "/" in token
                    if not (from_root or from_slam) or "*" in token or "{" in token:
                        continue
                    path = token if from_root else os.path.join("slam", token)
                    if path not in paths and not os.path.exists(os.path.join(ROOT, path)):
                        problems.append(f"{doc}:{number}: names `{token}`, which is not in the repository")
    if len(sys.argv) > 1:
        listed = subprocess.run(["ctest", "--test-dir", sys.argv[1], "-N"], capture_output=True, text=True)
        total = re.search(r"Total Tests: (\d+)", listed.stdout)
        if not total:
            problems.append(f"{sys.argv[1]}: `ctest -N` lists no tests (not a configured build folder?)")
        else:
            with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as text:
                readme = text.read()
            # "N tests" may break across lines ("the 958\ntests").
            for quoted in re.finditer(r"\b(\d{3,})\s+tests\b", readme):
                if quoted.group(1) != total.group(1):
                    number = readme.count("\n", 0, quoted.start()) + 1
                    problems.append(f"README.md:{number}: quotes {quoted.group(1)} tests; ctest lists {total.group(1)}")
    with open(os.path.join(ROOT, "docs", "architecture.md"), encoding="utf-8") as text:
        architecture = text.read()
    rows = set(MODULE_ROW.findall(architecture))
    folders = set(module_folders())
    for folder in sorted(folders):
        if folder not in rows:
            problems.append(f"docs/architecture.md: the module table has no row for slam/{folder}")
    for row in sorted(rows - folders):
        problems.append(f"docs/architecture.md: the module table has a row for slam/{row}, which holds no sources")
    if "rtabmap_algorithms.md" not in architecture:
        problems.append("docs/architecture.md: does not say where the spec cited as \"spec §\" lives")
    problems += results_problems()
    problems += check_includes.problems()
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
