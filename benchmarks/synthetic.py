"""Synthetic specs for benchmarks: a serial chain of N revolute links."""

from __future__ import annotations


def chain_spec(n_links: int, name: str = "chain") -> str:
    lines = [f"name: {name}", "links:"]
    for i in range(n_links):
        lines += [
            f"  - name: link{i}",
            "    visual: [{origin: {xyz: [0, 0, 50 mm]}, geometry: {box: {size: [40 mm, 40 mm, 100 mm]}}}]",
            "    collision: [{origin: {xyz: [0, 0, 50 mm]}, geometry: {box: {size: [40 mm, 40 mm, 100 mm]}}}]",
            "    inertial: {mass: 1 g, origin: {xyz: [0, 0, 50 mm]}, from: collision}",
        ]
    lines.append("joints:")
    for i in range(1, n_links):
        axis = ("+x", "+y", "+z")[i % 3]
        lines += [
            f"  - name: joint{i}",
            "    type: revolute",
            f"    parent: link{i - 1}",
            f"    child: link{i}",
            "    origin: {xyz: [0, 0, 100 mm], rpy: [0, 0, 15 deg]}",
            f"    axis: {axis}",
            "    limit: {lower: -90 deg, upper: 90 deg, effort: 2000 N*m, velocity: 1 rad/s}",
        ]
    return "\n".join(lines) + "\n"
