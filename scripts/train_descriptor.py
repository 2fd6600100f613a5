#!/usr/bin/python3
"""Trains DuskNet, duskmap's own patch descriptor, on the generator's training pairs.

    /usr/bin/python3 scripts/train_descriptor.py --data DIR [--config configs/dusknet.json]
        [--out slam/features/models/dusknet.onnx] [--figure docs/figures/dusknet_training.png]

DIR is what `duskmap features training-data --config configs/dusknet.json --out DIR` wrote
(manifest.json, patches.u8, points.f32). The config's "train" section holds every
hyper-parameter; they are logged with each epoch's losses. The scenes the manifest marks
"validation" choose the epoch (early stopping); no real image is read.

Loss: HardNet's hardest-in-batch triplet margin loss (Mishchuk et al., NeurIPS 2017) on the
L2 distances of a batch of matching pairs: for each pair, its distance against the closest
non-matching descriptor of the batch, in either image. Pairs of one scene whose world
points lie within `same_point_m` of each other are not negatives of each other.

The network (docs/learned_descriptor.md): instance normalisation of the patch, three
strided convolutions with batch normalisation and ReLU (32 -> 16 -> 8 -> 4 px), a fully
connected layer to 128 dimensions, batch normalisation without affine terms and L2
normalisation. Exported as ONNX (opset 11, constants folded) for OpenCV 4.6's DNN module,
which the export checks against torch. Refuses to replace a model it did not write.

Writes beside the model: <stem>_training_log.jsonl (hyper-parameters, then one line per
epoch), <stem>_data_manifest.json (the training data's manifest) and <stem>_reference.json
(16 validation patches and the exported model's descriptors of them, for the C++ test).
"""

import argparse
import copy
import hashlib
import json
import math
import os
import sys
import time

import numpy as np

FORMAT = "duskmap-training-pairs"
FORMAT_VERSION = 1
PRODUCER = "duskmap scripts/train_descriptor.py"
DEFAULT_TRAIN = {
    "seed": 20261207,
    "widths": [16, 32, 64],
    "first_kernel": 5,
    "descriptor_dims": 128,
    "batch_pairs": 512,
    "epochs": 12,
    "learning_rate": 0.002,
    "weight_decay": 0.0001,
    "margin": 1.0,
    "same_point_m": 0.05,
    "patience_epochs": 3,
    "threads": 2,
    "validation_block": 1024,
}


class TrainingError(Exception):
    pass


def fail(message):
    print(f"train_descriptor.py: {message}", file=sys.stderr)
    sys.exit(1)


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except FileNotFoundError:
        raise TrainingError(f"{path}: no such file")
    except (OSError, ValueError) as e:
        raise TrainingError(f"{path}: not a readable JSON file ({e})")


def train_options(config_path):
    config = read_json(config_path)
    if not isinstance(config, dict) or not isinstance(config.get("train"), dict):
        raise TrainingError(f"{config_path}: needs a \"train\" object")
    options = dict(DEFAULT_TRAIN)
    for key, value in config["train"].items():
        if key.startswith("_"):
            continue
        if key not in DEFAULT_TRAIN:
            raise TrainingError(f"{config_path}: train.{key}: unknown key (known: {', '.join(DEFAULT_TRAIN)})")
        if type(value) is not type(DEFAULT_TRAIN[key]) and not (
                isinstance(DEFAULT_TRAIN[key], float) and isinstance(value, int)):
            raise TrainingError(f"{config_path}: train.{key}: expected {type(DEFAULT_TRAIN[key]).__name__}")
        options[key] = value
    if len(options["widths"]) != 3 or min(options["widths"]) < 1:
        raise TrainingError(f"{config_path}: train.widths: three positive channel counts")
    for key in ("epochs", "batch_pairs", "descriptor_dims", "threads", "validation_block"):
        if options[key] < 1:
            raise TrainingError(f"{config_path}: train.{key}: must be >= 1")
    if options["batch_pairs"] < 2:
        raise TrainingError(f"{config_path}: train.batch_pairs: must be >= 2")
    return config, options


def load_training_data(folder):
    """The pairs of a training-data folder, checked: format, version, files and sizes."""
    manifest_path = os.path.join(folder, "manifest.json")
    if not os.path.isdir(folder):
        raise TrainingError(f"{folder}: no such training-data folder")
    if not os.path.isfile(manifest_path):
        raise TrainingError(f"{manifest_path}: missing (an incomplete training-data folder)")
    manifest = read_json(manifest_path)
    if manifest.get("format") != FORMAT:
        raise TrainingError(f"{manifest_path}: not a {FORMAT} manifest (format {manifest.get('format')!r})")
    if manifest.get("version") != FORMAT_VERSION:
        raise TrainingError(f"{manifest_path}: version {manifest.get('version')!r}, this script reads "
                            f"version {FORMAT_VERSION} (regenerate the data with this duskmap)")
    patch = int(manifest["patch"]["patch_size_px"])
    pairs = int(manifest["pairs"])
    expected = {"patches.u8": pairs * 2 * patch * patch, "points.f32": pairs * 3 * 4}
    for name, size in expected.items():
        path = os.path.join(folder, name)
        if not os.path.isfile(path):
            raise TrainingError(f"{path}: missing (an incomplete training-data folder)")
        if os.path.getsize(path) != size:
            raise TrainingError(f"{path}: {os.path.getsize(path)} bytes, the manifest says {size}")
    patches = np.fromfile(os.path.join(folder, "patches.u8"), dtype=np.uint8).reshape(pairs, 2, patch, patch)
    points = np.fromfile(os.path.join(folder, "points.f32"), dtype="<f4").reshape(pairs, 3)
    scene_of_pair = np.full(pairs, -1, dtype=np.int64)
    split_of_scene = {}
    for scene in manifest["scenes"]:
        first, count = int(scene["first_pair"]), int(scene["pairs"])
        if first < 0 or first + count > pairs:
            raise TrainingError(f"{manifest_path}: scene {scene['index']} pairs out of range")
        scene_of_pair[first:first + count] = int(scene["index"])
        split_of_scene[int(scene["index"])] = scene["split"]
    if (scene_of_pair < 0).any():
        raise TrainingError(f"{manifest_path}: pairs that belong to no scene")
    return manifest, patches, points, scene_of_pair, split_of_scene


def build_network(torch, options):
    nn = torch.nn
    functional = torch.nn.functional

    class InstanceNorm(nn.Module):
        def forward(self, x):
            return functional.instance_norm(x)

    class DuskNet(nn.Module):
        def __init__(self):
            super().__init__()
            a, b, c = options["widths"]
            k = options["first_kernel"]
            layers = [InstanceNorm()]
            for cin, cout, kernel in ((1, a, k), (a, b, 3), (b, c, 3)):
                layers += [nn.Conv2d(cin, cout, kernel, 2, kernel // 2, bias=False), nn.BatchNorm2d(cout), nn.ReLU()]
            self.features = nn.Sequential(*layers)
            self.fc = nn.Linear(c * 16, options["descriptor_dims"], bias=False)
            self.bn = nn.BatchNorm1d(options["descriptor_dims"], affine=False)

        def forward(self, x):
            return functional.normalize(self.bn(self.fc(self.features(x).flatten(1))), dim=1)

    return DuskNet()


def hardest_in_batch_loss(torch, desc_a, desc_b, not_negative, margin):
    """HardNet's loss; not_negative[i, j] marks pairs that must not serve as negatives."""
    distances = torch.cdist(desc_a, desc_b)  # [i, j]: a_i to b_j
    positive = distances.diagonal()
    big = 10.0
    masked = distances + big * not_negative
    nearest_b = masked.min(dim=1).values  # a_i against other b
    nearest_a = masked.min(dim=0).values  # b_i against other a
    aa = torch.cdist(desc_a, desc_a) + big * not_negative
    bb = torch.cdist(desc_b, desc_b) + big * not_negative
    hardest = torch.min(torch.min(nearest_b, nearest_a), torch.min(aa.min(dim=1).values, bb.min(dim=1).values))
    return torch.clamp(margin + positive - hardest, min=0.0).mean()


def not_negative_mask(torch, points, scenes, same_point_m):
    p = torch.from_numpy(points)
    s = torch.from_numpy(scenes)
    close = (torch.cdist(p, p) < same_point_m) & (s[:, None] == s[None, :])
    return close.float()  # includes the diagonal


def to_input(torch, patches_u8):
    return torch.from_numpy(patches_u8.astype(np.float32) / 255.0).unsqueeze(1)


def evaluate(torch, net, patches, points, scenes, options):
    """Validation loss and matching accuracy: in blocks, how often a's nearest b is its own."""
    net.eval()
    block = options["validation_block"]
    losses, correct, total = [], 0, 0
    with torch.no_grad():
        for start in range(0, len(patches) - 1, block):
            end = min(start + block, len(patches))
            if end - start < 2:
                break
            a = net(to_input(torch, patches[start:end, 0]))
            b = net(to_input(torch, patches[start:end, 1]))
            mask = not_negative_mask(torch, points[start:end], scenes[start:end], options["same_point_m"])
            losses.append(float(hardest_in_batch_loss(torch, a, b, mask, options["margin"])) * (end - start))
            distances = torch.cdist(a, b) + 10.0 * (mask - torch.eye(end - start))
            correct += int((distances.argmin(dim=1) == torch.arange(end - start)).sum())
            total += end - start
    net.train()
    return sum(losses) / max(total, 1), correct / max(total, 1)


def export_onnx(torch, net, path, metadata, check_patches):
    """ONNX for OpenCV 4.6: constants folded, no Identity over an initializer; checked in OpenCV."""
    import cv2
    import onnx
    import warnings
    net.eval()
    staging = path + ".tmp"
    example = to_input(torch, check_patches[:8])
    with warnings.catch_warnings():  # torch 1.13's exporter warns about instance_norm and constants
        warnings.simplefilter("ignore")
        torch.onnx.export(net, example, staging, opset_version=11, do_constant_folding=True,
                          input_names=["patches"], output_names=["descriptors"],
                          dynamic_axes={"patches": {0: "n"}, "descriptors": {0: "n"}})
    model = onnx.load(staging)
    initializers = {t.name: t for t in model.graph.initializer}
    nodes = []
    for node in model.graph.node:  # OpenCV 4.6 refuses an Identity whose input is an initializer
        if node.op_type == "Identity" and node.input[0] in initializers:
            tensor = copy.deepcopy(initializers[node.input[0]])
            tensor.name = node.output[0]
            model.graph.initializer.append(tensor)
        else:
            nodes.append(node)
    del model.graph.node[:]
    model.graph.node.extend(nodes)
    del model.metadata_props[:]
    for key, value in metadata.items():
        entry = model.metadata_props.add()
        entry.key, entry.value = key, value
    onnx.checker.check_model(model)
    onnx.save(model, staging)
    cv_net = cv2.dnn.readNetFromONNX(staging)
    x = to_input(torch, check_patches).numpy()
    cv_net.setInput(x)
    cv_out = cv_net.forward()
    with torch.no_grad():
        torch_out = net(torch.from_numpy(x)).numpy()
    difference = float(np.abs(cv_out - torch_out).max())
    if difference > 1e-4:
        os.remove(staging)
        raise TrainingError(f"{path}: OpenCV's DNN differs from torch by {difference:g}")
    os.replace(staging, path)
    return difference, cv_out


def write_reference(path, patches_u8, descriptors):
    """A fixed patch set and the model's descriptors of it, for the C++ test that catches an
    accidental change of the committed model (tests/features/dusknet_model_test.cc)."""
    reference = {"model": os.path.basename(path.replace("_reference.json", ".onnx")),
                 "patch_size_px": int(patches_u8.shape[-1]),
                 "source": "the first validation pairs' A patches (generated scenes)",
                 "patches": [p.reshape(-1).tolist() for p in patches_u8],
                 "descriptors": [[round(float(v), 7) for v in d] for d in descriptors]}
    with open(path, "w", encoding="utf-8") as f:
        json.dump(reference, f, separators=(",", ":"))
        f.write("\n")


def check_output_is_ours(path):
    """Training replaces only a model this script wrote."""
    if not os.path.exists(path):
        return
    import onnx
    try:
        model = onnx.load(path)
    except Exception as e:  # noqa: BLE001 - any failure means it is not a model we wrote
        raise TrainingError(f"{path}: exists and is not a readable ONNX model ({e}); not replaced")
    producer = {p.key: p.value for p in model.metadata_props}.get("producer")
    if producer != PRODUCER:
        raise TrainingError(f"{path}: exists and was not written by {PRODUCER}; not replaced")


def plot_curves(log, figure_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    epochs = [e["epoch"] for e in log]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 3.8))
    left.plot(epochs, [e["train_loss"] for e in log], "o-", label="training (mean over the epoch)")
    left.plot(epochs, [e["validation_loss"] for e in log], "s-", label="validation scenes")
    left.set_xlabel("epoch")
    left.set_ylabel("hardest-in-batch triplet loss")
    left.legend()
    left.grid(alpha=0.3)
    right.plot(epochs, [e["validation_accuracy"] for e in log], "s-", color="C2")
    best = max(log, key=lambda e: e["validation_accuracy"])
    right.axvline(best["epoch"], color="gray", ls="--", label=f"kept: epoch {best['epoch']}")
    right.set_xlabel("epoch")
    right.set_ylabel("validation matching accuracy")
    right.set_title("nearest neighbour among 1,024 pairs", fontsize=9)
    right.legend()
    right.grid(alpha=0.3)
    fig.suptitle("DuskNet training (generated scenes only)")
    fig.tight_layout()
    os.makedirs(os.path.dirname(figure_path) or ".", exist_ok=True)
    fig.savefig(figure_path, dpi=110)


def sha256_of(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def train(args):
    config, options = train_options(args.config)
    check_output_is_ours(args.out)
    manifest, patches, points, scene_of_pair, split_of_scene = load_training_data(args.data)
    import torch
    torch.manual_seed(options["seed"])
    torch.set_num_threads(options["threads"])
    rng = np.random.default_rng(options["seed"])

    validation = np.array([split_of_scene[s] == "validation" for s in scene_of_pair])
    if validation.all() or not validation.any():
        raise TrainingError(f"{args.data}/manifest.json: needs both training and validation scenes")
    train_index = np.flatnonzero(~validation)
    val_index = np.flatnonzero(validation)
    val_patches, val_points, val_scenes = patches[val_index], points[val_index], scene_of_pair[val_index]

    net = build_network(torch, options)
    optimizer = torch.optim.Adam(net.parameters(), lr=options["learning_rate"], weight_decay=options["weight_decay"])
    steps_per_epoch = len(train_index) // options["batch_pairs"]
    total_steps = steps_per_epoch * options["epochs"]
    schedule = torch.optim.lr_scheduler.LambdaLR(
        optimizer, lambda step: 0.5 * (1.0 + math.cos(math.pi * min(step, total_steps) / total_steps)))

    stem = os.path.splitext(args.out)[0]
    log_path = stem + "_training_log.jsonl"
    header = {"hyper_parameters": options, "config": os.path.relpath(args.config),
              "data_manifest_sha256": sha256_of(os.path.join(args.data, "manifest.json")),
              "training_pairs": int(len(train_index)), "validation_pairs": int(len(val_index)),
              "torch": torch.__version__, "parameters": sum(p.numel() for p in net.parameters())}
    log, best_state, best_accuracy, best_epoch, started = [], None, -1.0, 0, time.time()
    print(json.dumps(header), flush=True)
    for epoch in range(1, options["epochs"] + 1):
        epoch_start, losses = time.time(), []
        order = rng.permutation(train_index)
        for step in range(steps_per_epoch):
            batch = order[step * options["batch_pairs"]:(step + 1) * options["batch_pairs"]]
            swap = rng.random(len(batch)) < 0.5  # which patch of a pair is the anchor does not matter
            first = np.where(swap, 1, 0)
            a = to_input(torch, patches[batch, first])
            b = to_input(torch, patches[batch, 1 - first])
            mask = not_negative_mask(torch, points[batch], scene_of_pair[batch], options["same_point_m"])
            desc = net(torch.cat([a, b]))
            loss = hardest_in_batch_loss(torch, desc[:len(batch)], desc[len(batch):], mask, options["margin"])
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
            schedule.step()
            losses.append(float(loss))
        val_loss, val_accuracy = evaluate(torch, net, val_patches, val_points, val_scenes, options)
        entry = {"epoch": epoch, "train_loss": float(np.mean(losses)), "validation_loss": val_loss,
                 "validation_accuracy": val_accuracy, "learning_rate": schedule.get_last_lr()[0],
                 "epoch_s": round(time.time() - epoch_start, 1), "elapsed_s": round(time.time() - started, 1)}
        log.append(entry)
        print(json.dumps(entry), flush=True)
        if val_accuracy > best_accuracy:
            best_accuracy, best_epoch, best_state = val_accuracy, epoch, copy.deepcopy(net.state_dict())
        elif epoch - best_epoch >= options["patience_epochs"]:
            break  # early stopping on the validation scenes
    net.load_state_dict(best_state)
    metadata = {"producer": PRODUCER, "epoch": str(best_epoch),
                "config_sha256": sha256_of(args.config), "data_manifest_sha256": header["data_manifest_sha256"],
                "contract": "patch: N x 1 x 32 x 32 float (patch / 255), output N x D L2-normalised"}
    difference, cv_descriptors = export_onnx(torch, net, args.out, metadata, val_patches[:256, 0])
    write_reference(stem + "_reference.json", val_patches[:16, 0], cv_descriptors[:16])
    summary = {"kept_epoch": best_epoch, "validation_accuracy": best_accuracy,
               "opencv_max_difference": difference, "training_s": round(time.time() - started, 1),
               "model_bytes": os.path.getsize(args.out)}
    with open(log_path, "w", encoding="utf-8") as f:
        for line in [header] + log + [summary]:
            f.write(json.dumps(line) + "\n")
    with open(stem + "_data_manifest.json", "w", encoding="utf-8") as f:
        json.dump(manifest, f, indent=1)
        f.write("\n")
    plot_curves(log, args.figure)
    print(json.dumps(summary), flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", required=True, help="folder written by `duskmap features training-data`")
    parser.add_argument("--config", default="configs/dusknet.json")
    parser.add_argument("--out", default="slam/features/models/dusknet.onnx")
    parser.add_argument("--figure", default="docs/figures/dusknet_training.png")
    args = parser.parse_args()
    try:
        train(args)
    except TrainingError as e:
        fail(str(e))


if __name__ == "__main__":
    main()
