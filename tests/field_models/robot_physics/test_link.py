from __future__ import annotations

import dataclasses
import math

import numpy as np

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.robot_physics.config import LinkConfig, load_preset
from field_models.robot_physics.link import Command, Link, Primitive

PRESET = load_preset()
A = PlayerRef(LEFT, 1)
B = PlayerRef(RIGHT, 1)
C = PlayerRef(RIGHT, 2)
Z_999 = 3.2905


def make_link(
    config: LinkConfig = PRESET.link, *, period: int = 1, latency: int = 3, seed: int = 1
) -> Link:
    return Link(
        config,
        packet_period_ticks=period,
        latency_ticks=latency,
        rng=np.random.default_rng(seed),
    )


def lossless() -> LinkConfig:
    return dataclasses.replace(PRESET.link, loss_prob=0.0)


def cmd(seq: int, robot: PlayerRef | None = A, tick: int = 0) -> Command:
    return Command(seq, robot, Primitive.FORWARD, 0.5, sent_tick=tick)


def test_preset_link_in_ticks() -> None:
    assert PRESET.ticks(1.0 / PRESET.link.packets_per_s, "link") == 1
    assert PRESET.ticks(PRESET.link.latency_s, "link") == 3


def test_latency_exact_from_slot() -> None:
    link = make_link(lossless(), period=1, latency=3)
    arrivals: dict[int, int] = {}
    for tick in range(100):
        for c in link.deliver(tick):
            arrivals[c.seq] = tick
        if tick % 5 == 0:
            link.send(cmd(tick, tick=tick), tick)
    assert arrivals and all(arrivals[seq] - seq == 3 for seq in arrivals)


def test_send_before_or_after_deliver_same_tick() -> None:
    link = make_link(lossless(), latency=2)
    link.send(cmd(1), 10)  # before deliver(10)
    assert link.deliver(10) == [] and link.deliver(11) == []
    assert [c.seq for c in link.deliver(12)] == [1]
    link.deliver(20)
    link.send(cmd(2), 20)  # after deliver(20): slot 20 is still free
    assert [c.seq for c in link.deliver(22)] == [2]


def test_zero_latency_arrives_at_the_next_deliver() -> None:
    link = make_link(lossless(), latency=0)
    link.deliver(5)
    link.send(cmd(1), 5)
    assert [c.seq for c in link.deliver(6)] == [1]


def test_one_packet_per_slot_in_order() -> None:
    link = make_link(lossless(), period=4, latency=3)
    for seq, robot in enumerate((A, B, C), start=1):
        link.send(cmd(seq, robot), 1)  # slots at 4, 8, 12
    got = {tick: [c.seq for c in link.deliver(tick)] for tick in range(20)}
    assert got[7] == [1] and got[11] == [2] and got[15] == [3]
    assert sum(len(v) for v in got.values()) == 3
    assert link.sent == link.delivered == 3


def test_newer_command_to_same_address_takes_the_older_ones_turn() -> None:
    link = make_link(lossless(), period=4, latency=0)
    link.deliver(0)  # slot 0 done; next slots 4, 8
    link.send(cmd(1, A), 1)
    link.send(cmd(2, B), 1)
    link.send(cmd(3, A), 2)  # replaces seq 1, keeps A's place ahead of B
    link.send(cmd(4, None), 2)  # broadcast is its own address
    out = [(t, c.seq) for t in range(1, 20) for c in link.deliver(t)]
    assert out == [(4, 3), (8, 2), (12, 4)]
    assert link.superseded == 1


def test_loss_rate_within_binomial_tolerance() -> None:
    link = make_link(PRESET.link, seed=11)
    n = 30000
    received = 0
    for tick in range(n + 10):
        received += len(link.deliver(tick))
        if tick < n:
            link.send(cmd(tick + 1, A if tick % 2 else B, tick), tick)
    p = PRESET.link.loss_prob
    assert link.sent == n
    assert abs(link.lost - n * p) <= Z_999 * math.sqrt(n * p * (1 - p))
    assert received == link.delivered == n - link.lost


def test_lost_packets_are_independent_of_address_and_order_kept() -> None:
    cfg = dataclasses.replace(PRESET.link, loss_prob=0.5)
    link = make_link(cfg, seed=5)
    seqs = []
    for tick in range(2000):
        seqs += [c.seq for c in link.deliver(tick)]
        link.send(cmd(tick + 1, A, tick), tick)
    assert seqs == sorted(seqs)
    n = link.sent
    assert abs(link.lost - n / 2) <= Z_999 * math.sqrt(n / 4)


def test_same_seed_same_losses() -> None:
    def run(seed: int) -> list[int]:
        link = make_link(dataclasses.replace(PRESET.link, loss_prob=0.3), seed=seed)
        out = []
        for tick in range(300):
            out += [c.seq for c in link.deliver(tick)]
            link.send(cmd(tick + 1, A, tick), tick)
        return out

    assert run(2) == run(2)
    assert run(2) != run(3)
