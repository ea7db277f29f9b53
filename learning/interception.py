"""Layer 1: the interception net — (BD, BA, previous BD) -> turn angle TA (paper §5).

The paper's net (§5, "Learning a Low-level Skill"): fully connected, 3 inputs, 4 sigmoid hidden
units, a linear output; back-propagation with a learning rate of 1e-6, a weight decay on the
input-to-hidden weights "linearly decreasing ... starting at .1%", none on the output, 3000 epochs.

What this module keeps and what it changes (the defaults of :class:`InterceptionModel`):

* Architecture: as the paper (3 -> 4 sigmoid -> 1 linear), trained on the *saves* only.
* Epochs: 3000, as the paper.
* Weight decay: as the paper — after every update the input-to-hidden weights (not the biases,
  not the output layer) are multiplied by ``1 - d``, with ``d`` falling linearly from
  ``weight_decay`` = 0.1 % in the first epoch to 0 at the end.
* Inputs are standardised (mean 0, standard deviation 1 per column, the scaler stored in the model
  file). The paper fed raw distances and degrees, which is why it needed a learning rate as small
  as 1e-6; on standardised inputs the sigmoid units start in their linear range whatever the
  field's size, and one learning rate suits fields of every size.
* Optimiser: Adam, learning rate 0.01, full batch (one update per epoch): a rate of 1e-6 is tuned
  to raw inputs, not to standardised ones — there, plain gradient descent at 1e-6 barely moves
  the loss in 3000 epochs, and the paper's weight decay lowers it only by shrinking the weights
  (``tests/learning/test_interception.py`` checks both). ``optimizer="sgd"`` (default rate 0.5)
  is there for comparison. ``robotsoccer bench`` times a 1000-save fit.
* Precision: training runs in float64, so the saved weights, :meth:`InterceptionModel.predict`
  (numpy) and :meth:`InterceptionModel.as_function` (plain Python) agree to ~1e-15.

Training is reproducible: one seeded ``torch.Generator`` draws the initial weights and the batch
order (no global torch seed), and torch runs on one thread during ``fit`` because the thread count
changes the float summation order (notes/tooling.md §4).

Files are ``.npz`` archives of the weights and scaler plus JSON metadata (format tag, feature
schema, hyper-parameters, provenance), read with ``allow_pickle=False``; a corrupt or mismatched
file raises :class:`~learning.features.ModelFileError`. In the control loop, use
:meth:`InterceptionModel.as_function`: a closure over plain floats, far cheaper per call than
torch on one sample (notes/tooling.md §4).
The file layout, its validation and the plain-Python closure live in the torch-free
:mod:`learning.interception_file` (one implementation), so a control loop can load a net with
:func:`~learning.interception_file.load_turn_function` without importing torch.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Self

import numpy as np
import numpy.typing as npt
import torch
from torch import nn

from learning.datasets import Provenance
from learning.features import (
    FEATURE_NAMES,
    FeatureSchema,
    check_distance_scale,
    scale_distances,
)
from learning.interception_file import (
    DEFAULT_LEARNING_RATES,
    MODEL_FORMAT,
    MODEL_FORMAT_VERSION,
    SCALER_KEYS,
    WEIGHT_KEYS,
    NetFile,
    TurnAngleFunction,
    Unit,
    fold_net,
    read_net_file,
    turn_function,
    write_net_file,
)
from learning.interception_file import check_params as _check_params

__all__ = [
    "DEFAULT_LEARNING_RATES",
    "MODEL_FORMAT",
    "MODEL_FORMAT_VERSION",
    "SCALER_KEYS",
    "WEIGHT_KEYS",
    "InterceptionModel",
    "InterceptionNet",
    "TurnAngleFunction",
]

Array = npt.NDArray[np.float64]


class InterceptionNet(nn.Module):
    """The paper's net: 3 inputs -> `hidden` sigmoid units -> 1 linear output (§5).

    Its inputs are standardised features; :class:`InterceptionModel` does the scaling.
    """

    def __init__(self, hidden: int = 4) -> None:
        super().__init__()
        self.hidden = nn.Linear(len(FEATURE_NAMES), hidden)
        self.output = nn.Linear(hidden, 1)

    def forward(self, z: torch.Tensor) -> torch.Tensor:
        """(N, 3) standardised features -> (N,) turn angles [rad]."""
        out: torch.Tensor = self.output(torch.sigmoid(self.hidden(z)))
        return out.squeeze(-1)


class InterceptionModel:
    """The interception net as an estimator: ``fit(X, y)``, ``predict(X)``, save and load.

    ``X`` rows are :data:`~learning.features.FEATURE_NAMES` (BD [m], BA [rad], previous BD [m]),
    ``y`` the turn angles TA [rad]. See the module docstring for the defaults and why.

    Args:
        hidden: Number of sigmoid hidden units (paper: 4).
        optimizer: ``"adam"`` or ``"sgd"``.
        learning_rate: Step size; None picks :data:`DEFAULT_LEARNING_RATES` for the optimiser.
        weight_decay: Initial per-update decay of the input-to-hidden weights, falling linearly
            to 0 over the epochs (paper: 0.1 %).
        epochs: Passes over the data (paper: 3000).
        batch_size: Rows per update; None trains on the full batch.
        random_state: Seed of the initial weights and of the batch order.
        distance_scale_m: Distances are divided by this before the net [m] (the transfer study;
            see :mod:`learning.features`).

    Attributes:
        weights_: The net's ``state_dict`` as float64 arrays (``hidden.weight`` (H, 3), ...).
        input_mean_: (3,) mean of the scaled training features.
        input_scale_: (3,) standard deviation of the scaled training features (1 where constant).
        feature_schema_: The schema the model reads, with its active distance scale.
        loss_history_: (epochs,) training mean squared error per epoch [rad^2].
        n_train_: Rows it was fitted on.
        provenance_: The training data's provenance, when loaded from a file; else None.
    """

    weights_: dict[str, Array]
    input_mean_: Array
    input_scale_: Array
    feature_schema_: FeatureSchema
    loss_history_: Array
    n_train_: int
    provenance_: Provenance | None

    def __init__(
        self,
        hidden: int = 4,
        optimizer: str = "adam",
        learning_rate: float | None = None,
        weight_decay: float = 1e-3,
        epochs: int = 3000,
        batch_size: int | None = None,
        random_state: int = 0,
        distance_scale_m: float = 1.0,
    ) -> None:
        self.hidden = hidden
        self.optimizer = optimizer
        self.learning_rate = learning_rate
        self.weight_decay = weight_decay
        self.epochs = epochs
        self.batch_size = batch_size
        self.random_state = random_state
        self.distance_scale_m = distance_scale_m

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.get_params().items())
        return f"{type(self).__name__}({args})"

    def get_params(self) -> dict[str, Any]:
        """The constructor arguments, as given (plain types, stored in the model file)."""
        return {
            "hidden": self.hidden,
            "optimizer": self.optimizer,
            "learning_rate": self.learning_rate,
            "weight_decay": self.weight_decay,
            "epochs": self.epochs,
            "batch_size": self.batch_size,
            "random_state": self.random_state,
            "distance_scale_m": self.distance_scale_m,
        }

    # ------------------------------------------------------------------------- training

    def fit(self, x: npt.ArrayLike, y: npt.ArrayLike, *, decision: str = "turn") -> Self:
        """Train on saves: `x` (N, 3) features [m, rad, m], `y` (N,) turn angles [rad].

        `decision` names what the rows and targets are (:data:`~learning.features.DECISIONS`):
        ``"turn"`` (TA [rad]) or ``"lead"`` (lead times [s], with the track angle as the
        angle column); the file records it, and the drills refuse a net of the other kind.

        Returns:
            self, fitted.

        Raises:
            ValueError: A hyper-parameter is invalid, or `x`/`y` have wrong shapes or values.
        """
        _check_params(self.get_params())
        rows = scale_distances(x, self.distance_scale_m)
        targets = np.array(y, dtype=np.float64)  # a copy: torch wants writeable arrays
        if targets.shape != (rows.shape[0],) or rows.shape[0] < 2:
            raise ValueError(
                f"need >= 2 rows and y of shape (N,) = ({len(rows)},), got {targets.shape}"
            )
        if not np.isfinite(targets).all():
            raise ValueError("targets hold NaN or infinite values")
        mean = rows.mean(axis=0)
        scale = rows.std(axis=0)
        scale[scale == 0.0] = 1.0  # a constant column carries no information; leave it at 0
        net, history = self._train((rows - mean) / scale, targets)
        self.weights_ = {k: v.detach().numpy().copy() for k, v in net.state_dict().items()}
        self.input_mean_, self.input_scale_ = mean, scale
        self.feature_schema_ = FeatureSchema.for_decision(decision, self.distance_scale_m)
        self.loss_history_ = history
        self.n_train_ = int(rows.shape[0])
        self.provenance_ = None
        return self

    def fine_tuned(
        self,
        x: npt.ArrayLike,
        y: npt.ArrayLike,
        *,
        distance_scale_m: float | None = None,
        epochs: int = 1000,
        learning_rate: float = 1e-3,
    ) -> InterceptionModel:
        """A copy trained further on `x`, `y`, starting from this model's weights (warm start).

        The transfer study's fine-tuning: a net pre-trained on one field learns from a few
        examples of another. The copy keeps this model's input standardisation (the
        pre-training data's mean and spread, so each input keeps its meaning for the learned
        weights) and reads distances divided by `distance_scale_m` (None: this model's), so a
        Soccer Server net given ``distance_scale_m`` = one drill unit of the robot table reads
        the robots' metres as the drill units it learned in. It trains without the paper's
        weight decay: the decay pulls the weights toward 0, not toward the pre-trained ones,
        and the pre-training is the prior here.

        Args:
            x: (N, 3) features [m, rad, m] of the new field.
            y: (N,) turn angles [rad].
            distance_scale_m: Divisor of the new field's distances [m].
            epochs: Passes over the new data.
            learning_rate: The optimiser's step (this model's optimiser).

        Returns:
            A new fitted model; `n_train_` counts the new rows, `loss_history_` the new epochs.
        """
        self._check_fitted()
        scale_m = (
            self.feature_schema_.distance_scale_m
            if distance_scale_m is None
            else (distance_scale_m)
        )
        tuned = self.with_distance_scale(scale_m)
        tuned.epochs, tuned.learning_rate, tuned.weight_decay = epochs, learning_rate, 0.0
        _check_params(tuned.get_params())
        rows = scale_distances(x, scale_m)
        targets = np.array(y, dtype=np.float64)
        if targets.shape != (rows.shape[0],) or rows.shape[0] < 1 or not np.isfinite(targets).all():
            raise ValueError(f"need >= 1 row and finite y of shape ({len(rows)},)")
        z = (rows - self.input_mean_) / self.input_scale_
        with _one_thread():
            generator = torch.Generator().manual_seed(tuned.random_state)
            net = self.to_torch()
            history = _epochs(
                net, torch.from_numpy(z), torch.from_numpy(targets), generator, tuned.get_params()
            )
        tuned.weights_ = {k: v.detach().numpy().copy() for k, v in net.state_dict().items()}
        tuned.loss_history_ = history
        tuned.n_train_ = int(rows.shape[0])
        tuned.provenance_ = None
        return tuned

    def _train(self, z: Array, targets: Array) -> tuple[InterceptionNet, Array]:
        with _one_thread():
            # The one seeding block: a private generator, so fitting never touches global RNGs.
            generator = torch.Generator().manual_seed(self.random_state)
            net = _new_net(self.hidden)
            _initialise(net, generator)
            return net, _epochs(
                net, torch.from_numpy(z), torch.from_numpy(targets), generator, self.get_params()
            )

    # ------------------------------------------------------------------------- inference

    def predict(self, x: npt.ArrayLike) -> Array:
        """Turn angles for (N, 3) feature rows [m, rad, m] -> (N,) TA [rad]; numpy, batched."""
        self._check_fitted()
        rows = scale_distances(x, self.feature_schema_.distance_scale_m)
        w = self.weights_
        z = (rows - self.input_mean_) / self.input_scale_
        # sigmoid(a) = (1 + tanh(a / 2)) / 2: never overflows, and as_function uses the same form.
        h = 0.5 + 0.5 * np.tanh(0.5 * (z @ w["hidden.weight"].T + w["hidden.bias"]))
        out: Array = h @ w["output.weight"][0] + w["output.bias"][0]
        return out

    def as_function(self) -> TurnAngleFunction:
        """A plain-Python ``f(BD [m], BA [rad], previous BD [m]) -> TA [rad]`` for the control loop.

        The distance scale, the standardisation and the sigmoid's halves are folded into one
        coefficient set per hidden unit, so a call is 4 ``math.tanh`` and a dozen multiply-adds
        (notes/tooling.md §4: far cheaper than torch on one sample). Equals :meth:`predict` to
        1e-9.
        """
        self._check_fitted()
        units, offset = self._folded()
        return turn_function(units, offset)

    def _folded(self) -> tuple[tuple[Unit, ...], float]:
        return fold_net(
            self.weights_,
            self.input_mean_,
            self.input_scale_,
            self.feature_schema_.distance_scale_m,
        )

    def with_distance_scale(self, distance_scale_m: float) -> InterceptionModel:
        """The same fitted net reading distances divided by another scale (transfer study).

        E.g. a net trained on the Soccer Server with ``distance_scale_m=105`` (field lengths)
        applied on the robot table with ``.with_distance_scale(2.74)``.
        """
        self._check_fitted()
        check_distance_scale(distance_scale_m)
        other = type(self)(**{**self.get_params(), "distance_scale_m": distance_scale_m})
        other.__dict__.update(
            {k: v for k, v in self.__dict__.items() if k.endswith("_")},
            feature_schema_=dataclasses.replace(
                self.feature_schema_, distance_scale_m=distance_scale_m
            ),
        )
        return other

    def to_torch(self) -> InterceptionNet:
        """A float64 torch net holding the fitted weights (its inputs are standardised)."""
        self._check_fitted()
        net = _new_net(self.hidden)
        net.load_state_dict({k: torch.from_numpy(v.copy()) for k, v in self.weights_.items()})
        return net

    def _check_fitted(self) -> None:
        if not hasattr(self, "weights_"):
            raise RuntimeError("InterceptionModel is not fitted: call fit() or load() first")

    # ------------------------------------------------------------------------- files

    def save(self, path: str | os.PathLike[str], provenance: Provenance) -> Path:
        """Write the fitted model and its training data's provenance to `path` (``.npz``).

        Returns:
            The path written.
        """
        self._check_fitted()
        if provenance.schema_version != self.feature_schema_.version:
            raise ValueError(
                f"provenance schema version {provenance.schema_version} is not the model's "
                f"{self.feature_schema_.version}"
            )
        net = NetFile(
            dict(self.weights_),
            self.input_mean_,
            self.input_scale_,
            self.loss_history_,
            self.feature_schema_,
            self.get_params(),
            self.n_train_,
            provenance,
        )
        return write_net_file(path, net, torch.__version__)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> InterceptionModel:
        """Read a model written by :meth:`save`, validating everything before use.

        Checks the format tag and version, the feature schema, the hyper-parameters, every
        array's shape and dtype, and that all weights are finite.

        Raises:
            ModelFileError: The file is missing, corrupt, truncated, not a model, for another
                feature schema, or holds wrong shapes or non-finite weights.
        """
        return cls._from_file(read_net_file(path))

    @classmethod
    def _from_file(cls, net: NetFile) -> Self:
        model = cls(**net.hyperparameters)
        model.weights_ = dict(net.weights)
        model.input_mean_, model.input_scale_ = net.input_mean, net.input_scale
        model.loss_history_ = net.loss_history
        model.feature_schema_ = net.schema
        model.n_train_ = net.n_train
        model.provenance_ = net.provenance
        return model


@contextlib.contextmanager
def _one_thread() -> Iterator[None]:
    """Torch on one thread inside (notes/tooling.md §4: threads change the float sums)."""
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        yield
    finally:
        torch.set_num_threads(threads)


def _new_net(hidden: int) -> InterceptionNet:
    """A float64 net; torch's default init draws from the global RNG, so restore it after."""
    with torch.random.fork_rng(devices=[]):
        return InterceptionNet(hidden).double()


def _initialise(net: InterceptionNet, generator: torch.Generator) -> None:
    """Uniform(±1/sqrt(fan_in)) weights and biases, torch's default range, from `generator`."""
    with torch.no_grad():
        for layer in (net.hidden, net.output):
            bound = 1.0 / math.sqrt(layer.in_features)
            layer.weight.uniform_(-bound, bound, generator=generator)
            layer.bias.uniform_(-bound, bound, generator=generator)


def _epochs(
    net: InterceptionNet,
    xs: torch.Tensor,
    ys: torch.Tensor,
    generator: torch.Generator,
    params: dict[str, Any],
) -> Array:
    """Train `net` in place on (`xs`, `ys`) for the estimator's `params`; the loss per epoch.

    The module docstring's optimiser and the paper's decay of the input-to-hidden weights,
    mini-batches (if any) drawn from `generator`.
    """
    optimizer, epochs, weight_decay = params["optimizer"], params["epochs"], params["weight_decay"]
    rate = params["learning_rate"]
    if rate is None:
        rate = DEFAULT_LEARNING_RATES[optimizer]
    step: torch.optim.Optimizer
    if optimizer == "adam":
        step = torch.optim.Adam(net.parameters(), lr=rate)
    else:
        step = torch.optim.SGD(net.parameters(), lr=rate)
    history = np.empty(epochs)
    for epoch in range(epochs):
        # Paper §5: input-to-hidden decay "linearly decreasing ... starting at .1%".
        keep = 1.0 - weight_decay * (1.0 - epoch / epochs)
        total = 0.0
        for rows in _batches(len(ys), params["batch_size"], generator):
            xb, yb = (xs, ys) if rows is None else (xs[rows], ys[rows])
            loss = torch.mean((net(xb) - yb) ** 2)
            step.zero_grad()
            loss.backward()
            step.step()
            with torch.no_grad():
                net.hidden.weight.mul_(keep)
            total += loss.item() * len(yb)
        history[epoch] = total / len(ys)
    return history


def _batches(
    n: int, batch_size: int | None, generator: torch.Generator
) -> Iterator[torch.Tensor | None]:
    """Row indices of each mini-batch of one epoch (shuffled); None means the full batch."""
    if batch_size is None or batch_size >= n:
        yield None
        return
    order = torch.randperm(n, generator=generator)
    yield from order.split(batch_size)
