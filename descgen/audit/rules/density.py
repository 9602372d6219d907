"""UNIT: a link's mass must fit its size (catches grams typed as kilograms and back)."""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core import display, units
from descgen.core.findings import Finding, Severity
from descgen.core.model import Robot
from descgen.physics import inertia
from descgen.physics.bodies import PLACEHOLDER, PLACEHOLDER_MASS, dims


def _density_range(robot: Robot) -> units.Range:
    """The spec's ``plausibility.density``, else the default (a read URDF has none)."""
    if robot.density_range is not None:
        low, high = robot.density_range
        return units.Range("density", low, high)
    return units.DEFAULT_RANGES["density"]


@rule("UNIT010", "implausible-density", "error")
def implausible_density(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Divides each link's mass by the volume of its collision primitives (or visual ones
    when it has no collision) and flags a density outside foam..tungsten (5 to 25000 kg/m^3
    by default; `plausibility.density` in a spec).
    ## Why is this bad?
    A density a thousand times off is a mass in the wrong unit (1200 g written as 1200 kg),
    which no parser notices and which breaks simulation and the static-torque check.
    """
    r = _density_range(robot)
    for lk in robot.links:
        if lk.inertial is None or lk.inertial.mass is None or lk.inertial.mass <= PLACEHOLDER_MASS:
            continue
        shapes = [c.geometry for c in lk.collisions] or [v.geometry for v in lk.visuals]
        if not shapes or any(g is None for g in shapes):
            continue
        if max((d for g in shapes for d in dims(g)), default=0.0) < PLACEHOLDER:
            continue  # a millimetre-sized stand-in, not the part's shape
        vols = [inertia.volume(g) for g in shapes if g is not None]
        if any(v is None for v in vols):
            continue  # meshes: volume unknown without reading them
        vol = sum(v for v in vols if v is not None)
        if vol <= 0:
            continue
        rho = lk.inertial.mass / vol
        if r.low <= rho <= r.high:
            continue
        hint = "is the mass in the wrong unit (g vs kg)? or the geometry (mm vs m)?"
        off = display.thousand_off(rho, r.low, r.high)
        if off == 1000:
            hint = "the mass looks 1000x too large for the shape: grams written as kilograms, or a stand-in shape?"
        elif off == 0.001:
            hint = "the mass looks 1000x too small (kilograms written as grams?), or the geometry 10x too large"
        # heavier than any metal is impossible; lighter than foam may be a light part in a
        # generous shape, unless it is a thousand times lighter still
        severity: Severity = "error" if rho > r.high or rho < r.low / 1000 else "warning"
        yield at(
            "UNIT010",
            lk.inertial,
            f"link '{lk.name}' mass {lk.inertial.mass:.6g} kg in {vol:.4g} m^3 of geometry "
            f"implies {rho:.4g} kg/m^3, outside {r.low:g} to {r.high:g}",
            hint,
            severity=severity,
            subject=lk.subject,
        )
