"""The interception net's file and its plain-Python evaluation, without torch (paper §5).

Training needs torch (:mod:`learning.interception`); *using* a trained net does not. This module
holds everything a control loop needs and imports nothing heavier than numpy:

* the file layout (an ``.npz`` of the weights and input scaler plus JSON metadata, read with
  ``allow_pickle=False``) and its validation — :func:`read_net_file` checks the format tag and
  version, the feature schema, the hyper-parameters, every array's shape and dtype and that all
  weights are finite, and raises :class:`~learning.features.ModelFileError` naming the file;
* the folding of the distance scale, the standardisation and the sigmoid's halves into one
  coefficient set per hidden unit (:func:`fold_net`), and the closure over those plain floats
  (:func:`turn_function`): 4 ``tanh`` and a dozen multiply-adds per call, and its batch form
  (:func:`batch_turn_function`), the same operations in the same order on arrays, so that a
  trial gives the same bits alone or in a batch (numpy's ``tanh`` in both: ``math.tanh``
  differs from it in the last bit for about one argument in five);
* :func:`write_net_file`, the same layout written (the trainer's, which passes its torch
  version for the metadata);
* :func:`load_turn_function`: path in, ``f(BD [m], BA [rad], previous BD [m]) -> TA [rad]`` out.

:class:`learning.interception.InterceptionModel` saves, loads and evaluates through these same
functions, so there is one implementation of the file and of the plain-Python net.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeGuard

import numpy as np
import numpy.typing as npt

from learning.datasets import DatasetError, Provenance, read_npz, write_npz
from learning.features import (
    DISTANCE_COLUMNS,
    FEATURE_NAMES,
    FeatureSchema,
    ModelFileError,
    SchemaError,
)

MODEL_FORMAT = "robotsoccer/interception-net"
"""Format tag stored in every interception-net file."""

MODEL_FORMAT_VERSION = 1
"""Version of the file layout."""

DEFAULT_LEARNING_RATES = {"adam": 1e-2, "sgd": 0.5}
"""Learning rate used when ``learning_rate=None``, per optimiser (for standardised inputs)."""

PARAM_NAMES = (
    "hidden",
    "optimizer",
    "learning_rate",
    "weight_decay",
    "epochs",
    "batch_size",
    "random_state",
    "distance_scale_m",
)
"""The net's hyper-parameters, as stored in its file (the estimator's constructor arguments)."""

WEIGHT_KEYS = ("hidden.weight", "hidden.bias", "output.weight", "output.bias")
"""The net's ``state_dict`` keys, stored as arrays of the same names."""

SCALER_KEYS = ("input_mean", "input_scale")
"""The standardisation arrays stored beside the weights."""

Array = npt.NDArray[np.float64]
TurnAngleFunction = Callable[[float, float, float], float]
"""(BD [m], BA [rad], previous BD [m]) -> TA [rad]."""

Unit = tuple[float, float, float, float, float]
"""One folded hidden unit: (output weight k, c_BD, c_BA, c_prevBD, bias) of k·tanh(c·x + b)."""


@dataclass(frozen=True, slots=True)
class NetFile:
    """The validated content of an interception-net file.

    Attributes:
        weights: The ``state_dict`` arrays (:data:`WEIGHT_KEYS`), float64.
        input_mean: (3,) mean of the scaled training features.
        input_scale: (3,) standard deviation of the scaled training features (> 0).
        loss_history: (epochs,) training loss per epoch.
        schema: The feature schema the net reads, with its distance scale.
        hyperparameters: The estimator's constructor arguments (:data:`PARAM_NAMES`).
        n_train: Rows the net was fitted on.
        provenance: Where its training data came from.
    """

    weights: dict[str, Array]
    input_mean: Array
    input_scale: Array
    loss_history: Array
    schema: FeatureSchema
    hyperparameters: dict[str, Any]
    n_train: int
    provenance: Provenance


def write_net_file(path: str | os.PathLike[str], net: NetFile, torch_version: str) -> Path:
    """Write `net` to `path` in the layout :func:`read_net_file` reads, atomically.

    `torch_version` (the trainer's) is recorded in the metadata; reading ignores it.

    Returns:
        The path written.
    """
    meta = {
        "format": MODEL_FORMAT,
        "format_version": MODEL_FORMAT_VERSION,
        "schema": net.schema.to_dict(),
        "hyperparameters": net.hyperparameters,
        "provenance": net.provenance.to_dict(),
        "n_train": net.n_train,
        "torch_version": torch_version,
    }
    arrays = {
        **net.weights,
        "input_mean": net.input_mean,
        "input_scale": net.input_scale,
        "loss_history": net.loss_history,
    }
    return write_npz(Path(path), arrays, meta)


def read_net_file(path: str | os.PathLike[str]) -> NetFile:
    """Read and validate an interception-net file, never unpickling and never importing torch.

    Raises:
        ModelFileError: The file is missing, corrupt, truncated, not a net, for another feature
            schema, or holds wrong shapes or non-finite weights.
    """
    path = Path(path)
    arrays, meta = read_npz(path, (*WEIGHT_KEYS, *SCALER_KEYS, "loss_history"), ModelFileError)
    try:
        return _net_from(arrays, meta)
    except (ModelFileError, SchemaError, DatasetError) as exc:
        raise ModelFileError(f"{path}: {exc}") from None


def _net_from(arrays: Mapping[str, npt.NDArray[Any]], meta: Mapping[str, Any]) -> NetFile:
    if meta.get("format") != MODEL_FORMAT:
        raise ModelFileError(f"format tag {meta.get('format')!r} is not {MODEL_FORMAT!r}")
    if meta.get("format_version") != MODEL_FORMAT_VERSION:
        raise ModelFileError(f"unsupported model format version {meta.get('format_version')!r}")
    for key in ("schema", "hyperparameters", "provenance", "n_train"):
        if key not in meta:
            raise ModelFileError(f"metadata lacks {key!r}")
    schema = FeatureSchema.from_dict(meta["schema"])
    params = meta["hyperparameters"]
    if not isinstance(params, dict) or set(params) != set(PARAM_NAMES):
        raise ModelFileError(f"hyper-parameters {params!r} are not this model's")
    try:
        check_params(params)
    except ValueError as exc:
        raise ModelFileError(str(exc)) from None
    check_arrays(arrays, params["hidden"])
    return NetFile(
        weights={k: arrays[k] for k in WEIGHT_KEYS},
        input_mean=arrays["input_mean"],
        input_scale=arrays["input_scale"],
        loss_history=arrays["loss_history"],
        schema=schema,
        hyperparameters=dict(params),
        n_train=int(meta["n_train"]),
        provenance=Provenance.from_dict(meta["provenance"]),
    )


def check_params(params: Mapping[str, Any]) -> None:
    """Raise ValueError naming the first invalid hyper-parameter."""
    checks = {
        "hidden": _is_int(params["hidden"]) and params["hidden"] >= 1,
        "optimizer": params["optimizer"] in DEFAULT_LEARNING_RATES,
        "learning_rate": params["learning_rate"] is None or _is_positive(params["learning_rate"]),
        "weight_decay": _is_number(params["weight_decay"]) and 0 <= params["weight_decay"] < 1,
        "epochs": _is_int(params["epochs"]) and params["epochs"] >= 1,
        "batch_size": params["batch_size"] is None
        or (_is_int(params["batch_size"]) and params["batch_size"] >= 1),
        "random_state": _is_int(params["random_state"]) and params["random_state"] >= 0,
        "distance_scale_m": _is_positive(params["distance_scale_m"]),
    }
    for name, ok in checks.items():
        if not ok:
            raise ValueError(f"invalid hyper-parameter {name}={params[name]!r}")


def check_arrays(arrays: Mapping[str, npt.NDArray[Any]], hidden: int) -> None:
    """Raise ModelFileError unless every array has the expected shape, float64 and finite values."""
    n_in = len(FEATURE_NAMES)
    shapes = {
        "hidden.weight": (hidden, n_in),
        "hidden.bias": (hidden,),
        "output.weight": (1, hidden),
        "output.bias": (1,),
        "input_mean": (n_in,),
        "input_scale": (n_in,),
    }
    for key, shape in shapes.items():
        array = arrays[key]
        if array.shape != shape or array.dtype != np.float64:
            raise ModelFileError(
                f"array {key!r} is {array.dtype}{array.shape}, expected float64{shape} "
                f"for {hidden} hidden units"
            )
        if not np.isfinite(array).all():
            raise ModelFileError(f"array {key!r} holds NaN or infinite values")
    if not (arrays["input_scale"] > 0).all():
        raise ModelFileError("input_scale must be > 0")
    if arrays["loss_history"].ndim != 1 or arrays["loss_history"].dtype != np.float64:
        raise ModelFileError("loss_history must be a 1-D float64 array")


def fold_net(
    weights: Mapping[str, Array],
    input_mean: Array,
    input_scale: Array,
    distance_scale_m: float,
) -> tuple[tuple[Unit, ...], float]:
    """Fold scaling, standardisation and sigmoid halves into per-unit coefficients.

    With ``sigmoid(a) = (1 + tanh(a/2)) / 2`` and ``a_j = W1_j · ((x / s) - mean) / scale + b1_j``
    (s the distance scale on the distance columns), the net's output
    ``b2 + Σ_j v_j · sigmoid(a_j)`` equals ``offset + Σ_j k_j · tanh(c_j · x + b_j)``.

    Returns:
        The hidden units as (k, c_BD, c_BA, c_prevBD, b) and the offset.
    """
    divisor = np.array(input_scale, dtype=np.float64)
    divisor[list(DISTANCE_COLUMNS)] *= distance_scale_m
    coef = 0.5 * weights["hidden.weight"] / divisor
    standard_mean = input_mean / input_scale
    bias = 0.5 * (weights["hidden.bias"] - weights["hidden.weight"] @ standard_mean)
    v = weights["output.weight"][0]
    units = tuple(
        (float(0.5 * v[j]), float(c[0]), float(c[1]), float(c[2]), float(bias[j]))
        for j, c in enumerate(coef)
    )
    offset = float(weights["output.bias"][0] + 0.5 * v.sum())
    return units, offset


def turn_function(units: tuple[Unit, ...], offset: float) -> TurnAngleFunction:
    """The plain-Python net ``f(BD [m], BA [rad], previous BD [m]) -> TA [rad]`` of folded units.

    Bit for bit the per-element result of :func:`batch_turn_function`.
    """
    tanh = np.tanh  # a closure variable: faster than a global lookup per call

    def turn_angle_rad(
        ball_distance_m: float, ball_angle_rad: float, previous_ball_distance_m: float
    ) -> float:
        out = offset
        for k, c0, c1, c2, b in units:
            out += k * tanh(
                c0 * ball_distance_m + c1 * ball_angle_rad + c2 * previous_ball_distance_m + b
            )
        return float(out)

    return turn_angle_rad


BatchTurnFunction = Callable[[Array, Array, Array], Array]
"""(BD [m], BA [rad], previous BD [m]) arrays -> TA [rad] array."""


def batch_turn_function(units: tuple[Unit, ...], offset: float) -> BatchTurnFunction:
    """The net of :func:`turn_function` over arrays: the same operations, unit by unit.

    Written unit by unit rather than as a BLAS product because a product's summation order may
    change with the batch size, and a trial must give the same bits alone or in any batch.
    """

    def turn_angles_rad(
        ball_distance_m: Array, ball_angle_rad: Array, previous_ball_distance_m: Array
    ) -> Array:
        out = np.full(np.shape(ball_distance_m), offset)
        for k, c0, c1, c2, b in units:
            out += k * np.tanh(
                c0 * ball_distance_m + c1 * ball_angle_rad + c2 * previous_ball_distance_m + b
            )
        return out

    return turn_angles_rad


def folded(net: NetFile, distance_factor: float = 1.0) -> tuple[tuple[Unit, ...], float]:
    """The net's folded units, its distance scale multiplied by `distance_factor`.

    A factor other than 1 applies the net on a field of another size (the transfer study): with
    ``unit_here / unit_trained``, a distance of k drill units here enters the net as k of its
    training field's units (``learning.features``: the distance scale).
    """
    if not (math.isfinite(distance_factor) and distance_factor > 0.0):
        raise ValueError(f"distance_factor must be a finite number > 0, got {distance_factor!r}")
    scale = net.schema.distance_scale_m * distance_factor
    return fold_net(net.weights, net.input_mean, net.input_scale, scale)


def net_turn_function(net: NetFile, distance_factor: float = 1.0) -> TurnAngleFunction:
    """The plain-Python turn-angle function of a net read by :func:`read_net_file`."""
    return turn_function(*folded(net, distance_factor))


def training_spread(
    net: NetFile, distance_factor: float = 1.0
) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """The mean and standard deviation of the net's training inputs, in raw units.

    (BD [m], BA [rad], previous BD [m]) as the net reads them on a field of `distance_factor`
    (:func:`folded`): the stored scaler undone, distances multiplied by the distance scale.
    """
    scale = np.ones(3)
    scale[list(DISTANCE_COLUMNS)] = net.schema.distance_scale_m * distance_factor
    mean = np.asarray(net.input_mean, dtype=np.float64) * scale
    spread = np.asarray(net.input_scale, dtype=np.float64) * scale
    return (
        (float(mean[0]), float(mean[1]), float(mean[2])),
        (float(spread[0]), float(spread[1]), float(spread[2])),
    )


def load_batch_turn_function(
    path: str | os.PathLike[str], distance_factor: float = 1.0
) -> BatchTurnFunction:
    """Read a net file and return its batch form (:func:`batch_turn_function`).

    Raises:
        ModelFileError: As :func:`read_net_file`.
    """
    return batch_turn_function(*folded(read_net_file(path), distance_factor))


def load_turn_function(
    path: str | os.PathLike[str], distance_factor: float = 1.0
) -> TurnAngleFunction:
    """Read a net file and return its plain-Python ``f(BD, BA, previous BD) -> TA`` (no torch).

    `distance_factor`: see :func:`folded` (1: the field it was trained on).

    Raises:
        ModelFileError: As :func:`read_net_file`.
    """
    return net_turn_function(read_net_file(path), distance_factor)


def _is_int(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _is_number(value: object) -> TypeGuard[int | float]:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def _is_positive(value: object) -> bool:
    return _is_number(value) and value > 0
