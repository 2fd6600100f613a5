#!/usr/bin/python3
"""scripts/plot_report.py's scaling figure: drawn from scaling.csv (a measure left empty where no job
measured it) and listed in report.md; without scaling.csv neither. report.md's agreement section:
kept when some cell or finding compares with the paper, one line when none does."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "plot_report.py")
CELLS_HEADER = ("feature,row,session,job,frames,relocalized_pct,correct_pct,wrong,no_candidate_pct,"
                "mean_inliers_pct,mean_jump_mm,correct_0.25m_2deg_pct,correct_5m_10deg_pct\n")
SCALING_HEADER = ("feature,map,sessions,nodes,lcd_te_ms,lcd_ms,te_ms,memory_mb,map_load_s,"
                  "localizer_setup_s,map_open_s,relocalized_pct,correct_pct\n")


def write_report_dir(root, scaling_rows):
    with open(os.path.join(root, "cells.csv"), "w") as f:
        f.write(CELLS_HEADER)
    with open(os.path.join(root, "tables.md"), "w") as f:
        f.write("| map | SI |\n")
    if scaling_rows is not None:
        with open(os.path.join(root, "scaling.csv"), "w") as f:
            f.write(SCALING_HEADER + "".join(line + "\n" for line in scaling_rows))


def plot(root):
    return subprocess.run([sys.executable, SCRIPT, root, "--title", "curve.json"],
                          capture_output=True, text=True)


class ScalingFigure(unittest.TestCase):
    def test_drawn_from_scaling_csv_and_listed_in_report_md(self):
        with tempfile.TemporaryDirectory() as root:
            write_report_dir(root, [
                'SI,"1",1,100,10,4,6,1.5,0.5,0.1,0.6,50,40',
                'SI,"1-2",2,180,12,5,7,2.5,0.9,0.1,1,60,50',
                # The map open time of a map whose loading job did not run: no point.
                'SI,"1-2-3",3,250,15,6,9,3.5,,0.1,,70,60',
                'OR,"1",1,90,5,2,3,1,0.3,0.1,0.4,40,30',
                'OR,"1-2",2,170,6,2,4,2,0.5,0.1,0.6,45,35',
                'OR,"1-2-3",3,240,7,3,4,3,0.7,0.1,0.8,50,40',
            ])
            result = plot(root)
            self.assertEqual(result.returncode, 0, result.stderr)
            figure = os.path.join(root, "figures", "scaling.png")
            self.assertTrue(os.path.exists(figure), result.stdout)
            with open(figure, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            with open(os.path.join(root, "report.md")) as f:
                report = f.read()
            self.assertIn("![scaling.png](figures/scaling.png)", report)
            self.assertIn("### Scaling curve", report)

    def test_none_without_scaling_csv(self):
        with tempfile.TemporaryDirectory() as root:
            write_report_dir(root, None)
            result = plot(root)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertFalse(os.path.exists(os.path.join(root, "figures", "scaling.png")))
            with open(os.path.join(root, "report.md")) as f:
                self.assertNotIn("scaling", f.read().lower())


def write_agreement(root, cells, decided):
    with open(os.path.join(root, "agreement.md"), "w") as f:
        f.write("**Mean absolute deviation from the paper** AGREEMENT TABLE\n")
    with open(os.path.join(root, "agreement.json"), "w") as f:
        json.dump({"deviations": [{"name": "re-localization, single-session maps", "cells": cells}],
                   "findings_decided": decided}, f)


class AgreementSection(unittest.TestCase):
    def report_md(self, cells, decided):
        with tempfile.TemporaryDirectory() as root:
            write_report_dir(root, None)
            write_agreement(root, cells, decided)
            result = plot(root)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(os.path.join(root, "report.md")) as f:
                return f.read()

    def test_kept_when_a_cell_or_a_finding_compares(self):
        self.assertIn("AGREEMENT TABLE", self.report_md(cells=36, decided=0))
        self.assertIn("AGREEMENT TABLE", self.report_md(cells=0, decided=1))

    def test_one_line_when_nothing_compares(self):
        report = self.report_md(cells=0, decided=0)
        self.assertNotIn("AGREEMENT TABLE", report)
        self.assertIn("No cell of this experiment has a paper value", report)


if __name__ == "__main__":
    unittest.main()
