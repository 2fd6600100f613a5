#!/usr/bin/python3
"""Writes an ONNX model with SuperGlue's architecture and deterministic random weights.

The network follows SuperGlue (Sarlin, DeTone, Malisiewicz, Rabinovich, CVPR 2020) and the
layout of its reference implementation: a keypoint encoder MLP (Conv1d 3-32-64-128-256-256 with
BatchNorm and ReLU between layers) added to the 256-D descriptors; an attentional GNN of 18
layers alternating self and cross attention (4 heads, channel c of a projection belongs to head
c % 4, as in `view(b, 64, 4, n)`; each layer: q/k/v projections, softmax(q.k / 8), merge, then
the MLP 512-512-256 on [x, message], added residually); a final 256x256 projection; scores
<mdesc0_i, mdesc1_j> / 16 extended by one dustbin row and column holding the learned bin score;
and a fixed number of log-space Sinkhorn iterations. Initializer names follow the reference
state dict (kenc.encoder.0.weight, gnn.layers.3.attn.proj.1.bias, final_proj.weight, bin_score).

The graph is written so that OpenCV 4.6's importer can run it with any keypoint counts (no
Shape, Reduce or Einsum operators, which that importer cannot evaluate on dynamic sizes):
einsums are Transpose + MatMul, and each Sinkhorn half-step is a last-axis LogSoftmax plus the
log marginal (for the column step the matrix is transposed and back), which gives exactly the
reference's u/v iterations. The marginals are inputs, scaled by M + N so that the output equals
the reference's `Z - norm`:

  inputs   keypoints0 1xMx2, keypoints1 1xNx2   keypoints normalised as the reference does:
                                                (p - size/2) / (0.7 * max(width, height))
           scores0 1xM, scores1 1xN             SuperPoint detection scores
           descriptors0 1x256xM, descriptors1 1x256xN   L2-normalised SuperPoint descriptors
           log_mu 1x(M+1)x1 = [0 ... 0, log N]  log row marginals times (M + N)
           log_nu 1x(N+1)x1 = [0 ... 0, log M]  log column marginals times (M + N)
  output   scores 1x(M+1)x(N+1)                 log assignment (the reference's `scores` after
                                                log_optimal_transport), dustbins last

The weights are random (He initialisation, BatchNorm statistics near identity, bin score 1.0 as
the reference initialises it) from numpy's seeded generator: the model is only good for testing
duskmap's input preparation and decoding. docs/features.md explains how to export the official
weights with the same inputs and outputs.

Usage: make_test_superglue_onnx.py OUT.onnx [--seed N] [--iterations 20] [--layers 18]
                                   [--wrong-output] [--test-vector DIR]
  --wrong-output   returns the assignment transposed (1x(N+1)x(M+1)): a malformed model for tests.
  --test-vector    also writes DIR/{inputs,expected}: a small random input pair and the log
                   assignment computed by a plain numpy transcription of the reference
                   equations (einsum attention, logsumexp Sinkhorn), to check the graph.
Needs Debian's python3-onnx and python3-numpy.
"""
import argparse
import os

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

DIM = 256
HEADS = 4
ENCODER = [3, 32, 64, 128, 256, DIM]
NOMINAL_M, NOMINAL_N = 4, 3


class Builder:
    def __init__(self, rng, residual_gain):
        self.rng = rng
        self.residual_gain = residual_gain
        self.nodes = []
        self.inits = []
        self.weights = {}
        self.count = 0

    def name(self, base):
        self.count += 1
        return "%s_%d" % (base, self.count)

    def init(self, name, array):
        if array.dtype != np.int64:
            array = array.astype(np.float32)
        self.inits.append(numpy_helper.from_array(array, name))
        self.weights[name] = array
        return name

    def node(self, op, inputs, **attrs):
        out = self.name(op.lower())
        self.nodes.append(helper.make_node(op, inputs, [out], **attrs))
        return out

    def conv_params(self, prefix, c_in, c_out, zero_bias=False, gain=1.0):
        w = self.rng.standard_normal((c_out, c_in, 1)) * np.sqrt(2.0 / c_in) * gain
        b = np.zeros(c_out) if zero_bias else self.rng.standard_normal(c_out) * 0.01
        self.init(prefix + ".weight", w.astype(np.float32))
        self.init(prefix + ".bias", b.astype(np.float32))

    def conv(self, prefix, x):
        return self.node("Conv", [x, prefix + ".weight", prefix + ".bias"], kernel_shape=[1])

    def bn_params(self, prefix, c):
        self.init(prefix + ".weight", (1.0 + 0.1 * self.rng.standard_normal(c)).astype(np.float32))
        self.init(prefix + ".bias", (0.1 * self.rng.standard_normal(c)).astype(np.float32))
        self.init(prefix + ".running_mean", (0.1 * self.rng.standard_normal(c)).astype(np.float32))
        self.init(prefix + ".running_var", self.rng.uniform(0.5, 1.5, c).astype(np.float32))

    def bn(self, prefix, x):
        return self.node("BatchNormalization",
                         [x] + [prefix + s for s in (".weight", ".bias", ".running_mean", ".running_var")],
                         epsilon=1e-5)

    def mlp_params(self, prefix, channels):
        # nn.Sequential indices: Conv, BN, ReLU per hidden layer, last Conv (bias 0 as initialised).
        index = 0
        for i in range(1, len(channels)):
            last = i == len(channels) - 1
            self.conv_params("%s.%d" % (prefix, index), channels[i - 1], channels[i], zero_bias=last,
                             gain=self.residual_gain if last else 1.0)
            if not last:
                self.bn_params("%s.%d" % (prefix, index + 1), channels[i])
                index += 3

    def mlp(self, prefix, channels, x):
        index = 0
        for i in range(1, len(channels)):
            x = self.conv("%s.%d" % (prefix, index), x)
            if i < len(channels) - 1:
                x = self.node("Relu", [self.bn("%s.%d" % (prefix, index + 1), x)])
                index += 3
        return x


def build(seed, iterations, layers, wrong_output, residual_gain=0.02, projection_gain=8.0):
    b = Builder(np.random.default_rng(seed), residual_gain)
    # Parameters, in the reference's order.
    b.mlp_params("kenc.encoder", ENCODER)
    for layer in range(layers):
        p = "gnn.layers.%d" % layer
        b.conv_params(p + ".attn.merge", DIM, DIM)
        for k in range(3):
            b.conv_params("%s.attn.proj.%d" % (p, k), DIM, DIM)
        b.mlp_params(p + ".mlp", [2 * DIM, 2 * DIM, DIM])
    b.conv_params("final_proj", DIM, DIM, gain=projection_gain)
    b.init("bin_score", np.array([1.0], np.float32))
    b.init("head_shape", np.array([1, DIM // HEADS, HEADS, -1], np.int64))
    b.init("flat_shape", np.array([1, DIM, -1], np.int64))
    b.init("row_shape", np.array([1, 1, -1], np.int64))  # Unsqueeze would bake the import size
    b.init("sqrt_head_dim", np.array([np.sqrt(DIM // HEADS)], np.float32))
    b.init("sqrt_dim", np.array([np.sqrt(DIM)], np.float32))
    b.init("zero", np.array([0.0], np.float32))
    b.init("slice_start", np.array([0], np.int64))
    b.init("slice_end", np.array([1], np.int64))
    b.init("axis1", np.array([1], np.int64))
    b.init("axis2", np.array([2], np.int64))

    def encode(i):
        kpts = b.node("Transpose", ["keypoints%d" % i], perm=[0, 2, 1])        # 1x2xN
        scores = b.node("Reshape", ["scores%d" % i, "row_shape"])              # 1x1xN
        x = b.node("Concat", [kpts, scores], axis=1)                            # 1x3xN
        return b.node("Add", ["descriptors%d" % i, b.mlp("kenc.encoder", ENCODER, x)])

    def attention(p, x, source):
        q, k, v = [b.node("Reshape", [b.conv("%s.attn.proj.%d" % (p, j), t), "head_shape"])
                   for j, t in enumerate((x, source, source))]               # 1x64x4xN (b,d,h,n)
        q = b.node("Transpose", [q], perm=[0, 2, 3, 1])                        # b,h,n,d
        k = b.node("Transpose", [k], perm=[0, 2, 1, 3])                        # b,h,d,m
        logits = b.node("Div", [b.node("MatMul", [q, k]), "sqrt_head_dim"])
        prob = b.node("Softmax", [logits], axis=3)                              # b,h,n,m
        v = b.node("Transpose", [v], perm=[0, 2, 3, 1])                        # b,h,m,d
        out = b.node("Transpose", [b.node("MatMul", [prob, v])], perm=[0, 3, 1, 2])  # b,d,h,n
        return b.conv(p + ".attn.merge", b.node("Reshape", [out, "flat_shape"]))

    def propagate(p, x, source):
        message = attention(p, x, source)
        return b.mlp(p + ".mlp", [2 * DIM, 2 * DIM, DIM], b.node("Concat", [x, message], axis=1))

    desc0, desc1 = encode(0), encode(1)
    for layer in range(layers):
        p = "gnn.layers.%d" % layer
        src0, src1 = (desc1, desc0) if layer % 2 == 1 else (desc0, desc1)  # self, cross, ...
        delta0, delta1 = propagate(p, desc0, src0), propagate(p, desc1, src1)
        desc0, desc1 = b.node("Add", [desc0, delta0]), b.node("Add", [desc1, delta1])
    mdesc0 = b.node("Transpose", [b.conv("final_proj", desc0)], perm=[0, 2, 1])   # 1xMx256
    mdesc1 = b.conv("final_proj", desc1)                                          # 1x256xN
    scores = b.node("Div", [b.node("MatMul", [mdesc0, mdesc1]), "sqrt_dim"])       # 1xMxN

    # Dustbins: a column and a row filled with the bin score.
    def filled(x, axis):  # slice of width 1 along `axis`, every entry = bin_score
        one = b.node("Slice", [x, "slice_start", "slice_end", axis])
        return b.node("Add", [b.node("Mul", [one, "zero"]), "bin_score"])
    top = b.node("Concat", [scores, filled(scores, "axis2")], axis=2)             # 1xMx(N+1)
    z = b.node("Concat", [top, filled(top, "axis1")], axis=1)                      # 1x(M+1)x(N+1)

    # Log-space Sinkhorn: rows then columns, `iterations` times.
    for _ in range(iterations):
        z = b.node("Add", [b.node("LogSoftmax", [z], axis=2), "log_mu"])
        zt = b.node("Transpose", [z], perm=[0, 2, 1])
        zt = b.node("Add", [b.node("LogSoftmax", [zt], axis=2), "log_nu"])
        z = b.node("Transpose", [zt], perm=[0, 2, 1])
    if wrong_output:  # sides swapped: 1x(N+1)x(M+1)
        z = b.node("Transpose", [z], perm=[0, 2, 1])
    b.nodes.append(helper.make_node("Identity", [z], ["scores"]))

    # Declared sizes are nominal (M = 4, N = 3): OpenCV 4.6 infers shapes once at import and
    # cannot do so from symbolic sizes; at run time any M, N >= 1 work.
    f, m, n = TensorProto.FLOAT, NOMINAL_M, NOMINAL_N
    inputs = [helper.make_tensor_value_info("keypoints0", f, [1, m, 2]),
              helper.make_tensor_value_info("scores0", f, [1, m]),
              helper.make_tensor_value_info("descriptors0", f, [1, DIM, m]),
              helper.make_tensor_value_info("keypoints1", f, [1, n, 2]),
              helper.make_tensor_value_info("scores1", f, [1, n]),
              helper.make_tensor_value_info("descriptors1", f, [1, DIM, n]),
              helper.make_tensor_value_info("log_mu", f, [1, m + 1, 1]),
              helper.make_tensor_value_info("log_nu", f, [1, n + 1, 1])]
    out_shape = [1, n + 1, m + 1] if wrong_output else [1, m + 1, n + 1]
    outputs = [helper.make_tensor_value_info("scores", f, out_shape)]
    graph = helper.make_graph(b.nodes, "superglue_random", inputs, outputs, b.inits)
    model = helper.make_model(graph, producer_name="duskmap",
                              opset_imports=[helper.make_opsetid("", 11)])
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model, b.weights


# ---- numpy transcription of the reference equations (for --test-vector) ----

def ref_conv(w, prefix, x):
    return np.einsum("oc,bcn->bon", w[prefix + ".weight"][:, :, 0], x) + w[prefix + ".bias"][None, :, None]


def ref_mlp(w, prefix, channels, x):
    index = 0
    for i in range(1, len(channels)):
        x = ref_conv(w, "%s.%d" % (prefix, index), x)
        if i < len(channels) - 1:
            bn = "%s.%d" % (prefix, index + 1)
            x = (x - w[bn + ".running_mean"][None, :, None]) / np.sqrt(w[bn + ".running_var"][None, :, None] + 1e-5)
            x = np.maximum(x * w[bn + ".weight"][None, :, None] + w[bn + ".bias"][None, :, None], 0.0)
            index += 3
    return x


def ref_softmax(x, axis):
    e = np.exp(x - x.max(axis, keepdims=True))
    return e / e.sum(axis, keepdims=True)


def ref_logsumexp(x, axis):
    m = x.max(axis, keepdims=True)
    return (m + np.log(np.exp(x - m).sum(axis, keepdims=True))).squeeze(axis)


def ref_forward(w, layers, iterations, kpts0, scores0, desc0, kpts1, scores1, desc1):
    """Float64 forward pass written from the reference's equations (einsum, logsumexp)."""
    def encode(k, s, d):
        x = np.concatenate([k.transpose(0, 2, 1), s[:, None, :]], axis=1)
        return d + ref_mlp(w, "kenc.encoder", ENCODER, x)

    def propagate(p, x, src):
        q, k, v = [ref_conv(w, "%s.attn.proj.%d" % (p, j), t).reshape(1, DIM // HEADS, HEADS, -1)
                   for j, t in enumerate((x, src, src))]
        prob = ref_softmax(np.einsum("bdhn,bdhm->bhnm", q, k) / np.sqrt(DIM // HEADS), -1)
        message = ref_conv(w, p + ".attn.merge", np.einsum("bhnm,bdhm->bdhn", prob, v).reshape(1, DIM, -1))
        return ref_mlp(w, p + ".mlp", [2 * DIM, 2 * DIM, DIM], np.concatenate([x, message], axis=1))

    d0, d1 = encode(kpts0, scores0, desc0), encode(kpts1, scores1, desc1)
    for layer in range(layers):
        p = "gnn.layers.%d" % layer
        s0, s1 = (d1, d0) if layer % 2 == 1 else (d0, d1)
        d0, d1 = d0 + propagate(p, d0, s0), d1 + propagate(p, d1, s1)
    m0, m1 = ref_conv(w, "final_proj", d0), ref_conv(w, "final_proj", d1)
    scores = np.einsum("bdn,bdm->bnm", m0, m1) / np.sqrt(DIM)
    m, n = scores.shape[1], scores.shape[2]
    alpha = float(w["bin_score"][0])
    z = np.full((1, m + 1, n + 1), alpha)
    z[:, :m, :n] = scores
    norm = -np.log(m + n)
    log_mu = np.concatenate([np.full(m, norm), [np.log(n) + norm]])[None]
    log_nu = np.concatenate([np.full(n, norm), [np.log(m) + norm]])[None]
    u, v = np.zeros_like(log_mu), np.zeros_like(log_nu)
    for _ in range(iterations):
        u = log_mu - ref_logsumexp(z + v[:, None, :], 2)
        v = log_nu - ref_logsumexp(z + u[:, :, None], 1)
    return z + u[:, :, None] + v[:, None, :] - norm


def write_test_vector(directory, weights, layers, iterations, seed):
    """Raw little-endian float32 files plus a text index the C++ test reads."""
    rng = np.random.default_rng(seed + 1)
    os.makedirs(directory, exist_ok=True)
    sizes = {0: (7, (160, 120)), 1: (5, (200, 100))}  # keypoints, (width, height)
    arrays = {}
    for i, (count, (width, height)) in sizes.items():
        pixels = rng.uniform([0, 0], [width - 1, height - 1], (count, 2))
        desc = rng.standard_normal((DIM, count))
        desc /= np.linalg.norm(desc, axis=0, keepdims=True)
        arrays["pixels%d" % i] = pixels
        arrays["scores%d" % i] = rng.uniform(0.01, 1.0, count)
        arrays["descriptors%d" % i] = desc.T  # one row per keypoint, as duskmap stores them
    def normalise(pixels, width, height):
        return (pixels - np.array([width, height]) / 2.0) / (0.7 * max(width, height))
    expected = ref_forward(
        weights, layers, iterations,
        normalise(arrays["pixels0"], *sizes[0][1])[None], arrays["scores0"][None], arrays["descriptors0"].T[None],
        normalise(arrays["pixels1"], *sizes[1][1])[None], arrays["scores1"][None], arrays["descriptors1"].T[None])
    arrays["expected"] = expected[0]
    with open(os.path.join(directory, "index.txt"), "w") as index:
        index.write("image0 %d %d\nimage1 %d %d\n" % (sizes[0][1] + sizes[1][1]))
        for name, array in arrays.items():
            array.astype("<f4").tofile(os.path.join(directory, name + ".f32"))
            index.write("%s %s\n" % (name, " ".join(str(s) for s in array.shape)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=20200614)
    parser.add_argument("--iterations", type=int, default=20, help="Sinkhorn iterations (PyMatcher/Iterations)")
    parser.add_argument("--layers", type=int, default=18, help="GNN layers, alternating self and cross")
    parser.add_argument("--wrong-output", action="store_true")
    parser.add_argument("--test-vector", metavar="DIR")
    args = parser.parse_args()
    model, weights = build(args.seed, args.iterations, args.layers, args.wrong_output)
    onnx.save(model, args.out)
    if args.test_vector:
        write_test_vector(args.test_vector, weights, args.layers, args.iterations, args.seed)


if __name__ == "__main__":
    main()
