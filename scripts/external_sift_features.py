#!/usr/bin/env python3
"""An "external" feature extractor for duskmap's h5 feature type, as a worked
example of bringing your own features (docs/features.md, "Bring your own
features").

It reads the image list that `duskmap features export --image-list` writes
(one "<group name>\t<image file>" line per frame), runs OpenCV's Python SIFT on
each image, and writes the features in hloc's HDF5 layout: one group per
image with keypoints (N x 2 float32, OpenCV's pixel-centre convention),
descriptors (D x N float32) and scores (N float32). Replace `detect` with
your own model to score it through the paper's protocol.

Usage: external_sift_features.py IMAGE_LIST OUT.h5 [--max-features N]
Needs Debian's python3-opencv, python3-h5py and python3-numpy.
"""
import argparse
import os
import sys

import cv2
import h5py
import numpy as np


def detect(gray, max_features):
    """Keypoints (N x 2), descriptors (N x D) and scores (N) of one image."""
    sift = cv2.SIFT_create(nfeatures=max_features, contrastThreshold=0.02)
    keypoints, descriptors = sift.detectAndCompute(gray, None)
    if descriptors is None:
        return np.zeros((0, 2), np.float32), np.zeros((0, 128), np.float32), np.zeros(0, np.float32)
    xy = np.array([k.pt for k in keypoints], np.float32)
    scores = np.array([k.response for k in keypoints], np.float32)
    return xy, descriptors.astype(np.float32), scores


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("image_list")
    parser.add_argument("output")
    parser.add_argument("--max-features", type=int, default=1000)
    args = parser.parse_args()
    with open(args.image_list) as f:
        rows = [line.rstrip("\n").split("\t") for line in f if line.strip()]
    for number, row in enumerate(rows, 1):
        if len(row) != 2:
            sys.exit(f"{args.image_list}:{number}: expected '<group name><TAB><image file>'")
    partial = args.output + ".partial"
    with h5py.File(partial, "w") as out:
        for group_name, image_file in rows:
            gray = cv2.imread(image_file, cv2.IMREAD_GRAYSCALE)
            if gray is None:
                sys.exit(f"{image_file}: cannot read image")
            xy, descriptors, scores = detect(gray, args.max_features)
            group = out.create_group(group_name)
            group["keypoints"] = xy
            group["descriptors"] = descriptors.T  # D x N, as hloc stores them
            group["scores"] = scores
    os.replace(partial, args.output)
    print(f"{args.output}: {len(rows)} images")


if __name__ == "__main__":
    main()
