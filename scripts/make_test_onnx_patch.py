#!/usr/bin/python3
"""Writes a small ONNX patch descriptor for testing the `patch` contract (docs/features.md).

The network is linear: input "patches" Nx1xPxP (N dynamic), Flatten, then
Gemm with seeded random weights W (D x P*P) and bias b: output "descriptors"
NxD = x W^T + b. A test computes the same from W and b (--weights), so the
contract's input scaling, batching and L2 normalisation are checked against
a reference. It is untrained: its descriptors are random projections.

  --weights FILE        also writes W (D*P*P float32, row-major) then b (D
                        float32), little-endian
  --input-channels C    declares Nx C xPxP (C != 1 breaks the contract)
  --input-size S        declares NxSxS instead of PxP (breaks it for S != P)
  --output-rank3        output NxDx1 instead of NxD (breaks it)
  --nan                 a NaN bias: every output value is NaN (breaks it)
  --global-pool         GlobalAveragePool before the Gemm (W is D x C): the
                        network runs on any patch size, so only its declared
                        input size can break the contract

Usage: make_test_onnx_patch.py OUT.onnx [--patch P] [--dims D] [--seed N] [flags]
Needs Debian's python3-onnx and python3-numpy.
"""
import argparse

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper


def build(args):
    size = args.input_size or args.patch
    inputs_per_patch = args.input_channels * (1 if args.global_pool else size * size)
    rng = np.random.default_rng(args.seed)
    w = (rng.standard_normal((args.dims, inputs_per_patch)) / np.sqrt(inputs_per_patch)).astype(np.float32)
    b = (rng.standard_normal(args.dims) * 0.1).astype(np.float32)
    if args.nan:
        b[:] = np.nan
    inits = [numpy_helper.from_array(w, "W"), numpy_helper.from_array(b, "b")]
    nodes = [helper.make_node("Flatten", ["pooled" if args.global_pool else "patches"], ["flat"], axis=1),
             helper.make_node("Gemm", ["flat", "W", "b"], ["projected"], transB=1)]
    if args.global_pool:
        nodes.insert(0, helper.make_node("GlobalAveragePool", ["patches"], ["pooled"]))
    last = "projected"
    out_shape = ["N", args.dims]
    if args.output_rank3:
        inits.append(numpy_helper.from_array(np.array([-1, args.dims, 1], np.int64), "rank3"))
        nodes.append(helper.make_node("Reshape", [last, "rank3"], ["reshaped"]))
        last = "reshaped"
        out_shape = ["N", args.dims, 1]
    nodes.append(helper.make_node("Identity", [last], ["descriptors"]))
    graph = helper.make_graph(
        nodes, "patch_descriptor",
        [helper.make_tensor_value_info("patches", TensorProto.FLOAT, ["N", args.input_channels, size, size])],
        [helper.make_tensor_value_info("descriptors", TensorProto.FLOAT, out_shape)],
        initializer=inits)
    model = helper.make_model(graph, producer_name="duskmap make_test_onnx_patch.py",
                              opset_imports=[helper.make_opsetid("", 11)])
    model.ir_version = 6
    onnx.checker.check_model(model)
    return model, w, b


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--patch", type=int, default=32)
    parser.add_argument("--dims", type=int, default=16)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--weights")
    parser.add_argument("--input-channels", type=int, default=1)
    parser.add_argument("--input-size", type=int, default=0)
    parser.add_argument("--output-rank3", action="store_true")
    parser.add_argument("--nan", action="store_true")
    parser.add_argument("--global-pool", action="store_true")
    args = parser.parse_args()
    model, w, b = build(args)
    onnx.save(model, args.out)
    if args.weights:
        with open(args.weights, "wb") as f:
            f.write(w.astype("<f4").tobytes())
            f.write(b.astype("<f4").tobytes())


if __name__ == "__main__":
    main()
