"""Codes of ``descgen sweep``: each joint through its range, directions and self-collisions.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("sweep")


SWEEP001 = declare(
    "SWEEP001",
    "sweep-collision-at-limit",
    "warning",
    "Two links the SRDF does not disable collide at a joint limit while that joint is swept (the others at "
    "the state); the message gives the limit's value and where the contact starts.",
    """A joint driven to its limit (homing, a planner using the whole range, a teleoperator) drives the
      robot into itself there. Narrow the limit so the motion stops before the contact, change the collision
      shapes if they are too large, or disable the pair in the SRDF if the contact is by design.""",
)

SWEEP002 = declare(
    "SWEEP002",
    "sweep-collision-in-range",
    "warning",
    "Two links the SRDF does not disable collide inside a joint's range while that joint is swept (the others "
    "at the state); the message gives the joint values where the contact starts and ends.",
    """MoveIt plans around such a contact, but a jog or a controller that moves one joint alone runs into it.
      It is expected at some states (an arm folded over its base); check the shapes and the range.""",
)

SWEEP003 = declare(
    "SWEEP003",
    "sweep-no-range",
    "info",
    "A joint is not swept: it has no lower and upper limit, or its range is empty.",
    """Only joints with a range can be moved through it. A revolute or prismatic joint without limits is
      reported by the audit; an empty range (lower equal to upper) holds the joint still.""",
)

SWEEP004 = declare(
    "SWEEP004",
    "sweep-unknown-state",
    "error",
    "--state names no group state and no known pose of the robot.",
    """The other joints are held at the named state while each joint is swept; an unknown name is a typo.
      The message lists the names there are.""",
)

SWEEP005 = declare(
    "SWEEP005",
    "sweep-collisions-not-checked",
    "warning",
    "The self-collisions of the sweep were not checked: pinocchio (the collision extra) is not installed, or "
    "it could not load the collision geometry. The directions are still reported.",
    """The collision check needs pinocchio with coal: pip install 'descgen[collision]'. A sweep without it
      says nothing about contacts, so it is said rather than left out.""",
)

SWEEP006 = declare(
    "SWEEP006",
    "sweep-mesh-left-out",
    "warning",
    "A collision mesh was not found, so that shape is left out of the sweep's collision check.",
    """The mesh could not be resolved inside the description's package or --package-path (docs/security.md),
      so its link is checked without it and contacts with it are missed. Give --package-path or fix the
      filename.""",
)

SWEEP007 = declare(
    "SWEEP007",
    "sweep-too-large",
    "error",
    "The robot is too large to sweep: joints x links x grid steps is more than the sweep's bound "
    "(500,000 link poses); nothing is swept (exit 2).",
    """Every joint is moved through every grid step and every link's pose is computed there, so the work
      grows with the joints times the links: a 10,000-link chain would take hours. The bound keeps a sweep
      within about 20 s; sweep with fewer --steps, or a smaller description.""",
)

SWEEP008 = declare(
    "SWEEP008",
    "sweep-collisions-too-many",
    "warning",
    "The self-collisions of the sweep were not checked: more pair tests (pairs x grid steps) than the "
    "sweep's bound (2,000,000), or more collision shapes or a deeper tree than pinocchio is given "
    "(20,000 pairs of shapes, 1,000 joints deep). The directions are still reported.",
    """pinocchio keeps ~40 KB per pair of collision shapes, and its URDF parser overflows the stack on a
      tree thousands of joints deep (a crash, no message). Sweep with fewer --steps, disable pairs that
      cannot collide in the SRDF, or give fewer collision shapes.""",
)
