#!/usr/bin/python3
"""KAZE and SIFT keypoints per image with the paper's detector settings, and
their ratio: how a set of images compares with the paper's apartment (KAZE
640 / SIFT 770 features per frame) and with real photographs
(docs/calibration_log.md, "KAZE's features per frame against real
photographs").

OpenCV's KAZE (threshold 0.001, 4 octaves, 4 sublevels, PM_G2 diffusivity,
not extended, not upright) and SIFT (contrast threshold 0.02), uncapped, on
the grey image scaled to 640 pixels wide (area interpolation).

Usage: kaze_sift_ratio.py GLOB [GLOB ...] [--step N]
  one line per glob: images, mean KAZE, mean SIFT, their ratio, mean grey.
Needs Debian's python3-opencv and python3-numpy.
"""
import argparse
import glob
import sys

import cv2
import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("globs", nargs="+", help="image file patterns (quote them)")
    parser.add_argument("--step", type=int, default=1, help="every N-th image of each glob, sorted by name")
    args = parser.parse_args()
    if args.step < 1:
        sys.exit("kaze_sift_ratio.py: --step must be >= 1")
    kaze = cv2.KAZE_create(False, False, 0.001, 4, 4, cv2.KAZE_DIFF_PM_G2)
    sift = cv2.SIFT_create(0, 3, 0.02)
    status = 0
    for pattern in args.globs:
        files = sorted(glob.glob(pattern))[:: args.step]
        if not files:
            print(f"{pattern}: no image matches", file=sys.stderr)
            status = 1
            continue
        counts = []
        for path in files:
            grey = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
            if grey is None:
                print(f"{path}: not an image OpenCV can read", file=sys.stderr)
                status = 1
                continue
            if grey.shape[1] != 640:
                height = int(round(grey.shape[0] * 640 / grey.shape[1]))
                grey = cv2.resize(grey, (640, height), interpolation=cv2.INTER_AREA)
            counts.append((len(kaze.detect(grey)), len(sift.detect(grey)), grey.mean()))
        if not counts:
            continue
        c = np.array(counts)
        print(f"{pattern}: {len(c)} images, KAZE {c[:, 0].mean():.0f}, SIFT {c[:, 1].mean():.0f}, "
              f"KAZE/SIFT {c[:, 0].mean() / c[:, 1].mean():.2f}, mean grey {c[:, 2].mean():.0f}")
    return status


if __name__ == "__main__":
    sys.exit(main())
