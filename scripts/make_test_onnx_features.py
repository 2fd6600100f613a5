#!/usr/bin/python3
"""Writes small ONNX local-feature models for testing duskmap's generic `onnx` type.

Two contracts (docs/features.md, "Any ONNX local-feature model"):

  dense   (ALIKED/DISK-style): outputs "score_map" 1x1xHxW in (0, 1) (a sigmoid
          of a zero-mean 3x3 filter: 0.5 where the image is flat) and
          "descriptor_map" 1xDxHxW (a 3x3 convolution), both at full
          resolution (stride 1).
  sparse  (keypoints, descriptors and scores as outputs): the image is cut into
          8x8 cells; per cell the keypoint is the softmax-weighted mean position
          of the same kind of sigmoid response (a soft arg-max, subpixel), its
          score the softmax-weighted response (about the cell's largest), its
          descriptor a 1x1 convolution of the cell's 64 pixels. Outputs
          "keypoints" 1xNx2 (x, y, pixel centres), "descriptors" 1xNxD and
          "scores" 1xN, N = H/8 * W/8.
          No TopK: OpenCV 4.6's DNN module cannot import it.

Input "image": 1x1xHxW gray, or 1x3xHxW with --rgb (any H, W; the sparse model
needs multiples of 8). The weights are random (numpy's seeded generator): the
models are only good for testing the decoding and the contract checks.

  --malformed  writes a model that breaks its contract: the dense one gives its
               score map 2 channels, the sparse one gives 3 keypoint coordinates.
  --topk       passes the sparse model's scores through TopK (as exports that
               select their keypoints inside the graph do): OpenCV 4.6 cannot
               import it.
  --poison-scores nan|inf, --poison-descriptors nan|inf
               adds NaN or +infinity to every value of the dense model's score
               or descriptor map (a broken export: duskmap must refuse it).

Usage: make_test_onnx_features.py OUT.onnx --contract dense|sparse [--rgb]
       [--dims D] [--seed N] [--malformed] [--topk]
       [--poison-scores nan|inf] [--poison-descriptors nan|inf]
Needs Debian's python3-onnx and python3-numpy.
"""
import argparse

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper


class Graph:
    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)
        self.nodes, self.inits = [], []
        self.count = 0

    def name(self, stem):
        self.count += 1
        return f"{stem}_{self.count}"

    def const(self, value, dtype=np.float32):
        name = self.name("const")
        self.inits.append(numpy_helper.from_array(np.array(value, dtype=dtype), name))
        return name

    def op(self, op_type, inputs, output=None, **attributes):
        output = output or self.name(op_type.lower())
        self.nodes.append(helper.make_node(op_type, inputs, [output], **attributes))
        return output

    def conv(self, x, c_in, c_out, k, output=None):
        w = (self.rng.standard_normal((c_out, c_in, k, k)) * np.sqrt(2.0 / (c_in * k * k))).astype(np.float32)
        b = (self.rng.standard_normal(c_out) * 0.01).astype(np.float32)
        return self.op("Conv", [x, self.const(w), self.const(b)], output,
                       kernel_shape=[k, k], pads=[k // 2] * 4, strides=[1, 1])

    def score(self, x, c_in, output=None):
        """Sigmoid of a zero-mean 3x3 filter with gain: 0.5 on flat regions,
        above it at the filter's structures (a detector-like response)."""
        w = self.rng.standard_normal((1, c_in, 3, 3))
        w = (8.0 * (w - w.mean()) / np.abs(w - w.mean()).sum()).astype(np.float32)
        response = self.op("Conv", [x, self.const(w)], kernel_shape=[3, 3], pads=[1] * 4)
        return self.op("Sigmoid", [response], output)


def poisoned(g, value, poison, output):
    """`value` + NaN or +inf under the name `output`; `value` itself without poison."""
    if not poison:
        return g.op("Identity", [value], output)
    return g.op("Add", [value, g.const(np.nan if poison == "nan" else np.inf)], output)


def dense(g, x, channels, dims, malformed, topk=False, poison_scores=None, poison_descriptors=None):
    if malformed:
        g.op("Concat", [g.score(x, channels), g.score(x, channels)], "score_map", axis=1)
    elif poison_scores:
        poisoned(g, g.score(x, channels), poison_scores, "score_map")
    else:
        g.score(x, channels, "score_map")
    score_channels = 2 if malformed else 1
    if poison_descriptors:
        poisoned(g, g.conv(x, channels, dims, 3), poison_descriptors, "descriptor_map")
    else:
        g.conv(x, channels, dims, 3, "descriptor_map")
    return [("score_map", [1, score_channels, "H", "W"]), ("descriptor_map", [1, dims, "H", "W"])]


def sparse(g, x, channels, dims, malformed, topk=False, poison_scores=None, poison_descriptors=None):
    gray = g.conv(x, channels, 1, 1) if channels != 1 else x
    response = g.score(gray, 1)
    ones = g.op("Add", [g.op("Mul", [gray, g.const(0.0)]), g.const(1.0)])
    axis = lambda a: g.const(a, np.int64)
    # Pixel columns and rows (a CumSum over axis 2 crashes OpenCV 4.6's DNN:
    # rows are the columns of the transposed image).
    column_of = lambda t: g.op("Sub", [g.op("CumSum", [t, axis(3)]), g.const(1.0)])
    x_map = column_of(ones)
    y_map = g.op("Transpose", [column_of(g.op("Transpose", [ones], perm=[0, 1, 3, 2]))], perm=[0, 1, 3, 2])
    # Space to depth as a stride-8 convolution with one-hot kernels (OpenCV
    # imports SpaceToDepth only on tensors of a size known at load time):
    # channel 8 r + c of cell (i, j) is pixel (8 i + r, 8 j + c).
    one_hot = g.const(np.eye(64, dtype=np.float32).reshape(64, 1, 8, 8))
    cells = lambda t: g.op("Conv", [t, one_hot], kernel_shape=[8, 8], strides=[8, 8])
    cell_response = cells(response)
    weight = g.op("Softmax", [g.op("Mul", [cell_response, g.const(50.0)])], axis=1)
    channel_sum = g.const(np.ones((1, 64, 1, 1)))  # a 1x1 convolution sums the 64 channels
    mean_of = lambda t: g.op("Conv", [g.op("Mul", [weight, cells(t)]), channel_sum], kernel_shape=[1, 1])
    coordinates = [mean_of(x_map), mean_of(y_map)]
    if malformed:
        coordinates.append(mean_of(y_map))
    flat = g.const([0, 0, -1], np.int64)
    xy = g.op("Concat", coordinates, axis=1)
    g.op("Transpose", [g.op("Reshape", [xy, flat])], "keypoints", perm=[0, 2, 1])
    score = mean_of(response)  # the soft maximum (no ReduceMax: OpenCV 4.6 imports it as reshapes)
    if topk:
        flat_score = g.op("Reshape", [score, g.const([0, -1], np.int64)])
        g.nodes.append(helper.make_node("TopK", [flat_score, g.const([4], np.int64)],
                                        ["scores", "score_indices"], axis=1))
    else:
        g.op("Reshape", [score, g.const([0, -1], np.int64)], "scores")
    descriptor = g.conv(cells(gray), 64, dims, 1)
    g.op("Transpose", [g.op("Reshape", [descriptor, flat])], "descriptors", perm=[0, 2, 1])
    return [("keypoints", [1, "N", 3 if malformed else 2]), ("descriptors", [1, "N", dims]),
            ("scores", [1, "N"])]


def build(contract, rgb, dims, seed, malformed, topk=False, poison_scores=None, poison_descriptors=None):
    g = Graph(seed)
    channels = 3 if rgb else 1
    outputs = (dense if contract == "dense" else sparse)(g, "image", channels, dims, malformed, topk,
                                                         poison_scores, poison_descriptors)
    graph = helper.make_graph(
        g.nodes, f"{contract}_features_random",
        [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, channels, "H", "W"])],
        [helper.make_tensor_value_info(name, TensorProto.FLOAT, shape) for name, shape in outputs],
        g.inits)
    model = helper.make_model(graph, producer_name="duskmap", opset_imports=[helper.make_opsetid("", 13)])
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--contract", choices=["dense", "sparse"], required=True)
    parser.add_argument("--rgb", action="store_true")
    parser.add_argument("--dims", type=int, default=32)
    parser.add_argument("--seed", type=int, default=20240611)
    parser.add_argument("--malformed", action="store_true")
    parser.add_argument("--topk", action="store_true")
    parser.add_argument("--poison-scores", choices=["nan", "inf"])
    parser.add_argument("--poison-descriptors", choices=["nan", "inf"])
    args = parser.parse_args()
    if (args.poison_scores or args.poison_descriptors) and args.contract != "dense":
        parser.error("--poison-scores and --poison-descriptors are for the dense contract")
    onnx.save(build(args.contract, args.rgb, args.dims, args.seed, args.malformed, args.topk,
                    args.poison_scores, args.poison_descriptors), args.out)


if __name__ == "__main__":
    main()
