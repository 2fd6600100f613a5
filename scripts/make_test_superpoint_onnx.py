#!/usr/bin/python3
"""Writes an ONNX model with SuperPoint's architecture and deterministic random weights.

The network is layer-for-layer the SuperPointNet of DeTone et al. (Magic Leap's
reference implementation): a VGG-style shared encoder (conv1a/b 64, conv2a/b 64,
conv3a/b 128, conv4a/b 128, 3x3 convolutions with ReLU, 2x2 max-pool after the
first three blocks), a detector head (convPa 3x3 256 + ReLU, convPb 1x1 65 ->
output "semi") and a descriptor head (convDa 3x3 256 + ReLU, convDb 1x1 256 ->
output "desc"). Input "image": 1x1xHxW gray in [0, 1], H and W multiples of 8.

The weights are random (He initialisation from numpy's seeded generator), so the
model is only good for testing duskmap's decoding: the official weights carry a
non-commercial licence and are not shipped (docs/features.md explains how to
export them to ONNX with the same input and output names).

Usage: make_test_superpoint_onnx.py OUT.onnx [--seed N] [--wrong-head]
  --wrong-head writes a detector head with 64 channels (a malformed model for tests).
Needs Debian's python3-onnx and python3-numpy.
"""
import argparse

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper


def conv(nodes, inits, rng, name, x, c_in, c_out, k, relu):
    w = (rng.standard_normal((c_out, c_in, k, k)) * np.sqrt(2.0 / (c_in * k * k))).astype(np.float32)
    b = (rng.standard_normal(c_out) * 0.01).astype(np.float32)
    inits += [numpy_helper.from_array(w, name + ".weight"), numpy_helper.from_array(b, name + ".bias")]
    out = name if not relu else name + "_pre"
    nodes.append(helper.make_node("Conv", [x, name + ".weight", name + ".bias"], [out],
                                  kernel_shape=[k, k], pads=[k // 2] * 4, strides=[1, 1]))
    if relu:
        nodes.append(helper.make_node("Relu", [out], [name]))
    return name


def pool(nodes, name, x):
    nodes.append(helper.make_node("MaxPool", [x], [name], kernel_shape=[2, 2], strides=[2, 2]))
    return name


def build(seed, wrong_head):
    rng = np.random.default_rng(seed)
    nodes, inits = [], []
    x = "image"
    encoder = [("conv1a", 1, 64), ("conv1b", 64, 64), ("pool1", 0, 0),
               ("conv2a", 64, 64), ("conv2b", 64, 64), ("pool2", 0, 0),
               ("conv3a", 64, 128), ("conv3b", 128, 128), ("pool3", 0, 0),
               ("conv4a", 128, 128), ("conv4b", 128, 128)]
    for name, c_in, c_out in encoder:
        x = pool(nodes, name, x) if name.startswith("pool") else conv(nodes, inits, rng, name, x, c_in, c_out, 3, True)
    pa = conv(nodes, inits, rng, "convPa", x, 128, 256, 3, True)
    detector_channels = 64 if wrong_head else 65
    conv(nodes, inits, rng, "semi", pa, 256, detector_channels, 1, False)
    da = conv(nodes, inits, rng, "convDa", x, 128, 256, 3, True)
    conv(nodes, inits, rng, "desc", da, 256, 256, 1, False)
    graph = helper.make_graph(
        nodes, "superpoint_random",
        [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 1, "H", "W"])],
        [helper.make_tensor_value_info("semi", TensorProto.FLOAT, [1, detector_channels, "Hc", "Wc"]),
         helper.make_tensor_value_info("desc", TensorProto.FLOAT, [1, 256, "Hc", "Wc"])],
        inits)
    model = helper.make_model(graph, producer_name="duskmap", opset_imports=[helper.make_opsetid("", 11)])
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=20180620)
    parser.add_argument("--wrong-head", action="store_true")
    args = parser.parse_args()
    onnx.save(build(args.seed, args.wrong_head), args.out)


if __name__ == "__main__":
    main()
