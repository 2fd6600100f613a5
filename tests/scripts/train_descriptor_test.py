#!/usr/bin/python3
"""Tests of scripts/train_descriptor.py: its bad input, and a tiny training run end to end.

Run by ctest as scripts/TrainDescriptor; the training run is skipped without python3-torch.
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "train_descriptor.py")


def have_torch():
    try:
        import torch  # noqa: F401
        return True
    except ImportError:
        return False


def write_data(folder, pairs=1536, version=1, fmt="duskmap-training-pairs"):
    """A training-data folder of structured pairs: each B patch is its A patch lit differently."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng(3)
    import cv2
    coarse = rng.random((pairs, 6, 6)).astype(np.float32) * 255
    a = np.stack([cv2.resize(c, (32, 32), interpolation=cv2.INTER_CUBIC) for c in coarse])
    gain = rng.uniform(0.3, 1.2, (pairs, 1, 1))
    b = a * gain + rng.normal(0, 6, a.shape)
    np.clip(np.stack([a, b], 1), 0, 255).astype(np.uint8).tofile(os.path.join(folder, "patches.u8"))
    (rng.random((pairs, 3)) * 10).astype("<f4").tofile(os.path.join(folder, "points.f32"))
    split = pairs * 3 // 4
    manifest = {"format": fmt, "version": version, "patch": {"patch_size_px": 32}, "pairs": pairs,
                "scenes": [{"index": 0, "first_pair": 0, "pairs": split, "split": "train"},
                           {"index": 1, "first_pair": split, "pairs": pairs - split, "split": "validation"}]}
    with open(os.path.join(folder, "manifest.json"), "w") as f:
        json.dump(manifest, f)


def write_config(path, train=None):
    with open(path, "w") as f:
        json.dump({"data": {}, "train": train if train is not None else
                   {"epochs": 2, "batch_pairs": 256, "validation_block": 128}}, f)


class TrainDescriptorTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.data = os.path.join(self.dir, "data")
        self.config = os.path.join(self.dir, "config.json")
        self.model = os.path.join(self.dir, "model.onnx")
        write_data(self.data)
        write_config(self.config)

    def tearDown(self):
        self.tmp.cleanup()

    def run_script(self, *extra):
        args = [sys.executable, SCRIPT, "--data", self.data, "--config", self.config, "--out", self.model,
                "--figure", os.path.join(self.dir, "curve.png")] + list(extra)
        return subprocess.run(args, capture_output=True, text=True)

    def assert_fails_with(self, fragment):
        result = self.run_script()
        self.assertNotEqual(result.returncode, 0, result.stdout)
        lines = result.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, result.stderr)
        self.assertIn(fragment, lines[0])
        return lines[0]

    def test_missing_manifest_is_an_incomplete_folder(self):
        os.remove(os.path.join(self.data, "manifest.json"))
        self.assertIn("manifest.json", self.assert_fails_with("incomplete training-data folder"))

    def test_missing_patches_file(self):
        os.remove(os.path.join(self.data, "patches.u8"))
        self.assertIn("patches.u8", self.assert_fails_with("incomplete training-data folder"))

    def test_truncated_points_file(self):
        path = os.path.join(self.data, "points.f32")
        with open(path, "r+b") as f:
            f.truncate(100)
        self.assertIn("points.f32", self.assert_fails_with("the manifest says"))

    def test_other_version(self):
        write_data(self.data, version=2)
        self.assert_fails_with("version 2")

    def test_other_format(self):
        write_data(self.data, fmt="something-else")
        self.assert_fails_with("not a duskmap-training-pairs manifest")

    def test_unknown_train_key(self):
        write_config(self.config, {"epochz": 3})
        self.assert_fails_with("train.epochz: unknown key")

    def test_missing_config(self):
        os.remove(self.config)
        self.assert_fails_with("no such file")

    def test_refuses_to_replace_a_file_it_did_not_write(self):
        with open(self.model, "wb") as f:
            f.write(b"someone's model")
        self.assert_fails_with("not replaced")
        with open(self.model, "rb") as f:
            self.assertEqual(f.read(), b"someone's model")

    @unittest.skipUnless(have_torch(), "python3-torch is not installed (scripts/setup.sh installs it)")
    def test_tiny_training_run_exports_a_model_opencv_runs(self):
        result = self.run_script()
        self.assertEqual(result.returncode, 0, result.stderr)
        import cv2
        import onnx
        props = {p.key: p.value for p in onnx.load(self.model).metadata_props}
        self.assertEqual(props["producer"], "duskmap scripts/train_descriptor.py")
        net = cv2.dnn.readNetFromONNX(self.model)
        net.setInput(np.random.default_rng(0).random((5, 1, 32, 32)).astype(np.float32))
        out = net.forward()
        self.assertEqual(out.shape, (5, 128))
        np.testing.assert_allclose(np.linalg.norm(out, axis=1), 1.0, atol=1e-5)
        with open(os.path.join(self.dir, "model_training_log.jsonl")) as f:
            lines = [json.loads(line) for line in f]
        self.assertIn("hyper_parameters", lines[0])
        self.assertEqual([e["epoch"] for e in lines[1:-1]], [1, 2])
        self.assertGreater(lines[-1]["validation_accuracy"], 0.5)  # the pairs are learnable
        self.assertTrue(os.path.isfile(os.path.join(self.dir, "curve.png")))
        with open(os.path.join(self.dir, "model_reference.json")) as f:
            reference = json.load(f)
        self.assertEqual(len(reference["patches"]), 16)
        self.assertEqual(len(reference["patches"][0]), 32 * 32)
        patches = np.array(reference["patches"], dtype=np.float32).reshape(16, 1, 32, 32) / 255.0
        net.setInput(patches)
        np.testing.assert_allclose(net.forward(), np.array(reference["descriptors"]), atol=1e-5)
        self.assertEqual(self.run_script().returncode, 0)  # replaces a model it wrote


if __name__ == "__main__":
    unittest.main()
